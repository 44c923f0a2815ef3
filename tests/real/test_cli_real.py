"""``lynxsim real`` end to end: dry runs, refusals, signals, the acceptance run, compare."""

from __future__ import annotations

import csv
import json
import os
import signal
import subprocess
import sys
import time

import numpy as np
import pytest

from lynxsim.real.arm import DEFAULT_CALIBRATION
from lynxsim.real.log import read_log

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
OBSTACLE_AVOIDANCE = os.path.join(ROOT, "tasks", "obstacle_avoidance.toml")
PICK_AND_PLACE = os.path.join(ROOT, "tasks", "pick_and_place.toml")
CHANNELS = (0, 1, 2, 3, 5, 4)
"""The default calibration's joint channels and its gripper's."""


def _lynxsim(*argv: str, **kwargs) -> subprocess.Popen[str]:
    env = {**os.environ, "MUJOCO_GL": "egl"}
    return subprocess.Popen(
        [sys.executable, "-m", "lynxsim", *argv],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        env=env,
        cwd=ROOT,
        **kwargs,
    )


def test_dry_run_prints_the_stream_and_needs_no_port(cli, short_task):
    result = cli("real", "play", short_task(), "--calibration", "default", "--dry-run")
    assert result.code == 0, result.err
    rows = result.out.splitlines()
    assert rows[0].split()[2] == "approach"
    assert rows[0].split()[3].startswith("#0P")
    moves = [r for r in rows if r.split()[2] == "move"]
    assert len(moves) == 10  # 1 s at 100 ms
    assert all(r.split()[3].endswith("T100") for r in moves)
    assert "controller interpolation vs trajectory" in result.err


def test_play_without_port_or_dry_run_is_a_one_line_error(cli, short_task):
    result = cli("real", "play", short_task(), "--calibration", "default")
    assert result.code == 1
    assert result.err.strip().splitlines() == [
        "lynxsim: error: --port DEV is needed (or --dry-run to print the stream)"
    ]


def test_a_colliding_motion_is_refused_unless_forced(cli):
    refused = cli(
        "real", "play", PICK_AND_PLACE, "--calibration", "default", "--dry-run", "--quiet"
    )
    assert refused.code == 1
    assert refused.out == ""
    (line,) = refused.err.strip().splitlines()
    assert "collides in simulation" in line
    assert "--force" in line
    forced = cli(
        "real",
        "play",
        PICK_AND_PLACE,
        "--calibration",
        "default",
        "--dry-run",
        "--force",
        "--quiet",
    )
    assert forced.code == 0
    assert "approach" in forced.out


def test_out_of_range_pulses_are_refused_with_joint_and_time(cli, short_task, tmp_path):
    text = DEFAULT_CALIBRATION.read_text().replace("max_us = 2500", "max_us = 1600", 1)
    cal = tmp_path / "narrow.toml"
    cal.write_text(text)
    result = cli("real", "play", short_task(), "--calibration", str(cal), "--dry-run")
    assert result.code == 1
    assert "joint base: pulse" in result.err
    assert "calibrated range 500..1600 us" in result.err


def test_a_bad_calibration_file_is_one_line_naming_file_and_field(cli, short_task, tmp_path):
    cal = tmp_path / "bad.toml"
    cal.write_text(DEFAULT_CALIBRATION.read_text().replace("channel = 2", "channel = 99"))
    result = cli("real", "play", short_task(), "--calibration", str(cal), "--dry-run")
    assert result.code == 1
    assert result.err.strip() == (
        f"lynxsim: error: {cal}: joints.elbow.channel: must lie within 0..31, got 99"
    )


def test_a_silent_board_is_a_one_line_timeout(cli, short_task, tmp_path):
    from lynxsim.real.pty_server import PtyEmulator

    with PtyEmulator(answers=False) as emu:
        result = cli(
            "real",
            "play",
            short_task(),
            "--calibration",
            "default",
            "--port",
            emu.path,
            "--timeout-s",
            "0.2",
            "--quiet",
            "--log",
            str(tmp_path / "x.jsonl"),
        )
    assert result.code == 1
    (line,) = result.err.strip().splitlines()
    assert "no answer to 'VER'" in line
    assert not (tmp_path / "x.jsonl").exists()


@pytest.mark.slow
@pytest.mark.parametrize(
    ("signum", "code", "word"),
    [(signal.SIGINT, 130, "interrupted"), (signal.SIGTERM, 143, "terminated")],
    ids=["ctrl-c", "sigterm"],
)
def test_a_signal_during_play_stops_every_channel_before_exiting(
    emulator, tmp_path, signum, code, word
):
    log = tmp_path / "run.jsonl"
    proc = _lynxsim(
        "real",
        "play",
        OBSTACLE_AVOIDANCE,
        "--port",
        emulator.path,
        "--calibration",
        "default",
        "--log",
        str(log),
        "--quiet",
    )
    try:
        deadline = time.monotonic() + 120
        while time.monotonic() < deadline:
            with emulator.lock:
                moves = [ln for _, ln in emulator.board.lines if ln.endswith("T100")]
            if len(moves) >= 5:
                break
            assert proc.poll() is None, proc.communicate()
            time.sleep(0.02)
        proc.send_signal(signum)
        _out, err = proc.communicate(timeout=30)
    finally:
        if proc.poll() is None:
            proc.kill()
    assert proc.returncode == code
    assert err.strip().splitlines() == [f"lynxsim: {word}"]
    stops = [f"STOP {c}" for c in CHANNELS]
    deadline = time.monotonic() + 10.0  # the emulator reads what was sent on its own thread
    while True:
        with emulator.lock:
            received = [ln for _, ln in emulator.board.lines]
        if received[-len(stops) :] == stops or time.monotonic() > deadline:
            break
        time.sleep(0.01)
    tail = received[received.index("STOP 0") :]
    assert tail == stops
    record = read_log(log)
    assert record.end == "interrupted"
    assert any("STOP sent" in e for _, e in record.events)


@pytest.mark.slow
def test_acceptance_play_obstacle_avoidance_against_the_emulator(tmp_path):
    """The issue's acceptance: the log and the emulator's final pulses agree.

    ``lynxsim real play tasks/obstacle_avoidance.toml --port <emulator pty>
    --calibration <default>``, against ``lynxsim real emulate``.
    """
    state = tmp_path / "state.json"
    emulate = _lynxsim("real", "emulate", "--state", str(state))
    try:
        assert emulate.stdout is not None
        pty = emulate.stdout.readline().strip()
        assert pty.startswith("/dev/")
        log = tmp_path / "run.jsonl"
        play = _lynxsim(
            "real",
            "play",
            OBSTACLE_AVOIDANCE,
            "--port",
            pty,
            "--calibration",
            str(DEFAULT_CALIBRATION),
            "--log",
            str(log),
        )
        out, err = play.communicate(timeout=240)
        assert play.returncode == 0, err
        assert "(agree to QP's 10 us)" in out
    finally:
        emulate.send_signal(signal.SIGTERM)
        emulate.communicate(timeout=30)
    board = json.loads(state.read_text())
    record = read_log(log)
    assert record.end == "completed"
    assert board["rejected"] == 0
    commands = [ln for ln in board["received"] if not ln.startswith(("Q", "VER"))]
    assert commands == [text for _, text in record.sent]
    commanded = record.header["commanded_final_us"]
    final = [board["pulses_us"][str(c)] for c in record.header["channels"]]
    assert final == commanded
    assert list(record.final_pulses_us) == [10 * (p // 10) for p in final]


def _twin_csv(path, record, joints, shift_deg=0.0):
    t = np.asarray(record.header["twin"]["time_s"])
    q = np.asarray(record.header["twin"]["q_deg"])
    names = record.header["joint_names"]
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["time_s", *(f"{j}_deg" for j in joints)])
        for i in range(0, len(t), 3):
            w.writerow([t[i], *(q[i, names.index(j)] + shift_deg for j in joints)])


def test_compare_measured_angles_with_the_logged_simulation(cli, emulator, short_task, tmp_path):
    log = tmp_path / "run.jsonl"
    played = cli(
        "real",
        "play",
        short_task(),
        "--port",
        emulator.path,
        "--calibration",
        "default",
        "--log",
        str(log),
        "--quiet",
    )
    assert played.code == 0, played.err
    record = read_log(log)
    measured = tmp_path / "measured.csv"
    _twin_csv(measured, record, ["base", "elbow"], shift_deg=1.5)
    result = cli("real", "compare", str(log), str(measured), "--json")
    assert result.code == 0, result.err
    rows = json.loads(result.out)
    assert [r["joint"] for r in rows] == ["base", "elbow"]
    for r in rows:
        assert r["max_error_rad"] == pytest.approx(np.radians(1.5), abs=1e-5)
        assert r["samples"] > 10
    bad = tmp_path / "bad.csv"
    bad.write_text("time_s,base_deg\n0.0,1.0\n0.1,oops\n")
    result = cli("real", "compare", str(log), str(bad))
    assert result.code == 1
    assert result.err.strip() == (
        f"lynxsim: error: {bad}: row 3, base_deg: not a finite number: 'oops'"
    )
    cut = tmp_path / "cut.jsonl"
    cut.write_text("\n".join(log.read_text().splitlines()[:-1]) + "\n")
    result = cli("real", "compare", str(cut), str(measured))
    assert result.code == 1
    assert "no end record" in result.err


def test_play_with_the_ssc32_controller_reports_the_twin_and_the_difference(
    cli, short_task, tmp_path
):
    out = tmp_path / "short.mp4"
    result = cli("play", short_task(), "--controller", "ssc32", "--no-video", "--out", str(out))
    assert result.code == 0, result.err
    assert "ssc32 twin vs ideal playback: tool error max" in result.out
    assert "trajectory quintic+ssc32" in result.out
    report = json.loads(out.with_suffix(".json").read_text())
    assert report["trajectory"] == "quintic+ssc32"


def test_the_ssc32_controller_is_refused_for_rrr_tasks(cli):
    result = cli(
        "play",
        os.path.join(ROOT, "tasks", "rrr_closed_curve.toml"),
        "--controller",
        "ssc32",
        "--no-video",
    )
    assert result.code == 1
    assert "--controller ssc32 applies only to arm tasks" in result.err
