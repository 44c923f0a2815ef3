"""A joint trajectory as SSC-32U command lines, timed and checked against the calibration.

Two ways to send a motion:

* ``streamed``: a group move every ``period_ms`` whose ``T`` is the period, its
  targets the trajectory one period later; the board's linear interpolation
  then follows the trajectory by chords.
* ``waypoints``: one timed group move per segment, to the segment's end
  waypoint in its duration (``T`` = the segment's time); the board moves each
  channel linearly in pulse width between the waypoints, whatever the
  trajectory's shape.

Either stream starts with an approach line to the first pose (``T`` =
``approach_ms``; a board that has not yet moved a channel ignores it and the
servo jumps), holds ``hold_s``, then moves. With a gripper in the calibration
and ``grip``, the gripper opens in the approach, closes 0.25 s before the
motion and opens 0.1 s after it (the simulation's schedule,
:func:`lynxsim.sim.arm.task.pick_and_place_gripper`).

Refused, with a :class:`~lynxsim.errors.CommandLimitError` naming joint and
time: a target outside a joint's calibrated pulse range, a move faster than its
speed limit. Refused with an :class:`~lynxsim.errors.InvalidInputError`: a
stream the serial line cannot carry at the board's baud rate.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Literal

import numpy as np
import numpy.typing as npt

from lynxsim.errors import CommandLimitError, InvalidInputError
from lynxsim.real.board import FRAME_S
from lynxsim.real.calibration import Calibration
from lynxsim.real.protocol import MAX_TIME_MS, ServoTarget, format_move
from lynxsim.traj import Trajectory

__all__ = [
    "GRIP_BEFORE_S",
    "MAX_LINK_LOAD",
    "RELEASE_AFTER_S",
    "CommandStream",
    "LineKind",
    "StreamMode",
    "StreamOptions",
    "TimedLine",
    "command_stream",
    "transmit_s",
]

StreamMode = Literal["streamed", "waypoints"]
"""How a trajectory becomes lines: a move every period, or one move per segment."""
LineKind = Literal["approach", "move", "gripper"]
"""What a line does: go to the first pose, follow the motion, or open/close the gripper."""

MAX_LINK_LOAD = 0.8
"""Largest fraction of a streaming period one line may take on the serial line [-]."""
GRIP_BEFORE_S = 0.25
"""The gripper closes this long before the motion [s] (as the simulation's schedule)."""
RELEASE_AFTER_S = 0.1
"""The gripper opens this long after the motion [s] (as the simulation's schedule)."""
_BITS_PER_BYTE = 10
"""A serial byte: start bit, 8 data bits, stop bit."""


def transmit_s(text: str, baud: int) -> float:
    """Time a line and its CR take on the serial line at ``baud`` [s]."""
    return (len(text) + 1) * _BITS_PER_BYTE / baud


@dataclass(frozen=True)
class StreamOptions:
    """How to turn a trajectory into lines.

    Attributes:
        mode: ``"streamed"`` or ``"waypoints"``.
        period_ms: Streaming period, a multiple of the 20 ms frame, 20..1000 [ms].
        approach_ms: ``T`` of the approach to the first pose [ms], 1..65535.
        hold_s: From the approach line to the first move [s], at least the approach.

    Raises:
        InvalidInputError: A value out of its range.
    """

    mode: StreamMode = "streamed"
    period_ms: int = 100
    approach_ms: int = 2000
    hold_s: float = 2.5

    def __post_init__(self) -> None:
        if self.mode not in ("streamed", "waypoints"):
            raise InvalidInputError(f"mode must be 'streamed' or 'waypoints', got {self.mode!r}")
        frame_ms = round(FRAME_S * 1000)
        if (
            isinstance(self.period_ms, bool)
            or not isinstance(self.period_ms, int)
            or not 20 <= self.period_ms <= 1000
            or self.period_ms % frame_ms
        ):
            raise InvalidInputError(
                f"period_ms must be a multiple of {frame_ms} ms within 20..1000, "
                f"got {self.period_ms!r}"
            )
        if not (isinstance(self.approach_ms, int) and 1 <= self.approach_ms <= MAX_TIME_MS):
            raise InvalidInputError(
                f"approach_ms must be 1..{MAX_TIME_MS}, got {self.approach_ms!r}"
            )
        hold = float(self.hold_s)
        if not (math.isfinite(hold) and self.approach_ms / 1000 <= hold <= 60.0):
            raise InvalidInputError(
                f"hold_s must lie within {self.approach_ms / 1000:g}..60 s (the approach's "
                f"time at least), got {self.hold_s!r}"
            )


@dataclass(frozen=True)
class TimedLine:
    """One line and when to send it.

    Attributes:
        at_s: Send time from the start of the stream [s].
        text: The line, without its CR.
        kind: What it does.
    """

    at_s: float
    text: str
    kind: LineKind


@dataclass(frozen=True)
class CommandStream:
    """A motion as timed lines for one board.

    Attributes:
        lines: In send order.
        options: The options it was made with.
        baud: The board's baud rate [bit/s].
        channels: The joints' channels, in joint order.
        gripper_channel: The gripper's channel, or None if the stream does not grip.
        motion_start_s: When the first move line is sent [s].
        duration_s: The trajectory's duration [s].
        targets_us: Targets of the move lines, (K, n) [us].
        final_us: The final joint pulses, (n,) [us].
    """

    lines: tuple[TimedLine, ...]
    options: StreamOptions
    baud: int
    channels: tuple[int, ...]
    gripper_channel: int | None
    motion_start_s: float
    duration_s: float
    targets_us: npt.NDArray[np.int64]
    final_us: tuple[int, ...]

    @property
    def end_s(self) -> float:
        """When the last line is sent [s]."""
        return self.lines[-1].at_s

    def arrivals(self) -> list[tuple[float, str]]:
        """(time its CR reaches the board [s], line) at the stream's baud rate."""
        return [(ln.at_s + transmit_s(ln.text, self.baud), ln.text) for ln in self.lines]


def _check_range(calibration: Calibration, pulses: npt.NDArray[np.float64], t: np.ndarray) -> None:
    for i, joint in enumerate(calibration.joints):
        low = pulses[:, i] < joint.min_us
        high = pulses[:, i] > joint.max_us
        if low.any() or high.any():
            k = int(np.argmax(low | high))
            limit = joint.min_us if low[k] else joint.max_us
            raise CommandLimitError(
                f"joint {joint.name}: pulse {pulses[k, i]:.0f} us at {t[k]:.3f} s leaves its "
                f"calibrated range {joint.min_us}..{joint.max_us} us (channel {joint.channel})",
                joint=joint.name,
                quantity="pulse",
                time_s=float(t[k]),
                value=float(pulses[k, i]),
                limit=float(limit),
            )


def _check_speed(
    calibration: Calibration, pulses: npt.NDArray[np.int64], times: np.ndarray
) -> None:
    """Each move's pulse rate within the speed limit (1 us of rounding allowed per move)."""
    dt = np.diff(times)
    for i, joint in enumerate(calibration.joints):
        step = np.abs(np.diff(pulses[:, i])).astype(float)
        rate = np.maximum(step - 1.0, 0.0) / dt
        k = int(np.argmax(rate))
        if rate[k] > joint.max_speed_us_s:
            raise CommandLimitError(
                f"joint {joint.name}: {step[k]:.0f} us in {dt[k] * 1e3:.0f} ms at "
                f"{times[k]:.3f} s is {step[k] / dt[k]:.0f} us/s, over its speed limit "
                f"{joint.max_speed_us_s:.0f} us/s "
                f"({math.degrees(joint.max_speed_rad_s):.0f} deg/s)",
                joint=joint.name,
                quantity="speed",
                time_s=float(times[k]),
                value=float(step[k] / dt[k]),
                limit=joint.max_speed_us_s,
            )


def command_stream(
    trajectory: Trajectory,
    calibration: Calibration,
    options: StreamOptions | None = None,
    *,
    grip: bool = False,
) -> CommandStream:
    """The lines that make the board play a trajectory.

    Args:
        trajectory: Any joint trajectory (every type, ``planned`` included).
        calibration: The arm's calibration (its joints in the trajectory's order).
        options: Mode, period, approach (defaults if None).
        grip: Close the gripper for the motion (a pick-and-place), if the
            calibration has one.

    Returns:
        The :class:`CommandStream`.

    Raises:
        CommandLimitError: A target pulse outside a joint's calibrated range, or a
            move faster than its speed limit (names joint, time, value, limit).
        InvalidInputError: A waypoint segment longer than 65.535 s, or a streamed
            line that takes more than 80 % of the period at the baud rate.
    """
    options = options or StreamOptions()
    duration = trajectory.duration
    if options.mode == "streamed":
        period = options.period_ms / 1000.0
        count = max(1, math.ceil(duration / period - 1e-9))
        bounds = np.minimum(np.arange(count + 1) * period, duration)
    else:
        bounds = np.asarray(trajectory.waypoint_times, dtype=float)
    times_ms = np.round(np.diff(bounds) * 1000.0).astype(np.int64)
    if times_ms.max() > MAX_TIME_MS:
        raise InvalidInputError(
            f"a timed move of {times_ms.max() / 1000:.3f} s is longer than the board's "
            f"{MAX_TIME_MS / 1000:.3f} s: use mode 'streamed'"
        )
    times_ms = np.maximum(times_ms, 1)
    exact = calibration.pulses_us(trajectory.sample(bounds).q)
    _check_range(calibration, exact, bounds)
    pulses = np.round(exact).astype(np.int64)
    _check_speed(calibration, pulses, bounds)

    channels = calibration.channels
    gripper = calibration.gripper if grip else None
    approach = [ServoTarget(c, int(p)) for c, p in zip(channels, pulses[0])]
    if gripper is not None:
        approach.append(ServoTarget(gripper.channel, gripper.open_us))
    hold = float(options.hold_s)
    lines = [TimedLine(0.0, format_move(tuple(approach), options.approach_ms), "approach")]
    if gripper is not None:
        close = (ServoTarget(gripper.channel, gripper.closed_us),)
        lines.append(TimedLine(hold - GRIP_BEFORE_S, format_move(close), "gripper"))
    for k in range(len(bounds) - 1):
        targets = tuple(ServoTarget(c, int(p)) for c, p in zip(channels, pulses[k + 1]))
        lines.append(
            TimedLine(hold + float(bounds[k]), format_move(targets, int(times_ms[k])), "move")
        )
    if gripper is not None:
        release = (ServoTarget(gripper.channel, gripper.open_us),)
        lines.append(TimedLine(hold + duration + RELEASE_AFTER_S, format_move(release), "gripper"))
    if options.mode == "streamed":
        worst = max((ln for ln in lines if ln.kind == "move"), key=lambda ln: len(ln.text))
        load = transmit_s(worst.text, calibration.baud) / (options.period_ms / 1000.0)
        if load > MAX_LINK_LOAD:
            raise InvalidInputError(
                f"at {calibration.baud} baud a line of {len(worst.text) + 1} bytes takes "
                f"{transmit_s(worst.text, calibration.baud) * 1e3:.1f} ms, "
                f"{load:.0%} of the {options.period_ms} ms period (at most "
                f"{MAX_LINK_LOAD:.0%}): use a longer period or a faster baud rate"
            )
    return CommandStream(
        lines=tuple(lines),
        options=options,
        baud=calibration.baud,
        channels=channels,
        gripper_channel=None if gripper is None else gripper.channel,
        motion_start_s=hold,
        duration_s=duration,
        targets_us=pulses[1:],
        final_us=tuple(int(p) for p in pulses[-1]),
    )
