"""Only :mod:`lynxsim.sim` imports MuJoCo: every other module reaches it through ``sim``."""

from __future__ import annotations

import ast
from pathlib import Path

PACKAGE = Path(__file__).resolve().parents[1] / "lynxsim"
SIM = PACKAGE / "sim"


def _imported(tree: ast.AST) -> list[tuple[int, str]]:
    """Every module an ``import`` or ``from ... import`` names, at any depth (functions too)."""
    out = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            out += [(node.lineno, alias.name) for alias in node.names]
        elif isinstance(node, ast.ImportFrom) and node.module is not None and node.level == 0:
            out.append((node.lineno, node.module))
    return out


def _is_mujoco(module: str) -> bool:
    return module == "mujoco" or module.startswith("mujoco.")


def test_no_module_outside_sim_imports_mujoco() -> None:
    offenders = [
        f"{source.relative_to(PACKAGE)}:{line} imports {module}"
        for source in sorted(PACKAGE.rglob("*.py"))
        if not source.is_relative_to(SIM)
        for line, module in _imported(ast.parse(source.read_text()))
        if _is_mujoco(module)
    ]
    assert offenders == []


def test_the_walk_sees_imports_inside_functions_and_submodules() -> None:
    source = "def f():\n    import mujoco.viewer\n    from mujoco import rollout\n"
    found = [m for _, m in _imported(ast.parse(source)) if _is_mujoco(m)]
    assert found == ["mujoco.viewer", "mujoco"]
    assert any(_is_mujoco(m) for _, m in _imported(ast.parse((SIM / "render.py").read_text())))
