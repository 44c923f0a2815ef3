"""Formatting and parsing SSC-32U lines: the manual's examples, round trips, errors."""

from __future__ import annotations

import pytest
from hypothesis import given
from hypothesis import strategies as st

from lynxsim.errors import ProtocolError
from lynxsim.real.protocol import (
    GroupMove,
    QueryPulses,
    QueryStatus,
    QueryVersion,
    ServoTarget,
    StopServo,
    decode_pulse_byte,
    format_move,
    format_query_pulses,
    format_stop,
    parse_line,
)


def test_the_guides_examples_parse():
    assert parse_line("#5P1500S750") == GroupMove((ServoTarget(5, 1500, 750),))
    assert parse_line("#3P1600T1000") == GroupMove((ServoTarget(3, 1600),), 1000)
    assert parse_line("#5 P1600 #17 P750 S500 #2 P2250 T2000") == GroupMove(
        (ServoTarget(5, 1600), ServoTarget(17, 750, 500), ServoTarget(2, 2250)), 2000
    )
    assert parse_line("STOP 31") == StopServo(31)
    assert parse_line("stop0") == StopServo(0)
    assert parse_line("Q") == QueryStatus()
    assert parse_line("QP 0 QP 1") == QueryPulses((0, 1))
    assert parse_line("VER") == QueryVersion()


targets = st.lists(
    st.builds(
        ServoTarget,
        st.integers(0, 31),
        st.integers(500, 2500),
        st.one_of(st.none(), st.integers(1, 65535)),
    ),
    min_size=1,
    max_size=8,
    unique_by=lambda s: s.channel,
).map(tuple)


@given(targets, st.one_of(st.none(), st.integers(1, 65535)))
def test_format_then_parse_gives_the_move_back(move_targets, time_ms):
    text = format_move(move_targets, time_ms)
    assert text.isascii()
    assert "\r" not in text
    assert parse_line(text) == GroupMove(move_targets, time_ms)


@given(st.text(max_size=40))
def test_any_text_parses_or_raises_protocol_error(text):
    message, command = None, None
    try:
        command = parse_line(text)
    except ProtocolError as exc:
        message = str(exc)
    assert (message is None) != (command is None)
    assert message is None or message


def test_formatting_refuses_what_the_board_would_not_read():
    with pytest.raises(ProtocolError, match="channel 40"):
        format_move((ServoTarget(40, 1500),))
    with pytest.raises(ProtocolError, match="time 0"):
        format_move((ServoTarget(1, 1500),), 0)
    with pytest.raises(ProtocolError, match="a channel twice"):
        format_move((ServoTarget(1, 1500), ServoTarget(1, 1600)))
    with pytest.raises(ProtocolError, match="channel"):
        format_stop(32)
    with pytest.raises(ProtocolError, match="at least one"):
        format_query_pulses(())
    assert format_stop(4) == "STOP 4"
    assert format_query_pulses((0, 5)) == "QP0 QP5"


def test_qp_bytes_decode_at_10_us():
    assert decode_pulse_byte(150) == 1500
    with pytest.raises(ProtocolError, match="one byte"):
        decode_pulse_byte(256)
