"""From normalised actions to servo targets: tool-space (through the IK) or joint-space.

A controller keeps the commanded joint vector between control steps; an action
moves that command, never the measured pose, so a zero action holds the arm
where it was told to be (the servos' sag under gravity does not creep in).
Pure Python floats: the env writes :attr:`q_cmd` into ``MjData.ctrl``.
"""

from __future__ import annotations

import enum
import math
from collections.abc import Sequence

from lynxsim.arm import LYNX_ARM, IKStatus, ik_nearest, tool_pose_of
from lynxsim.errors import InvalidInputError

__all__ = ["ControlMode", "JointSpaceController", "TargetStatus", "ToolSpaceController"]


class ControlMode(enum.Enum):
    """How an env reads its arm action.

    TOOL: deltas of the tool point (x, y, z) and pitch, solved by the analytic IK.
    JOINT: deltas of the five joint angles.
    """

    TOOL = "tool"
    JOINT = "joint"


class TargetStatus(enum.IntEnum):
    """What became of a requested target (``info["target_status"]``).

    The first four mirror :class:`lynxsim.arm.IKStatus`; every status but
    ACCEPTED means the previous target is held.
    """

    ACCEPTED = 0
    OUT_OF_REACH = int(IKStatus.OUT_OF_REACH)
    JOINT_RANGE = int(IKStatus.JOINT_RANGE)
    NOT_FINITE = int(IKStatus.NOT_FINITE)
    JOINT_JUMP = 4
    """The nearest solution is more than ``max_joint_jump`` from the current command
    (the arm would flip configuration, e.g. across the base axis)."""


def _check_positive(**values: float) -> None:
    for name, v in values.items():
        if isinstance(v, bool) or not isinstance(v, int | float):
            raise InvalidInputError(f"{name} must be a positive number, got {v!r}")
        try:
            positive = math.isfinite(v) and v > 0.0
        except OverflowError:  # an int beyond float64
            positive = False
        if not positive:
            raise InvalidInputError(f"{name} must be a positive number, got {v!r}")


class ToolSpaceController:
    """Tool-space deltas, turned into joint targets by :func:`~lynxsim.arm.ik_nearest`.

    The requested tool point is clipped to a box and the pitch to a range; an
    unsolvable or discontinuous request holds the previous (feasible) target.

    Args:
        position_step: Tool-point move for an action of 1 [m].
        pitch_step: Pitch change for an action of 1 [rad].
        roll: Wrist roll held [rad].
        box_lower: Lower corner of the box the tool point is clipped to, (3,) [m].
        box_upper: Upper corner, (3,) [m].
        pitch_range: (min, max) pitch [rad].
        max_joint_jump: Largest change of any joint command in one step [rad].

    Raises:
        InvalidInputError: Non-positive steps or an empty box.
    """

    def __init__(
        self,
        position_step: float,
        pitch_step: float,
        roll: float,
        box_lower: Sequence[float],
        box_upper: Sequence[float],
        pitch_range: tuple[float, float] = (-math.pi / 2, math.pi / 2),
        max_joint_jump: float = 0.5,
    ) -> None:
        _check_positive(
            position_step=position_step, pitch_step=pitch_step, max_joint_jump=max_joint_jump
        )
        if (
            len(box_lower) != 3
            or len(box_upper) != 3
            or any(lo > hi for lo, hi in zip(box_lower, box_upper))
        ):
            raise InvalidInputError(f"empty target box {box_lower} .. {box_upper}")
        self.position_step = float(position_step)
        self.pitch_step = float(pitch_step)
        self.roll = float(roll)
        self._lo = tuple(float(v) for v in box_lower)
        self._hi = tuple(float(v) for v in box_upper)
        self._pitch_lo, self._pitch_hi = pitch_range
        self._max_jump = float(max_joint_jump)
        self.q_cmd: tuple[float, ...] = (0.0,) * 5
        """Commanded joints, 5 values [rad]."""
        self.target: tuple[float, float, float, float] = tool_pose_of(self.q_cmd)
        """Commanded tool point and pitch ``(x, y, z, pitch)`` [m, rad]."""

    def reset(self, q: Sequence[float]) -> None:
        """Command the joints ``q`` (5 values [rad]) and the tool pose they give."""
        self.q_cmd = tuple(float(v) for v in q)
        self.target = tool_pose_of(self.q_cmd)

    def apply(self, action: Sequence[float]) -> TargetStatus:
        """Move the target by an action ``(dx, dy, dz, dpitch)`` in [-1, 1].

        Returns:
            ACCEPTED, or why the previous target is held.
        """
        x, y, z, pitch = self.target
        s, lo, hi = self.position_step, self._lo, self._hi
        x = min(hi[0], max(lo[0], x + action[0] * s))
        y = min(hi[1], max(lo[1], y + action[1] * s))
        z = min(hi[2], max(lo[2], z + action[2] * s))
        pitch = min(self._pitch_hi, max(self._pitch_lo, pitch + action[3] * self.pitch_step))
        status, q = ik_nearest(x, y, z, pitch, self.roll, self.q_cmd)
        if q is None:
            return TargetStatus(int(status))
        ref, jump = self.q_cmd, self._max_jump
        if (
            abs(q[0] - ref[0]) > jump
            or abs(q[1] - ref[1]) > jump
            or abs(q[2] - ref[2]) > jump
            or abs(q[3] - ref[3]) > jump
        ):
            return TargetStatus.JOINT_JUMP
        self.q_cmd = q
        self.target = (x, y, z, pitch)
        return TargetStatus.ACCEPTED


class JointSpaceController:
    """Joint-angle deltas, clipped to the joint ranges.

    Args:
        joint_step: Joint change for an action of 1 [rad].

    Raises:
        InvalidInputError: A non-positive step.
    """

    def __init__(self, joint_step: float) -> None:
        _check_positive(joint_step=joint_step)
        self.joint_step = float(joint_step)
        self._lo = LYNX_ARM.q_min
        self._hi = LYNX_ARM.q_max
        self.q_cmd: tuple[float, ...] = (0.0,) * 5
        """Commanded joints, 5 values [rad]."""
        self.target: tuple[float, float, float, float] = tool_pose_of(self.q_cmd)
        """Tool point and pitch of the commanded joints ``(x, y, z, pitch)`` [m, rad]."""

    def reset(self, q: Sequence[float]) -> None:
        """Command the joints ``q`` (5 values [rad])."""
        self.q_cmd = tuple(float(v) for v in q)
        self.target = tool_pose_of(self.q_cmd)

    def apply(self, action: Sequence[float]) -> TargetStatus:
        """Move the joint targets by an action ``(dq1, .., dq5)`` in [-1, 1]; always ACCEPTED."""
        s, lo, hi = self.joint_step, self._lo, self._hi
        self.q_cmd = tuple(min(hi[i], max(lo[i], self.q_cmd[i] + action[i] * s)) for i in range(5))
        self.target = tool_pose_of(self.q_cmd)
        return TargetStatus.ACCEPTED
