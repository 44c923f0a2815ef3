"""Running a sweep: its rows cut into shards, each computed anywhere, saved as it finishes.

The rows of a sweep are grouped: one group per (task, type, planner seed, cube
position, radius), each with one row per obstacle placement. A shard is a run
of consecutive rows of one group; :func:`compute_shard` computes it from the
sweep alone (pure and deterministic: the same shard gives the same arrays, bit
for bit, in any process on the same build), so a backend may compute shards in
this process, in a process pool (:class:`LocalBackend`) or as Ray tasks
(:class:`lynxsim.sweep.ray_backend.RayBackend`).

The tasks may be of any robot that stands in the table scene; each shard asks
the task's robot (:func:`lynxsim.robots.get`) for its motions and its
simulation side (:func:`lynxsim.robots.simulation`). For waypoint types, a
shard plays its group's run once without the swept obstacle and judges its
placements on the recorded states (the adapter's
:meth:`~lynxsim.sim.adapter.SimAdapter.record`, :mod:`lynxsim.sim.sweep_judge`); planned runs,
whose path depends on where the obstacle stands, are planned and played row by
row, and a sweep without an obstacle plays each row.

:func:`run_sweep` saves each finished shard at once (atomically, under a name
that includes the digest of the sweep file and its tasks, each file carrying
that digest, its index and a checksum: :mod:`lynxsim.sweep.shard_files`), skips
shards already saved and verified, and assembles the table from the shards in order.
"""

from __future__ import annotations

import dataclasses
import multiprocessing
import os
from collections.abc import Callable, Iterable, Iterator
from concurrent.futures import FIRST_COMPLETED, Future, ProcessPoolExecutor, wait
from dataclasses import dataclass
from pathlib import Path
from typing import Protocol

from lynxsim.bounds import MAX_JOBS
from lynxsim.errors import InvalidInputError, LynxsimError
from lynxsim.fileio import file_stem
from lynxsim.inputs import count
from lynxsim.processes import pool_initializer
from lynxsim.robots import get, motion, plan, restore, rows, simulation
from lynxsim.scene import Box, Obstacle, Scene
from lynxsim.sim.report import RunReport
from lynxsim.sim.sweep_judge import PlacementJudge
from lynxsim.sweep.shard_files import Notice, saved_shard, shard_folder, shard_path, write_shard
from lynxsim.sweep.spec import SweepSpec
from lynxsim.sweep.table import Table, concat, empty, write_npz
from lynxsim.tasks import Task
from lynxsim.traj import TrajectoryKind
from lynxsim.traj.motion import Motion
from lynxsim.verdicts import Verdict

__all__ = [
    "Backend",
    "Group",
    "LocalBackend",
    "Shard",
    "ShardHook",
    "SweepOutcome",
    "compute_shard",
    "groups",
    "run_sweep",
    "shards",
]

ShardHook = Callable[[int], None]
"""Called inside the worker with the shard's index, midway through computing it."""


@dataclass(frozen=True)
class Group:
    """Rows sharing a task, type, planner seed, cube position and radius.

    Attributes:
        index: Its place among the groups.
        task: Index of the task in the sweep.
        kind: The trajectory type.
        seed: The planner's seed (planned), else -1.
        cube: Index of the cube position, or -1 for the task's own.
        radius: Index of the radius, or -1 for the obstacle's own.
        first_row: Its first row in the table.
        rows: Its number of rows (the placements; 1 without an obstacle).
    """

    index: int
    task: int
    kind: TrajectoryKind
    seed: int
    cube: int
    radius: int
    first_row: int
    rows: int


@dataclass(frozen=True)
class Shard:
    """Consecutive rows of one group.

    Attributes:
        index: Its place among the shards (its file name).
        group: The group.
        start: First placement (row within the group).
        stop: One past the last.
    """

    index: int
    group: Group
    start: int
    stop: int

    @property
    def rows(self) -> int:
        """Its number of rows."""
        return self.stop - self.start


def groups(spec: SweepSpec) -> list[Group]:
    """The groups of a sweep, in table order."""
    out: list[Group] = []
    cubes = range(len(spec.cube_positions)) if spec.cube_positions else [-1]
    radii = (
        range(len(spec.obstacle.radii_mm))
        if spec.obstacle is not None and spec.obstacle.radii_mm
        else [-1]
    )
    row = 0
    for t in range(len(spec.tasks)):
        for kind in spec.kinds:
            seeds = spec.planner_seeds if kind is TrajectoryKind.PLANNED else (-1,)
            for seed in seeds:
                for cube in cubes:
                    for radius in radii:
                        out.append(
                            Group(len(out), t, kind, seed, cube, radius, row, spec.placements)
                        )
                        row += spec.placements
    return out


def shards(spec: SweepSpec) -> list[Shard]:
    """The shards of a sweep, in table order (planned groups: a shard per 64 rows at most)."""
    out: list[Shard] = []
    for group in groups(spec):
        size = spec.rows_per_shard
        if group.kind is TrajectoryKind.PLANNED:
            size = min(size, 64)  # a plan and a physics run per row
        for start in range(0, group.rows, size):
            out.append(Shard(len(out), group, start, min(start + size, group.rows)))
    return out


def _variant(spec: SweepSpec, group: Group) -> tuple[Task, Obstacle | None]:
    """The group's task (its cube moved) and its swept obstacle (its radius set).

    Raises:
        InvalidInputError: An obstacle of the task encloses the moved cube's start.
    """
    task = spec.tasks[group.task]
    scene = task.scene
    if group.cube >= 0 and spec.cube_positions is not None and scene.cube is not None:
        cube = dataclasses.replace(scene.cube, position=spec.cube_positions[group.cube])
        scene = Scene(scene.obstacles, scene.table, cube)
    obstacle: Obstacle | None = None
    if spec.obstacle is not None:
        obstacle = scene.obstacle(spec.obstacle.name)
        radii = spec.obstacle.radii_mm
        if group.radius >= 0 and radii is not None and not isinstance(obstacle, Box):
            obstacle = dataclasses.replace(obstacle, radius=radii[group.radius] / 1000.0)
    return dataclasses.replace(task, scene=scene), obstacle


def _fill_inputs(
    table: Table, spec: SweepSpec, shard: Shard, task: Task, obstacle: Obstacle | None
) -> None:
    g = shard.group
    table["task"][:] = task.name
    table["type"][:] = g.kind.value
    table["planner_seed"][:] = g.seed
    if task.scene.cube is not None:
        table["cube_x_m"][:], table["cube_y_m"][:], table["cube_z_m"][:] = task.scene.cube.position
    if spec.obstacle is not None and obstacle is not None:
        table["obstacle_x_m"][:] = spec.obstacle.x_mm[shard.start : shard.stop] / 1000.0
        table["obstacle_y_m"][:] = spec.obstacle.y_mm[shard.start : shard.stop] / 1000.0
        if not isinstance(obstacle, Box):
            table["obstacle_radius_m"][:] = obstacle.radius


def _report_row(table: Table, i: int, report: RunReport, method: str) -> None:
    """Row ``i`` from a run's own report (everything as ``lynxsim play`` reports it)."""
    verdict = report.obstacle
    table["verdict"][i] = (Verdict.COLLIDED if report.collided else Verdict.CLEAR).label
    table["collided"][i] = report.collided
    if verdict is not None and verdict.first_time_s is not None:
        table["first_contact_s"][i] = verdict.first_time_s
        table["first_obstacle"][i] = verdict.first_obstacle or ""
    _tracking(table, i, report)
    if report.min_clearance_m is not None:
        table["min_clearance_m"][i] = report.min_clearance_m
        table["min_clearance_time_s"][i] = report.min_clearance_time_s or 0.0
    table["method"][i] = method


def _tracking(table: Table, i: int, report: RunReport) -> None:
    table["tool_max_error_m"][i] = report.tool_max_error_m
    table["tool_rms_error_m"][i] = report.tool_rms_error_m
    table["tool_final_error_m"][i] = report.tool_final_error_m
    table["max_torque_ratio"][i] = max(report.max_torque_ratio, default=0.0)
    table["healthy"][i] = 1 if report.healthy else 0


def _placed(task: Task, obstacle: Obstacle, x_m: float, y_m: float) -> Task | None:
    """The task with the obstacle moved there, or None where no scene allows it."""
    moved = dataclasses.replace(obstacle, position=(x_m, y_m, obstacle.position[2]))
    others = tuple(moved if o.name == obstacle.name else o for o in task.scene.obstacles)
    try:
        scene = Scene(others, task.scene.table, task.scene.cube)
    except InvalidInputError:
        return None
    return dataclasses.replace(task, scene=scene)


def _motion(task: Task, kind: TrajectoryKind, seed: int) -> Motion:
    robot = get(task.robot)
    if kind is TrajectoryKind.PLANNED:
        return plan(robot, task, seed=seed).trajectory
    return motion(robot, task, kind)


def _physics_rows(
    table: Table, spec: SweepSpec, shard: Shard, task: Task, obstacle: Obstacle | None
) -> None:
    """Each row planned (if planned) and played on its own."""
    adapter = simulation(get(task.robot))
    kind, seed = shard.group.kind, shard.group.seed
    for i in range(shard.rows):
        placed: Task | None = task
        if obstacle is not None and spec.obstacle is not None:
            j = shard.start + i
            placed = _placed(
                task, obstacle, spec.obstacle.x_mm[j] / 1000.0, spec.obstacle.y_mm[j] / 1000.0
            )
        if placed is None:
            table["verdict"][i], table["method"][i] = Verdict.INVALID.label, "none"
            continue
        try:
            report = adapter.play(placed, _motion(placed, kind, seed)).report
        except LynxsimError:
            table["verdict"][i], table["method"][i] = Verdict.NO_MOTION.label, "none"
            continue
        _report_row(table, i, report, "physics")


def _recorded_rows(
    table: Table,
    spec: SweepSpec,
    shard: Shard,
    task: Task,
    obstacle: Obstacle,
    hook: ShardHook | None,
) -> None:
    """The group's run recorded without the obstacle; each placement judged on it."""
    if spec.obstacle is None:
        raise InvalidInputError("a sweep without an obstacle has no placements to judge")
    adapter = simulation(get(task.robot))
    others = tuple(o for o in task.scene.obstacles if o.name != obstacle.name)
    try:
        base = Scene(others, task.scene.table, task.scene.cube)
        run = adapter.record(task, _motion(task, shard.group.kind, -1), base)
    except LynxsimError:
        table["verdict"][:], table["method"][:] = Verdict.NO_MOTION.label, "none"
        return
    if hook is not None:
        hook(shard.index)
    judged = PlacementJudge(run, obstacle, adapter.scene_model).judge(
        spec.obstacle.x_mm[shard.start : shard.stop] / 1000.0,
        spec.obstacle.y_mm[shard.start : shard.stop] / 1000.0,
    )
    report = run.report
    base_hit = report.obstacle.first_time_s if report.obstacle is not None else None
    base_first = report.obstacle.first_obstacle if report.obstacle is not None else None
    table["method"][:] = "recorded"
    for i in range(shard.rows):
        code = Verdict(int(judged.verdict[i]))
        table["verdict"][i] = code.label
        if code == Verdict.INVALID:
            continue
        if code == Verdict.START_OVERLAP:
            table["collided"][i] = True
            table["first_obstacle"][i] = obstacle.name
            continue
        if code == Verdict.COLLIDED:
            t = float(judged.first_contact_s[i])
            table["collided"][i] = True
            if base_hit is not None and base_hit < t:
                t, name = base_hit, base_first or ""
            else:
                name = obstacle.name
            table["verdict"][i] = Verdict.COLLIDED.label
            table["first_contact_s"][i], table["first_obstacle"][i] = t, name
            continue
        # Never touched: the run with the obstacle there is the recorded run, exactly.
        clearance = float(judged.min_clearance_m[i])
        when = float(judged.min_clearance_time_s[i])
        if report.min_clearance_m is not None and report.min_clearance_m < clearance:
            clearance, when = report.min_clearance_m, float(report.min_clearance_time_s or 0.0)
        table["min_clearance_m"][i], table["min_clearance_time_s"][i] = clearance, when
        _tracking(table, i, report)
        if base_hit is not None:
            table["verdict"][i], table["collided"][i] = Verdict.COLLIDED.label, True
            table["first_contact_s"][i], table["first_obstacle"][i] = base_hit, base_first or ""


def compute_shard(spec: SweepSpec, shard: Shard, hook: ShardHook | None = None) -> Table:
    """Compute a shard's rows (see the module docstring).

    Args:
        spec: The sweep.
        shard: One of :func:`shards`.
        hook: Called with the shard's index midway (tests use it to kill the worker).

    Returns:
        The shard's rows.
    """
    table = empty(shard.rows)
    try:
        task, obstacle = _variant(spec, shard.group)
    except InvalidInputError:  # an obstacle encloses the moved cube: no such scene
        table["verdict"][:], table["method"][:] = Verdict.INVALID.label, "none"
        task, obstacle = spec.tasks[shard.group.task], None
        _fill_inputs(table, spec, shard, task, None)
        return concat([table])
    _fill_inputs(table, spec, shard, task, obstacle)
    if obstacle is None or shard.group.kind is TrajectoryKind.PLANNED:
        if hook is not None:
            hook(shard.index)
        _physics_rows(table, spec, shard, task, obstacle)
    else:
        _recorded_rows(table, spec, shard, task, obstacle, hook)
    return concat([table])


class Backend(Protocol):
    """Computes shards somewhere; reports each as it finishes."""

    def run(
        self,
        spec: SweepSpec,
        todo: list[Shard],
        done: Callable[[Shard, Table], None],
        hook: ShardHook | None = None,
    ) -> None:
        """Compute every shard of ``todo`` and call ``done(shard, rows)`` for each, in any order."""


@dataclass(frozen=True)
class LocalBackend:
    """Shards computed in this process (``jobs == 1``) or in a pool of worker processes.

    The workers end when this process dies, even by SIGKILL
    (:func:`lynxsim.processes.die_with_parent`).

    Attributes:
        jobs: Worker processes (1: none), an integer from 1 to :data:`lynxsim.bounds.MAX_JOBS`.

    Raises:
        InvalidInputError: ``jobs`` is not such an integer.
    """

    jobs: int = 1

    def __post_init__(self) -> None:
        count(self.jobs, "jobs", 1, MAX_JOBS)

    def run(
        self,
        spec: SweepSpec,
        todo: list[Shard],
        done: Callable[[Shard, Table], None],
        hook: ShardHook | None = None,
    ) -> None:
        """Compute the shards; ``done`` runs in this process as each finishes."""
        if self.jobs <= 1 or len(todo) <= 1:
            for shard in todo:
                done(shard, compute_shard(spec, shard, hook))
            return
        context = multiprocessing.get_context("spawn")  # no forked MuJoCo state
        # Each worker dies with this process and knows the robots registered here.
        initializer, initargs = pool_initializer(restore, rows())
        with ProcessPoolExecutor(
            max_workers=self.jobs,
            mp_context=context,
            initializer=initializer,
            initargs=initargs,
        ) as pool:
            pending: dict[Future[Table], Shard] = {}
            queue: Iterator[Shard] = iter(todo)
            for shard in _take(queue, 2 * self.jobs):
                pending[pool.submit(compute_shard, spec, shard, hook)] = shard
            while pending:
                finished, _ = wait(pending, return_when=FIRST_COMPLETED)
                for future in finished:
                    shard = pending.pop(future)
                    done(shard, future.result())
                    for more in _take(queue, 1):
                        pending[pool.submit(compute_shard, spec, more, hook)] = more


def _take(items: Iterator[Shard], count: int) -> Iterable[Shard]:
    for _ in range(count):
        item = next(items, None)
        if item is None:
            return
        yield item


@dataclass(frozen=True)
class SweepOutcome:
    """What :func:`run_sweep` produced.

    Attributes:
        table: The rows, in table order.
        csv: The CSV file.
        npz: The NPZ file.
        computed: Shards computed by this call.
        reused: Shards found saved by an earlier call.
    """

    table: Table
    csv: Path
    npz: Path
    computed: int
    reused: int


def run_sweep(
    spec: SweepSpec,
    out: str | os.PathLike[str],
    *,
    backend: Backend | None = None,
    progress: Callable[[int, int], None] | None = None,
    hook: ShardHook | None = None,
    notice: Notice | None = None,
) -> SweepOutcome:
    """Run a sweep: compute the shards not saved yet, save each as it finishes, write the table.

    A saved shard is used only after it is verified
    (:func:`lynxsim.sweep.shard_files.read_shard`); one that cannot be used is
    computed again and ``notice`` gets one line saying which and why.

    Args:
        spec: The sweep.
        out: Output folder: ``STEM.csv``, ``STEM.npz`` and the shards in
            ``STEM.shards/`` (``STEM`` made from the sweep's name, never a path).
        backend: Where shards are computed (default: this process).
        progress: Called as ``progress(rows_done, rows_total)``.
        hook: Passed to :func:`compute_shard`.
        notice: Called with one line per saved shard that could not be used.

    Returns:
        The :class:`SweepOutcome`.
    """
    from lynxsim.sweep.table import write_csv

    out = Path(out)
    stem = file_stem(spec.name)
    folder = shard_folder(spec, out)
    every = shards(spec)
    total = sum(s.rows for s in every)
    tables: dict[int, Table] = {}
    todo: list[Shard] = []
    for shard in every:
        path = shard_path(folder, shard.index)
        saved = saved_shard(path, spec.digest, shard.index, shard.rows, notice)
        if saved is None:
            todo.append(shard)
        else:
            tables[shard.index] = saved
    rows_done = sum(s.rows for s in every if s.index in tables)
    if progress is not None:
        progress(rows_done, total)

    def done(shard: Shard, table: Table) -> None:
        nonlocal rows_done
        write_shard(shard_path(folder, shard.index), table, sweep=spec.digest, index=shard.index)
        tables[shard.index] = table
        rows_done += shard.rows
        if progress is not None:
            progress(rows_done, total)

    reused = len(tables)
    (backend or LocalBackend()).run(spec, todo, done, hook)
    table = concat([tables[s.index] for s in every])
    npz = write_npz(out / f"{stem}.npz", table)
    csv = write_csv(out / f"{stem}.csv", table)
    return SweepOutcome(table, csv, npz, len(every) - reused, reused)
