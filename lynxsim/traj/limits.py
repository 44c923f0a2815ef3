"""What a trajectory is held to: joint ranges and joint derivative limits, n joints.

:class:`JointBounds` names the joints and gives their ranges; :class:`JointLimits`
bounds the magnitude of every joint's velocity, acceleration and jerk. Neither
has a default here: a robot supplies its own (the arm's are
:data:`lynxsim.arm.motion.ARM_BOUNDS` and :data:`lynxsim.arm.motion.ARM_LIMITS`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from lynxsim.errors import InvalidInputError, NonFiniteInputError
from lynxsim.inputs import instance, real_array

__all__ = ["JointBounds", "JointLimits", "check_limits"]

FloatArray = npt.NDArray[np.float64]

_LIMIT_FIELDS = ("velocity", "acceleration", "jerk")


def _finite_vector(values: object, what: str) -> FloatArray:
    arr = real_array(values, what)
    if arr.ndim != 1 or arr.size < 1:
        raise InvalidInputError(f"{what} must have shape (n,), n >= 1, got {arr.shape}")
    if not np.isfinite(arr).all():
        raise NonFiniteInputError(f"{what} must be finite, got {arr.tolist()}")
    return arr


@dataclass(frozen=True)
class JointBounds:
    """The joints of a robot: their names and ranges.

    Attributes:
        names: One name per joint, shape (n,), n >= 1 (used in messages).
        lower: Lower end of every joint's range, shape (n,) [rad].
        upper: Upper end of every joint's range, shape (n,) [rad].

    Raises:
        InvalidInputError: The names are not n non-empty, distinct strings, a
            range is not n real numbers, or a lower end exceeds its upper end.
        NonFiniteInputError: A range end is NaN or infinite.
    """

    names: tuple[str, ...]
    lower: tuple[float, ...]
    upper: tuple[float, ...]

    def __post_init__(self) -> None:
        names = self.names
        if not (
            isinstance(names, tuple | list)
            and names
            and all(isinstance(n, str) and n for n in names)
        ):
            raise InvalidInputError(f"joint names must be non-empty strings, got {names!r}")
        if len(set(names)) != len(names):
            raise InvalidInputError(f"joint names must be distinct, got {names!r}")
        n = len(names)
        lower = _finite_vector(self.lower, "lower joint bounds")
        upper = _finite_vector(self.upper, "upper joint bounds")
        if lower.shape != (n,) or upper.shape != (n,):
            raise InvalidInputError(
                f"{n} joints need {n} lower and upper bounds, got shapes {lower.shape} "
                f"and {upper.shape}"
            )
        bad = np.flatnonzero(lower > upper)
        if bad.size:
            j = int(bad[0])
            raise InvalidInputError(
                f"joint {j + 1} ({names[j]}): lower bound {float(lower[j])!r} > upper bound "
                f"{float(upper[j])!r} rad"
            )
        object.__setattr__(self, "names", tuple(names))
        object.__setattr__(self, "lower", tuple(float(v) for v in lower))
        object.__setattr__(self, "upper", tuple(float(v) for v in upper))

    @property
    def n_joints(self) -> int:
        """The number of joints n."""
        return len(self.names)

    @property
    def lower_array(self) -> FloatArray:
        """:attr:`lower` as an array, shape (n,) [rad]."""
        return np.asarray(self.lower, dtype=float)

    @property
    def upper_array(self) -> FloatArray:
        """:attr:`upper` as an array, shape (n,) [rad]."""
        return np.asarray(self.upper, dtype=float)


def _positive(values: object, what: str) -> FloatArray:
    arr = real_array(values, f"{what} limits")
    if arr.ndim > 1:
        raise InvalidInputError(
            f"{what} limits must be a number or have shape (n,), got {arr.shape}"
        )
    if not np.isfinite(arr).all():
        raise NonFiniteInputError(f"{what} limits must be finite, got {arr.tolist()}")
    if (arr <= 0.0).any():
        raise InvalidInputError(f"{what} limits must be positive, got {arr.tolist()}")
    return arr


@dataclass(frozen=True)
class JointLimits:
    """Per-joint bounds on the magnitude of the joint derivatives, n joints.

    Attributes:
        velocity: Shape (n,) [rad/s].
        acceleration: Shape (n,) [rad/s^2].
        jerk: Shape (n,) [rad/s^3].

    A scalar given for a field applies to every joint; at least one field must
    have one value per joint (that fixes n), or use :meth:`for_joints`.

    Raises:
        InvalidInputError: A limit is not a real number, not positive, the
            fields disagree in length, or every field is a scalar.
        NonFiniteInputError: A limit is NaN or infinite.
    """

    velocity: tuple[float, ...]
    acceleration: tuple[float, ...]
    jerk: tuple[float, ...]

    def __post_init__(self) -> None:
        arrays = {name: _positive(getattr(self, name), name) for name in _LIMIT_FIELDS}
        sized = [(name, a) for name, a in arrays.items() if a.ndim == 1]
        if not sized:
            raise InvalidInputError(
                "joint limits need the number of joints: give at least one of velocity, "
                "acceleration, jerk per joint, or use JointLimits.for_joints(n, ...)"
            )
        first, reference = sized[0]
        n = reference.size
        if n < 1:
            raise InvalidInputError(f"{first} limits must have shape (n,), n >= 1, got (0,)")
        for name, arr in arrays.items():
            if arr.ndim == 1 and arr.shape != (n,):
                raise InvalidInputError(
                    f"{name} limits must be a number or have shape ({n},) as the {first} "
                    f"limits, got {arr.shape}"
                )
            object.__setattr__(self, name, tuple(float(v) for v in np.broadcast_to(arr, (n,))))

    @classmethod
    def for_joints(
        cls,
        n_joints: int,
        velocity: npt.ArrayLike,
        acceleration: npt.ArrayLike,
        jerk: npt.ArrayLike,
    ) -> JointLimits:
        """Limits of ``n_joints`` joints, each field a scalar (every joint) or shape (n,).

        Raises:
            InvalidInputError: ``n_joints`` is not a positive integer, a field has
                another shape, or a limit is malformed (as the constructor).
            NonFiniteInputError: A limit is NaN or infinite.
        """
        if isinstance(n_joints, bool) or not isinstance(n_joints, int) or n_joints < 1:
            raise InvalidInputError(f"n_joints must be a positive integer, got {n_joints!r}")
        fields = {
            name: _positive(value, name)
            for name, value in zip(_LIMIT_FIELDS, (velocity, acceleration, jerk))
        }
        for name, arr in fields.items():
            if arr.ndim == 1 and arr.shape != (n_joints,):
                raise InvalidInputError(
                    f"{name} limits must be a number or have shape ({n_joints},), got {arr.shape}"
                )
        return cls(*(tuple(np.broadcast_to(a, (n_joints,)).tolist()) for a in fields.values()))

    @property
    def n_joints(self) -> int:
        """The number of joints n."""
        return len(self.velocity)

    def of_order(self, order: int) -> FloatArray:
        """Limits of derivative ``order`` (1, 2 or 3), shape (n,) [rad/s^order]."""
        return np.array((self.velocity, self.acceleration, self.jerk)[order - 1])


def check_limits(limits: object) -> JointLimits:
    """``limits`` if it is a :class:`JointLimits`, else raise InvalidInputError."""
    return instance(limits, JointLimits, "limits")
