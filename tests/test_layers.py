"""The layers of lynxsim: which package may import which, and no package-level cycle.

Every import statement of every module is read with :mod:`ast`, at module level
and inside functions (an import deferred into a function still runs), except
those under ``if TYPE_CHECKING:``. A package is ``lynxsim.X``;
``lynxsim.sim.arm`` and ``lynxsim.sim.rrr`` count apart from the generic
``lynxsim.sim``. :data:`ALLOWED` writes down the layers of the design (issue
22); :data:`CHECKED` names the packages held to them and to having no cycle.
"""

from __future__ import annotations

import ast
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parents[1] / "lynxsim"

BASE = frozenset(
    {
        "errors",
        "bounds",
        "inputs",
        "angles",
        "fileio",
        "resources",
        "scene",
        "random_scenes",
        "poses",
        "registry",
        "run_options",
        "verdicts",
        "processes",
        "web",
    }
)
"""Layer 0: plain values and checks, importing nothing of lynxsim above them."""

MATH = frozenset({"traj", "plan", "arm", "rrr"})
"""Layer 1: the pure math of trajectories, planning and each robot."""

_BELOW_SIM = BASE | MATH | {"tasks"}
_BELOW_ROBOTS = _BELOW_SIM | {"sim", "sim.arm", "sim.rrr"}
_TOP = frozenset({"envs", "sweep", "reproduce", "datasets", "demo"})

ALLOWED: dict[str, frozenset[str]] = {
    **{name: BASE for name in sorted(BASE)},
    "traj": BASE,
    "plan": BASE | {"traj"},
    "arm": BASE | {"traj", "plan"},
    "rrr": BASE | {"traj"},
    "real": BASE | {"traj", "arm", "real"},
    "tasks": BASE | {"traj"},
    "sim": _BELOW_SIM,
    "sim.arm": BASE | {"sim", "arm", "traj", "plan", "tasks", "real"},
    "sim.rrr": BASE | {"sim", "rrr", "traj", "tasks"},
    "robots": _BELOW_ROBOTS,
    "plots": _BELOW_SIM,
    **{name: _BELOW_ROBOTS | {"robots", "plots"} | _TOP for name in sorted(_TOP)},
    "cli": _BELOW_ROBOTS | {"robots", "plots", "real", "cli"} | _TOP,
    "__main__": frozenset({"cli"}),
    "models": frozenset(),
    "lynxsim": frozenset(),
}
"""The packages each package may import (itself and the empty root ``lynxsim`` always), from
the design of issue 22."""

TASKS_TRAJ_MODULES = frozenset({"lynxsim.traj.kinds", "lynxsim.traj.timing"})
"""Of :mod:`lynxsim.traj`, the task loader reads only the kinds and the durations."""

CHECKED: tuple[str, ...] = tuple(ALLOWED)
"""The packages held to :data:`ALLOWED` and to no cycle: the whole package."""


def _module_name(path: Path) -> str:
    parts = path.relative_to(PACKAGE.parent).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def package_of(module: str) -> str | None:
    """The package of a module name (``sim.arm`` and ``sim.rrr`` apart); None outside lynxsim."""
    parts = module.split(".")
    if parts[0] != "lynxsim":
        return None
    if len(parts) == 1:
        return "lynxsim"
    if parts[1] == "sim" and len(parts) > 2 and parts[2] in ("arm", "rrr"):
        return f"sim.{parts[2]}"
    return parts[1]


def _is_type_checking(test: ast.expr) -> bool:
    return (isinstance(test, ast.Name) and test.id == "TYPE_CHECKING") or (
        isinstance(test, ast.Attribute) and test.attr == "TYPE_CHECKING"
    )


def _runtime_imports(tree: ast.AST, module: str, is_package: bool) -> Iterator[tuple[str, int]]:
    """``(imported module, line)`` of every import that runs, ``if TYPE_CHECKING:`` left out."""
    if isinstance(tree, ast.If) and _is_type_checking(tree.test):
        for node in tree.orelse:
            yield from _runtime_imports(node, module, is_package)
        return
    if isinstance(tree, ast.Import):
        for alias in tree.names:
            yield alias.name, tree.lineno
    elif isinstance(tree, ast.ImportFrom):
        if tree.level:
            base = module.split(".")
            base = base[: len(base) - tree.level + (1 if is_package else 0)]
            source = ".".join([*base, tree.module] if tree.module else base)
        else:
            source = tree.module or ""
        yield source, tree.lineno
        for alias in tree.names:  # from lynxsim import traj: the submodule itself
            candidate = f"{source}.{alias.name}"
            if (PACKAGE.parent / candidate.replace(".", "/")).is_dir() or (
                PACKAGE.parent / (candidate.replace(".", "/") + ".py")
            ).is_file():
                yield candidate, tree.lineno
    for child in ast.iter_child_nodes(tree):
        yield from _runtime_imports(child, module, is_package)


def import_edges() -> list[tuple[str, str, str]]:
    """``(importing module, imported module, "file:line")`` of every lynxsim import in lynxsim."""
    edges = []
    for path in sorted(PACKAGE.rglob("*.py")):
        module = _module_name(path)
        tree = ast.parse(path.read_text(encoding="utf-8"), str(path))
        for target, line in _runtime_imports(tree, module, path.name == "__init__.py"):
            if package_of(target) is not None:
                edges.append((module, target, f"{path.relative_to(PACKAGE.parent)}:{line}"))
    return edges


def package_graph(
    edges: list[tuple[str, str, str]], packages: tuple[str, ...]
) -> dict[str, set[str]]:
    """Package -> packages it imports, both among ``packages``, self-imports left out."""
    graph: dict[str, set[str]] = {p: set() for p in packages}
    for source, target, _ in edges:
        a, b = package_of(source), package_of(target)
        if a in graph and b in graph and a != b:
            graph[a].add(b)
    return graph


def find_cycle(graph: dict[str, set[str]]) -> list[str] | None:
    """One cycle of a directed graph as a path that ends where it starts, or None."""
    state: dict[str, int] = {}  # 1: on the current path, 2: done
    stack: list[str] = []

    def visit(node: str) -> list[str] | None:
        state[node] = 1
        stack.append(node)
        for nxt in sorted(graph[node]):
            if state.get(nxt) == 1:
                return [*stack[stack.index(nxt) :], nxt]
            if nxt not in state and (found := visit(nxt)) is not None:
                return found
        stack.pop()
        state[node] = 2
        return None

    for node in sorted(graph):
        if node not in state and (found := visit(node)) is not None:
            return found
    return None


def test_the_walker_sees_function_level_imports_and_skips_type_checking_blocks():
    source = (
        "from typing import TYPE_CHECKING\n"
        "from lynxsim.errors import InvalidInputError\n"
        "if TYPE_CHECKING:\n"
        "    from lynxsim.tasks import Task\n"
        "else:\n"
        "    import lynxsim.bounds\n"
        "def f():\n"
        "    from lynxsim.sim.arm import planning\n"
        "    from . import limits\n"
    )
    found = [m for m, _ in _runtime_imports(ast.parse(source), "lynxsim.traj.build", False)]
    assert "lynxsim.tasks" not in found
    assert {"lynxsim.errors", "lynxsim.bounds", "lynxsim.sim.arm", "lynxsim.traj"} <= set(found)
    assert "lynxsim.traj.limits" in found
    assert package_of("lynxsim.sim.arm.planning") == "sim.arm"
    assert package_of("lynxsim.sim.render") == "sim"
    assert find_cycle({"a": {"b"}, "b": {"c"}, "c": {"a"}}) == ["a", "b", "c", "a"]
    assert find_cycle({"a": {"b"}, "b": set()}) is None


def test_every_package_has_a_layer():
    packages = {package_of(_module_name(p)) for p in PACKAGE.rglob("*.py")}
    assert packages <= set(ALLOWED), sorted(packages - set(ALLOWED))


@pytest.mark.parametrize("package", CHECKED)
def test_a_package_imports_only_the_layers_below_it(package):
    allowed = ALLOWED[package] | {package, "lynxsim"}  # the root package imports nothing
    offenders = [
        f"{where}: {target}"
        for source, target, where in import_edges()
        if package_of(source) == package and package_of(target) not in allowed
    ]
    assert offenders == []


def test_the_task_loader_reads_only_the_kinds_and_durations_of_traj():
    offenders = [
        f"{where}: {target}"
        for source, target, where in import_edges()
        if package_of(source) == "tasks"
        and package_of(target) == "traj"
        and target not in TASKS_TRAJ_MODULES
    ]
    assert offenders == []


def test_no_package_level_cycle():
    assert find_cycle(package_graph(import_edges(), CHECKED)) is None


@pytest.mark.parametrize(
    ("modules", "absent"),
    [
        ("lynxsim.traj, lynxsim.plan", "lynxsim.arm"),
        ("lynxsim.tasks", "lynxsim.arm"),
        ("lynxsim.tasks", "lynxsim.rrr"),
        ("lynxsim.tasks", "lynxsim.robots"),
    ],
)
def test_importing_the_robot_free_layers_loads_no_robot(modules, absent):
    code = f"import sys, {modules}; print({absent!r} in sys.modules)"
    run = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, timeout=120, check=False
    )
    assert run.returncode == 0, run.stderr[-2000:]
    assert run.stdout.strip() == "False"
