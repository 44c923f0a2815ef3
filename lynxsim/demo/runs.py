"""The demo's runs: every task of the tasks folder, of every registered robot, in every type.

A :class:`DemoRun` is a task of a robot with one motion it builds
(:attr:`lynxsim.robots.Robot.kinds`); each is a :class:`~lynxsim.demo.jobs.Job`
that writes, under one output folder, its MP4 (from the robot's first camera),
its JSON run report, its replay data and its replay page, and, for a robot with
joint kinematics, its joint profiles in ``plots/``; each such task's tool paths
of every type are one more job (:func:`demo_jobs`). Jobs pickle to worker
processes with the robot's record, whose module registers it there again.
"""

from __future__ import annotations

import dataclasses
import functools
import os
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass
from pathlib import Path

from lynxsim.demo.jobs import Job, JobProgress, run_jobs
from lynxsim.errors import LynxsimError
from lynxsim.fileio import file_stem
from lynxsim.plots.trajectory import plot_joint_profiles, plot_tool_paths
from lynxsim.robots import Robot, get, motion, names, simulation
from lynxsim.run_options import RunValues
from lynxsim.sim.recording import ProgressFn
from lynxsim.sim.render import RenderSettings
from lynxsim.sim.report import RunReport
from lynxsim.tasks import Task, load_task
from lynxsim.traj import Trajectory
from lynxsim.traj.motion import Motion
from lynxsim.web.page import page_from_file
from lynxsim.web.replay_file import REPLAY_SUFFIX

__all__ = [
    "PLOT_COST",
    "DemoRun",
    "demo_jobs",
    "demo_runs",
    "demo_tasks",
    "play_run",
    "run_demo",
]

PLOT_COST = 10.0
"""Cost of a job that only draws a plot, in the unit of :attr:`Job.cost` (frames)."""


@dataclass(frozen=True)
class DemoRun:
    """One simulation of the demo: a task of a robot with one motion.

    Attributes:
        robot: The task's robot.
        task: The task.
        motion: The motion the robot built for it.
        options: The run's options (None: the robot's defaults).
    """

    robot: Robot
    task: Task
    motion: Motion
    options: RunValues | None = None

    @property
    def stem(self) -> str:
        """File name stem of its outputs."""
        return file_stem(self.task.name, self.motion.label)


def demo_tasks(folder: str | os.PathLike[str]) -> list[Task]:
    """Every task file (``*.toml``) of ``folder``, robot by robot (in registration order).

    Raises:
        TaskFileError: A task file is malformed (names file and field).
    """
    tasks = [load_task(p) for p in sorted(Path(folder).glob("*.toml"))]
    return [t for name in names() for t in tasks if t.robot == name]


def demo_runs(tasks: Sequence[Task], skipped: Callable[[str], None]) -> Iterator[DemoRun]:
    """Every (task, type) its robot builds; reports those that fail to ``skipped``."""
    for task in tasks:
        robot = get(task.robot)
        for kind in robot.kinds:
            try:
                yield DemoRun(robot, task, motion(robot, task, kind))
            except LynxsimError as exc:
                skipped(f"{task.name} {kind.value}: {exc}")


def play_run(
    run: DemoRun, out: Path, render: RenderSettings, progress: ProgressFn | None
) -> RunReport:
    """Plot (joint robots), simulate and record one run; write its JSON report and page."""
    if run.robot.kinematics is not None and isinstance(run.motion, Trajectory):
        plot_joint_profiles(run.motion, out / "plots" / f"{run.stem}.png")
    playback = simulation(run.robot).play(
        run.task,
        run.motion,
        options=run.options,
        video=out / f"{run.stem}.mp4",
        render=dataclasses.replace(render, camera=run.robot.cameras[0]),
        progress=progress,
        replay=out / f"{run.stem}{REPLAY_SUFFIX}",
    )
    playback.report.write_json(out / f"{run.stem}.json")
    page_from_file(out / f"{run.stem}{REPLAY_SUFFIX}", out / f"{run.stem}.html")
    return playback.report


def _plot_paths(
    robot: Robot,
    task: Task,
    trajectories: dict[str, Trajectory],
    out: Path,
    progress: ProgressFn | None,
) -> None:
    """Draw one task's tool paths of every type into one comparison."""
    if robot.kinematics is not None:
        plot_tool_paths(
            trajectories,
            out / "plots" / f"{file_stem(task.name, 'paths')}.png",
            tool=robot.kinematics.tool_points,
            obstacles=task.scene.obstacles,
            title=f"{task.name}: tool paths of every type",
        )
    if progress is not None:
        progress(1.0)


def demo_jobs(
    runs: list[DemoRun], out: Path, render: RenderSettings
) -> list[Job[RunReport | None]]:
    """The jobs of the runs: each run (its report), then each joint task's path comparison (None).

    Args:
        runs: From :func:`demo_runs`.
        out: Output folder (videos, reports; plots in ``out/plots``).
        render: Video settings (the camera: each robot's first).
    """
    jobs: list[Job[RunReport | None]] = []
    for run in runs:
        work = functools.partial(play_run, run, out, render)
        frames = run.motion.duration * render.fps
        jobs.append(Job(run.stem, PLOT_COST + frames, work))  # profiles plotted, then the video
    by_task: dict[str, tuple[Robot, Task, dict[str, Trajectory]]] = {}
    for run in runs:
        if run.robot.kinematics is not None and isinstance(run.motion, Trajectory):
            entry = by_task.setdefault(run.task.name, (run.robot, run.task, {}))
            entry[2][run.motion.label] = run.motion
    for name, (robot, task, trajectories) in by_task.items():
        plot = functools.partial(_plot_paths, robot, task, trajectories, out)
        jobs.append(Job(file_stem(name, "paths"), PLOT_COST, plot))
    return jobs


def run_demo(
    runs: list[DemoRun],
    out: Path,
    render: RenderSettings,
    progress: JobProgress | None = None,
    *,
    jobs: int = 1,
) -> list[RunReport]:
    """Simulate and record each run; plot each joint task's profiles and path comparison.

    Args:
        runs: From :func:`demo_runs`.
        out: Output folder (videos, reports; plots in ``out/plots``).
        render: Video settings.
        progress: See :func:`~lynxsim.demo.jobs.run_jobs` (the jobs: one per
            run, then one per task with joint kinematics).
        jobs: Worker processes running jobs at the same time (1: in this process).

    Returns:
        The run reports, in the order of ``runs``.
    """
    results = run_jobs(demo_jobs(runs, out, render), progress, workers=jobs)
    return [r for r in results if r is not None]
