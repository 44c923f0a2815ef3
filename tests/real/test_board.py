"""The emulated SSC-32U against its user guide's documented examples and timing."""

from __future__ import annotations

import pytest

from lynxsim.real.board import FRAME_S, Ssc32Board, virtual_run

FRAME_TOL_S = 1e-9
"""Frame times are exact multiples of 20 ms, up to rounding [s]."""


def _board(*lines: tuple[float, str]) -> Ssc32Board:
    board = Ssc32Board()
    for t, line in lines:
        board.execute(line, t)
    return board


def test_timed_group_move_of_the_guide_starts_and_ends_together():
    # Guide: "#5 P1600 #10 P750 T2500" takes 2.5 s for both servos.
    board = _board((0.0, "#5P1500#10P1500"), (1.0, "#5 P1600 #10 P750 T2500"))
    move = board.moves[-1]
    assert move.end_s - move.start_s == pytest.approx(2.5, abs=FRAME_TOL_S)
    at = move.start_s + 1.0  # a frame boundary, 40 % of the way
    assert board.pulse_us(5, at) == 1540
    assert board.pulse_us(10, at) == 1200
    assert board.pulses_us((5, 10), move.end_s) == (1600, 750)


@pytest.mark.parametrize(("ch17_from_us", "expected_s"), [(2000, 2.5), (1000, 2.0)])
def test_speed_and_time_combine_as_in_the_guide(ch17_from_us, expected_s):
    # Guide: "#5 P1600 #17 P750 S500 #2 P2250 T2000" lasts at least 2 s, and ch17
    # moves at most 500 us/s: 2.5 s from 2000 us, 2 s from 1000 us.
    board = _board(
        (0.0, f"#5P1500#17P{ch17_from_us}#2P1500"), (1.0, "#5 P1600 #17 P750 S500 #2 P2250 T2000")
    )
    move = board.moves[-1]
    assert move.end_s - move.start_s == pytest.approx(expected_s, abs=FRAME_TOL_S)
    assert board.pulses_us((5, 17, 2), move.end_s) == (1600, 750, 2250)
    assert board.pulse_us(5, move.end_s - FRAME_S) < 1600  # all arrive together


def test_speed_alone_sets_the_time_of_a_single_servo():
    # Guide: "#5P1500S750"; 1000 us at 750 us/s take 1.333 s.
    board = _board((0.0, "#5P500"), (0.5, "#5P1500S750"))
    move = board.moves[-1]
    assert move.end_s - move.start_s == pytest.approx(4 / 3, abs=FRAME_S)


def test_first_command_of_a_channel_ignores_time_and_jumps():
    board = _board((0.0, "#3P1600T1000"))
    assert board.pulse_us(3, 0.0) == 1600
    assert board.pulse_us(3, FRAME_S) == 1600


def test_pulses_change_only_every_20_ms_in_1_us_steps():
    times, pulses, _ = virtual_run([(0.0, "#0P1000"), (0.1, "#0P1100T1000")], (0,), 1.5)
    assert times[1] - times[0] == pytest.approx(FRAME_S)
    steps = abs(pulses[1:, 0] - pulses[:-1, 0])
    assert set(steps.tolist()) <= {0, 2}  # 100 us over 50 frames: 2 us a frame
    assert pulses[-1, 0] == 1100
    assert pulses[:, 0].dtype.kind == "i"


def test_stop_freezes_the_servo_but_q_waits_for_the_original_time():
    board = _board((0.0, "#0P1000#1P1000"), (0.0, "#0P2000#1P2000T1000"), (0.5, "STOP 0"))
    frozen = board.pulse_us(0, 0.5)
    assert 1400 <= frozen <= 1600
    assert board.pulse_us(0, 0.9) == frozen
    assert board.pulse_us(1, 1.0) == 2000  # the other servo goes on
    assert board.execute("Q", 0.9) == b"+"
    assert board.execute("Q", 1.0) == b"."


def test_q_answers_plus_while_moving_and_dot_when_done():
    board = _board((0.0, "#0P1500"), (0.0, "#0P2000T200"))
    assert board.execute("Q", 0.1) == b"+"
    assert board.execute("Q", 0.2) == b"."


def test_qp_answers_one_byte_per_channel_of_pulse_over_10_us():
    # Guide: 1500 us reads back as 150.
    board = _board((0.0, "#0P1500#1P2345"))
    assert board.execute("QP0", 0.0) == bytes([150])
    assert board.execute("QP 0 QP 1", 0.0) == bytes([150, 234])
    assert board.execute("QP7", 0.0) == bytes([0])  # a channel never moved sends no pulses


def test_ver_answers_a_line():
    answer = Ssc32Board().execute("ver", 0.0)
    assert answer.endswith(b"\r")
    assert answer.startswith(b"SSC32")


def test_spaces_tabs_line_feeds_and_case_are_ignored():
    board = Ssc32Board()
    assert board.feed(b"# 0 p 1 2 3 4\t\n\r", 0.0) == b""
    assert board.pulse_us(0, 0.0) == 1234
    assert board.feed(b"q\r", 0.0) in (b".", b"+")


def test_a_line_runs_only_when_its_cr_arrives():
    board = Ssc32Board()
    board.feed(b"#0P1700", 0.0)
    assert board.pulse_us(0, 0.1) == 0
    board.feed(b"\r", 0.2)
    assert board.pulse_us(0, 0.2) == 1700


@pytest.mark.parametrize(
    "line",
    [
        "#32P1500",  # channels are 0..31
        "#0P1500T0",  # time is 1..65535 ms
        "#0P1500T65536",
        "#0P1500S0",
        "#0P1500#0P1600",  # one channel twice
        "#0PO50#1P1500",  # offset and move mixed
        "#0PO101",
        "#0P15X0",
        "QP32",
        "STOP",
        "T1000",
        "HELLO",
        "#0P1500 Q",
    ],
)
def test_malformed_lines_are_dropped_whole_without_answer(line):
    board = _board((0.0, "#0P1000#1P1000"))
    assert board.feed(line.encode() + b"\r", 0.1) == b""
    assert board.rejected[-1][1] == line
    assert board.pulses_us((0, 1), 1.0) == (1000, 1000)


def test_out_of_range_pulses_are_clamped_and_p0_turns_the_pulses_off():
    board = _board((0.0, "#0P100#1P2800#2P1500"), (0.1, "#2P0"))
    assert board.pulses_us((0, 1, 2), 0.2) == (500, 2500, 0)
    board.execute("#2P1800T1000", 0.3)  # after P0 the board no longer knows the servo: it jumps
    assert board.pulse_us(2, 0.3) == 1800


def test_position_offset_shifts_the_output():
    board = _board((0.0, "#0P1500"), (0.0, "#0PO-40"))
    assert board.pulse_us(0, 0.0) == 1460


def test_a_silent_board_never_answers():
    board = Ssc32Board(answers=False)
    assert board.feed(b"VER\rQ\rQP0\r", 0.0) == b""
