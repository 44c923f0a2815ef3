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

__all__ = [
    "ControlMode",
    "JointSpaceController",
    "TargetFallback",
    "TargetStatus",
    "ToolSpaceController",
]

_BISECTIONS = 12
"""Halvings of the search for the farthest feasible fraction of a request (1/4096)."""


class ControlMode(enum.Enum):
    """How an env reads its arm action.

    TOOL: deltas of the tool point (x, y, z) and pitch, solved by the analytic IK
        (``-v0``, ``-v1``; :class:`ToolSpaceController`).
    TOOL_ROLL: deltas of the tool point, pitch and wrist roll; an infeasible request
        goes to the nearest feasible target (``-v2``;
        :class:`lynxsim.envs.tool_action.ToolRollController`).
    JOINT: deltas of the five joint angles.
    """

    TOOL = "tool"
    JOINT = "joint"
    TOOL_ROLL = "tool_roll"


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


class TargetFallback(enum.Enum):
    """What a tool-space controller does with a request it cannot reach in full.

    HOLD: keep the previous target (``-v0`` envs).
    NEAREST: take the feasible target nearest the request: the farthest point
        along the request that is feasible, or, if a component alone is feasible
        further, the request with the other component kept (the position moved
        with the pitch kept, or the pitch turned with the position kept); the
        target is held only when no part of the request is feasible (``-v1``).
    """

    HOLD = "hold"
    NEAREST = "nearest"


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
        fallback: What an infeasible request does (:class:`TargetFallback`).

    Attributes:
        shortfall_m: After :meth:`apply`: distance from the requested tool point to
            the commanded one [m] (0 when the request was taken in full).
        shortfall_rad: After :meth:`apply`: |requested - commanded pitch| [rad].

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
        fallback: TargetFallback = TargetFallback.HOLD,
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
        self.box = (self._lo, self._hi)
        """The box the tool point is clipped to: (lower, upper) corners [m]."""
        self._pitch_lo, self._pitch_hi = pitch_range
        self._max_jump = float(max_joint_jump)
        self.fallback = TargetFallback(fallback)
        self.shortfall_m = 0.0
        self.shortfall_rad = 0.0
        self.q_cmd: tuple[float, ...] = (0.0,) * 5
        """Commanded joints, 5 values [rad]."""
        self.target: tuple[float, float, float, float] = tool_pose_of(self.q_cmd)
        """Commanded tool point and pitch ``(x, y, z, pitch)`` [m, rad]."""

    def reset(self, q: Sequence[float]) -> None:
        """Command the joints ``q`` (5 values [rad]) and the tool pose they give."""
        self.q_cmd = tuple(float(v) for v in q)
        self.target = tool_pose_of(self.q_cmd)
        self.shortfall_m = 0.0
        self.shortfall_rad = 0.0

    def apply(self, action: Sequence[float]) -> TargetStatus:
        """Move the target by an action ``(dx, dy, dz, dpitch)`` in [-1, 1].

        Returns:
            ACCEPTED, or why the request could not be taken in full (then the
            target is held, or with :attr:`TargetFallback.NEAREST` moved as far as
            is feasible; :attr:`shortfall_m` and :attr:`shortfall_rad` say by how
            much it falls short).
        """
        x, y, z, pitch = self.target
        s, lo, hi = self.position_step, self._lo, self._hi
        request = (
            min(hi[0], max(lo[0], x + action[0] * s)),
            min(hi[1], max(lo[1], y + action[1] * s)),
            min(hi[2], max(lo[2], z + action[2] * s)),
            min(self._pitch_hi, max(self._pitch_lo, pitch + action[3] * self.pitch_step)),
        )
        status, q = self._solve(request)
        if q is not None:
            self._take(request, q, request)
            return TargetStatus.ACCEPTED
        if self.fallback is TargetFallback.NEAREST:
            best = self._nearest(request)
            if best is not None:
                self._take(best[0], best[1], request)
                return status
        self._take(self.target, self.q_cmd, request)
        return status

    def _solve(
        self, target: tuple[float, float, float, float]
    ) -> tuple[TargetStatus, tuple[float, ...] | None]:
        """Joints for a target, or why there are none (unreachable, range, jump)."""
        status, q = ik_nearest(*target, self.roll, self.q_cmd)
        if q is None:
            return TargetStatus(int(status)), None
        ref, jump = self.q_cmd, self._max_jump
        if (
            abs(q[0] - ref[0]) > jump
            or abs(q[1] - ref[1]) > jump
            or abs(q[2] - ref[2]) > jump
            or abs(q[3] - ref[3]) > jump
        ):
            return TargetStatus.JOINT_JUMP, None
        return TargetStatus.ACCEPTED, q

    def _nearest(
        self, request: tuple[float, float, float, float]
    ) -> tuple[tuple[float, float, float, float], tuple[float, ...]] | None:
        """The feasible target nearest the request, and its joints, or None if none moves.

        Three candidates, each the farthest feasible point (by bisection) along a
        move from the current target: the whole request, its position alone and
        its pitch alone; nearest in step units (position / ``position_step``,
        pitch / ``pitch_step``) wins.
        """
        x, y, z, pitch = self.target
        rx, ry, rz, rp = request
        moves = dict.fromkeys(((rx, ry, rz, rp), (rx, ry, rz, pitch), (x, y, z, rp)))
        best: tuple[float, tuple[float, float, float, float], tuple[float, ...]] | None = None
        for end in moves:
            if end == self.target:
                continue
            found = None
            low, high = 0.0, 1.0
            for _ in range(_BISECTIONS):
                mid = 0.5 * (low + high)
                point = (x + mid * (end[0] - x), y + mid * (end[1] - y),
                         z + mid * (end[2] - z), pitch + mid * (end[3] - pitch))  # fmt: skip
                _, q = self._solve(point)
                if q is None:
                    high = mid
                else:
                    low, found = mid, (point, q)
            if found is None:
                continue
            point = found[0]
            miss = math.hypot(
                math.dist(point[:3], request[:3]) / self.position_step,
                (point[3] - rp) / self.pitch_step,
            )
            if best is None or miss < best[0]:
                best = (miss, *found)
        return None if best is None else (best[1], best[2])

    def _take(
        self,
        target: tuple[float, float, float, float],
        q: tuple[float, ...],
        request: tuple[float, float, float, float],
    ) -> None:
        self.q_cmd = q
        self.target = target
        self.shortfall_m = math.dist(target[:3], request[:3])
        self.shortfall_rad = abs(target[3] - request[3])


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
        self.shortfall_m = 0.0
        """Always 0: every joint request is taken (clipped to the ranges)."""
        self.shortfall_rad = 0.0
        """Always 0."""

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
