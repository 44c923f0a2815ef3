"""The 3-RRR's extras of the main job: its paths over its workspace, and Figure 20 judged.

The 3-RRR's tasks are played as every robot's are (:mod:`lynxsim.demo.runs`:
an MP4 from its first camera, the orthographic ``top``, with the platform's path
traced, the JSON run report, the replay data and page). Its extras write, under
the same output folder, in ``plots/`` per 3-RRR task of ``tasks/`` the path drawn
over its workspace and the workspace maps of the report's Figure 21
orientations, and ``rrr_figure20_simulation.txt``, the simulation's verdicts on
the report's Figure 20 poses. Each is a :class:`~lynxsim.demo.jobs.Job` of its
own (:func:`rrr_jobs`); :func:`run_rrr_demo` runs the 3-RRR's part alone.
"""

from __future__ import annotations

import functools
import math
from pathlib import Path

import numpy as np

from lynxsim.demo.jobs import Job, JobProgress, job_progress
from lynxsim.demo.runs import PLOT_COST, DemoRun, play_run
from lynxsim.fileio import atomic_path, file_stem
from lynxsim.plots.rrr import plot_rrr_path, plot_rrr_workspace, view_extent
from lynxsim.reproduce.figure20 import figure20_simulation, format_figure20_simulation
from lynxsim.robots.rrr import ROBOT, path_from_task
from lynxsim.rrr import mode_label
from lynxsim.rrr.modes import HOME_MODE, MODE_OPTION
from lynxsim.rrr.workspace import workspace_maps
from lynxsim.run_options import RunValues
from lynxsim.sim.recording import ProgressFn
from lynxsim.sim.render import RenderSettings
from lynxsim.sim.report import RunReport
from lynxsim.tasks import Task, find_tasks

__all__ = [
    "FIGURE20_FILE",
    "PATH_PLOT_SAMPLES",
    "WORKSPACE_ALPHAS_DEG",
    "WORKSPACE_RESOLUTION_M",
    "rrr_jobs",
    "run_rrr_demo",
]

FIGURE20_FILE = "rrr_figure20_simulation.txt"
"""Name of the Figure 20 verdicts file in the output folder."""
PATH_PLOT_SAMPLES = 400
"""Samples of each path drawn in its plot."""
WORKSPACE_ALPHAS_DEG = (0.0, 20.0, -20.0, 50.0, -50.0)
"""The orientations of the report's Figure 21 [deg]."""
WORKSPACE_RESOLUTION_M = 0.002
"""Grid step of the demo's workspace maps [m]."""
_WORKSPACE_COST = 6 * PLOT_COST
"""Cost of the workspace maps and their six plots, in frames (see :class:`Job`)."""
_FIGURE20_COST = 4 * PLOT_COST
"""Cost of the Figure 20 verdicts (settling and pulling in MuJoCo), in frames."""


def _path_plot(task: Task, out: Path, mode: int, progress: ProgressFn | None = None) -> None:
    """A 3-RRR task's platform path drawn over its workspace, in ``plots/``."""
    path = path_from_task(task)
    stem = file_stem(task.name, path.label)
    poses = path.sample(np.linspace(0.0, path.duration, PATH_PLOT_SAMPLES)).pose
    plot_rrr_path(
        poses,
        out / "plots" / f"{stem}.png",
        mode=mode,
        title=f"{task.name}: platform path ({path.label}, {path.duration:.2f} s), "
        f"working mode {mode} ({mode_label(mode)})",
    )
    if progress is not None:
        progress(1.0)


def _workspace_plots(out: Path, mode: int, progress: ProgressFn | None = None) -> None:
    """The workspace maps of the report's Figure 21 orientations, one plot each and together."""
    alphas = [math.radians(a) for a in WORKSPACE_ALPHAS_DEG]
    maps = workspace_maps(alphas, view_extent(alphas), WORKSPACE_RESOLUTION_M)
    for wmap, alpha_deg in zip(maps, WORKSPACE_ALPHAS_DEG):
        plot_rrr_workspace([wmap], out / "plots" / f"rrr_workspace_alpha{alpha_deg:+.0f}.png")
    plot_rrr_workspace(maps, out / "plots" / "rrr_workspace.png", mode=mode)
    if progress is not None:
        progress(1.0)


def _figure20(out: Path, progress: ProgressFn | None = None) -> None:
    """The simulation's verdicts on the report's Figure 20 poses, into :data:`FIGURE20_FILE`."""
    with atomic_path(out / FIGURE20_FILE) as tmp:
        tmp.write_text(format_figure20_simulation(figure20_simulation()) + "\n")
    if progress is not None:
        progress(1.0)


def rrr_jobs(
    out: Path,
    *,
    tasks: Path = Path("tasks"),
    mode: int = HOME_MODE,
) -> list[Job[None]]:
    """The 3-RRR's extras: each task's path plot, the workspace maps, Figure 20's verdicts.

    Args:
        out: Output folder (as :func:`run_rrr_demo`).
        tasks: Folder of task files.
        mode: Working mode 0..7 the plots draw.
    """
    jobs: list[Job[None]] = []
    for task in find_tasks(tasks, ROBOT.name):
        plot = functools.partial(_path_plot, task, out, mode)
        jobs.append(Job(f"{task.name}_path_plot", PLOT_COST, plot))
    workspace = functools.partial(_workspace_plots, out, mode)
    jobs.append(Job("rrr_workspace", _WORKSPACE_COST, workspace))
    jobs.append(Job(FIGURE20_FILE, _FIGURE20_COST, functools.partial(_figure20, out)))
    return jobs


def run_rrr_demo(
    out: Path,
    render: RenderSettings,
    progress: JobProgress | None = None,
    *,
    tasks: Path = Path("tasks"),
    mode: int = HOME_MODE,
) -> list[RunReport]:
    """Simulate, record and plot every 3-RRR task; judge Figure 20 by simulation (in this process).

    Args:
        out: Output folder (videos, reports, ``rrr_figure20_simulation.txt``;
            plots in ``out/plots``).
        render: Video settings; the camera is always ``top`` (the plane seen
            from above), size, quality and fps are taken from here.
        progress: Called as ``progress(run index, fraction of that run)``.
        tasks: Folder of task files.
        mode: Working mode 0..7 of every run (default 7, the report's).

    Returns:
        The run reports, in task-file order.
    """
    out = Path(out)
    options = RunValues.of(ROBOT.run_options, {MODE_OPTION.name: mode})
    reports = []
    for i, task in enumerate(find_tasks(tasks, ROBOT.name)):
        run = DemoRun(ROBOT, task, path_from_task(task), options)
        _path_plot(task, out, mode)
        reports.append(play_run(run, out, render, job_progress(progress, i)))
    _workspace_plots(out, mode)
    _figure20(out)
    return reports
