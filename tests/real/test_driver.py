"""lynxsim's own driver (pyserial) against the emulated board on a real pseudo-terminal."""

from __future__ import annotations

import threading
import time

import numpy as np
import pytest

from lynxsim.arm.motion import quintic
from lynxsim.errors import BoardTimeoutError, SerialLinkError
from lynxsim.real.arm import load_arm_calibration
from lynxsim.real.board import FRAME_S
from lynxsim.real.driver import Ssc32Link, play_stream
from lynxsim.real.log import RunLogWriter, read_log
from lynxsim.real.pty_server import PtyEmulator
from lynxsim.real.stream import StreamOptions, command_stream

CAL = load_arm_calibration()
QUICK = StreamOptions(approach_ms=200, hold_s=0.3)
"""A short approach: the tests' board is not a real arm."""
START = np.array([0.2, 1.2, -1.4, -0.6, 0.3])
END = np.array([-0.4, 0.9, -1.0, -0.2, 0.5])


def _lines_when(emu, done, timeout_s: float = 2.0) -> list[str]:
    """The board's received lines once ``done(lines)`` holds (the server reads on its thread)."""
    deadline = time.monotonic() + timeout_s
    while True:
        with emu.lock:
            lines = [line for _, line in emu.board.lines]
        if done(lines) or time.monotonic() > deadline:
            return lines
        time.sleep(0.01)


def _stream(duration_s: float = 1.0):
    return command_stream(quintic([START, END], durations=duration_s), CAL, QUICK)


def test_a_streamed_trajectory_ends_at_the_right_pulses_at_the_right_time(emulator, tmp_path):
    stream = _stream(1.2)
    with Ssc32Link(emulator.path, CAL.baud) as link:
        assert link.version().startswith("SSC32")
        result = play_stream(link, stream, RunLogWriter(tmp_path / "run.jsonl", {"test": 1}))
    board = emulator.board
    assert board.rejected == []
    assert emulator.pulses_us(CAL.channels) == stream.final_us
    assert result.agrees
    moves = board.moves[1:]  # after the approach
    assert len(moves) == len([ln for ln in stream.lines if ln.kind == "move"])
    took = moves[-1].end_s - moves[0].start_s
    assert abs(took - stream.duration_s) <= FRAME_S
    log = read_log(tmp_path / "run.jsonl")
    assert log.end == "completed"
    assert [text for _, text in log.sent] == [ln.text for ln in stream.lines]
    assert log.final_pulses_us == result.final_pulses_us
    assert [q for _, q, _ in log.queries][-2:] == ["Q", "QP0 QP1 QP2 QP3 QP5"]


def test_a_port_that_vanishes_mid_stream_is_a_one_line_error_and_the_log_says_so(tmp_path):
    emu = PtyEmulator()
    stream = _stream(2.0)
    timer = threading.Timer(0.8, emu.close)
    with Ssc32Link(emu.path, CAL.baud) as link:
        timer.start()
        with pytest.raises(SerialLinkError, match="did it vanish") as info:
            play_stream(link, stream, RunLogWriter(tmp_path / "run.jsonl", {}))
    timer.join()
    assert "\n" not in str(info.value)
    log = read_log(tmp_path / "run.jsonl")
    assert log.end == "error"
    assert 0 < len(log.sent) < len(stream.lines)
    assert any("STOP could not be sent" in e for _, e in log.events)


def test_a_board_that_never_answers_times_out(tmp_path):
    with PtyEmulator(answers=False) as emu, Ssc32Link(emu.path, CAL.baud, timeout_s=0.2) as link:
        with pytest.raises(BoardTimeoutError, match=r"no answer to 'VER' .* within 0\.2 s"):
            link.version()
        with pytest.raises(BoardTimeoutError, match=r"no answer to 'Q'"):
            play_stream(link, _stream(), RunLogWriter(tmp_path / "run.jsonl", {}))
        received = _lines_when(emu, lambda lines: lines[-1:] == ["STOP 5"])
    log = read_log(tmp_path / "run.jsonl")
    assert log.end == "error"
    assert [f"STOP {c}" for c in CAL.channels] == received[-5:]  # stopped all the same


def test_opening_a_missing_port_is_a_serial_link_error(tmp_path):
    with pytest.raises(SerialLinkError, match="cannot open"):
        Ssc32Link(str(tmp_path / "no-such-tty"), 9600)
