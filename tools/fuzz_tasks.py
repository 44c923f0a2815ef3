"""Fuzz campaign of the task-file loader and the motion builders.

Mutates the shipped task files (``tasks/*.toml``) two ways: structure-aware
(parse to a dict, delete keys, swap types, insert huge, denormal or NaN numbers,
400-digit integers, deep nesting, control characters, empty arrays, wrong
shapes, unknown keys; then write TOML again) and byte-level (flip, insert,
delete and repeat bytes of the raw text). Every mutant is written to a file and
loaded with :func:`lynxsim.tasks.load_task`; a task that loads is built into
its motion of its own type with its robot record (:attr:`lynxsim.robots.Robot.motion`) and
sampled. The contract:

* ``load_task`` returns a :class:`~lynxsim.tasks.Task` or raises
  :class:`~lynxsim.errors.TaskFileError` naming the file;
* the builder returns a motion whose samples are finite or raises a
  :class:`~lynxsim.errors.LynxsimError`.

Anything else (an untyped exception, a NaN sample) is a finding: the script
prints the counts, saves each finding's mutant to ``--save-dir`` (if given) and
exits 1::

    python tools/fuzz_tasks.py --mutants 10000 --seed 0 --save-dir /tmp/findings

``tests/fuzz/test_fuzz_tasks.py`` drives the same mutators and oracle with
hypothesis.
"""

from __future__ import annotations

import argparse
import copy
import math
import random
import sys
import tempfile
import time
import tomllib
import traceback
import warnings
from collections import Counter
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Literal

import numpy as np

from lynxsim.errors import LynxsimError, TaskFileError
from lynxsim.robots import get
from lynxsim.tasks import Task, load_task
from lynxsim.traj.kinds import TrajectoryKind

TASKS = Path(__file__).resolve().parents[1] / "tasks"
"""The shipped task files, the seeds of every mutant."""

SAMPLES = 101
"""Samples of a built motion checked for finiteness, spread over its duration."""

Outcome = Literal["loaded", "task_file_error", "builder_error", "untyped", "non_finite"]
OUTCOMES: tuple[Outcome, ...] = (
    "loaded",
    "task_file_error",
    "builder_error",
    "untyped",
    "non_finite",
)
FINDINGS: tuple[Outcome, ...] = ("untyped", "non_finite")
"""Outcomes that break the contract."""


# ------------------------------------------------------------------ TOML text


@dataclass(frozen=True)
class Raw:
    """A TOML value written verbatim (deep nesting, integers of any length)."""

    text: str


def toml_string(text: str) -> str:
    """``text`` as a TOML basic string, control characters, quotes and backslashes escaped."""
    out = []
    for c in text:
        code = ord(c)
        if code < 0x20 or code == 0x7F or c in '"\\':
            out.append(f"\\u{code:04x}")
        else:
            out.append(c)
    return '"' + "".join(out) + '"'


def toml_value(value: Any) -> str:
    """``value`` as an inline TOML value (arrays and inline tables)."""
    if isinstance(value, Raw):
        return value.text
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        if math.isnan(value):
            return "nan"
        if math.isinf(value):
            return "inf" if value > 0 else "-inf"
        return repr(value)
    if isinstance(value, str):
        return toml_string(value)
    if isinstance(value, list):
        return "[" + ", ".join(toml_value(v) for v in value) + "]"
    if isinstance(value, dict):
        items = ", ".join(f"{toml_string(str(k))} = {toml_value(v)}" for k, v in value.items())
        return "{" + items + "}"
    raise TypeError(f"no TOML form for {type(value).__name__}")


def to_toml(data: dict[str, Any]) -> str:
    """A document: one ``key = value`` line per top-level key, values inline."""
    return "".join(f"{toml_string(str(k))} = {toml_value(v)}\n" for k, v in data.items())


# ------------------------------------------------------------------ mutators


def seeds(folder: Path = TASKS) -> list[tuple[str, str, dict[str, Any]]]:
    """Every shipped task file: (stem, raw text, parsed dict)."""
    out = []
    for path in sorted(folder.glob("*.toml")):
        text = path.read_text(encoding="utf-8")
        out.append((path.stem, text, tomllib.loads(text)))
    return out


def nested(depth: int, leaf: str = "1") -> Raw:
    """Arrays nested ``depth`` deep around ``leaf``."""
    return Raw("[" * depth + leaf + "]" * depth)


SPECIAL_NUMBERS: tuple[Any, ...] = (
    0,
    0.0,
    -0.0,
    -1.0,
    1e-3,
    1e-4,
    3600.0,
    3600.5,
    5e-324,
    -5e-324,
    2.2250738585072014e-308,
    1e-300,
    1e300,
    -1e300,
    6.5e306,
    1.7976931348623157e308,
    float("nan"),
    float("inf"),
    float("-inf"),
    10**400,
    -(10**400),
    2**63,
    10_000.0,
    -10_000.0,
    10_000.5,
    1e5,
    1e9,
    720.0,
    1e-9,
    Raw("1" * 400),
    Raw("-" + "9" * 400),
    Raw("0x" + "f" * 100),
    Raw("1e999"),
)
"""Numbers at and past the edges: denormals, overflow, NaN, huge integers, the bounds."""

CONTROL = ("\x00", "\n", "\r", "\t", "\x1b[31m", "\x1b]0;x\x07", "\x7f", "\x08", "\u202e", "\u2028")
"""Control and format characters: NUL, newlines, escape sequences, bidi override."""

STRINGS: tuple[str, ...] = (
    "",
    " ",
    "x" * 101,
    "x" * 10_000,
    "é" * 100,
    "P1",
    "home",
    "quintic",
    "arm",
    "rrr",
    "cylinder",
    "box",
    "sphere",
    "../../etc/passwd",
    "名前",
    *CONTROL,
    *(f"a{c}b" for c in CONTROL),
)

KEYS = (
    "name",
    "description",
    "robot",
    "trajectory",
    "type",
    "segment_duration_s",
    "stretch",
    "pass_through",
    "poses",
    "position_mm",
    "pitch_deg",
    "roll_deg",
    "q_deg",
    "x_mm",
    "y_mm",
    "alpha_deg",
    "obstacles",
    "shape",
    "radius_mm",
    "height_mm",
    "size_mm",
    "yaw_deg",
    "cube",
    "mass_kg",
    "friction",
    "colour",
    "",
    "\x00",
)
"""Keys of the schema, to move around, and a few unknown ones."""


def _value(rng: random.Random, depth: int = 0) -> Any:
    """A random value of any TOML type, biased to the edges."""
    roll = rng.random()
    if roll < 0.3:
        return rng.choice(SPECIAL_NUMBERS)
    if roll < 0.45:
        return rng.choice(STRINGS)
    if roll < 0.5:
        return rng.choice((True, False))
    if roll < 0.6:
        return rng.uniform(-1000.0, 1000.0)
    if roll < 0.65:
        return nested(rng.choice((2, 10, 100, 300, 1000, 5000)))
    if roll < 0.7:
        return rng.randint(-1000, 1000)
    if depth < 2 and roll < 0.85:
        return [_value(rng, depth + 1) for _ in range(rng.choice((0, 1, 2, 3, 3, 5, 6)))]
    if depth < 2:
        return {rng.choice(KEYS): _value(rng, depth + 1) for _ in range(rng.randint(0, 3))}
    return rng.choice(SPECIAL_NUMBERS)


def _paths(node: Any, prefix: tuple[Any, ...] = ()) -> list[tuple[Any, ...]]:
    """Every path (keys and indices) to a node below ``node``."""
    out = []
    if isinstance(node, dict):
        for k, v in node.items():
            out.append((*prefix, k))
            out += _paths(v, (*prefix, k))
    elif isinstance(node, list):
        for i, v in enumerate(node):
            out.append((*prefix, i))
            out += _paths(v, (*prefix, i))
    return out


def _get(root: Any, path: Sequence[Any]) -> Any:
    for step in path:
        root = root[step]
    return root


def _mutate_once(rng: random.Random, data: dict[str, Any], others: list[dict[str, Any]]) -> None:
    """Apply one structural mutation to ``data`` in place."""
    paths = _paths(data)
    if not paths:
        data[rng.choice(KEYS)] = _value(rng)
        return
    path = rng.choice(paths)
    parent = _get(data, path[:-1])
    key = path[-1]
    node = parent[key]
    op = rng.choice(
        (
            "delete",
            "replace",
            "replace",
            "special",
            "special",
            "scale",
            "string",
            "shape",
            "unknown",
            "enum",
            "graft",
            "nest",
            "jiggle",
            "jiggle",
            "jiggle",
        )
    )
    if op == "jiggle" and not (
        isinstance(node, float) or (type(node) is int and abs(node) <= 2**53)
    ):
        op = "special"
    if op == "scale" and type(node) is int and abs(node) > 2**53:
        op = "special"  # an int beyond a float (an earlier mutation's) cannot be scaled
    if op == "delete":
        del parent[key]
    elif op == "replace":
        parent[key] = _value(rng)
    elif op == "special" or (op == "scale" and not isinstance(node, int | float)):
        parent[key] = rng.choice(SPECIAL_NUMBERS)
    elif op == "jiggle":  # a plausible value: most such mutants load and build
        parent[key] = rng.choice((node * rng.uniform(-2.0, 2.0), node + rng.uniform(-50.0, 50.0)))
    elif op == "scale":
        factor = rng.choice((-1.0, 0.0, 1e-3, 10.0, 1e3, 1e6, 1e-300, 1e300))
        parent[key] = node * factor if not isinstance(node, bool) else factor
    elif op == "string":
        if isinstance(node, str) and node:
            at = rng.randint(0, len(node))
            parent[key] = node[:at] + rng.choice(STRINGS) + node[at:]
        else:
            parent[key] = rng.choice(STRINGS)
    elif op == "shape":
        if isinstance(node, list):
            choice = rng.choice(("empty", "drop", "dup", "extend", "reverse"))
            if choice == "empty":
                parent[key] = []
            elif choice == "drop" and node:
                del node[rng.randrange(len(node))]
            elif choice == "dup" and node and len(node) < 64:  # e.g. a pose twice: a pause
                i = rng.randrange(len(node))
                node.insert(i, copy.deepcopy(node[i]))
            elif choice == "extend":
                node.append(_value(rng))
            else:
                node.reverse()
        else:
            parent[key] = [node] if rng.random() < 0.5 else {"value": node}
    elif op == "unknown":
        target = node if isinstance(node, dict) else data
        target[rng.choice(KEYS)] = _value(rng)
    elif op == "enum":
        choices = [k.value for k in TrajectoryKind]
        choices += ["arm", "rrr", "cylinder", "box", "sphere"]
        parent[key] = rng.choice(choices)
    elif op == "graft":  # a subtree of another task file (e.g. an rrr pose in an arm task)
        other = rng.choice(others)
        other_paths = _paths(other)
        if other_paths:
            parent[key] = copy.deepcopy(_get(other, rng.choice(other_paths)))
    else:  # nest
        parent[key] = nested(rng.choice((1, 2, 50, 500, 3000)), toml_value(node))


def mutate_structure(rng: random.Random, data: dict[str, Any], others: list[dict[str, Any]]) -> str:
    """A structure-aware mutant of ``data`` (1 to 4 mutations) as TOML text."""
    mutant = copy.deepcopy(data)
    for _ in range(rng.choice((1, 1, 1, 2, 2, 3, 4))):
        _mutate_once(rng, mutant, others)
    return to_toml(mutant)


def mutate_bytes(rng: random.Random, raw: bytes) -> bytes:
    """A byte-level mutant of ``raw`` (1 to 8 edits)."""
    data = bytearray(raw)
    for _ in range(rng.randint(1, 8)):
        op = rng.choice(("flip", "insert", "delete", "repeat", "truncate", "number"))
        at = rng.randrange(len(data) + 1)
        if op == "flip" and at < len(data):
            data[at] ^= 1 << rng.randrange(8)
        elif op == "insert":
            data[at:at] = rng.choice(
                (bytes([rng.randrange(256)]), b"\x00", b"\n", b"[", b"]", b'"', b"\xff", b"=")
            )
        elif op == "delete" and at < len(data):
            del data[at : at + rng.randint(1, 16)]
        elif op == "repeat" and at < len(data):
            chunk = data[at : at + rng.randint(1, 64)]
            data[at:at] = chunk * rng.randint(1, 8)
        elif op == "truncate":
            del data[at:]
        elif op == "number":  # a digit run made huge or tiny
            digits = [i for i, b in enumerate(data) if 0x30 <= b <= 0x39]
            if digits:
                i = rng.choice(digits)
                data[i : i + 1] = rng.choice((b"9" * 400, b"e308", b"e-320", b"0" * 30))
    return bytes(data)


def mutant(rng: random.Random, corpus: list[tuple[str, str, dict[str, Any]]]) -> bytes:
    """One mutant of a random seed file: structural (3 in 4) or byte-level."""
    stem, text, data = rng.choice(corpus)
    if rng.random() < 0.25:
        return mutate_bytes(rng, text.encode("utf-8"))
    others = [d for s, _, d in corpus if s != stem]
    return mutate_structure(rng, data, others).encode("utf-8")


# ------------------------------------------------------------------ oracle


@dataclass(frozen=True)
class Result:
    """What one mutant did.

    Attributes:
        outcome: Which of :data:`OUTCOMES`.
        detail: The error message or traceback (empty when it loaded and built).
        task: The loaded task, if it loaded.
    """

    outcome: Outcome
    detail: str = ""
    task: Task | None = None


def samples_are_finite(motion: Any) -> bool:
    """Whether a built motion's duration and its samples over it are all finite."""
    duration = float(motion.duration)
    if not math.isfinite(duration) or duration < 0.0:
        return False
    t = np.linspace(0.0, duration, SAMPLES)
    sample = motion.sample(t)
    return all(np.isfinite(np.asarray(a, dtype=float)).all() for a in sample)


def build_and_check(task: Task, kind: str | None = None) -> Result:
    """Build ``task``'s motion (of ``kind``; None: its own) and check its samples."""
    try:
        motion = get(task.robot).motion(
            task, task.trajectory if kind is None else TrajectoryKind(kind)
        )
        finite = samples_are_finite(motion)
    except LynxsimError as exc:
        return Result("builder_error", f"{type(exc).__name__}: {exc}", task)
    except Exception:
        return Result("untyped", traceback.format_exc(), task)
    if not finite:
        return Result("non_finite", f"non-finite samples building {kind or task.trajectory}", task)
    return Result("loaded", "", task)


def check(text: bytes, path: Path, *, all_kinds: bool = False) -> Result:
    """Write ``text`` to ``path``, load it, build its motion of its own type.

    With ``all_kinds``, build every trajectory type too; the first finding wins.
    """
    path.write_bytes(text)
    try:
        task = load_task(path)
    except TaskFileError as exc:
        if exc.path != str(path) or "\n" in str(exc):
            return Result("untyped", f"TaskFileError not naming the file in one line: {exc!r}")
        return Result("task_file_error", str(exc))
    except Exception:
        return Result("untyped", traceback.format_exc())
    result = build_and_check(task)
    if all_kinds and result.outcome not in FINDINGS:
        for kind in TrajectoryKind:
            other = build_and_check(task, kind.value)
            if other.outcome in FINDINGS:
                return other
    return result


# ------------------------------------------------------------------ campaign


def _first_line(detail: str) -> str:
    lines = [line for line in detail.strip().splitlines() if line.strip()]
    return lines[-1][:160] if lines else ""


def main(argv: Sequence[str] | None = None) -> int:
    """Run the campaign; 1 if any mutant broke the contract."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--mutants", type=int, default=10_000, help="how many (default 10000)")
    parser.add_argument("--seed", type=int, default=0, help="random seed (default 0)")
    parser.add_argument(
        "--save-dir", type=Path, default=None, help="folder for findings' mutants (default none)"
    )
    parser.add_argument(
        "--all-kinds",
        action="store_true",
        help="also build every trajectory type of each loaded task (findings only)",
    )
    args = parser.parse_args(argv)
    if args.mutants < 1:
        parser.error("--mutants must be at least 1")
    warnings.simplefilter("error", RuntimeWarning)  # as the test suite (pyproject.toml)
    rng = random.Random(args.seed)
    corpus = seeds()
    counts: Counter[str] = Counter()
    errors: Counter[str] = Counter()
    findings: Counter[str] = Counter()
    slowest = (0.0, -1)
    if args.save_dir is not None:
        args.save_dir.mkdir(parents=True, exist_ok=True)
    start = time.perf_counter()
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "mutant.toml"
        for i in range(args.mutants):
            text = mutant(rng, corpus)
            t0 = time.perf_counter()
            result = check(text, path, all_kinds=args.all_kinds)
            slowest = max(slowest, (time.perf_counter() - t0, i))
            counts[result.outcome] += 1
            if result.outcome == "builder_error":
                errors[result.detail.split(":")[0]] += 1
            if result.outcome in FINDINGS:
                signature = f"{result.outcome}: {_first_line(result.detail)}"
                findings[signature] += 1
                if args.save_dir is not None:
                    (args.save_dir / f"{result.outcome}_{i:06d}.toml").write_bytes(text)
                    (args.save_dir / f"{result.outcome}_{i:06d}.txt").write_text(result.detail)
    elapsed = time.perf_counter() - start
    print(f"mutants:                     {args.mutants} (seed {args.seed}, {elapsed:.1f} s)")
    print(f"loaded ok (finite motion):   {counts['loaded']}")
    print(f"TaskFileError:               {counts['task_file_error']}")
    print(f"other LynxsimError (build):  {counts['builder_error']}")
    for name, n in errors.most_common():
        print(f"    {n:6d}  {name}")
    print(f"untyped exceptions:          {counts['untyped']}")
    print(f"non-finite samples:          {counts['non_finite']}")
    for signature, n in findings.most_common():
        print(f"    {n:6d}  {signature}")
    print(f"slowest mutant:              #{slowest[1]} ({slowest[0]:.2f} s)")
    return 1 if any(counts[o] for o in FINDINGS) else 0


if __name__ == "__main__":
    sys.exit(main())
