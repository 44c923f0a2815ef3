"""The main job: every task of ``tasks/`` simulated with every trajectory type.

Writes, under one output folder, an MP4 and a JSON run report per run, joint
profile plots and a tool-path comparison per task; returns the reports for the
summary table. Used by ``lynxsim demo``.
"""

from __future__ import annotations

import functools
import multiprocessing
from collections.abc import Callable, Iterator
from concurrent.futures import ProcessPoolExecutor, as_completed
from dataclasses import dataclass
from pathlib import Path

from lynxsim.errors import LynxsimError
from lynxsim.fileio import file_stem
from lynxsim.plots.trajectory import plot_joint_profiles, plot_tool_paths
from lynxsim.sim.arm.planning import task_trajectory
from lynxsim.sim.arm.task import run_arm_trajectory
from lynxsim.sim.render import RenderSettings
from lynxsim.sim.report import RunReport
from lynxsim.tasks import Task
from lynxsim.traj import Trajectory, TrajectoryKind

__all__ = ["DemoRun", "arm_runs", "run_arm_demo"]


@dataclass(frozen=True)
class DemoRun:
    """One simulation of the demo: a task with one trajectory type."""

    task: Task
    trajectory: Trajectory

    @property
    def stem(self) -> str:
        """File name stem of its outputs."""
        return file_stem(self.task.name, self.trajectory.kind.value)


def arm_runs(tasks: list[Task], skipped: Callable[[str], None]) -> Iterator[DemoRun]:
    """Every (task, type) pair that can be built; reports the others to ``skipped``."""
    for task in tasks:
        for kind in TrajectoryKind:
            try:
                yield DemoRun(task, task_trajectory(task, kind))
            except LynxsimError as exc:
                skipped(f"{task.name} {kind.value}: {exc}")


def _play(
    run: DemoRun,
    out: Path,
    render: RenderSettings,
    progress: Callable[[float], None] | None = None,
) -> RunReport:
    """Plot, simulate and record one run; write its JSON report (a worker's whole job)."""
    plot_joint_profiles(run.trajectory, out / "plots" / f"{run.stem}.png")
    playback = run_arm_trajectory(
        run.trajectory,
        task=run.task.name,
        scene=run.task.scene,
        video=out / f"{run.stem}.mp4",
        render=render,
        progress=progress,
    )
    playback.report.write_json(out / f"{run.stem}.json")
    return playback.report


def run_arm_demo(
    runs: list[DemoRun],
    out: Path,
    render: RenderSettings,
    progress: Callable[[int, float], None] | None = None,
    *,
    jobs: int = 1,
) -> list[RunReport]:
    """Simulate and record each run; plot each task's profiles and path comparison.

    Args:
        runs: From :func:`arm_runs`.
        out: Output folder (videos, reports; plots in ``out/plots``).
        render: Video settings.
        progress: Called as ``progress(k, fraction)`` with ``k + fraction`` the
            runs done so far (one run at a time; with ``jobs > 1`` whole runs).
        jobs: Worker processes playing runs at the same time (1: in this process).

    Returns:
        The run reports, in the order of ``runs``.
    """
    plots = out / "plots"
    reports: list[RunReport | None] = [None] * len(runs)
    if jobs <= 1:
        for i, run in enumerate(runs):
            update = None if progress is None else functools.partial(progress, i)
            reports[i] = _play(run, out, render, update)
    else:
        context = multiprocessing.get_context("spawn")  # no forked MuJoCo or GL state
        with ProcessPoolExecutor(max_workers=jobs, mp_context=context) as pool:
            futures = {pool.submit(_play, run, out, render): i for i, run in enumerate(runs)}
            for done, future in enumerate(as_completed(futures)):
                reports[futures[future]] = future.result()
                if progress is not None:
                    progress(done, 1.0)
    by_task: dict[str, tuple[Task, dict[str, Trajectory]]] = {}
    for run in runs:
        by_task.setdefault(run.task.name, (run.task, {}))[1][run.trajectory.kind.value] = (
            run.trajectory
        )
    for name, (task, trajectories) in by_task.items():
        plot_tool_paths(
            trajectories,
            plots / f"{file_stem(name, 'paths')}.png",
            obstacles=task.scene.obstacles,
            title=f"{name}: tool paths of every type",
        )
    return [r for r in reports if r is not None]
