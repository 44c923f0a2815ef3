"""The 3-RRR part of the main job: its tasks played in MuJoCo, and Figure 20 judged by simulation.

Writes, under one output folder, per task of ``tasks/`` with ``robot = "rrr"``
an MP4 from the orthographic ``top`` camera with the platform's path traced,
its JSON run report and, in ``plots/``, the path drawn over its workspace;
and ``rrr_figure20_simulation.txt``, the simulation's verdicts on the
report's Figure 20 poses. Returns the run reports for the summary table.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable
from pathlib import Path

import numpy as np

from lynxsim.fileio import atomic_path
from lynxsim.plots.rrr import plot_rrr_path
from lynxsim.rrr import mode_label
from lynxsim.sim.render import RenderSettings
from lynxsim.sim.report import RunReport
from lynxsim.sim.rrr_scene import HOME_MODE
from lynxsim.sim.rrr_task import path_from_task, run_rrr_path
from lynxsim.sim.rrr_verify import figure20_simulation, format_figure20_simulation
from lynxsim.tasks import Task, load_task

__all__ = ["FIGURE20_FILE", "PATH_PLOT_SAMPLES", "rrr_tasks", "run_rrr_demo"]

FIGURE20_FILE = "rrr_figure20_simulation.txt"
"""Name of the Figure 20 verdicts file in the output folder."""
PATH_PLOT_SAMPLES = 400
"""Samples of each path drawn in its plot."""


def rrr_tasks(folder: Path) -> list[Task]:
    """Every task file of ``folder`` for the 3-RRR robot, sorted by file name."""
    tasks = [load_task(p) for p in sorted(Path(folder).glob("*.toml"))]
    return [t for t in tasks if t.robot == "rrr"]


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
    for i, task in enumerate(rrr_tasks(tasks)):
        path = path_from_task(task)
        stem = f"{task.name}_{path.label}"
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
    with atomic_path(out / FIGURE20_FILE) as tmp:
        tmp.write_text(format_figure20_simulation(figure20_simulation()) + "\n")
    return reports
