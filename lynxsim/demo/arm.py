"""The arm part of the main job: every task of ``tasks/`` simulated with every trajectory type.

Writes, under one output folder, an MP4, a JSON run report, its replay data and
its replay page per run, joint
profile plots and a tool-path comparison per task; returns the reports for the
summary table. Each run and each comparison is a :class:`~lynxsim.demo.jobs.Job`
of its own (``lynxsim demo`` runs them in a pool with the 3-RRR part's).
"""

from __future__ import annotations

import functools
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from pathlib import Path

from lynxsim.demo.jobs import Job, JobProgress, run_jobs
from lynxsim.errors import LynxsimError
from lynxsim.fileio import file_stem
from lynxsim.plots.trajectory import plot_joint_profiles, plot_tool_paths
from lynxsim.sim.arm.planning import task_trajectory
from lynxsim.sim.arm.task import run_arm_trajectory
from lynxsim.sim.recording import ProgressFn
from lynxsim.sim.render import RenderSettings
from lynxsim.sim.report import RunReport
from lynxsim.tasks import Task
from lynxsim.traj import Trajectory, TrajectoryKind
from lynxsim.web.page import page_from_file
from lynxsim.web.replay_file import REPLAY_SUFFIX

__all__ = ["PLOT_COST", "DemoRun", "arm_jobs", "arm_runs", "run_arm_demo"]

PLOT_COST = 10.0
"""Cost of a job that only draws a plot, in the unit of :attr:`Job.cost` (frames)."""


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
    run: DemoRun, out: Path, render: RenderSettings, progress: ProgressFn | None
) -> RunReport:
    """Plot, simulate and record one run; write its JSON report."""
    plot_joint_profiles(run.trajectory, out / "plots" / f"{run.stem}.png")
    playback = run_arm_trajectory(
        run.trajectory,
        task=run.task.name,
        scene=run.task.scene,
        video=out / f"{run.stem}.mp4",
        render=render,
        progress=progress,
        replay=out / f"{run.stem}{REPLAY_SUFFIX}",
    )
    playback.report.write_json(out / f"{run.stem}.json")
    page_from_file(out / f"{run.stem}{REPLAY_SUFFIX}", out / f"{run.stem}.html")
    return playback.report


def _plot_paths(
    task: Task, trajectories: dict[str, Trajectory], out: Path, progress: ProgressFn | None
) -> None:
    """Draw one task's tool paths of every type into one comparison."""
    plot_tool_paths(
        trajectories,
        out / "plots" / f"{file_stem(task.name, 'paths')}.png",
        obstacles=task.scene.obstacles,
        title=f"{task.name}: tool paths of every type",
    )
    if progress is not None:
        progress(1.0)


def arm_jobs(runs: list[DemoRun], out: Path, render: RenderSettings) -> list[Job[RunReport | None]]:
    """The jobs of the arm part: each run (its report), then each task's path comparison (None).

    Args:
        runs: From :func:`arm_runs`.
        out: Output folder (videos, reports; plots in ``out/plots``).
        render: Video settings.
    """
    jobs: list[Job[RunReport | None]] = []
    for run in runs:
        work = functools.partial(_play, run, out, render)
        frames = run.trajectory.duration * render.fps
        jobs.append(Job(run.stem, PLOT_COST + frames, work))  # profiles plotted, then the video
    by_task: dict[str, tuple[Task, dict[str, Trajectory]]] = {}
    for run in runs:
        by_task.setdefault(run.task.name, (run.task, {}))[1][run.trajectory.kind.value] = (
            run.trajectory
        )
    for name, (task, trajectories) in by_task.items():
        plot = functools.partial(_plot_paths, task, trajectories, out)
        jobs.append(Job(file_stem(name, "paths"), PLOT_COST, plot))
    return jobs


def run_arm_demo(
    runs: list[DemoRun],
    out: Path,
    render: RenderSettings,
    progress: JobProgress | None = None,
    *,
    jobs: int = 1,
) -> list[RunReport]:
    """Simulate and record each run; plot each task's profiles and path comparison.

    Args:
        runs: From :func:`arm_runs`.
        out: Output folder (videos, reports; plots in ``out/plots``).
        render: Video settings.
        progress: See :func:`~lynxsim.demo.jobs.run_jobs` (the jobs: one per
            run, then one per task).
        jobs: Worker processes running jobs at the same time (1: in this process).

    Returns:
        The run reports, in the order of ``runs``.
    """
    results = run_jobs(arm_jobs(runs, out, render), progress, workers=jobs)
    return [r for r in results if r is not None]
