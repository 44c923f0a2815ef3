"""Shared sweeps of the sweep tests: small ones over the report's tasks."""

from __future__ import annotations

import os

os.environ.setdefault("MUJOCO_GL", "egl")

from pathlib import Path

import numpy as np

from lynxsim.sweep.spec import ObstacleSweep, SweepSpec, _digest
from lynxsim.tasks import load_task
from lynxsim.traj import TrajectoryKind

ROOT = Path(__file__).resolve().parents[2]
TASKS = ROOT / "tasks"


def grid_spec(
    step_mm: float,
    kinds: tuple[TrajectoryKind, ...],
    *,
    tasks: tuple[str, ...] = ("pick_and_place.toml", "obstacle_avoidance.toml"),
    x_mm: tuple[float, float] = (-250.0, 450.0),
    y_mm: tuple[float, float] = (-500.0, 500.0),
    rows_per_shard: int = 2048,
) -> SweepSpec:
    """The report's cylinder on a grid over (part of) the table."""
    files = tuple(TASKS / t for t in tasks)
    xs = x_mm[0] + step_mm * np.arange(int((x_mm[1] - x_mm[0]) / step_mm) + 1)
    ys = y_mm[0] + step_mm * np.arange(int((y_mm[1] - y_mm[0]) / step_mm) + 1)
    gx, gy = np.meshgrid(xs, ys)
    name = f"test_{step_mm:g}_{'_'.join(k.value for k in kinds)}"
    return SweepSpec(
        name=name,
        description="",
        tasks=tuple(load_task(f) for f in files),
        task_files=files,
        kinds=kinds,
        planner_seeds=(0,),
        obstacle=ObstacleSweep("cylinder", gx.reshape(-1), gy.reshape(-1), None, gx.shape),
        cube_positions=None,
        rows_per_shard=rows_per_shard,
        source=None,
        digest=_digest(f"{name}{x_mm}{y_mm}{rows_per_shard}".encode(), files),
    )
