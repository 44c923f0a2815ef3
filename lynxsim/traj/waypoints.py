"""Waypoints of a trajectory: joint vectors of any number of joints, with names.

A generator accepts an array of joint vectors, shape (N, n) [rad], or a
:class:`Waypoints` (joints and names); :func:`resolve_waypoints` checks either
against the joints' :class:`~lynxsim.traj.limits.JointBounds`. Task poses (a
tool point, a platform pose) become joints in their robot's own room, e.g.
:mod:`lynxsim.arm.motion.waypoints`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from lynxsim.angles import LIMIT_TOL
from lynxsim.bounds import MAX_SAMPLES
from lynxsim.errors import InvalidInputError, JointRangeError, NonFiniteInputError
from lynxsim.inputs import finite_array, instance, real_array
from lynxsim.traj.check import CHECK_POINTS
from lynxsim.traj.limits import JointBounds

__all__ = [
    "MAX_WAYPOINTS",
    "Waypoints",
    "WaypointsLike",
    "check_bounds",
    "check_range",
    "check_waypoint_count",
    "joint_array",
    "resolve_waypoints",
]

FloatArray = npt.NDArray[np.float64]

MAX_WAYPOINTS = 1 + MAX_SAMPLES // CHECK_POINTS
"""Most waypoints of one trajectory: the check evaluates ``CHECK_POINTS`` samples per
segment, at most :data:`~lynxsim.bounds.MAX_SAMPLES` in all (9,757 waypoints)."""


def check_waypoint_count(n: int) -> None:
    """Raise unless ``n`` waypoints make a trajectory (2 to :data:`MAX_WAYPOINTS`)."""
    if not 2 <= n <= MAX_WAYPOINTS:
        raise InvalidInputError(f"a trajectory needs 2 to {MAX_WAYPOINTS:,} waypoints, got {n:,}")


def check_bounds(bounds: object) -> JointBounds:
    """``bounds`` if it is a :class:`~lynxsim.traj.limits.JointBounds`, else raise."""
    return instance(bounds, JointBounds, "bounds")


@dataclass(frozen=True)
class Waypoints:
    """Joint waypoints and their names.

    Attributes:
        q: Joints at the waypoints, shape (N, n), N >= 2 [rad], read-only.
        names: One label per waypoint (messages, plots).

    Raises:
        InvalidInputError: ``q`` is not real numbers of shape (N, n) with
            2 <= N <= :data:`MAX_WAYPOINTS`, or the names are not N strings.
        NonFiniteInputError: A joint value is NaN or infinite.
    """

    q: FloatArray
    names: tuple[str, ...]

    def __post_init__(self) -> None:
        q = np.array(finite_array(self.q, "waypoint joints"))  # a copy: frozen below
        if q.ndim != 2 or q.shape[1] < 1 or q.shape[0] < 2:
            raise InvalidInputError(
                f"waypoint joints must have shape (N, n), N >= 2, got {q.shape}"
            )
        check_waypoint_count(q.shape[0])
        names = self.names
        if not (
            isinstance(names, tuple)
            and len(names) == q.shape[0]
            and all(isinstance(n, str) for n in names)
        ):
            raise InvalidInputError(f"waypoint names must be a tuple of {q.shape[0]} strings")
        q.setflags(write=False)
        object.__setattr__(self, "q", q)

    @property
    def n_joints(self) -> int:
        """The number of joints n."""
        return int(self.q.shape[1])


WaypointsLike = Waypoints | npt.ArrayLike
"""What generators accept: :class:`Waypoints`, or joint vectors of shape (N, n) [rad]."""


def check_range(q: FloatArray, name: str, bounds: JointBounds) -> None:
    """Raise JointRangeError if waypoint ``name``'s joints ``q`` (n,) leave their ranges."""
    lower, upper = bounds.lower_array, bounds.upper_array
    excess = np.maximum(lower - q, q - upper)
    j = int(np.argmax(excess))
    if excess[j] > LIMIT_TOL:
        lo, hi = math.degrees(lower[j]), math.degrees(upper[j])
        raise JointRangeError(  # math.degrees: inf for a joint beyond 1e306 rad, no warning
            f"waypoint {name}: joint {j + 1} ({bounds.names[j]}) = "
            f"{math.degrees(q[j]):.4g} deg is outside its range [{lo:.4g}, {hi:.4g}] deg "
            f"by {math.degrees(excess[j]):.4g} deg",
            joint=j + 1,
        )


def joint_array(waypoints: object, n: int, accepted: str = "Waypoints") -> FloatArray:
    """Joint waypoints given as an array: real, finite, shape (N, n), 2 to MAX_WAYPOINTS rows.

    Args:
        waypoints: The array (or nested sequences).
        n: The number of joints.
        accepted: What else the caller accepts, for the message of a wrong type.

    Raises:
        InvalidInputError: Not real numbers (its subclass kept), a wrong shape or count.
        NonFiniteInputError: A value is NaN or infinite.
    """
    try:
        arr = real_array(waypoints, "joint waypoints")
    except InvalidInputError as exc:  # keeps its class (InvalidTypeError for a wrong type)
        raise type(exc)(
            f"waypoints must be {accepted} or joints of shape (N, {n}): {exc}"
        ) from None
    if arr.ndim != 2 or arr.shape[1] != n:
        raise InvalidInputError(f"joint waypoints must have shape (N, {n}), got {arr.shape}")
    check_waypoint_count(arr.shape[0])
    if not np.isfinite(arr).all():
        raise NonFiniteInputError("joint waypoints must be finite")
    return arr


def resolve_waypoints(waypoints: WaypointsLike, bounds: JointBounds) -> Waypoints:
    """Check joint waypoints against the joints' ranges.

    Args:
        waypoints: :class:`Waypoints`, or at least two joint vectors, shape (N, n)
            [rad] (named ``P1``, ``P2``, ...).
        bounds: The joints (n of them) and their ranges.

    Returns:
        The :class:`Waypoints`.

    Raises:
        JointRangeError: A joint vector has a joint out of range (names the waypoint).
        InvalidInputError: Fewer than two or more than :data:`MAX_WAYPOINTS`
            waypoints, a wrong shape (n joints as ``bounds``), values that are not
            real numbers, or ``bounds`` not a :class:`~lynxsim.traj.limits.JointBounds`.
        NonFiniteInputError: A value is NaN or infinite.
    """
    bounds = check_bounds(bounds)
    n = bounds.n_joints
    if isinstance(waypoints, Waypoints):
        wp = waypoints
        if wp.n_joints != n:
            raise InvalidInputError(
                f"waypoints of {wp.n_joints} joints, but the bounds are for {n} joints"
            )
    else:
        arr = joint_array(waypoints, n)
        wp = Waypoints(arr, tuple(f"P{i + 1}" for i in range(arr.shape[0])))
    for q, name in zip(wp.q, wp.names):
        check_range(q, name, bounds)
    return wp
