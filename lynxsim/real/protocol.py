"""The SSC-32U serial protocol subset lynxsim speaks: typed commands, formatting, parsing.

Facts from the SSC-32U user guide: commands are ASCII, end with a carriage
return (CR) and run when it arrives; spaces, tabs and line feeds are ignored and
letters may be of either case; ``#<ch>P<pw>S<spd>...T<time>`` moves one or more
channels (0..31) to pulse widths [us] (normally 500..2500), each at most at its
speed [us/s], the whole move taking at least ``time`` [ms] (1..65535), all
channels of the line starting and ending together; ``#<ch>PO<offset>`` shifts a
channel by -100..100 us; ``Q`` answers ``.`` (move done) or ``+`` (moving);
``QP<ch>`` answers one byte per channel, the pulse width / 10 us; ``STOP <ch>``
stops a channel where it is; ``VER`` answers the firmware version. Commands of
different types cannot share a line.

Pure Python: no pyserial.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

from lynxsim.errors import ProtocolError

__all__ = [
    "CR",
    "MAX_OFFSET_US",
    "MAX_TIME_MS",
    "QUERY_STATUS",
    "QUERY_VERSION",
    "Command",
    "GroupMove",
    "PulseOffset",
    "QueryPulses",
    "QueryStatus",
    "QueryVersion",
    "ServoTarget",
    "StopServo",
    "decode_pulse_byte",
    "format_move",
    "format_query_pulses",
    "format_stop",
    "parse_line",
]

CR = "\r"
"""The line terminator (ASCII 13)."""
QUERY_STATUS = "Q"
"""Query movement status: answers ``.`` when the last move is done, ``+`` while moving."""
QUERY_VERSION = "VER"
"""Query the firmware version: answers a line ended by CR."""
MAX_TIME_MS = 65535
"""Longest move time ``T`` [ms]."""
MAX_OFFSET_US = 100
"""Largest magnitude of a ``PO`` offset [us]."""
_MAX_VALUE = 65535
"""Largest pulse or speed argument read (the board's 16-bit arguments)."""
_MAX_LINE = 512
"""Longest line parsed [characters]."""


@dataclass(frozen=True)
class ServoTarget:
    """One channel of a move.

    Attributes:
        channel: 0..31.
        pulse_us: Target pulse width [us] (0 turns the channel's pulses off).
        speed_us_s: Fastest pulse change allowed [us/s], or None.
    """

    channel: int
    pulse_us: int
    speed_us_s: int | None = None


@dataclass(frozen=True)
class GroupMove:
    """``#<ch>P<pw>[S<spd>]...[T<time>]``: channels that start and end together.

    Attributes:
        targets: One per channel, no channel twice.
        time_ms: Least duration of the move [ms], or None.
    """

    targets: tuple[ServoTarget, ...]
    time_ms: int | None = None


@dataclass(frozen=True)
class PulseOffset:
    """``#<ch>PO<offset>...``: per channel, a shift of its output [us], -100..100."""

    offsets: tuple[tuple[int, int], ...]


@dataclass(frozen=True)
class StopServo:
    """``STOP <ch>``: stop the channel at its present pulse width."""

    channel: int


@dataclass(frozen=True)
class QueryStatus:
    """``Q``: is the last move done?"""


@dataclass(frozen=True)
class QueryPulses:
    """``QP<ch>...``: the channels' present pulse widths, one byte each (pulse / 10 us)."""

    channels: tuple[int, ...]


@dataclass(frozen=True)
class QueryVersion:
    """``VER``: the firmware version."""


Command = GroupMove | PulseOffset | StopServo | QueryStatus | QueryPulses | QueryVersion
"""Every command lynxsim formats and its emulator understands."""

_MOVE = re.compile(r"#(\d{1,5})P(\d{1,5})(?:S(\d{1,5}))?")
_OFFSET = re.compile(r"#(\d{1,5})PO([+-]?\d{1,5})")
_TIME = re.compile(r"T(\d{1,5})")
_QP = re.compile(r"QP(\d{1,5})")


def _channel(text: str, line: str) -> int:
    channel = int(text)
    if channel > 31:
        raise ProtocolError(f"channel {channel} is not in 0..31: {line!r}")
    return channel


def _value(text: str, what: str, low: int, high: int, line: str) -> int:
    value = int(text)
    if not low <= value <= high:
        raise ProtocolError(f"{what} {value} is not in {low}..{high}: {line!r}")
    return value


def _scan(pattern: re.Pattern[str], text: str, line: str) -> list[re.Match[str]]:
    """Consecutive matches of ``pattern`` covering the whole of ``text``."""
    matches, pos = [], 0
    while pos < len(text):
        m = pattern.match(text, pos)
        if m is None:
            raise ProtocolError(f"cannot read {text[pos : pos + 20]!r} in {line!r}")
        matches.append(m)
        pos = m.end()
    return matches


def _group(body: str, line: str) -> GroupMove | PulseOffset:
    time_ms = None
    t = re.search(r"T(\d{1,5})$", body)
    if t is not None:
        time_ms = _value(t.group(1), "time", 1, MAX_TIME_MS, line)
        body = body[: t.start()]
    if not body:
        raise ProtocolError(f"a time without a servo: {line!r}")
    if "PO" in body:
        if time_ms is not None:
            raise ProtocolError(f"an offset cannot take a time: {line!r}")
        offsets = [
            (_channel(m.group(1), line), _value(m.group(2), "offset", -100, 100, line))
            for m in _scan(_OFFSET, body, line)
        ]
        if len({c for c, _ in offsets}) != len(offsets):
            raise ProtocolError(f"a channel twice in one line: {line!r}")
        return PulseOffset(tuple(offsets))
    targets = [
        ServoTarget(
            _channel(m.group(1), line),
            _value(m.group(2), "pulse", 0, _MAX_VALUE, line),
            None if m.group(3) is None else _value(m.group(3), "speed", 1, _MAX_VALUE, line),
        )
        for m in _scan(_MOVE, body, line)
    ]
    if len({s.channel for s in targets}) != len(targets):
        raise ProtocolError(f"a channel twice in one line: {line!r}")
    return GroupMove(tuple(targets), time_ms)


def parse_line(line: str) -> Command:
    """Read one command line (without its CR).

    Spaces, tabs and line feeds are dropped and letters read as capitals, as the
    board does.

    Raises:
        ProtocolError: The line is not a command of this subset, mixes command
            types, or an argument is out of its range (channel 0..31, time
            1..65535 ms, speed 1..65535 us/s, offset -100..100 us).
    """
    if len(line) > _MAX_LINE:
        raise ProtocolError(f"line of {len(line)} characters, more than {_MAX_LINE}")
    text = re.sub(r"[ \t\n]", "", line).upper()
    if not (text.isascii() and text.isprintable()):
        raise ProtocolError(f"not printable ASCII: {line!r}")
    if text == QUERY_STATUS:
        return QueryStatus()
    if text == QUERY_VERSION:
        return QueryVersion()
    if text.startswith("STOP"):
        if not re.fullmatch(r"STOP\d{1,5}", text):
            raise ProtocolError(f"STOP takes one channel number: {line!r}")
        return StopServo(_channel(text[4:], line))
    if text.startswith("QP"):
        return QueryPulses(tuple(_channel(m.group(1), line) for m in _scan(_QP, text, line)))
    if text.startswith("#"):
        return _group(text, line)
    raise ProtocolError(f"not a command: {line!r}")


def format_move(targets: tuple[ServoTarget, ...], time_ms: int | None = None) -> str:
    """A group move line, without the CR: ``#0P1500#1P1620T100``.

    Raises:
        ProtocolError: No target, a channel twice, or a value out of its range.
    """
    text = "".join(
        f"#{s.channel}P{s.pulse_us}" + ("" if s.speed_us_s is None else f"S{s.speed_us_s}")
        for s in targets
    ) + ("" if time_ms is None else f"T{time_ms}")
    command = parse_line(text)  # one definition of the valid lines: the parser's
    if not isinstance(command, GroupMove) or command.targets != targets:
        raise ProtocolError(f"not a group move: {text!r}")
    return text


def format_stop(channel: int) -> str:
    """``STOP <ch>`` without the CR."""
    return f"STOP {_value(str(channel), 'channel', 0, 31, str(channel))}"


def format_query_pulses(channels: tuple[int, ...]) -> str:
    """``QP<ch> QP<ch>...`` without the CR (one answer byte per channel)."""
    if not channels:
        raise ProtocolError("QP needs at least one channel")
    return " ".join(f"QP{_value(str(c), 'channel', 0, 31, str(c))}" for c in channels)


def decode_pulse_byte(value: int) -> int:
    """A ``QP`` answer byte as a pulse width [us] (10 us resolution)."""
    if not 0 <= value <= 255:
        raise ProtocolError(f"a QP answer is one byte, got {value}")
    return 10 * value
