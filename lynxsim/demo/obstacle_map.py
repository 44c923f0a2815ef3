"""The sweep part of the main job: where may the report's cylinder stand (a coarse map)."""

from __future__ import annotations

import functools
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from lynxsim.demo.jobs import Job
from lynxsim.sim.recording import ProgressFn
from lynxsim.verdicts import Verdict

__all__ = ["MAP_DIR", "MAP_STEP_MM", "MapSummary", "map_job"]

MAP_DIR = "sweeps"
"""Folder of the map's table and PNGs inside the demo's output folder."""
MAP_STEP_MM = 25.0
"""Grid step of the demo's map [mm] (the 5 mm one:
``lynxsim sweep sweeps/report_obstacle_map.toml``)."""
_MAP_COST = 600.0
"""Cost of the map (about 14,000 judged placements), in frames (see :class:`Job`)."""


@dataclass(frozen=True)
class MapSummary:
    """Per task and trajectory type, the share of placements the motion clears.

    Attributes:
        rows: ``(task, type, placements, clear)`` for each map, in the table's order.
        maps: The PNGs written.
    """

    rows: tuple[tuple[str, str, int, int], ...]
    maps: tuple[Path, ...]


def _draw(out: Path, tasks: Path, progress: ProgressFn | None) -> MapSummary:
    from lynxsim.sweep.maps import run_report_map

    def rows_done(done: int, total: int) -> None:
        if progress is not None and total:
            progress(done / total)

    table, maps = run_report_map(out, tasks=tasks, step_mm=MAP_STEP_MM, progress=rows_done)
    keys = list(dict.fromkeys(zip(table["task"].tolist(), table["type"].tolist())))
    rows = []
    for task, kind in keys:
        valid = table["verdict"] != Verdict.INVALID.label
        mine = (table["task"] == task) & (table["type"] == kind) & valid
        clear = int(np.sum(mine & (table["verdict"] == Verdict.CLEAR.label)))
        rows.append((str(task), str(kind), int(np.sum(mine)), clear))
    return MapSummary(tuple(rows), tuple(maps))


def map_job(out: Path, tasks: Path) -> Job[MapSummary]:
    """Sweep the report's cylinder over the table on a :data:`MAP_STEP_MM` grid.

    The table and one map per task and type go to ``out/MAP_DIR``.
    """
    work = functools.partial(_draw, out / MAP_DIR, tasks)
    return Job("obstacle map", _MAP_COST, work)
