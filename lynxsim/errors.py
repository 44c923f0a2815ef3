"""Exceptions raised by lynxsim.

Every error a caller can provoke derives from :class:`LynxsimError`. Errors that
stem from a bad value also derive from :class:`ValueError`, so that generic code
catching ``ValueError`` keeps working.
"""

from __future__ import annotations

__all__ = [
    "InvalidInputError",
    "JointRangeError",
    "LynxsimError",
    "NonFiniteInputError",
    "OutOfReachError",
    "UnreachablePlatformPoseError",
    "UnreachablePoseError",
]


class LynxsimError(Exception):
    """Base class of every error lynxsim raises on purpose."""


class InvalidInputError(LynxsimError, ValueError):
    """An argument has the wrong shape, type or value."""


class NonFiniteInputError(InvalidInputError):
    """An input holds NaN or infinity."""


class UnreachablePoseError(LynxsimError, ValueError):
    """A target pose has no inverse-kinematics solution.

    Attributes:
        reason: Short machine-readable reason (``"out_of_reach"``,
            ``"joint_range"`` or ``"not_finite"``).
    """

    reason = "unreachable"


class OutOfReachError(UnreachablePoseError):
    """The wrist point lies outside the annulus the two arm links can reach."""

    reason = "out_of_reach"


class JointRangeError(UnreachablePoseError):
    """Every geometric solution puts at least one joint outside its range.

    Attributes:
        joint: 1-based number of the offending joint.
    """

    reason = "joint_range"

    def __init__(self, message: str, joint: int) -> None:
        super().__init__(message)
        self.joint = joint


class UnreachablePlatformPoseError(UnreachablePoseError):
    """A 3-RRR platform pose that at least one leg cannot reach.

    A leg reaches its platform joint only when the base-to-platform-joint
    distance lies in ``[|s_a - L|, s_a + L]``.

    Attributes:
        legs: 1-based numbers of the legs that cannot reach, ascending.
    """

    reason = "out_of_reach"

    def __init__(self, message: str, legs: tuple[int, ...]) -> None:
        super().__init__(message)
        self.legs = legs
