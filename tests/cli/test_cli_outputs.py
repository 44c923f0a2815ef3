"""Outputs are the user's, complete or absent; errors after loading name the task file.

Outputs land inside the asked folder and never replace what is not a regular
file; a full disk or SIGTERM leaves no partial file.
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from lynxsim.sim.video import decoded_frames
from tests.helpers import full_disk, short_arm_task


def _task(folder: Path, name: str = "short", body: str | None = None) -> Path:
    path = folder / "task.toml"
    path.write_text(short_arm_task(name) if body is None else body)
    return path


@pytest.mark.parametrize("name", ["../escaped", "/tmp/lynxsim_abs", "a/../../b", ".hidden"])
def test_task_names_never_choose_the_folder(cli, tmp_path, monkeypatch, name):
    monkeypatch.chdir(tmp_path)
    task = _task(tmp_path, name)
    out = tmp_path / "work" / "out"
    result = cli("traj", str(task), "--out-dir", str(out), "--no-compare")
    assert result.code == 0, result.err
    written = {p for p in (tmp_path / "work").rglob("*") if p.is_file()}
    assert {p.parent for p in written} == {out}
    assert {p.suffix for p in written} == {".csv", ".png"}
    assert all(".." not in p.name and not p.name.startswith(".") for p in written)
    assert not Path("/tmp/lynxsim_abs_quintic.csv").exists()
    result = cli("play", str(task), "--no-video", "--quiet")
    assert result.code == 0, result.err
    written = {p for p in tmp_path.rglob("*") if p.is_file()} - written - {task}
    assert len(written) == 2  # the report and its replay data
    report, replay = sorted(written, key=lambda p: p.suffix)
    assert report.parent == replay.parent == tmp_path / "videos"
    assert report.suffix == ".json"
    assert replay.name == report.with_suffix(".replay.npz").name
    assert ".." not in report.name


def test_out_never_replaces_a_fifo_or_a_folder(cli, tmp_path):
    task = _task(tmp_path)
    fifo = tmp_path / "pipe.mp4"
    os.mkfifo(fifo)
    result = cli("play", str(task), "--out", str(fifo), "--quiet")
    assert result.code == 1
    assert result.err == f"lynxsim: error: will not replace {fifo}: it is not a regular file\n"
    assert fifo.is_fifo()
    folder = tmp_path / "clip.mp4"
    folder.mkdir()
    result = cli("play", str(task), "--out", str(folder), "--quiet")
    assert result.code == 1
    assert result.err == f"lynxsim: error: will not replace {folder}: it is a folder\n"
    assert folder.is_dir()
    assert not any(folder.iterdir())
    assert sorted(p.name for p in tmp_path.iterdir()) == ["clip.mp4", "pipe.mp4", "task.toml"]


def test_out_must_be_an_mp4(cli, tmp_path):
    result = cli("play", str(_task(tmp_path)), "--out", str(tmp_path / "x.avi"), "--quiet")
    assert result.code == 1
    assert result.err == f"lynxsim: error: --out must name an .mp4 file, got {tmp_path / 'x.avi'}\n"


def test_full_disk_leaves_the_previous_video_untouched(tmp_path):
    task = _task(tmp_path)
    dest = tmp_path / "clip.mp4"
    dest.write_bytes(b"the previous video")
    proc = subprocess.run(
        [sys.executable, "-m", "lynxsim", "play", str(task), "--out", str(dest), "--quiet"],
        capture_output=True,
        text=True,
        preexec_fn=full_disk(20_000),
        timeout=300,
        env={**os.environ, "MUJOCO_GL": "egl"},
    )
    assert proc.returncode == 1, proc.stderr
    assert proc.stderr.count("\n") == 1, proc.stderr
    assert proc.stderr.startswith("lynxsim: error: "), proc.stderr
    assert "Traceback" not in proc.stderr
    assert proc.stderr.startswith(f"lynxsim: error: {task}: cannot write {dest}: "), proc.stderr
    assert ".tmp" not in proc.stderr  # the temporary name is no concern of the user's
    assert "@ 0x" not in proc.stderr  # nor ffmpeg's internals
    assert "exit -" not in proc.stderr
    assert dest.read_bytes() == b"the previous video"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["clip.mp4", "task.toml"]


@pytest.mark.parametrize(
    ("argv", "written"),
    [
        (["traj", "{task}", "--out-dir", "{tmp}/plots", "--no-compare"], "{tmp}/plots/short_"),
        (["workspace", "--out", "{tmp}/ws.png", "--samples", "2000", "--quiet"], "{tmp}/ws.png"),
    ],
    ids=["traj", "workspace"],
)
def test_a_full_disk_names_the_file_not_its_temporary_name(tmp_path, argv, written):
    task = _task(tmp_path)
    argv = [a.format(task=task, tmp=tmp_path) for a in argv]
    proc = subprocess.run(
        [sys.executable, "-m", "lynxsim", *argv],
        capture_output=True,
        text=True,
        preexec_fn=full_disk(2_000),
        timeout=300,
        env={**os.environ, "MUJOCO_GL": "egl"},
    )
    assert proc.returncode == 1, proc.stderr
    (line,) = proc.stderr.splitlines()
    assert line.startswith(f"lynxsim: error: cannot write {written.format(tmp=tmp_path)}"), line
    assert line.endswith(": File too large"), line
    assert ".tmp" not in line


def test_full_disk_leaves_no_empty_folder(tmp_path):
    task = _task(tmp_path)
    dest = tmp_path / "new" / "deeper" / "clip.mp4"
    proc = subprocess.run(
        [sys.executable, "-m", "lynxsim", "play", str(task), "--out", str(dest), "--quiet"],
        capture_output=True,
        text=True,
        preexec_fn=full_disk(20_000),
        timeout=300,
        env={**os.environ, "MUJOCO_GL": "egl"},
    )
    assert proc.returncode == 1, proc.stderr
    assert proc.stderr.count("\n") == 1, proc.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["task.toml"]


def test_sigterm_removes_partial_outputs(tmp_path):
    body = short_arm_task().replace("segment_duration_s = 1.0", "segment_duration_s = 60.0")
    task = _task(tmp_path, body=body)
    dest = tmp_path / "clip.mp4"
    proc = subprocess.Popen(
        [sys.executable, "-m", "lynxsim", "play", str(task), "--out", str(dest), "--quiet"],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        env={**os.environ, "MUJOCO_GL": "egl"},
    )
    deadline = time.monotonic() + 120
    while not list(tmp_path.glob(".clip.*.tmp.mp4")):  # the encoder has started
        assert proc.poll() is None, proc.communicate()
        assert time.monotonic() < deadline
        time.sleep(0.05)
    proc.send_signal(signal.SIGTERM)
    _, err = proc.communicate(timeout=60)
    assert proc.returncode == 143
    assert err == "lynxsim: terminated\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["task.toml"]


def test_video_decodes_to_every_frame(cli, tmp_path):
    dest = tmp_path / "clip.mp4"
    result = cli("play", str(_task(tmp_path)), "--out", str(dest), "--fps", "20", "--quiet")
    assert result.code == 0, result.err
    motion_s, settle_s, fps = 1.0, 0.5, 20
    assert decoded_frames(dest) == round((motion_s + settle_s) * fps) + 1  # both ends drawn


def test_errors_after_loading_name_the_task_file(cli, tmp_path):
    body = short_arm_task().replace("[100.0, 250.0, 50.0]", "[0.0, 450.0, 100.0]")
    task = _task(tmp_path, body=body)
    for argv in (
        ["traj", str(task), "--out-dir", str(tmp_path)],
        ["play", str(task), "--no-video"],
    ):
        result = cli(*argv)
        assert result.code == 1
        assert result.err.startswith(f"lynxsim: error: {task}: "), result.err
        assert "out of the arm's reach" in result.err
        assert result.err.count("\n") == 1


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["traj", "T", "--rate-hz", "1e12"], "--rate-hz: must be between 1 and 10000 Hz, got 1e12"),
        (["workspace", "--samples", "999999999999"], "must be between 1 and 10,000,000"),
        (["rrr", "workspace", "--resolution-mm", "1e-300"], "must be between 0.1 and 100 mm"),
        (["play", "T", "--fps", "inf"], "--fps: must be a finite number, got 'inf'"),
        (["traj", "T", "--segment-duration-s", "5e-324"], "must be between 0.001 and 3600 s"),
        (["env", "--seed", "-1"], "--seed: must be between 0 and"),
        (["env", "--episodes", "1" + "0" * 400], "--episodes: must be an integer"),
    ],
    ids=["rate", "samples", "resolution", "fps", "duration", "seed", "huge-int"],
)
def test_counts_rates_and_durations_are_bounded(cli, tmp_path, argv, message):
    argv = [str(_task(tmp_path)) if a == "T" else a for a in argv]
    result = cli(*argv)
    assert result.code == 2
    assert result.err.count("\n") == 1
    assert message in result.err
    assert result.out == ""


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["fk", "0", "1e12", "300", "1e308", "1e3"], "Q2 must be between -720 and 720 deg"),
        (["ik", "0", "300", "1e300", "-90"], "Z must be between -10000 and 10000 mm"),
        (["rrr", "ik", "1e9", "0", "0"], "X must be between -10000 and 10000 mm, got 1e+09 mm"),
        (["rrr", "fk", "0", "0", "1e20", "--si"], "THETA3 must be between -12.5664 and 12.5664"),
        (["rrr", "workspace", "--alpha-deg", "1e300"], "--alpha-deg must be between -720 and"),
    ],
    ids=["fk", "ik", "rrr-ik", "rrr-fk", "rrr-alpha"],
)
def test_absurd_coordinates_are_refused_before_any_work(cli, argv, message):
    result = cli(*argv)
    assert result.code == 1
    assert result.err.startswith("lynxsim: error: ")
    assert message in result.err
    assert result.err.count("\n") == 1
    assert result.out == ""


def test_a_fifo_as_task_file_is_refused_not_read(cli, tmp_path):
    """Reading a FIFO blocks until someone writes to it: refused before any read."""
    fifo = tmp_path / "task.toml"
    os.mkfifo(fifo)
    for argv in (["traj", str(fifo)], ["play", str(fifo), "--no-video"], ["plan", str(fifo)]):
        result = cli(*argv)
        assert result.code == 1
        assert result.err == f"lynxsim: error: {fifo}: not a regular file\n"


@pytest.mark.parametrize(
    "argv",
    [
        ["workspace", "--samples", "100", "--out", "{folder}"],
        ["rrr", "workspace", "--out", "{folder}"],
        ["rrr", "poses", "--out", "{folder}"],
    ],
    ids=["workspace", "rrr-workspace", "rrr-poses"],
)
def test_a_wrong_out_is_refused_before_any_work(cli, tmp_path, argv):
    folder = tmp_path / "x.png"
    folder.mkdir()
    result = cli(*[a.format(folder=folder) for a in argv])
    assert result.code == 1
    assert result.err == f"lynxsim: error: will not replace {folder}: it is a folder\n"
    assert result.out == ""


def test_play_never_replaces_a_json_file_that_is_not_its_report(cli, tmp_path):
    task = _task(tmp_path)
    dest = tmp_path / "clip.mp4"
    first = cli("play", str(task), "--out", str(dest), "--no-video", "--quiet")
    assert first.code == 0, first.err
    again = cli("play", str(task), "--out", str(dest), "--no-video", "--quiet")
    assert again.code == 0, again.err  # its own report from before is replaced
    mine = dest.with_suffix(".json")
    mine.write_text('{"notes": "my own file"}\n')
    result = cli("play", str(task), "--out", str(dest), "--no-video", "--quiet")
    assert result.code == 1
    assert result.err == (
        f"lynxsim: error: will not replace {mine}: it is not a lynxsim run report "
        f"(the report of {dest} goes there; move it or choose another --out)\n"
    )
    assert mine.read_text() == '{"notes": "my own file"}\n'
