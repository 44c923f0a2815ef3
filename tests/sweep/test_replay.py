"""The sweep's central claim: a placement judged on a recorded run is what its own run gives.

Rows of a sweep over the report's tasks are replayed one by one with ``lynxsim
play TASK --type T --json`` (in-process), the cylinder moved to the row's
placement in a copy of the task file: the same verdict, and bit for bit the
same first contact time (collided rows) or minimum clearance and its time
(clear rows). A placement that overlaps the arm or the cube before the motion
(``start_overlap``) is a collision in its own run too.
"""

from __future__ import annotations

import json
import re
from pathlib import Path

import numpy as np
import pytest

from lynxsim.cli import main
from lynxsim.sweep.runner import run_sweep
from lynxsim.traj import TrajectoryKind
from tests.sweep.conftest import TASKS, grid_spec

SAMPLES = {"clear": 30, "collided": 22, "start_overlap": 8}
"""Rows replayed per verdict (60 in all)."""

_PLACEMENT = re.compile(r"position_mm = \[150\.0, 150\.0, 0\.0\]")


def _task_with_cylinder_at(task: str, x_m: float, y_m: float, folder: Path) -> Path:
    """A copy of the task file with its cylinder's centre at (x, y), written in mm."""
    text = (TASKS / f"{task}.toml").read_text()
    assert len(_PLACEMENT.findall(text)) == 1
    x_mm, y_mm = round(x_m * 1e3, 6), round(y_m * 1e3, 6)
    assert x_mm / 1000.0 == x_m  # the file's mm give the row's metres
    assert y_mm / 1000.0 == y_m
    moved = _PLACEMENT.sub(f"position_mm = [{x_mm!r}, {y_mm!r}, 0.0]", text)
    path = folder / f"{task}_{x_mm:g}_{y_mm:g}.toml"
    path.write_text(moved)
    return path


def _play(path: Path, kind: str, out: Path, capsys: pytest.CaptureFixture[str]) -> dict:
    code = main(["play", str(path), "--type", kind, "--json", "--no-video", "--out", str(out)])
    captured = capsys.readouterr()
    assert code == 0, captured.err
    report: dict = json.loads(captured.out)
    return report


@pytest.mark.slow
def test_sampled_rows_equal_their_own_runs(tmp_path, capsys):
    kinds = (
        TrajectoryKind.LINE,
        TrajectoryKind.QUINTIC,
        TrajectoryKind.RUCKIG,
        TrajectoryKind.LSPB,
    )
    table = run_sweep(grid_spec(40.0, kinds), tmp_path / "sweep").table
    rng = np.random.default_rng(12)
    replayed = 0
    for verdict, count in SAMPLES.items():
        rows = np.flatnonzero(table["verdict"] == verdict)
        assert len(rows) >= count, verdict
        for i in rng.choice(rows, size=count, replace=False).tolist():
            task, kind = str(table["task"][i]), str(table["type"][i])
            x, y = float(table["obstacle_x_m"][i]), float(table["obstacle_y_m"][i])
            path = _task_with_cylinder_at(task, x, y, tmp_path)
            report = _play(path, kind, tmp_path / "play.mp4", capsys)
            where = f"row {i}: {task} {kind} at ({x * 1e3:g}, {y * 1e3:g}) mm"
            assert report["collided"] == bool(table["collided"][i]), where
            if verdict == "clear":
                assert report["min_clearance_m"] == table["min_clearance_m"][i], where
                assert report["min_clearance_time_s"] == table["min_clearance_time_s"][i], where
                assert report["tool_max_error_m"] == table["tool_max_error_m"][i], where
                assert report["healthy"] == bool(table["healthy"][i]), where
            elif verdict == "collided":
                assert report["obstacle"]["first_time_s"] == table["first_contact_s"][i], where
            replayed += 1
    assert replayed >= 50
