"""``lynxsim play`` and ``lynxsim demo`` from the command line."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import imageio.v2 as imageio
import pytest

from lynxsim.cli import main
from tests.helpers import short_rrr_task
from tests.rrr_sim.test_rrr_playback import RRR_METRIC_NAMES

ROOT = Path(__file__).resolve().parents[2]

SHORT_TASK = """
name = "short"
robot = "arm"
[trajectory]
type = "quintic"
segment_duration_s = 1.0
stretch = true
[[poses]]
position_mm = [0.0, -250.0, 300.0]
pitch_deg = 0.0
[[poses]]
position_mm = [0.0, -300.0, 0.0]
pitch_deg = -90.0
[[obstacles]]
name = "cylinder"
shape = "cylinder"
position_mm = [150.0, 150.0, 0.0]
radius_mm = 40.0
height_mm = 400.0
"""


def test_play_json_reports_collision_and_exits_zero(capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)  # the report goes to ./videos: not the repository's
    code = main(["play", str(ROOT / "tasks" / "pick_and_place.toml"), "--no-video", "--json"])
    assert code == 0
    assert (tmp_path / "videos" / "pick_and_place_quintic.json").is_file()
    report = json.loads(capsys.readouterr().out)
    assert report["collided"] is True
    assert report["trajectory"] == "quintic"
    assert report["obstacle"]["first_pair"][1] == "cylinder"
    assert report["obstacle"]["first_obstacle"] == "cylinder"
    assert report["healthy"] is True


def test_play_prints_table_and_writes_video_and_report(tmp_path, capsys):
    task = tmp_path / "short.toml"
    task.write_text(SHORT_TASK)
    video = tmp_path / "short.mp4"
    argv = ["play", str(task), "--type", "ruckig", "--out", str(video), "--quality", "fast"]
    assert main([*argv, "--quiet"]) == 0
    out = capsys.readouterr().out
    assert "obstacles: clear" in out
    assert "  cylinder: clear, minimum clearance" in out
    assert "tool tracking error: max" in out
    assert json.loads(video.with_suffix(".json").read_text())["trajectory"] == "ruckig"
    assert imageio.get_reader(video).count_frames() > 30


def test_play_bad_task_file_is_one_line_naming_file_and_field(tmp_path):
    task = tmp_path / "bad.toml"
    task.write_text(SHORT_TASK.replace("pitch_deg = -90.0", 'pitch_deg = "down"'))
    proc = subprocess.run(
        [sys.executable, "-m", "lynxsim", "play", str(task), "--no-video"],
        capture_output=True,
        text=True,
        check=False,
    )
    assert proc.returncode != 0
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1, proc.stderr
    assert "bad.toml" in lines[0]
    assert "poses[1].pitch_deg" in lines[0]


@pytest.mark.slow
def test_demo_renders_every_type_with_plots_and_summary(tmp_path, capsys):
    tasks = tmp_path / "tasks"
    tasks.mkdir()
    (tasks / "short.toml").write_text(SHORT_TASK)
    out = tmp_path / "out"
    argv = ["demo", "--tasks", str(tasks), "--out-dir", str(out), "--quality", "fast", "--quiet"]
    assert main(argv) == 0
    printed = capsys.readouterr().out
    kinds = ["free", "cubic", "quintic", "lspb", "line", "ruckig"]
    for kind in kinds:
        assert (out / f"short_{kind}.mp4").is_file()
        assert (out / f"short_{kind}.json").is_file()
        assert (out / "plots" / f"short_{kind}.png").is_file()
        assert f"short                {kind:14s}" in printed
    assert (out / "plots" / "short_paths.png").is_file()
    assert "Table 4" in printed
    for alpha in ("+0", "+20", "-20", "+50", "-50"):
        assert (out / "plots" / f"rrr_workspace_alpha{alpha}.png").is_file()
    assert "e (300 mm, 250 mm, -40 deg): simulation says UNREACHABLE" in printed
    assert "scripted expert, seed 0: success True" in printed
    assert imageio.get_reader(out / "LynxPickAndPlace-v1_expert.mp4").count_frames() > 50
    assert "skipped: the obstacle map needs" in printed


def test_cli_play_runs_rrr_tasks_and_prints_the_robot_metrics(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)  # the report goes to ./videos: not the repository's
    task = tmp_path / "short_rrr.toml"
    task.write_text(short_rrr_task())
    assert main(["play", str(task), "--no-video", "--json"]) == 0
    assert (tmp_path / "videos" / "short_rrr_quintic.json").is_file()
    report = json.loads(capsys.readouterr().out)
    assert report["trajectory"] == "quintic"
    assert set(report["metrics"]) == set(RRR_METRIC_NAMES)
    assert report["metrics"]["working_mode"] == 7
    assert main(["play", str(task), "--no-video", "--quiet", "--mode", "0"]) == 0
    out = capsys.readouterr().out
    assert "loop closure: max " in out
    assert "working mode: 0" in out
    assert "platform orientation error: max " in out


def test_cli_play_refuses_types_the_rrr_does_not_plan(tmp_path, capsys):
    task = tmp_path / "short_rrr.toml"
    task.write_text(short_rrr_task())
    assert main(["play", str(task), "--no-video", "--type", "ruckig"]) == 1
    assert "'ruckig' is not planned for the 3-RRR robot" in capsys.readouterr().err


def test_demo_with_a_missing_tasks_folder_is_one_line_before_any_work(cli, tmp_path):
    result = cli("demo", "--tasks", str(tmp_path / "nowhere"), "--out-dir", str(tmp_path / "out"))
    assert result.code == 1
    assert result.err.strip().count("\n") == 0
    assert "no such folder of task files" in result.err
    assert result.out == ""  # not even the kinematic tables
    assert not (tmp_path / "out").exists()
