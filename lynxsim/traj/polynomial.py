"""Joint-space polynomial trajectories: free motion, cubic and quintic.

Every segment moves all joints along the straight line in joint space from one
waypoint to the next, ``q(tau) = q0 + (q1 - q0) s(tau / T)``:

* free motion: ``s(u) = u`` (the report's fixed joint increments per step);
* cubic: zero velocity at both ends (report eqs. 35–42);
* quintic: zero velocity and acceleration at both ends (report eqs. 43–52).

The cubic and quintic coefficients solve the boundary-condition systems of the
report with its typos corrected (SPEC 3.5: the velocity row reads
``0, 1, 2 t0, 3 t0^2, 4 t0^3, 5 t0^4`` and the final-acceleration row
``0, 0, 2, 6 tf, 12 tf^2, 20 tf^3``).
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
import numpy.typing as npt

from lynxsim.bounds import MAX_SEGMENT_S, MIN_SEGMENT_S
from lynxsim.errors import InvalidInputError, NonFiniteInputError
from lynxsim.inputs import finite_array, flag, number_in_range
from lynxsim.traj.check import check_trajectory
from lynxsim.traj.kinds import TrajectoryKind
from lynxsim.traj.limits import JointBounds, JointLimits, check_limits
from lynxsim.traj.timing import Durations, scaled_shortest, segment_durations
from lynxsim.traj.trajectory import PolynomialSegment, Trajectory
from lynxsim.traj.waypoints import WaypointsLike, check_bounds, resolve_waypoints

__all__ = [
    "cubic",
    "cubic_coefficients",
    "free_motion",
    "quintic",
    "quintic_coefficients",
    "quintic_scaling",
]

FloatArray = npt.NDArray[np.float64]

DURATION_HINT = "give longer durations, set stretch, or leave the durations out for the shortest"


def _boundary_system(
    t0: object, tf: object, values: tuple[object, ...]
) -> tuple[float, float, FloatArray]:
    """Check the times and boundary values of a polynomial fit.

    Returns:
        ``t0, tf`` [s] and the boundary values broadcast and stacked, shape
        (len(values),) + S.

    Raises:
        InvalidInputError: A time is not a number in [-3600, 3600] s, ``tf - t0``
            is not in [0.001, 3600] s, or the values are not real numbers that
            broadcast together.
        NonFiniteInputError: A time or value is NaN or infinite.
    """
    t0 = number_in_range(t0, "t0", -MAX_SEGMENT_S, MAX_SEGMENT_S, "s")
    tf = number_in_range(tf, "tf", -MAX_SEGMENT_S, MAX_SEGMENT_S, "s")
    number_in_range(tf - t0, "tf - t0", MIN_SEGMENT_S, MAX_SEGMENT_S, "s")
    arrays = [finite_array(v, "boundary values") for v in values]
    try:
        b = np.array(np.broadcast_arrays(*arrays), dtype=float)
    except ValueError as exc:
        raise InvalidInputError(f"boundary values do not broadcast: {exc}") from None
    return t0, tf, b


def _solve(a: FloatArray, b: FloatArray) -> FloatArray:
    """``a^-1 b`` over the leading axis of ``b``; raise if the coefficients overflow."""
    with np.errstate(over="ignore", invalid="ignore"):
        x = np.linalg.solve(a, b.reshape(b.shape[0], -1))
    out: FloatArray = np.asarray(x, dtype=np.float64).reshape(b.shape)
    if not np.isfinite(out).all():
        raise NonFiniteInputError("boundary values too large: the coefficients overflow float64")
    return out


def cubic_coefficients(
    t0: float,
    tf: float,
    q0: npt.ArrayLike,
    v0: npt.ArrayLike,
    qf: npt.ArrayLike,
    vf: npt.ArrayLike,
) -> FloatArray:
    """Cubic ``q(t) = a0 + a1 t + a2 t^2 + a3 t^3`` through boundary conditions.

    Solves the report's eq. 42 with the velocity row corrected to
    ``0, 1, 2 t0, 3 t0^2``.

    Args:
        t0: Start time [s], in [-3600, 3600].
        tf: End time [s], ``tf - t0`` in [0.001, 3600] s.
        q0: Start position, shape S [rad].
        v0: Start velocity, broadcastable to S [rad/s].
        qf: End position, broadcastable to S [rad].
        vf: End velocity, broadcastable to S [rad/s].

    Returns:
        ``a0..a3``, shape (4,) + S [rad/s^k], ascending powers of ``t``.

    Raises:
        InvalidInputError: Times out of range, values not real numbers or not
            broadcastable.
        NonFiniteInputError: A value is NaN or infinite, or the coefficients overflow.
    """
    t0, tf, b = _boundary_system(t0, tf, (q0, v0, qf, vf))
    a = np.array(
        [
            [1.0, t0, t0**2, t0**3],
            [0.0, 1.0, 2 * t0, 3 * t0**2],
            [1.0, tf, tf**2, tf**3],
            [0.0, 1.0, 2 * tf, 3 * tf**2],
        ]
    )
    return _solve(a, b)


def quintic_coefficients(
    t0: float,
    tf: float,
    q0: npt.ArrayLike,
    v0: npt.ArrayLike,
    a0: npt.ArrayLike,
    qf: npt.ArrayLike,
    vf: npt.ArrayLike,
    af: npt.ArrayLike,
) -> FloatArray:
    """Quintic ``q(t) = sum_k a_k t^k`` through position, velocity, acceleration at both ends.

    Solves the report's eq. 52 with its two typos corrected (SPEC 3.5).

    Args:
        t0: Start time [s], in [-3600, 3600].
        tf: End time [s], ``tf - t0`` in [0.001, 3600] s.
        q0: Start position, shape S [rad].
        v0: Start velocity, broadcastable to S [rad/s].
        a0: Start acceleration, broadcastable to S [rad/s^2].
        qf: End position, broadcastable to S [rad].
        vf: End velocity, broadcastable to S [rad/s].
        af: End acceleration, broadcastable to S [rad/s^2].

    Returns:
        ``a0..a5``, shape (6,) + S [rad/s^k], ascending powers of ``t``.

    Raises:
        InvalidInputError: Times out of range, values not real numbers or not
            broadcastable.
        NonFiniteInputError: A value is NaN or infinite, or the coefficients overflow.
    """
    t0, tf, b = _boundary_system(t0, tf, (q0, v0, a0, qf, vf, af))

    def rows(t: float) -> list[list[float]]:
        return [
            [1.0, t, t**2, t**3, t**4, t**5],
            [0.0, 1.0, 2 * t, 3 * t**2, 4 * t**3, 5 * t**4],
            [0.0, 0.0, 2.0, 6 * t, 12 * t**2, 20 * t**3],
        ]

    a = np.array(rows(t0) + rows(tf))
    return _solve(a, b)


def quintic_scaling(u: FloatArray) -> FloatArray:
    """The rest-to-rest quintic ``s(u) = 10 u^3 - 15 u^4 + 6 u^5`` and its derivatives.

    Args:
        u: Normalised time in [0, 1], shape (n,).

    Returns:
        ``s, ds/du, d2s/du2, d3s/du3``, shape (4, n); ``s`` clipped into [0, 1]
        (rounding would otherwise overshoot 1 by an ulp just before ``u = 1``,
        enough to cross a boundary such as a serial arm's base-axis fold).
    """
    u2 = u * u
    w = u - u2  # u (1 - u)
    return np.stack(
        [
            np.clip(u2 * u * (10.0 - 15.0 * u + 6.0 * u2), 0.0, 1.0),
            30.0 * w * w,
            60.0 * w * (1.0 - 2.0 * u),
            60.0 - 360.0 * w,
        ]
    )


_UNIT_PEAKS = {
    # Peak |d^k s / du^k| of each shape, k = 1, 2, 3.
    TrajectoryKind.FREE: (1.0, 0.0, 0.0),
    TrajectoryKind.CUBIC: (1.5, 6.0, 12.0),
    TrajectoryKind.QUINTIC: (15.0 / 8.0, 10.0 / math.sqrt(3.0), 60.0),
}


def _free_coefficients(q0: FloatArray, q1: FloatArray, duration: float) -> FloatArray:
    return np.stack([q0, (q1 - q0) / duration])


def _cubic_coefficients(q0: FloatArray, q1: FloatArray, duration: float) -> FloatArray:
    return cubic_coefficients(0.0, duration, q0, 0.0, q1, 0.0)


def _quintic_coefficients(q0: FloatArray, q1: FloatArray, duration: float) -> FloatArray:
    return quintic_coefficients(0.0, duration, q0, 0.0, 0.0, q1, 0.0, 0.0)


_COEFFICIENTS: dict[TrajectoryKind, Callable[[FloatArray, FloatArray, float], FloatArray]] = {
    TrajectoryKind.FREE: _free_coefficients,
    TrajectoryKind.CUBIC: _cubic_coefficients,
    TrajectoryKind.QUINTIC: _quintic_coefficients,
}


def check_options(
    bounds: object, limits: object, stretch: object
) -> tuple[JointBounds, JointLimits, bool]:
    """The generators' keyword options, type-checked.

    Raises:
        InvalidInputError: ``bounds`` is not a :class:`JointBounds`, ``limits``
            not a :class:`JointLimits` of as many joints, or ``stretch`` not a bool.
    """
    bounds, limits = check_bounds(bounds), check_limits(limits)
    if limits.n_joints != bounds.n_joints:
        raise InvalidInputError(
            f"limits of {limits.n_joints} joints for bounds of {bounds.n_joints} joints"
        )
    return bounds, limits, flag(stretch, "stretch")


def _joint_polynomial(
    kind: TrajectoryKind,
    waypoints: WaypointsLike,
    durations: Durations,
    bounds: JointBounds,
    limits: JointLimits,
    stretch: bool,
) -> Trajectory:
    bounds, limits, stretch = check_options(bounds, limits, stretch)
    wp = resolve_waypoints(waypoints, bounds)
    delta = np.abs(np.diff(wp.q, axis=0))
    peaks = np.stack([f * delta for f in _UNIT_PEAKS[kind]])
    shortest = scaled_shortest(peaks, limits, kind.limited_orders)
    times = segment_durations(durations, shortest, wp.names, stretch=stretch)
    make = _COEFFICIENTS[kind]
    segments = tuple(
        PolynomialSegment(np.array([0.0, t]), make(q0, q1, float(t))[None])
        for q0, q1, t in zip(wp.q[:-1], wp.q[1:], times)
    )
    traj = Trajectory(kind, segments, wp, bounds, limits)
    check_trajectory(traj, hint=DURATION_HINT)
    return traj


def free_motion(
    waypoints: WaypointsLike,
    durations: Durations = None,
    *,
    bounds: JointBounds,
    limits: JointLimits,
    stretch: bool = False,
) -> Trajectory:
    """Free motion: every joint at constant speed from waypoint to waypoint.

    Velocity jumps at every waypoint (acceleration impulses there), so only
    joint ranges and velocity limits are checked.

    Args:
        waypoints: Joints, shape (N, n) [rad], or :class:`~lynxsim.traj.waypoints.Waypoints`.
        durations: Segment durations [s]; see :mod:`lynxsim.traj.timing`.
        bounds: The joints (n) and their ranges.
        limits: Joint limits to respect (n joints).
        stretch: Lengthen given durations that are too short for the limits.

    Returns:
        The checked :class:`Trajectory`.

    Raises:
        LimitViolationError: Given durations break a limit (names joint, time, excess).
        JointRangeError: A waypoint has a joint out of its range (names the waypoint).
        InvalidInputError: Malformed waypoints, durations or options.
    """
    return _joint_polynomial(TrajectoryKind.FREE, waypoints, durations, bounds, limits, stretch)


def cubic(
    waypoints: WaypointsLike,
    durations: Durations = None,
    *,
    bounds: JointBounds,
    limits: JointLimits,
    stretch: bool = False,
) -> Trajectory:
    """Cubic polynomial per segment, at rest at every waypoint.

    Acceleration jumps at the waypoints, so joint ranges, velocity and
    acceleration limits are checked. Arguments, returns and errors as
    :func:`free_motion`.
    """
    return _joint_polynomial(TrajectoryKind.CUBIC, waypoints, durations, bounds, limits, stretch)


def quintic(
    waypoints: WaypointsLike,
    durations: Durations = None,
    *,
    bounds: JointBounds,
    limits: JointLimits,
    stretch: bool = False,
) -> Trajectory:
    """Quintic polynomial per segment, zero velocity and acceleration at every waypoint.

    Velocity and acceleration are continuous; ranges, velocity, acceleration
    and jerk limits are checked. Arguments, returns and errors as
    :func:`free_motion`.
    """
    return _joint_polynomial(TrajectoryKind.QUINTIC, waypoints, durations, bounds, limits, stretch)
