"""Sweep files: which tasks, which trajectory types, and what varies between runs.

A sweep file is TOML in the report's units, each key naming its unit, read
with the task files' validating readers (:mod:`lynxsim.tasks`); every problem is
a :class:`SweepFileError` naming the file and the field. Example::

    name = "report_obstacle_map"     # optional; default the file's stem
    description = "Where may the cylinder stand?"
    tasks = ["../tasks/pick_and_place.toml", "../tasks/obstacle_avoidance.toml"]
                                     # task files, relative to this file (robots of the
                                     # table scene)
    types = ["free", "cubic", "quintic", "lspb", "line", "ruckig"]
                                     # or "waypoint" (every type but planned), "all"
    planner_seeds = [0]              # planned only: one plan per seed (default [0])
    rows_per_shard = 2048            # rows computed and saved together (default 2048)

    [obstacle]                       # optional: the obstacle that moves
    name = "cylinder"                # an obstacle of every task, by name
    radius_mm = [30.0, 40.0]         # optional: radii (cylinder, sphere); default its own

    [obstacle.grid]                  # its centre on a grid ...
    step_mm = 5.0
    x_mm = [-250.0, 450.0]           # optional: default the table's extent
    y_mm = [-500.0, 500.0]

    # [obstacle.random]              # ... or at random, uniform in a rectangle
    # count = 1000
    # seed = 0
    # x_mm = [-250.0, 450.0]         # optional: default the table's extent
    # y_mm = [-500.0, 500.0]

    [cube]                           # optional: the cube's start positions
    positions_mm = [[0.0, 300.0, 0.0], [20.0, 300.0, 0.0]]

Only the obstacle's centre x, y change; its height, z and shape stay the
task's. The number of runs (rows) is the product of tasks, types (planned: times
the seeds), cube positions, radii and obstacle positions, at most
:data:`lynxsim.bounds.MAX_CELLS`.
"""

from __future__ import annotations

import dataclasses
import hashlib
import math
import os
import tomllib
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt

from lynxsim.bounds import MAX_CELLS
from lynxsim.errors import TaskFileError
from lynxsim.registry import info
from lynxsim.scene import TABLE, Box, Obstacle
from lynxsim.tasks import Task, load_task
from lynxsim.tasks.reader import FieldReader as _Reader
from lynxsim.traj.kinds import WAYPOINT_KINDS, TrajectoryKind

__all__ = [
    "DEFAULT_ROWS_PER_SHARD",
    "ObstacleSweep",
    "SweepFileError",
    "SweepSpec",
    "load_sweep",
    "parse_sweep",
    "table_extent_mm",
]

FloatArray = npt.NDArray[np.float64]

DEFAULT_ROWS_PER_SHARD = 2048
"""Rows computed and saved together unless the sweep file says otherwise."""
_MAX_ROWS_PER_SHARD = 1_000_000
_MAX_SEED = 2**63 - 1
_MAX_LIST = 10_000
"""Longest list of tasks, seeds, radii or cube positions."""

_TOP_KEYS = (
    "name",
    "description",
    "tasks",
    "types",
    "planner_seeds",
    "rows_per_shard",
    "obstacle",
    "cube",
)
_OBSTACLE_KEYS = ("name", "radius_mm", "grid", "random")
_GRID_KEYS = ("step_mm", "x_mm", "y_mm")
_RANDOM_KEYS = ("count", "seed", "x_mm", "y_mm")
_CUBE_KEYS = ("positions_mm",)
_TYPE_GROUPS: dict[str, tuple[TrajectoryKind, ...]] = {
    "waypoint": WAYPOINT_KINDS,
    "all": tuple(TrajectoryKind),
}


class SweepFileError(TaskFileError):
    """A sweep file is not valid TOML or breaks the sweep schema (names file and field)."""


class _SweepReader(_Reader):
    """The task files' readers, failing with :class:`SweepFileError`."""

    def fail(self, field: str | None, problem: str) -> TaskFileError:
        return SweepFileError(self.path, field, problem)


def table_extent_mm() -> tuple[tuple[float, float], tuple[float, float]]:
    """The table top's x and y ranges [mm] (the default area of a sweep)."""
    (cx, cy), (sx, sy) = TABLE.center, TABLE.size
    return (
        (round((cx - sx / 2) * 1e3, 9), round((cx + sx / 2) * 1e3, 9)),
        (round((cy - sy / 2) * 1e3, 9), round((cy + sy / 2) * 1e3, 9)),
    )


@dataclass(frozen=True)
class ObstacleSweep:
    """Where the swept obstacle stands, and its sizes.

    Attributes:
        name: The obstacle's name in every task.
        x_mm: Centre x of each placement, (N,) [mm] (the file's unit, converted
            to metres as the task loader does: ``x_mm / 1000``).
        y_mm: Centre y of each placement, (N,) [mm].
        radii_mm: Radii [mm], or ``None`` for the task's own.
        grid_shape: ``(ny, nx)`` for a grid (row-major, x fastest), or None (random).
    """

    name: str
    x_mm: FloatArray
    y_mm: FloatArray
    radii_mm: tuple[float, ...] | None
    grid_shape: tuple[int, int] | None


@dataclass(frozen=True)
class SweepSpec:
    """A validated sweep (SI inside, except the placement values kept in mm, see above).

    Attributes:
        name: Sweep name (output file stems are made from it, never folders).
        description: Free text.
        tasks: The tasks (of robots that stand in the table scene).
        task_files: Their files, as given (resolved against the sweep file's folder).
        kinds: The trajectory types.
        planner_seeds: Seeds of the planned runs.
        obstacle: The swept obstacle, or None (nothing moves but the cube).
        cube_positions: Cube start positions, each (x, y, z) [m], or None for the tasks' own.
        rows_per_shard: Rows computed and saved together.
        source: The sweep file.
        digest: SHA-256 of the sweep file and its task files (shards of another
            digest are never reused).
    """

    name: str
    description: str
    tasks: tuple[Task, ...]
    task_files: tuple[Path, ...]
    kinds: tuple[TrajectoryKind, ...]
    planner_seeds: tuple[int, ...]
    obstacle: ObstacleSweep | None
    cube_positions: tuple[tuple[float, float, float], ...] | None
    rows_per_shard: int
    source: Path | None
    digest: str

    @property
    def placements(self) -> int:
        """Obstacle placements per (task, type, seed, cube, radius): 1 without an obstacle."""
        return 1 if self.obstacle is None else len(self.obstacle.x_mm)


def _mm_range(
    r: _Reader, raw: Mapping[str, Any], key: str, field: str, default: tuple[float, float]
) -> tuple[float, float]:
    if key not in raw:
        return default
    value = raw[key]
    if not isinstance(value, list) or len(value) != 2:
        raise r.fail(
            f"{field}.{key}", f"must be a list [low, high] of 2 numbers, got {value!r}"[:200]
        )
    low, high = (r.coordinate_mm(v, f"{field}.{key}[{i}]") for i, v in enumerate(value))
    if low > high:
        raise r.fail(f"{field}.{key}", f"low {low:g} mm is above high {high:g} mm")
    return low, high


def _count(r: _Reader, value: object, field: str, low: int, high: int) -> int:
    if isinstance(value, bool) or not isinstance(value, int):
        raise r.fail(field, f"must be an integer, got {value!r}"[:200])
    if not low <= value <= high:
        shown = f"{value:,}" if len(str(abs(value))) <= 30 else "a huge integer"
        raise r.fail(field, f"must be between {low:,} and {high:,}, got {shown}")
    return value


def _list(r: _Reader, value: object, field: str) -> list[Any]:
    if not isinstance(value, list) or not value:
        raise r.fail(field, f"must be a non-empty list, got {value!r}"[:200])
    if len(value) > _MAX_LIST:
        raise r.fail(field, f"must have at most {_MAX_LIST:,} entries, got {len(value):,}")
    return value


def _grid(r: _Reader, raw: Mapping[str, Any]) -> tuple[FloatArray, FloatArray, tuple[int, int]]:
    field = "obstacle.grid"
    grid = r.table(raw, field, _GRID_KEYS)
    step = r.size_mm(r.required(grid, "step_mm", f"{field}.step_mm"), f"{field}.step_mm")
    x_range, y_range = table_extent_mm()
    x0, x1 = _mm_range(r, grid, "x_mm", field, x_range)
    y0, y1 = _mm_range(r, grid, "y_mm", field, y_range)
    nx, ny = (math.floor((hi - lo) / step + 1e-9) + 1 for lo, hi in ((x0, x1), (y0, y1)))
    if nx * ny > MAX_CELLS:
        raise r.fail(
            f"{field}.step_mm",
            f"{nx:,} x {ny:,} = {nx * ny:,} placements; at most {MAX_CELLS:,} (a larger step)",
        )
    xs = x0 + step * np.arange(nx)
    ys = y0 + step * np.arange(ny)
    gx, gy = np.meshgrid(xs, ys)  # (ny, nx): x fastest
    return gx.reshape(-1), gy.reshape(-1), (ny, nx)


def _random(r: _Reader, raw: Mapping[str, Any]) -> tuple[FloatArray, FloatArray]:
    field = "obstacle.random"
    table = r.table(raw, field, _RANDOM_KEYS)
    count = _count(r, r.required(table, "count", f"{field}.count"), f"{field}.count", 1, MAX_CELLS)
    seed = _count(r, table.get("seed", 0), f"{field}.seed", 0, _MAX_SEED)
    x_range, y_range = table_extent_mm()
    x0, x1 = _mm_range(r, table, "x_mm", field, x_range)
    y0, y1 = _mm_range(r, table, "y_mm", field, y_range)
    rng = np.random.default_rng(seed)
    return rng.uniform(x0, x1, count), rng.uniform(y0, y1, count)


def _obstacle(r: _Reader, raw: object, tasks: tuple[Task, ...]) -> ObstacleSweep:
    table = r.table(raw, "obstacle", _OBSTACLE_KEYS)
    name = r.name(r.required(table, "name", "obstacle.name"), "obstacle.name")
    swept: list[Obstacle] = []
    for i, task in enumerate(tasks):
        found = [o for o in task.scene.obstacles if o.name == name]
        if not found:
            names = ", ".join(o.name for o in task.scene.obstacles) or "none"
            raise r.fail(
                "obstacle.name",
                f"task {task.name!r} (tasks[{i}]) has no obstacle {name!r}; its obstacles: {names}",
            )
        swept.append(found[0])
    radii: tuple[float, ...] | None = None
    if "radius_mm" in table:
        if any(isinstance(o, Box) for o in swept):
            raise r.fail("obstacle.radius_mm", f"obstacle {name!r} is a box, which has no radius")
        values = _list(r, table["radius_mm"], "obstacle.radius_mm")
        radii = tuple(r.size_mm(v, f"obstacle.radius_mm[{i}]") for i, v in enumerate(values))
        for i, radius in enumerate(radii):
            field = f"obstacle.radius_mm[{i}]"
            if f"{radius:g}" in (f"{v:g}" for v in radii[:i]):
                raise r.fail(field, f"repeats {radius:g} mm (each radius names its own maps)")
            for task, o in zip(tasks, swept, strict=True):
                assert not isinstance(o, Box)  # refused above
                low = dataclasses.replace(o, radius=radius / 1000.0).bottom_z
                if low < task.scene.table.top_z:
                    raise r.fail(
                        field,
                        f"a {o.shape} of radius {radius:g} mm at {o.name!r}'s height would reach "
                        f"into the table of task {task.name!r} (its bottom at z = "
                        f"{low * 1e3:g} mm, the table top at {task.scene.table.top_z * 1e3:g} mm)",
                    )
    modes = [k for k in ("grid", "random") if k in table]
    if len(modes) != 1:
        raise r.fail("obstacle", "needs exactly one of [obstacle.grid] or [obstacle.random]")
    if modes[0] == "grid":
        x, y, shape = _grid(r, table["grid"])
        return ObstacleSweep(name, x, y, radii, shape)
    x, y = _random(r, table["random"])
    return ObstacleSweep(name, x, y, radii, None)


def _kinds(r: _Reader, raw: object) -> tuple[TrajectoryKind, ...]:
    valid = [k.value for k in TrajectoryKind]
    if isinstance(raw, str):
        if raw not in _TYPE_GROUPS:
            raise r.fail(
                "types", f"unknown group {raw!r}; expected a list of types or one of: waypoint, all"
            )
        return _TYPE_GROUPS[raw]
    kinds: list[TrajectoryKind] = []
    for i, item in enumerate(_list(r, raw, "types")):
        name = r.string(item, f"types[{i}]")
        if name not in valid:
            raise r.fail(
                f"types[{i}]", f"unknown type {name[:60]!r}; expected one of: {', '.join(valid)}"
            )
        if TrajectoryKind(name) in kinds:
            raise r.fail(f"types[{i}]", f"type {name!r} listed twice")
        kinds.append(TrajectoryKind(name))
    return tuple(kinds)


def _tasks(r: _Reader, raw: object, folder: Path) -> tuple[tuple[Task, ...], tuple[Path, ...]]:
    tasks: list[Task] = []
    files: list[Path] = []
    for i, item in enumerate(_list(r, raw, "tasks")):
        field = f"tasks[{i}]"
        text = r.text(item, field, 4096, empty=False)
        path = Path(text) if Path(text).is_absolute() else folder / text
        try:
            task = load_task(path)
        except TaskFileError as exc:
            raise r.fail(field, str(exc)) from None
        except OSError as exc:
            raise r.fail(field, f"cannot read {path}: {exc.strerror or exc}") from None
        if not info(task.robot).scene:  # obstacles are swept through the table scene
            raise r.fail(
                field,
                f"{path} is a task of robot {task.robot!r}, which stands in no table scene; "
                "sweeps move obstacles of the table scene",
            )
        if any(t.name == task.name for t in tasks):
            raise r.fail(field, f"two tasks are named {task.name!r}; names must be unique")
        tasks.append(task)
        files.append(path)
    return tuple(tasks), tuple(files)


def _cube(
    r: _Reader, raw: object, tasks: tuple[Task, ...]
) -> tuple[tuple[float, float, float], ...]:
    table = r.table(raw, "cube", _CUBE_KEYS)
    field = "cube.positions_mm"
    values = _list(r, r.required(table, "positions_mm", field), field)
    if any(t.scene.cube is None for t in tasks):
        raise r.fail("cube", "a task has no cube to move")
    out = []
    for i, item in enumerate(values):
        x, y, z = r.position_mm(item, f"{field}[{i}]")
        position = (x / 1000.0, y / 1000.0, z / 1000.0)
        for task in tasks:
            assert task.scene.cube is not None  # checked above
            low = dataclasses.replace(task.scene.cube, position=position).bottom_z
            if low < task.scene.table.top_z:
                raise r.fail(
                    f"{field}[{i}]",
                    f"task {task.name!r}'s cube centred at z = {z:g} mm would reach into the "
                    f"table (its bottom at z = {low * 1e3:g} mm, the table top at "
                    f"{task.scene.table.top_z * 1e3:g} mm)",
                )
        out.append(position)
    return tuple(out)


def _digest(raw: bytes, task_files: tuple[Path, ...]) -> str:
    h = hashlib.sha256(raw)
    for path in task_files:
        h.update(b"\0task\0")
        h.update(path.read_bytes())
    return h.hexdigest()


def parse_sweep(data: Mapping[str, Any], path: str, raw: bytes = b"") -> SweepSpec:
    """Validate a parsed sweep file (see the module docstring).

    Args:
        data: The TOML document.
        path: The file, for messages and to resolve task files.
        raw: The file's bytes (for the digest).

    Raises:
        SweepFileError: Names the file and the field.
    """
    r = _SweepReader(path)
    top = r.table(data, "", _TOP_KEYS)
    stem = Path(path).stem
    name = r.name(top.get("name", stem or "sweep"), "name")
    description = r.text(top.get("description", ""), "description", 1000, empty=True)
    tasks, files = _tasks(r, r.required(top, "tasks", "tasks"), Path(path).parent)
    kinds = _kinds(r, r.required(top, "types", "types"))
    seeds_raw = _list(r, top.get("planner_seeds", [0]), "planner_seeds")
    seeds = tuple(
        _count(r, v, f"planner_seeds[{i}]", 0, _MAX_SEED) for i, v in enumerate(seeds_raw)
    )
    if len(set(seeds)) != len(seeds):
        raise r.fail("planner_seeds", "a seed is listed twice")
    per_shard = _count(
        r,
        top.get("rows_per_shard", DEFAULT_ROWS_PER_SHARD),
        "rows_per_shard",
        1,
        _MAX_ROWS_PER_SHARD,
    )
    obstacle = _obstacle(r, top["obstacle"], tasks) if "obstacle" in top else None
    cubes = _cube(r, top["cube"], tasks) if "cube" in top else None
    runs = len(tasks) * sum(len(seeds) if k is TrajectoryKind.PLANNED else 1 for k in kinds)
    rows = runs * (1 if cubes is None else len(cubes))
    if obstacle is not None:
        rows *= len(obstacle.x_mm) * (1 if obstacle.radii_mm is None else len(obstacle.radii_mm))
    if rows > MAX_CELLS:
        raise r.fail("", f"{rows:,} runs; a sweep has at most {MAX_CELLS:,}")
    return SweepSpec(
        name=name,
        description=description,
        tasks=tasks,
        task_files=files,
        kinds=kinds,
        planner_seeds=seeds,
        obstacle=obstacle,
        cube_positions=cubes,
        rows_per_shard=per_shard,
        source=Path(path),
        digest=_digest(raw, files),
    )


def load_sweep(path: str | os.PathLike[str]) -> SweepSpec:
    """Read and validate a sweep file and the task files it names.

    Raises:
        SweepFileError: The file is not UTF-8 TOML or breaks the schema (names
            the file and the field; a bad task file is named too).
        OSError: The sweep file cannot be read.
    """
    path = Path(path)
    if path.exists() and not path.is_file():
        raise SweepFileError(str(path), None, "not a regular file")
    raw = path.read_bytes()
    try:
        data = tomllib.loads(raw.decode("utf-8"))
    except UnicodeDecodeError as exc:
        raise SweepFileError(str(path), None, f"not UTF-8 text ({exc.reason})") from None
    except (tomllib.TOMLDecodeError, ValueError, RecursionError) as exc:
        raise SweepFileError(str(path), None, f"not valid TOML: {exc}") from None
    return parse_sweep(data, str(path), raw)
