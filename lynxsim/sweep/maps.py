"""A sweep's maps, and the report's obstacle map as the demo draws it."""

from __future__ import annotations

import dataclasses
import os
from collections.abc import Callable
from pathlib import Path

from lynxsim.fileio import file_stem, unique_stems
from lynxsim.scene import Box
from lynxsim.sweep.runner import Backend, Group, LocalBackend, groups, run_sweep
from lynxsim.sweep.spec import ObstacleSweep, SweepSpec, _digest, table_extent_mm
from lynxsim.sweep.table import Table
from lynxsim.tasks import load_task
from lynxsim.traj.kinds import WAYPOINT_KINDS

__all__ = ["REPORT_MAP_TASKS", "report_map_spec", "run_report_map", "write_maps"]

REPORT_MAP_TASKS = ("pick_and_place.toml", "obstacle_avoidance.toml")
"""The report's tasks, whose cylinder the report's obstacle map moves."""


def write_maps(spec: SweepSpec, table: Table, out: str | os.PathLike[str]) -> list[Path]:
    """One map per (task, type, planner seed, cube, radius) of a sweep with an obstacle.

    Files ``out/STEM_TASK_TYPE[_seedS][_cubeC][_rRmm].png``, every part made
    safe (:func:`lynxsim.fileio.file_stem`); where two come out the same, the
    later ones end in ``_2``, ``_3``... (:func:`lynxsim.fileio.unique_stems`).

    Returns:
        The PNG files written (none without a swept obstacle).
    """
    from lynxsim.plots.sweep_map import plot_obstacle_map

    if spec.obstacle is None:
        return []
    every = groups(spec)
    # names that clean or cut to the same stem must not overwrite each other's maps
    stems = unique_stems([file_stem(*_map_parts(spec, group)) for group in every])
    written = []
    for group, stem in zip(every, stems, strict=True):
        task = spec.tasks[group.task]
        rows = {k: v[group.first_row : group.first_row + group.rows] for k, v in table.items()}
        label = f"{task.name}, {group.kind.value}"
        if group.seed >= 0:
            label += f", seed {group.seed}"
        if group.cube >= 0:
            label += f", cube {group.cube}"
        obstacle = task.scene.obstacle(spec.obstacle.name)
        if group.radius >= 0 and spec.obstacle.radii_mm is not None:
            radius_mm = spec.obstacle.radii_mm[group.radius]
            label += f", radius {radius_mm:g} mm"
            if not isinstance(obstacle, Box):
                obstacle = dataclasses.replace(obstacle, radius=radius_mm / 1000.0)
        dest = Path(out) / f"{stem}.png"
        plot_obstacle_map(
            rows,
            dest,
            obstacle=obstacle,
            table=task.scene.table,
            poses=task.poses,
            title=f"{label}: where may the {obstacle.name} stand?",
        )
        written.append(dest)
    return written


def _map_parts(spec: SweepSpec, group: Group) -> list[str]:
    """The name pieces of a group's map: sweep, task, type, and what else varies."""
    parts = [spec.name, spec.tasks[group.task].name, group.kind.value]
    if group.seed >= 0:
        parts.append(f"seed{group.seed}")
    if group.cube >= 0:
        parts.append(f"cube{group.cube}")
    if group.radius >= 0 and spec.obstacle is not None and spec.obstacle.radii_mm is not None:
        parts.append(f"r{spec.obstacle.radii_mm[group.radius]:g}mm")
    return parts


def report_map_spec(tasks: str | os.PathLike[str] = "tasks", step_mm: float = 25.0) -> SweepSpec:
    """The report's obstacle map as a sweep: the cylinder over the table, every waypoint type.

    Args:
        tasks: The folder holding the report's task files (:data:`REPORT_MAP_TASKS`).
        step_mm: Grid step [mm] (``sweeps/report_obstacle_map.toml``: 5 mm; the demo: 25 mm).

    Raises:
        TaskFileError: A task file is malformed.
        OSError: A task file cannot be read.
    """
    import numpy as np

    files = tuple(Path(tasks) / name for name in REPORT_MAP_TASKS)
    loaded = tuple(load_task(f) for f in files)
    (x0, x1), (y0, y1) = table_extent_mm()
    xs = x0 + step_mm * np.arange(int((x1 - x0) / step_mm + 1e-9) + 1)
    ys = y0 + step_mm * np.arange(int((y1 - y0) / step_mm + 1e-9) + 1)
    gx, gy = np.meshgrid(xs, ys)
    name = f"report_obstacle_map_{step_mm:g}mm"
    return SweepSpec(
        name=name,
        description="The report's cylinder swept over the table",
        tasks=loaded,
        task_files=files,
        kinds=WAYPOINT_KINDS,
        planner_seeds=(0,),
        obstacle=ObstacleSweep(
            "cylinder", gx.reshape(-1), gy.reshape(-1), None, (len(ys), len(xs))
        ),
        cube_positions=None,
        rows_per_shard=2048,
        source=None,
        digest=_digest(f"{name}\0{step_mm!r}".encode(), files),
    )


def run_report_map(
    out: str | os.PathLike[str],
    *,
    tasks: str | os.PathLike[str] = "tasks",
    step_mm: float = 25.0,
    backend: Backend | None = None,
    progress: Callable[[int, int], None] | None = None,
) -> tuple[Table, list[Path]]:
    """Compute and draw the report's obstacle map (the coarse one by default, for the demo).

    Args:
        out: Output folder (table, shards and one PNG per task and type).
        tasks: The folder of the report's task files.
        step_mm: Grid step [mm].
        backend: Where shards are computed (default: this process).
        progress: Called as ``progress(rows_done, rows_total)``.

    Returns:
        The table and the maps written.
    """
    spec = report_map_spec(tasks, step_mm)
    outcome = run_sweep(spec, out, backend=backend or LocalBackend(), progress=progress)
    return outcome.table, write_maps(spec, outcome.table, out)
