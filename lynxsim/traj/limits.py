"""Joint velocity, acceleration and jerk limits, and the arm's default ones.

:class:`JointLimits` bounds the magnitude of every joint's derivatives.
:data:`DEFAULT_LIMITS` are the arm's, derived from its servos' datasheets in
:mod:`lynxsim.arm.servos` (derating and ramp times explained there):

velocity [rad/s] 3.49, 4.49, 2.73, 3.14, 5.71; acceleration = velocity / 0.25 s;
jerk = acceleration / 0.1 s.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from lynxsim.arm.servos import AL5D_SERVOS
from lynxsim.errors import InvalidInputError, NonFiniteInputError
from lynxsim.inputs import instance, real_array

__all__ = ["DEFAULT_LIMITS", "JointLimits", "check_limits"]

FloatArray = npt.NDArray[np.float64]


def _positive_5(values: object, what: str) -> tuple[float, ...]:
    arr = real_array(values, f"{what} limits")
    if arr.shape == ():
        arr = np.full(5, float(arr))
    if arr.shape != (5,):
        raise InvalidInputError(
            f"{what} limits must be a number or have shape (5,), got {arr.shape}"
        )
    if not np.isfinite(arr).all():
        raise NonFiniteInputError(f"{what} limits must be finite, got {arr.tolist()}")
    if (arr <= 0.0).any():
        raise InvalidInputError(f"{what} limits must be positive, got {arr.tolist()}")
    return tuple(float(v) for v in arr)


@dataclass(frozen=True)
class JointLimits:
    """Per-joint bounds on the magnitude of the joint derivatives.

    Attributes:
        velocity: Shape (5,) [rad/s].
        acceleration: Shape (5,) [rad/s^2].
        jerk: Shape (5,) [rad/s^3].

    A scalar given for a field applies to every joint.

    Raises:
        InvalidInputError: A limit is not a real number, not positive or has the
            wrong shape.
        NonFiniteInputError: A limit is NaN or infinite.
    """

    velocity: tuple[float, ...]
    acceleration: tuple[float, ...]
    jerk: tuple[float, ...]

    def __post_init__(self) -> None:
        for name in ("velocity", "acceleration", "jerk"):
            object.__setattr__(self, name, _positive_5(getattr(self, name), name))

    def of_order(self, order: int) -> FloatArray:
        """Limits of derivative ``order`` (1, 2 or 3), shape (5,) [rad/s^order]."""
        return np.array((self.velocity, self.acceleration, self.jerk)[order - 1])


DEFAULT_LIMITS = JointLimits(
    velocity=tuple(s.velocity_limit for s in AL5D_SERVOS),
    acceleration=tuple(s.acceleration_limit for s in AL5D_SERVOS),
    jerk=tuple(s.jerk_limit for s in AL5D_SERVOS),
)
"""The arm's default limits: :class:`~lynxsim.arm.servos.ServoSpec`'s
``velocity_limit``, ``acceleration_limit`` and ``jerk_limit`` of
:data:`~lynxsim.arm.servos.AL5D_SERVOS`."""


def check_limits(limits: object) -> JointLimits:
    """``limits`` if it is a :class:`JointLimits`, else raise InvalidInputError."""
    return instance(limits, JointLimits, "limits")
