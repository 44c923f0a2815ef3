"""What the board really sends for a stream, and how far that is from the trajectory.

The stream's lines are played into an emulated board (:func:`~lynxsim.real.board.virtual_run`)
at the times their CRs reach it over the serial line; every 20 ms frame's
pulses are read back and turned into joint angles through the calibration.
The time base is the motion's: 0 at the frame where the first move starts
(the stream's hold and the line's transmission are the constant
``latency_s`` before it). The worst distance between these angles and the
trajectory, per joint and (with a forward kinematics) at the tool, is what
the user should expect the controller's own interpolation to add.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from lynxsim.real.board import MoveRecord, virtual_run
from lynxsim.real.calibration import Calibration
from lynxsim.real.stream import CommandStream
from lynxsim.traj import Trajectory

__all__ = ["BoardMotion", "StreamDeviation", "ToolFn", "board_motion", "stream_deviation"]

FloatArray = npt.NDArray[np.float64]

ToolFn = Callable[[FloatArray], FloatArray]
"""Forward kinematics of the tool point: joints (N, n) [rad] -> points (N, 3) [m]."""

_AFTER_S = 0.5
"""Frames recorded after the trajectory's end [s]."""


@dataclass(frozen=True)
class BoardMotion:
    """The pulses the board sends for a stream, one row per 20 ms frame.

    Attributes:
        time_s: Frame times on the motion's clock, (F,) [s], 0 where the first move starts.
        pulses_us: Pulse of each joint's channel, (F, n) [us].
        q_rad: The joint angles those pulses command, (F, n) [rad].
        latency_s: From the stream's start (the approach line sent) to time 0 [s].
        end_s: On the motion's clock, the frame at which the last move ended [s].
    """

    time_s: FloatArray
    pulses_us: npt.NDArray[np.int64]
    q_rad: FloatArray
    latency_s: float
    end_s: float


def board_motion(
    stream: CommandStream, calibration: Calibration, after_s: float = _AFTER_S
) -> BoardMotion:
    """Play a stream into an emulated board in virtual time; see :class:`BoardMotion`."""
    arrivals = stream.arrivals()
    until = stream.end_s + stream.duration_s + after_s + 1.0
    times, pulses, board = virtual_run(arrivals, stream.channels, until)
    pairs = [(m, ln) for m, ln in zip(_line_moves(board.moves, arrivals), stream.lines)]
    moves = [(m, ln) for m, ln in pairs if ln.kind == "move"]
    # The host's clock and the board's frames are not in phase, and lines differ in
    # length: each move starts a whole number of frames after it is sent. The motion's
    # time 0 is the typical (median) start.
    latency = float(np.median([m.start_s - ln.at_s for m, ln in moves]))
    start = stream.motion_start_s + latency
    end = moves[-1][0].end_s - start
    keep = (times >= start - 1e-9) & (times <= start + stream.duration_s + after_s + 1e-9)
    clock = times[keep] - start
    return BoardMotion(
        time_s=clock,
        pulses_us=pulses[keep],
        q_rad=calibration.angles_rad(pulses[keep]),
        latency_s=float(start),
        end_s=float(end),
    )


def _line_moves(moves: list[MoveRecord], arrivals: list[tuple[float, str]]) -> list[MoveRecord]:
    """The board's move records, one per line (every stream line is a move)."""
    if len(moves) != len(arrivals):
        raise RuntimeError(f"{len(arrivals)} lines gave {len(moves)} moves")  # a stream bug
    return moves


@dataclass(frozen=True)
class StreamDeviation:
    """How far the board's interpolation strays from the trajectory.

    Attributes:
        joint_max_rad: Per joint, the largest |board angle - trajectory|, (n,) [rad].
        joint_max_time_s: When each happens, on the motion's clock, (n,) [s].
        tool_max_m: Largest tool distance between the two [m], None without kinematics.
        tool_max_time_s: When it happens [s], None without kinematics.
        latency_s: From the stream's start to the motion's start [s].
        end_lag_s: When the last move ends, minus the trajectory's duration [s].
    """

    joint_max_rad: tuple[float, ...]
    joint_max_time_s: tuple[float, ...]
    tool_max_m: float | None
    tool_max_time_s: float | None
    latency_s: float
    end_lag_s: float

    def lines(self, names: tuple[str, ...]) -> list[str]:
        """The figures as readable lines (degrees, mm, ms)."""
        joints = ", ".join(
            f"{n} {np.degrees(v):.2f} deg" for n, v in zip(names, self.joint_max_rad)
        )
        out = [f"controller interpolation vs trajectory, worst joint error: {joints}"]
        if self.tool_max_m is not None and self.tool_max_time_s is not None:
            out.append(
                f"worst tool error {self.tool_max_m * 1e3:.2f} mm at {self.tool_max_time_s:.3f} s"
            )
        out.append(
            f"motion starts {self.latency_s:.3f} s after the stream; last move ends "
            f"{self.end_lag_s * 1e3:+.0f} ms from the trajectory's end"
        )
        return out


def stream_deviation(
    trajectory: Trajectory,
    stream: CommandStream,
    calibration: Calibration,
    tool: ToolFn | None = None,
    motion: BoardMotion | None = None,
) -> StreamDeviation:
    """The worst deviation of the board's interpolation from the trajectory.

    Args:
        trajectory: The trajectory the stream was made from.
        stream: Its stream.
        calibration: The calibration the stream was made with.
        tool: Forward kinematics for the tool-space figure (None: joints only).
        motion: The stream's :func:`board_motion` if already computed.

    Returns:
        The :class:`StreamDeviation`, compared at every 20 ms frame of the motion.
    """
    motion = motion or board_motion(stream, calibration)
    inside = motion.time_s <= trajectory.duration + 1e-9
    t = motion.time_s[inside]
    q_ref = trajectory.sample(np.clip(t, 0.0, trajectory.duration)).q
    q_board = motion.q_rad[inside]
    err = np.abs(q_board - q_ref)
    k = np.argmax(err, axis=0)
    tool_max = tool_time = None
    if tool is not None:
        dist = np.linalg.norm(tool(q_board) - tool(q_ref), axis=1)
        i = int(np.argmax(dist))
        tool_max, tool_time = float(dist[i]), float(t[i])
    return StreamDeviation(
        joint_max_rad=tuple(float(err[k[j], j]) for j in range(err.shape[1])),
        joint_max_time_s=tuple(float(t[k[j]]) for j in range(err.shape[1])),
        tool_max_m=tool_max,
        tool_max_time_s=tool_time,
        latency_s=motion.latency_s,
        end_lag_s=motion.end_s - trajectory.duration,
    )
