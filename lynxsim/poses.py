"""The pose value types of task files: a serial arm's tool pose, joints, a planar platform pose.

Pure values, validated on construction, SI units. They know no robot: the arm's
inverse kinematics turns an :class:`ArmPose` into joints
(:mod:`lynxsim.arm.motion.waypoints`), a :class:`JointPose` of any number of
joints is what :mod:`lynxsim.traj` moves through, and a :class:`PlanarPose` is
a 3-RRR platform's target (:mod:`lynxsim.rrr`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from lynxsim.bounds import MAX_COORDINATE_M
from lynxsim.errors import InvalidInputError, NonFiniteInputError
from lynxsim.inputs import finite_array, real_number

__all__ = ["ArmPose", "JointPose", "PlanarPose"]


def _floats(values: object, n: int | None, what: str) -> tuple[float, ...]:
    """Finite real numbers of shape (n,) (any length >= 1 when ``n`` is None)."""
    arr = finite_array(values, what)
    if n is None:
        if arr.ndim != 1 or arr.size < 1:
            raise InvalidInputError(f"{what} must have shape (n,), n >= 1, got {arr.shape}")
    elif arr.shape != (n,):
        raise InvalidInputError(f"{what} must have shape ({n},), got {arr.shape}")
    return tuple(float(v) for v in arr)


def _angle(value: object, what: str) -> float:
    v = real_number(value, what)
    if not math.isfinite(v):
        raise NonFiniteInputError(f"{what} must be finite, got {v!r}")
    return v


def _name(value: object) -> str:
    if not isinstance(value, str):
        raise InvalidInputError(f"a waypoint name must be a string, got {value!r}")
    return value


@dataclass(frozen=True)
class ArmPose:
    """A task pose of a serial arm's tool, solved by the arm's inverse kinematics.

    Attributes:
        position: Tool point in the base frame, (x, y, z) [m].
        pitch: Tool pitch above the horizontal [rad] (see :func:`lynxsim.arm.ik`).
        roll: Wrist roll [rad]; ``None`` keeps the previous pose's roll
            (0 for the first pose).
        name: Label used in messages and plots (default ``P1``, ``P2``, ...).

    Raises:
        InvalidInputError: A value is not a real number, the position has not
            three of them or a coordinate exceeds
            :data:`~lynxsim.bounds.MAX_COORDINATE_M`, or the name is not a string.
        NonFiniteInputError: A value is NaN or infinite.
    """

    position: tuple[float, float, float]
    pitch: float
    roll: float | None = None
    name: str = ""

    def __post_init__(self) -> None:
        position = _floats(self.position, 3, "pose position")
        if max(abs(v) for v in position) > MAX_COORDINATE_M:
            raise InvalidInputError(
                f"pose position coordinates must be within ±{MAX_COORDINATE_M:g} m "
                f"(the arm reaches under 1 m), got {position} m"
            )
        object.__setattr__(self, "position", position)
        object.__setattr__(self, "pitch", _angle(self.pitch, "pose pitch"))
        if self.roll is not None:
            object.__setattr__(self, "roll", _angle(self.roll, "pose roll"))
        _name(self.name)

    def describe(self) -> str:
        """The pose in the report's units, e.g. ``P3 (x 250, y 0, z 300 mm, pitch 0 deg)``."""
        x, y, z = (1e3 * v for v in self.position)
        roll = "" if self.roll is None else f", roll {math.degrees(self.roll):.4g} deg"
        return (
            f"{self.name} (x {x:.4g}, y {y:.4g}, z {z:.4g} mm, "
            f"pitch {math.degrees(self.pitch):.4g} deg{roll})"
        )


@dataclass(frozen=True)
class JointPose:
    """A waypoint given by its joints, any number of them.

    Attributes:
        q: Joint values, shape (n,), n >= 1 [rad].
        name: Label used in messages and plots.

    Raises:
        InvalidInputError: ``q`` is not a non-empty 1-D sequence of real numbers,
            or the name is not a string.
        NonFiniteInputError: A joint value is NaN or infinite.
    """

    q: tuple[float, ...]
    name: str = ""

    def __post_init__(self) -> None:
        object.__setattr__(self, "q", _floats(self.q, None, "joint pose q"))
        _name(self.name)


@dataclass(frozen=True)
class PlanarPose:
    """A platform pose of a planar parallel robot (the 3-RRR).

    Attributes:
        x: Platform centre x in the base frame [m].
        y: Platform centre y in the base frame [m].
        alpha: Platform orientation, counter-clockwise seen from +z [rad].
        name: Label used in messages and plots.
    """

    x: float
    y: float
    alpha: float
    name: str = ""
