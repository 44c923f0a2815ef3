"""The 3-RRR part of the main job: its tasks played in MuJoCo, and Figure 20 judged by simulation.

Writes, under one output folder, per task of ``tasks/`` with ``robot = "rrr"``
an MP4 from the orthographic ``top`` camera with the platform's path traced,
its JSON run report and, in ``plots/``, the path drawn over its workspace;
the workspace maps of the report's Figure 21 orientations in ``plots/``;
and ``rrr_figure20_simulation.txt``, the simulation's verdicts on the
report's Figure 20 poses. Returns the run reports for the summary table.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable
from pathlib import Path

import numpy as np

from lynxsim.fileio import atomic_path, file_stem
from lynxsim.plots.rrr import plot_rrr_path, plot_rrr_workspace, view_extent
from lynxsim.reproduce.figure20 import figure20_simulation, format_figure20_simulation
from lynxsim.rrr import mode_label
from lynxsim.rrr.task import path_from_task
from lynxsim.rrr.workspace import workspace_maps
from lynxsim.sim.render import RenderSettings
from lynxsim.sim.report import RunReport
from lynxsim.sim.rrr.model import HOME_MODE
from lynxsim.sim.rrr.task import run_rrr_path
from lynxsim.tasks import find_tasks

__all__ = [
    "FIGURE20_FILE",
    "PATH_PLOT_SAMPLES",
    "WORKSPACE_ALPHAS_DEG",
    "WORKSPACE_RESOLUTION_M",
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


def _run_progress(
    progress: Callable[[int, float], None] | None, index: int
) -> Callable[[float], None] | None:
    if progress is None:
        return None
    report = progress

    def update(fraction: float) -> None:
        report(index, fraction)

    return update


def run_rrr_demo(
    out: Path,
    render: RenderSettings,
    progress: Callable[[int, float], None] | None = None,
    *,
    tasks: Path = Path("tasks"),
    mode: int = HOME_MODE,
) -> list[RunReport]:
    """Simulate, record and plot every 3-RRR task; judge Figure 20 by simulation.

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
    settings = dataclasses.replace(render, camera="top")
    reports = []
    for i, task in enumerate(find_tasks(tasks, "rrr")):
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
        playback = run_rrr_path(
            path,
            task=task.name,
            mode=mode,
            video=out / f"{stem}.mp4",
            render=settings,
            progress=_run_progress(progress, i),
        )
        playback.report.write_json(out / f"{stem}.json")
        reports.append(playback.report)
    alphas = [math.radians(a) for a in WORKSPACE_ALPHAS_DEG]
    maps = workspace_maps(alphas, view_extent(alphas), WORKSPACE_RESOLUTION_M)
    for wmap, alpha_deg in zip(maps, WORKSPACE_ALPHAS_DEG):
        plot_rrr_workspace([wmap], out / "plots" / f"rrr_workspace_alpha{alpha_deg:+.0f}.png")
    plot_rrr_workspace(maps, out / "plots" / "rrr_workspace.png", mode=mode)
    with atomic_path(out / FIGURE20_FILE) as tmp:
        tmp.write_text(format_figure20_simulation(figure20_simulation()) + "\n")
    return reports
