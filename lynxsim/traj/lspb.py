"""Linear segments with parabolic blends (trapezoidal velocity) in joint space.

Each segment moves the joints along the straight line in joint space,
``q = q0 + dq s(tau)``, with a trapezoidal profile of the path parameter ``s``:
constant acceleration ``A`` for the blend time ``tb``, cruise at ``V = A tb``,
constant deceleration for ``tb``. The joint that is closest to its limits
decides: ``A`` is the largest path acceleration all joints allow, so the blends
run at that joint's acceleration limit; the cruise speed follows from the
duration. With no duration given, the segment is the shortest trapezoid (or
triangle) within the velocity and acceleration limits. Every segment starts and
ends at rest, so the waypoints are passed exactly.
"""

from __future__ import annotations

import math

import numpy as np
import numpy.typing as npt

from lynxsim.bounds import MAX_SEGMENT_S, MIN_SEGMENT_S
from lynxsim.errors import InvalidInputError
from lynxsim.inputs import finite_array, number_in_range, positive_number, real_number
from lynxsim.traj.check import check_trajectory
from lynxsim.traj.kinds import TrajectoryKind
from lynxsim.traj.limits import JointBounds, JointLimits
from lynxsim.traj.polynomial import DURATION_HINT, check_options
from lynxsim.traj.timing import Durations, segment_durations
from lynxsim.traj.trajectory import PolynomialSegment, Trajectory
from lynxsim.traj.waypoints import WaypointsLike, resolve_waypoints

__all__ = ["lspb", "lspb_segment"]

FloatArray = npt.NDArray[np.float64]

MIN_BLEND = 1e-12
"""Shortest blend as a fraction of the segment [-]: a segment whose joints barely move
(path acceleration beyond float64) still gets three distinct pieces; the blends are then
longer than the limits need, so the joints accelerate less."""


def _path_limits(delta: FloatArray, limits: JointLimits) -> tuple[FloatArray, FloatArray]:
    """Largest path speed and acceleration all joints allow, shape (M,) each [1/s, 1/s^2]."""
    d = np.abs(delta)
    with np.errstate(divide="ignore", over="ignore"):  # no motion, or a denormal one: inf
        v = np.min(np.asarray(limits.velocity) / d, axis=1)
        a = np.min(np.asarray(limits.acceleration) / d, axis=1)
    return v, a


def _shortest(v: FloatArray, a: FloatArray) -> FloatArray:
    """Shortest rest-to-rest time for a unit path: trapezoid, or triangle if V is never reached.

    Returns:
        Shape (M,) [s]: 0 for a segment without motion, inf where the limits are
        too low for float64 (refused by :func:`~lynxsim.traj.timing.check_planned`).
    """
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        triangle = v * v >= a
        t = np.where(triangle, 2.0 / np.sqrt(a), 1.0 / v + v / a)
    # 0 without motion (v = a = inf); inf where the limits underflow (v = a = 0).
    return np.where(np.isnan(t), np.inf, t)


def lspb_segment(
    q0: FloatArray, q1: FloatArray, duration: float, accel: float
) -> PolynomialSegment:
    """One LSPB segment from rest to rest.

    Args:
        q0: Start joints, shape (n,) [rad].
        q1: End joints, shape (n,) [rad], as many.
        duration: Segment duration, 0.001 to 3600 [s].
        accel: Path acceleration of the blends [1/s^2] (``s`` runs from 0 to 1),
            positive, ``inf`` for a segment without motion. If the duration is
            too short for it (``accel duration^2 < 4``), the blends take half the
            segment each (a triangle at ``4 / duration^2``); blends are at least
            :data:`MIN_BLEND` of the duration.

    Returns:
        The piecewise-quadratic segment (two or three pieces).

    Raises:
        InvalidInputError: A value is not a real number, or out of range.
        NonFiniteInputError: A joint value is NaN or infinite.
    """
    q0, q1 = (finite_array(q, name) for q, name in ((q0, "q0"), (q1, "q1")))
    if q0.ndim != 1 or q0.size < 1 or q1.shape != q0.shape:
        raise InvalidInputError(
            f"q0 and q1 must have one shape (n,), n >= 1, got {q0.shape}, {q1.shape}"
        )
    zero = np.zeros(q0.size)
    t = number_in_range(duration, "duration", MIN_SEGMENT_S, MAX_SEGMENT_S, "s")
    accel = real_number(accel, "accel")
    if accel != math.inf:
        accel = positive_number(accel, "accel", "1/s^2")
    disc = t * t - 4.0 / accel
    # The smaller root of tb^2 - t tb + 1/accel = 0, in the form without cancellation.
    tb = 2.0 / (accel * (t + math.sqrt(disc))) if disc > 0.0 else 0.5 * t
    tb = max(tb, MIN_BLEND * t)
    a = 1.0 / (tb * (t - tb))  # path acceleration that reaches s = 1 at t
    v = a * tb
    s_tb = 0.5 * a * tb * tb
    with np.errstate(over="ignore", invalid="ignore"):  # joints beyond 1e307 rad: refused below
        dq = q1 - q0
        blend_in = np.stack([q0, zero, 0.5 * a * dq])
        cruise = np.stack([q0 + s_tb * dq, v * dq, zero])
        blend_out = np.stack([q1 - s_tb * dq, v * dq, -0.5 * a * dq])
    if t - 2.0 * tb > 0.0:
        return PolynomialSegment(
            np.array([0.0, tb, t - tb, t]), np.stack([blend_in, cruise, blend_out])
        )
    return PolynomialSegment(np.array([0.0, tb, t]), np.stack([blend_in, blend_out]))


def lspb(
    waypoints: WaypointsLike,
    durations: Durations = None,
    *,
    bounds: JointBounds,
    limits: JointLimits,
    stretch: bool = False,
) -> Trajectory:
    """Linear segments with parabolic blends, at rest at every waypoint.

    Acceleration jumps at the blend ends, so joint ranges, velocity and
    acceleration limits are checked.

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
    bounds, limits, stretch = check_options(bounds, limits, stretch)
    wp = resolve_waypoints(waypoints, bounds)
    delta = np.diff(wp.q, axis=0)
    v, a = _path_limits(delta, limits)
    times = segment_durations(durations, _shortest(v, a), wp.names, stretch=stretch)
    segments = tuple(
        lspb_segment(q0, q1, float(t), float(acc))
        for q0, q1, t, acc in zip(wp.q[:-1], wp.q[1:], times, a)
    )
    traj = Trajectory(TrajectoryKind.LSPB, segments, wp, bounds, limits)
    check_trajectory(traj, hint=DURATION_HINT)
    return traj
