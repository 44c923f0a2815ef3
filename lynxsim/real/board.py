"""An SSC-32U servo controller, emulated in given time: its parser, its moves, its answers.

The board as its user guide describes it: a line runs when its CR arrives;
each channel's pulse is sent every 20 ms (:data:`FRAME_S`) with 1 us
resolution; a move goes linearly from where the channel is to its target,
all channels of a line starting and ending together, the move lasting the
longer of its ``T`` and the time its slowest ``S``-limited channel needs
(the guide's worked example: ``#5P1600 #17P750S500 #2P2250T2000`` takes 2.5 s
when channel 17 starts at 2000 us); the first command of a channel ignores
``S`` and ``T`` (the board does not know where the servo is) and the servo
jumps; ``STOP`` freezes a channel, while ``Q`` keeps answering ``+`` until the
original move's time is over.

What the guide leaves open, and this emulator decides (a client may rely on
none of it): a move starts at the first 20 ms frame at or after its CR; a line
it cannot read is dropped whole, with no answer (the guide documents no
error reply); pulse arguments 1..499 us are sent as 500 us and those above
2500 us as 2500 us (as users measured on real boards), 0 turns the channel's
pulses off; ``QP`` truncates to 10 us.

Pure Python: the caller gives the time (:class:`Ssc32Board` never reads a
clock), so the same board serves a real-time pseudo-terminal
(:mod:`lynxsim.real.pty_server`) and a virtual-time run
(:func:`virtual_run`).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np
import numpy.typing as npt

from lynxsim.errors import ProtocolError
from lynxsim.real.calibration import MAX_PULSE_US, MIN_PULSE_US
from lynxsim.real.protocol import (
    GroupMove,
    PulseOffset,
    QueryPulses,
    QueryStatus,
    QueryVersion,
    StopServo,
    parse_line,
)

__all__ = ["FRAME_S", "VERSION", "MoveRecord", "Ssc32Board", "virtual_run"]

FRAME_S = 0.020
"""Period of the servo pulses: every channel's pulse is sent every 20 ms [s]."""
VERSION = "SSC32-V2.50USB lynxsim-emulator"
"""What the emulator answers to ``VER`` (a real board names its firmware)."""
_MAX_BUFFER = 512
"""Characters of a line kept before the line is dropped as too long."""
_EPS = 1e-9


def frame_at_or_after(t: float) -> float:
    """The first frame boundary at or after ``t`` [s]."""
    return math.ceil(t / FRAME_S - _EPS) * FRAME_S


def frame_at_or_before(t: float) -> float:
    """The last frame boundary at or before ``t`` [s]."""
    return math.floor(t / FRAME_S + _EPS) * FRAME_S


@dataclass
class _Channel:
    """A channel's present move: linear from ``start_us`` at ``t0`` to ``target_us`` at ``t1``."""

    on: bool = False
    start_us: float = 0.0
    target_us: float = 0.0
    t0: float = 0.0
    t1: float = 0.0
    offset_us: int = 0

    def value(self, t: float) -> float:
        """Pulse width [us] at time ``t`` (unrounded, without offset)."""
        if t >= self.t1 or self.t1 <= self.t0:
            return self.target_us
        if t <= self.t0:
            return self.start_us
        return self.start_us + (self.target_us - self.start_us) * (t - self.t0) / (
            self.t1 - self.t0
        )


@dataclass(frozen=True)
class MoveRecord:
    """A group move the board ran.

    Attributes:
        received_s: When its CR arrived [s].
        start_s: The frame it counts from (the one being sent when it arrived) [s].
        end_s: The frame its targets were reached at [s].
        targets: Channel -> target pulse [us] (after clamping to 500..2500).
    """

    received_s: float
    start_s: float
    end_s: float
    targets: dict[int, int]


@dataclass
class Ssc32Board:
    """The emulated board. Feed it bytes with the time they arrive; read its pulses at any time.

    Args:
        version: The ``VER`` answer (without CR).
        answers: False: a board that never answers (wrong baud, logic supply off).

    Attributes:
        moves: Every group move run, in order.
        rejected: Every line dropped: (time [s], line, why).
        lines: Every complete line received: (time [s], line).
    """

    version: str = VERSION
    answers: bool = True
    moves: list[MoveRecord] = field(default_factory=list)
    rejected: list[tuple[float, str, str]] = field(default_factory=list)
    lines: list[tuple[float, str]] = field(default_factory=list)
    _channels: dict[int, _Channel] = field(default_factory=dict)
    _buffer: list[str] = field(default_factory=list)
    _group_end_s: float = 0.0

    def feed(self, data: bytes, now_s: float) -> bytes:
        """Bytes arriving at ``now_s`` [s]; returns the board's answers to complete lines."""
        out = []
        for byte in data:
            if byte == 13:
                line = "".join(self._buffer)
                self._buffer.clear()
                out.append(self.execute(line, now_s))
            elif len(self._buffer) <= _MAX_BUFFER:
                self._buffer.append(chr(byte))
        return b"".join(out)

    def execute(self, line: str, now_s: float) -> bytes:
        """Run one line (without CR) that arrived at ``now_s`` [s]; returns its answer."""
        self.lines.append((now_s, line))
        try:
            command = parse_line(line)
        except ProtocolError as exc:
            self.rejected.append((now_s, line, str(exc)))
            return b""
        answer = b""
        if isinstance(command, GroupMove):
            self._move(command, now_s)
        elif isinstance(command, PulseOffset):
            for channel, offset in command.offsets:
                self._channels.setdefault(channel, _Channel()).offset_us = offset
        elif isinstance(command, StopServo):
            ch = self._channels.get(command.channel)
            if ch is not None:
                held = ch.value(frame_at_or_before(now_s))
                ch.start_us = ch.target_us = held
                ch.t0 = ch.t1 = now_s
        elif isinstance(command, QueryStatus):
            answer = b"+" if self.busy(now_s) else b"."
        elif isinstance(command, QueryPulses):
            answer = bytes(min(255, self.pulse_us(c, now_s) // 10) for c in command.channels)
        elif isinstance(command, QueryVersion):
            answer = (self.version + "\r").encode("ascii")
        return answer if self.answers else b""

    def _move(self, command: GroupMove, now_s: float) -> None:
        # A move counts from the frame now being sent: the first step shows at the next frame.
        origin = frame_at_or_before(now_s)
        duration = 0.0 if command.time_ms is None else command.time_ms / 1000.0
        plan: list[tuple[int, float | None, float]] = []  # channel, from (None: unknown), to
        for target in command.targets:
            ch = self._channels.get(target.channel)
            if target.pulse_us == 0:
                plan.append((target.channel, None, 0.0))
                continue
            goal = float(min(max(target.pulse_us, MIN_PULSE_US), MAX_PULSE_US))
            here = ch.value(origin) if ch is not None and ch.on else None
            plan.append((target.channel, here, goal))
            if here is not None and target.speed_us_s is not None:
                duration = max(duration, abs(goal - here) / target.speed_us_s)
        end = origin + duration
        for channel, here, goal in plan:
            ch = self._channels.setdefault(channel, _Channel())
            if goal == 0.0:  # P0: pulses off; the next command does not know the servo
                ch.on = False
                continue
            ch.on = True
            ch.start_us = goal if here is None else here
            ch.target_us = goal
            ch.t0, ch.t1 = (origin, end) if here is not None else (origin, origin)
        end_frame = frame_at_or_after(end)
        self._group_end_s = end_frame  # Q answers for the last move
        self.moves.append(MoveRecord(now_s, origin, end_frame, {c: int(g) for c, _, g in plan}))

    def busy(self, now_s: float) -> bool:
        """What ``Q`` answers at ``now_s``: True (``+``) until the last move's end frame."""
        return now_s < self._group_end_s - _EPS

    def pulse_us(self, channel: int, now_s: float) -> int:
        """The pulse width sent on ``channel`` in the frame running at ``now_s`` [us] (0: off)."""
        ch = self._channels.get(channel)
        if ch is None or not ch.on:
            return 0
        value = round(ch.value(frame_at_or_before(now_s))) + ch.offset_us
        return int(min(max(value, MIN_PULSE_US), MAX_PULSE_US))

    def pulses_us(self, channels: Sequence[int], now_s: float) -> tuple[int, ...]:
        """:meth:`pulse_us` of several channels."""
        return tuple(self.pulse_us(c, now_s) for c in channels)


def virtual_run(
    lines: Sequence[tuple[float, str]], channels: Sequence[int], until_s: float
) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.int64], Ssc32Board]:
    """Play timed lines into a fresh board and record every frame's pulses.

    Args:
        lines: (arrival time [s], line without CR), in time order.
        channels: The channels to record.
        until_s: Last time recorded [s].

    Returns:
        Frame times, shape (F,) [s], from 0 to ``until_s``; the pulses sent on
        each channel at each frame, shape (F, len(channels)) [us] (0: off); the board.
    """
    board = Ssc32Board()
    n = math.floor(until_s / FRAME_S + _EPS) + 1
    times = np.arange(n, dtype=np.float64) * FRAME_S
    pulses = np.zeros((n, len(channels)), dtype=np.int64)
    i = 0
    for k, t in enumerate(times):
        while i < len(lines) and lines[i][0] <= t + _EPS:
            board.execute(lines[i][1], lines[i][0])
            i += 1
        pulses[k] = board.pulses_us(channels, float(t))
    return times, pulses, board
