"""``lynxsim traj``: samples and plots from a task file, one-line errors."""

from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np
import pytest

from lynxsim.cli import main
from lynxsim.traj import TrajectoryKind

TASKS = Path(__file__).resolve().parents[2] / "tasks"


def test_list_names_every_type(capsys):
    assert main(["traj", "--list"]) == 0
    listed = [line.split()[0] for line in capsys.readouterr().out.splitlines()]
    assert listed == [k.value for k in TrajectoryKind]


def test_writes_csv_samples_and_plots(tmp_path, capsys):
    code = main(
        [
            "traj",
            str(TASKS / "pick_and_place.toml"),
            "--type",
            "cubic",
            "--out-dir",
            str(tmp_path),
            "--rate-hz",
            "100",
            "--no-compare",
        ]
    )
    assert code == 0
    csv = tmp_path / "pick_and_place_cubic.csv"
    header = csv.read_text().splitlines()[0].split(",")
    assert header[:3] == ["t_s", "q1_deg", "q2_deg"]
    assert "qddd5_deg_s3" in header
    assert header[-4:] == ["x_mm", "y_mm", "z_mm", "pitch_deg"]
    data = np.loadtxt(csv, delimiter=",", skiprows=1)
    assert data.shape == (401, len(header))
    assert data[0, 1:5] == pytest.approx([90.0, 15.89, -18.47, -87.42], abs=0.01)
    assert (tmp_path / "pick_and_place_cubic_joints.png").is_file()
    assert "4.000 s" in capsys.readouterr().out


def test_writes_npz_in_si_with_the_comparison(tmp_path):
    code = main(
        [
            "traj",
            str(TASKS / "pick_and_place.toml"),
            "--type",
            "ruckig",
            "--out-dir",
            str(tmp_path),
            "--format",
            "npz",
            "--si",
            "--shortest",
            "--pass-through",
            "--rate-hz",
            "50",
        ]
    )
    assert code == 0
    with np.load(tmp_path / "pick_and_place_ruckig.npz") as f:
        assert f["q_rad"].shape[1] == 5
        assert f["tool_position_m"].shape[1] == 3
        assert str(f["kind"]) == "ruckig"
        assert f["waypoint_names"].tolist() == ["P1", "P2", "P3", "P4", "P5"]
        assert f["waypoint_times_s"][-1] < 4.0  # shortest, not the task's 1 s per segment
    assert (tmp_path / "pick_and_place_paths.png").is_file()


def test_malformed_task_is_a_one_line_error_naming_file_and_field(tmp_path, capsys):
    bad = tmp_path / "bad.toml"
    text = (
        (TASKS / "pick_and_place.toml")
        .read_text()
        .replace("pitch_deg = 0.0", 'pitch_deg = "flat"', 1)
    )
    bad.write_text(text)
    assert main(["traj", str(bad), "--out-dir", str(tmp_path)]) == 1
    err = capsys.readouterr().err
    assert err.count("\n") == 1
    assert err.startswith(f"lynxsim: error: {bad}: poses[1].pitch_deg: must be a number")


def test_limit_violation_is_a_one_line_error(tmp_path, capsys):
    code = main(
        [
            "traj",
            str(TASKS / "pick_and_place.toml"),
            "--type",
            "line",
            "--segment-duration-s",
            "0.5",
            "--no-stretch",
            "--out-dir",
            str(tmp_path),
            "--no-compare",
        ]
    )
    assert code == 1
    err = capsys.readouterr().err
    assert err.count("\n") == 1
    assert "line trajectory: joint" in err


def test_task_is_required_without_list(capsys):
    assert main(["traj"]) == 1
    assert "give a task file" in capsys.readouterr().err


def test_names_with_dollar_signs_are_drawn_as_written(tmp_path):
    """A ``$`` in a task or pose name is text, not Matplotlib mathtext (which fails to parse it)."""
    task = (TASKS / "pick_and_place.toml").read_text()
    task = task.replace('name = "pick_and_place"', 'name = "cost $_$ x"', 1)
    task = task.replace('name = "P2"', 'name = "$\\\\foo$"', 1)
    path = tmp_path / "dollars.toml"
    path.write_text(task)
    assert "cost $_$ x" in task
    assert "$\\\\foo$" in task
    code = main(["traj", str(path), "--type", "quintic", "--out-dir", str(tmp_path / "out")])
    assert code == 0
    pngs = sorted(p.name for p in (tmp_path / "out").glob("*.png"))
    assert len(pngs) == 2  # the joint profiles and the tool-path comparison
    for png in (tmp_path / "out").glob("*.png"):
        assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_a_name_the_font_cannot_draw_warns_nothing(tmp_path):
    """Letters missing from the plot font are drawn as boxes, without a warning per glyph."""
    task = (TASKS / "pick_and_place.toml").read_text()
    path = tmp_path / "cjk.toml"
    path.write_text(task.replace('name = "pick_and_place"', 'name = "中文任务"', 1))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        code = main(["traj", str(path), "--type", "quintic", "--out-dir", str(tmp_path / "out")])
    assert code == 0
    assert len(list((tmp_path / "out").glob("*.png"))) == 2
