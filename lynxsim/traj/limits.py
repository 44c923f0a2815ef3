"""Joint velocity, acceleration and jerk limits, and the arm's default ones.

The default limits come from the no-load speeds of the Lynxmotion AL5D's Hitec
servos (Hitec product datasheets, "operating speed" at 6.0 V):

=========  ============  ==============  ========================
joint      servo         s per 60 deg    no-load speed [rad/s]
=========  ============  ==============  ========================
base       HS-485HB      0.18            5.82
shoulder   HS-805BB      0.14            7.48
elbow      HS-755HB      0.23            4.55
wrist      HS-645MG      0.20            5.24
roll       HS-225MG      0.11            9.52
=========  ============  ==============  ========================

Derating (:data:`SPEED_DERATING` = 0.6): the datasheet speed holds at 6.0 V
with no load. At 4.8 V the same datasheets give 74–83 % of it (supply sag
under five moving servos), and a DC servo's speed falls linearly with torque:
holding the arm against gravity takes the shoulder and elbow a fifth to a third
of their stall torque. 0.6 keeps the commanded speed inside what a loaded servo
reaches on a sagging supply.

Hobby servos publish no acceleration or jerk limits. lynxsim assumes that a
joint reaches its speed limit in :data:`ACCELERATION_RAMP_S` = 0.25 s and its
acceleration limit in :data:`JERK_RAMP_S` = 0.1 s: at 0.25 s the torque that
accelerates the arm's links (inertia about the shoulder ~0.014 kg m^2) stays
near a tenth of the HS-805BB's stall torque, gentle on the plastic brackets.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
import numpy.typing as npt

from lynxsim.errors import InvalidInputError, NonFiniteInputError

__all__ = [
    "ACCELERATION_RAMP_S",
    "AL5D_SERVOS",
    "DEFAULT_LIMITS",
    "JERK_RAMP_S",
    "SPEED_DERATING",
    "JointLimits",
    "ServoSpec",
]

FloatArray = npt.NDArray[np.float64]

SPEED_DERATING = 0.6
"""Fraction of the datasheet no-load speed at 6.0 V used as velocity limit [-]."""

ACCELERATION_RAMP_S = 0.25
"""Assumed time from rest to the velocity limit at the acceleration limit [s]."""

JERK_RAMP_S = 0.1
"""Assumed time from zero to the acceleration limit at the jerk limit [s]."""


class ServoSpec(NamedTuple):
    """A joint's servo and its datasheet speed.

    Attributes:
        joint: Joint name, as in :attr:`lynxsim.arm.ArmGeometry.joint_names`.
        model: Hitec model number.
        seconds_per_60deg: No-load transit time of 60 deg at 6.0 V [s].
    """

    joint: str
    model: str
    seconds_per_60deg: float

    @property
    def no_load_speed(self) -> float:
        """Datasheet no-load speed at 6.0 V [rad/s]."""
        return math.radians(60.0) / self.seconds_per_60deg


AL5D_SERVOS = (
    ServoSpec("base", "HS-485HB", 0.18),
    ServoSpec("shoulder", "HS-805BB", 0.14),
    ServoSpec("elbow", "HS-755HB", 0.23),
    ServoSpec("wrist_pitch", "HS-645MG", 0.20),
    ServoSpec("wrist_roll", "HS-225MG", 0.11),
)
"""The AL5D's servos, joints q1..q5 in order (Hitec datasheets, 6.0 V)."""


def _positive_5(values: npt.ArrayLike, what: str) -> tuple[float, ...]:
    arr = np.asarray(values, dtype=float)
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
        InvalidInputError: A limit is not positive or has the wrong shape.
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


def _servo_limits() -> JointLimits:
    velocity = np.array([SPEED_DERATING * s.no_load_speed for s in AL5D_SERVOS])
    acceleration = velocity / ACCELERATION_RAMP_S
    return JointLimits(
        velocity=tuple(velocity),
        acceleration=tuple(acceleration),
        jerk=tuple(acceleration / JERK_RAMP_S),
    )


DEFAULT_LIMITS = _servo_limits()
"""The arm's default limits, derived from :data:`AL5D_SERVOS` (see the module docs).

velocity [rad/s]: 3.49, 4.49, 2.73, 3.14, 5.71; acceleration = velocity / 0.25 s;
jerk = acceleration / 0.1 s.
"""
