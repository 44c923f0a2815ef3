"""Fuzz campaign of the surfaces added since the first one: sweeps, shards, datasets, planner, envs.

Five targets, inputs drawn by a seeded :class:`random.Random`:

* ``sweep``: mutants of the shipped sweep files (the task-file campaign's
  mutators, :mod:`tools.fuzz_tasks`), loaded with :func:`lynxsim.sweep.spec.load_sweep`;
* ``shard``: a saved shard truncated, bit-flipped, overwritten, swapped for
  another shard's file or with one value edited, read with
  :func:`lynxsim.sweep.shard_files.read_shard` (it must give back the exact rows
  or raise);
* ``dataset``: :func:`lynxsim.datasets.write_dataset` with odd arguments (one
  episode at most when they are valid); whatever it raises, nothing may be
  left under its output folder;
* ``planner``: :class:`lynxsim.plan.request.PlanRequest` with odd fields;
* ``env``: ``gym.make`` of a lynxsim env with one odd option, then ``reset``
  and one ``step``.

The contract: a valid result, or a :class:`~lynxsim.errors.LynxsimError`.
Anything else (an untyped exception, a partial file, rows that differ) is a
finding: the script prints the counts and one line per finding, and exits 1::

    python -m tools.fuzz_surfaces --inputs 2000 --seed 0

``tests/fuzz/test_fuzz_surfaces.py`` drives the same targets with hypothesis.
"""

from __future__ import annotations

import argparse
import io
import math
import os
import random
import shutil
import sys
import tempfile
import time
import tomllib
import traceback
import warnings
from collections import Counter
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from lynxsim.errors import LynxsimError
from tools import fuzz_tasks

ROOT = Path(__file__).resolve().parents[1]

ODD: tuple[Any, ...] = (
    None, "", "x", "nan", -1, 0, 1, 2, 10**400, -(10**40), 1e300, -1e300,
    math.nan, math.inf, -math.inf, 5e-324, True, False, 2.5, -0.0, [], [1, 2], {"a": 1},
    (1,), 1 + 2j, np.float64(3.0), np.int64(7), np.array([1.0, 2.0]), b"bytes",
)  # fmt: skip
"""Odd values any argument may get."""

Outcome = str
"""``"ok"``, ``"typed"``, ``"untyped"`` or ``"partial"``."""


def _odd(rng: random.Random) -> Any:
    return rng.choice(ODD)


# ------------------------------------------------------------------ targets


def _sweep_corpus() -> list[tuple[str, str, dict[str, Any]]]:
    out = []
    for path in sorted((ROOT / "sweeps").glob("*.toml")):
        data = tomllib.loads(path.read_text())
        data["tasks"] = [str((path.parent / t).resolve()) for t in data["tasks"]]
        data["obstacle"]["grid"]["step_mm"] = 50.0  # keep each load quick
        out.append((path.stem, fuzz_tasks.to_toml(data), data))
    return out


def sweep_input(rng: random.Random, work: Path) -> Outcome:
    """A sweep-file mutant, loaded."""
    from lynxsim.sweep.spec import SweepFileError, load_sweep

    path = work / "mutant.toml"
    path.write_bytes(fuzz_tasks.mutant(rng, _SWEEPS))
    try:
        load_sweep(path)
    except SweepFileError as exc:
        if "\n" in str(exc) or str(path) not in str(exc):
            raise AssertionError(
                f"SweepFileError not naming the file in one line: {exc!r}"
            ) from None
        return "typed"
    return "ok"


def _shard_table(rows: int, seed: int) -> dict[str, np.ndarray]:
    from lynxsim.sweep.table import COLUMNS, empty

    rng = np.random.default_rng(seed)
    table = empty(rows)
    for name, kind in COLUMNS.items():
        if kind == "f8":
            table[name] = rng.uniform(-1.0, 1.0, rows)
        elif kind == "?":
            table[name] = rng.random(rows) < 0.5
        elif kind in ("i8", "i1"):
            table[name] = rng.integers(-1, 2, rows).astype(kind)
    table["task"][:] = "pick_and_place"
    table["verdict"][:] = [("clear", "collided")[int(b)] for b in table["collided"]]
    return table


def _damaged(rng: random.Random, shards: list[bytes]) -> bytes:
    data = bytearray(shards[0])
    op = rng.randrange(5)
    if op == 0:
        return bytes(data[: rng.randrange(len(data))])
    if op == 1:
        for _ in range(rng.randint(1, 4)):
            data[rng.randrange(len(data))] ^= 1 << rng.randrange(8)
        return bytes(data)
    if op == 2:
        start = rng.randrange(len(data))
        stop = min(len(data), start + rng.randint(1, 64))
        data[start:stop] = bytes([rng.randrange(256)]) * (stop - start)
        return bytes(data)
    if op == 3:
        return shards[rng.randrange(1, len(shards))]
    with np.load(io.BytesIO(shards[0])) as npz:
        arrays = {name: npz[name] for name in npz.files}
    name = rng.choice([n for n in arrays if not n.startswith("_")])
    column = arrays[name].copy()
    i = rng.randrange(len(column))
    if column.dtype.kind == "U":
        column = column.astype(object)
        column[i] = str(column[i]) + "x"
        column = column.astype(str)
    elif column.dtype.kind == "b":
        column[i] = not column[i]
    else:
        column[i] = column[i] + 1
    arrays[name] = column
    buffer = io.BytesIO()
    np.savez(buffer, **arrays)  # type: ignore[arg-type]
    return buffer.getvalue()


def shard_input(rng: random.Random, work: Path) -> Outcome:
    """A damaged shard, read: the exact rows back or a ShardFileError."""
    from lynxsim.sweep.shard_files import ShardFileError, read_shard
    from lynxsim.sweep.table import COLUMNS, finish

    path = work / "shard.npz"
    path.write_bytes(_damaged(rng, _SHARDS))
    try:
        rows = read_shard(path, sweep=_DIGEST, index=0, rows=10)
    except ShardFileError as exc:
        if "\n" in str(exc):
            raise AssertionError(f"ShardFileError of several lines: {exc!r}") from None
        return "typed"
    clean = finish(_TABLES[0])
    for name in COLUMNS:
        kind = clean[name].dtype.kind
        if not np.array_equal(rows[name], clean[name], equal_nan=kind == "f"):
            raise AssertionError(f"a damaged shard was read with column {name} changed")
    return "ok"


def dataset_input(rng: random.Random, work: Path) -> Outcome:
    """``write_dataset`` with odd arguments; nothing left behind on an error."""
    from lynxsim.datasets import write_dataset

    out = work / "datasets"
    kwargs: dict[str, Any] = {}
    episodes: Any = 1
    if rng.random() < 0.8:
        key = rng.choice(("episodes", "env_id", "noise", "seed", "format", "dataset_id",
                          "images", "image_size"))  # fmt: skip
        value = _odd(rng) if rng.random() < 0.7 else rng.choice(
            ("../x", "a/b/c", "lynxsim/x-v0/y", "minari", "npz", "front", ("front",), 16, 513, 0)
        )  # fmt: skip
        if key == "episodes":
            episodes = value if not (isinstance(value, int) and value > 1) else 1
        else:
            kwargs[key] = value
    try:
        summary = write_dataset(out, episodes, **kwargs)
    except LynxsimError:
        left = [p for p in out.rglob("*")] if out.exists() else []
        if left:
            raise AssertionError(f"partial output after a typed error: {left[:3]}") from None
        return "typed"
    if not summary.path.is_dir():
        raise AssertionError("write_dataset returned a folder that does not exist")
    shutil.rmtree(out)
    return "ok"


def planner_input(rng: random.Random, work: Path) -> Outcome:
    """A PlanRequest with one odd field."""
    from lynxsim.arm.geometry import LYNX_ARM
    from lynxsim.arm.motion.space import ARM_LIMITS, joint_bounds
    from lynxsim.plan.request import PlanRequest

    fields: dict[str, Any] = {
        "start": np.zeros(5),
        "goal_sets": (np.full((1, 5), 0.3),),
        "grasped": (False,),
        "labels": ("move",),
        "pose_names": ("P1", "P2"),
        "bounds": joint_bounds(LYNX_ARM),
        "limits": ARM_LIMITS,
        "lipschitz": 0.5,
    }
    key = rng.choice(list(fields))
    fields[key] = _odd(rng) if rng.random() < 0.8 else rng.choice(
        ((np.full((0, 5), 0.1),), (np.full((1, 4), 0.1),), ("a", "b"), (True, False), ())
    )  # fmt: skip
    try:
        PlanRequest(**fields)
    except LynxsimError:
        return "typed"
    return "ok"


ENV_OPTIONS: dict[str, tuple[Any, ...]] = {
    "control": ("tool", "joint", "tool_roll", "x"),
    "target_fallback": ("hold", "nearest", "y"),
    "reward_type": ("dense", "sparse", "z"),
    "distance_threshold": (0.01, 0.0, -1.0, 10.0),
    "random_obstacles": (1, (1, 3), (3, 1), -1, 100),
    "collision_penalty": (1.0, -1.0),
    "terminate_on_collision": (True, 1),
    "collision_check": ("physics_step", "sometimes"),
    "control_dt": (0.02, 0.001, 0.0031, 1e9),
    "position_step": (0.01, 0.0, 100.0),
    "pitch_step": (0.05, -1.0),
    "roll_step": (0.05, 1e9),
    "joint_step": (0.01, -0.5),
    "width": (64, 0, 100_000),
    "height": (48, -1),
    "camera": ("front", "nowhere"),
    "render_quality": ("lean", "ugly"),
    "pixels": ("front", ("front", "front"), ("nowhere",)),
    "pixel_width": (16, 0, 10_000),
    "pixel_height": (16, 3),
    "randomize": ("all",),
}
"""Options of the envs, each with valid and invalid values (and any odd one)."""


def env_input(rng: random.Random, work: Path) -> Outcome:
    """``gym.make`` with one odd option, then ``reset`` and one ``step``."""
    import gymnasium as gym

    import lynxsim.envs  # noqa: F401  (registers the envs)
    from lynxsim.envs.registration import ENV_IDS

    key = rng.choice(list(ENV_OPTIONS))
    value = rng.choice(ENV_OPTIONS[key]) if rng.random() < 0.6 else _odd(rng)
    env_id = rng.choice([e for e in ENV_IDS if not e.endswith("-v0")])
    try:
        env = gym.make(env_id, **{key: value})
    except LynxsimError:
        return "typed"
    try:
        env.reset(seed=rng.randrange(1000))
        env.step(env.action_space.sample())
    except LynxsimError:
        return "typed"
    finally:
        env.close()
    return "ok"


TARGETS: dict[str, Callable[[random.Random, Path], Outcome]] = {
    "sweep": sweep_input,
    "shard": shard_input,
    "dataset": dataset_input,
    "planner": planner_input,
    "env": env_input,
}
"""Each target and the share of the inputs it gets (datasets and envs cost most)."""

WEIGHTS = {"sweep": 4, "shard": 4, "dataset": 1, "planner": 4, "env": 1}

_SWEEPS: list[tuple[str, str, dict[str, Any]]] = []
_TABLES: list[dict[str, np.ndarray]] = []
_SHARDS: list[bytes] = []
_DIGEST = "d" * 64


def prepare(work: Path) -> None:
    """The seeds: the sweep corpus and eight saved shards (shard 0 is the one damaged)."""
    from lynxsim.sweep.shard_files import write_shard

    _SWEEPS[:] = _sweep_corpus()
    _TABLES[:] = [_shard_table(10, seed) for seed in range(8)]
    shards = []
    for i, table in enumerate(_TABLES):
        path = work / f"seed_{i}.npz"
        write_shard(path, table, sweep=_DIGEST, index=0 if i == 0 else i)
        shards.append(path.read_bytes())
    _SHARDS[:] = shards


def run_one(target: str, rng: random.Random, work: Path) -> tuple[Outcome, str]:
    """One input of ``target``: its outcome and, for a finding, a line saying what happened."""
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        try:
            return TARGETS[target](rng, work), ""
        except AssertionError as exc:
            return "partial" if "partial" in str(exc) else "untyped", str(exc)[:200]
        except Exception as exc:
            last = traceback.format_exc().strip().splitlines()[-1]
            return "untyped", f"{type(exc).__name__}: {last[:200]}"


def main(argv: Sequence[str] | None = None) -> int:
    """Run the campaign; exit 1 on any finding."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--inputs", type=int, default=2000)
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args(argv)
    os.environ.setdefault("MUJOCO_GL", "egl")
    rng = random.Random(args.seed)
    counts: dict[str, Counter[str]] = {t: Counter() for t in TARGETS}
    findings: list[str] = []
    names, weights = list(WEIGHTS), list(WEIGHTS.values())
    start_wall, start_cpu = time.perf_counter(), time.process_time()
    with tempfile.TemporaryDirectory() as tmp:
        work = Path(tmp)
        prepare(work)
        for i in range(args.inputs):
            target = rng.choices(names, weights)[0]
            outcome, detail = run_one(target, random.Random(rng.getrandbits(64)), work)
            counts[target][outcome] += 1
            if detail:
                findings.append(f"input {i} ({target}, {outcome}): {detail}")
    wall, cpu = time.perf_counter() - start_wall, time.process_time() - start_cpu
    for target, c in counts.items():
        print(
            f"{target:8s} inputs {sum(c.values()):5d}  ok {c['ok']:5d}  typed {c['typed']:5d}  "
            f"untyped {c['untyped']}  partial {c['partial']}"
        )
    print(f"{args.inputs} inputs in {wall:.0f} s wall, {cpu:.0f} s CPU; findings: {len(findings)}")
    for line in findings:
        print(line)
    return 1 if findings else 0


if __name__ == "__main__":
    sys.exit(main())
