"""``lynxsim plan``: per-segment figures, samples and a plot; clear one-line errors."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

TASKS = Path(__file__).resolve().parents[2] / "tasks"


def test_plan_prints_segments_and_writes_samples_and_plot(cli, tmp_path):
    result = cli("plan", str(TASKS / "three_obstacles.toml"), "--out-dir", str(tmp_path), "--json")
    assert result.code == 0, result.err
    report = json.loads(result.out)
    assert [s["segment"] for s in report["segments"]] == [
        "P1 -> P2",
        "P2 -> P3",
        "P3 -> P4",
        "P4 -> P5",
    ]
    assert all(s["min_clearance_m"] >= 0.01 for s in report["segments"])
    assert all(s["timed_min_clearance_m"] >= 0.005 for s in report["segments"])
    assert {s["planner"] for s in report["segments"]} <= {"direct", "compiled", "RRTConnect"}
    samples = np.loadtxt(report["samples"], delimiter=",", skiprows=1)
    assert samples.shape[1] == 1 + 4 * 5 + 3 + 1
    assert samples[-1, 0] <= report["duration_s"]
    assert Path(report["plot"]).stat().st_size > 10_000
    assert sorted(p.name for p in tmp_path.iterdir()) == [
        "three_obstacles_planned.csv",
        "three_obstacles_planned_path.png",
    ]


def test_plan_table_at_the_terminal(cli, tmp_path):
    result = cli("plan", str(TASKS / "obstacle_avoidance.toml"), "--out-dir", str(tmp_path))
    assert result.code == 0, result.err
    lines = result.out.splitlines()
    assert lines[0].startswith("obstacle_avoidance: planned with compiled, margin 10 mm, seed 0")
    assert lines[1].split()[:3] == ["segment", "found", "by"]
    assert len(lines) == 2 + 5 + 2  # header, 5 segments, two "wrote" lines


def test_plan_with_ompl_on_the_exact_checker(cli, tmp_path):
    result = cli("plan", str(TASKS / "obstacle_avoidance.toml"), "--planner", "RRTConnect",
                 "--search-world", "exact", "--out-dir", str(tmp_path), "--json")  # fmt: skip
    assert result.code == 0, result.err
    report = json.loads(result.out)
    assert report["planner"] == "RRTConnect"
    assert {s["planner"] for s in report["segments"]} <= {"direct", "RRTConnect"}


def test_unknown_planner_lists_the_planners(cli, tmp_path):
    result = cli("plan", str(TASKS / "obstacle_avoidance.toml"), "--planner", "Dijkstra",
                 "--out-dir", str(tmp_path))  # fmt: skip
    assert result.code == 1
    assert result.err.count("\n") == 1
    assert result.err.startswith("lynxsim: error: --planner: unknown planner 'Dijkstra'; ")
    assert "RRTConnect" in result.err
    assert list(tmp_path.iterdir()) == []


def test_plan_refuses_a_3rrr_task_and_a_tiny_margin(cli, tmp_path):
    result = cli("plan", str(TASKS / "rrr_closed_curve.toml"), "--out-dir", str(tmp_path))
    assert result.code == 1
    assert "which does not plan; robots that plan: arm" in result.err
    assert result.err.count("\n") == 1
    result = cli("plan", str(TASKS / "pick_and_place.toml"), "--margin-mm", "0.01")
    assert result.code == 2
    assert "--margin-mm: must be between 1 and 100 mm" in result.err
