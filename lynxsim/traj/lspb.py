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

import numpy as np
import numpy.typing as npt

from lynxsim.arm import LYNX_ARM, ArmGeometry
from lynxsim.traj.check import check_trajectory
from lynxsim.traj.kinds import TrajectoryKind
from lynxsim.traj.limits import DEFAULT_LIMITS, JointLimits
from lynxsim.traj.polynomial import DURATION_HINT
from lynxsim.traj.timing import Durations, segment_durations
from lynxsim.traj.trajectory import PolynomialSegment, Trajectory
from lynxsim.traj.waypoints import WaypointsLike, resolve_waypoints

__all__ = ["lspb", "lspb_segment"]

FloatArray = npt.NDArray[np.float64]


def _path_limits(delta: FloatArray, limits: JointLimits) -> tuple[FloatArray, FloatArray]:
    """Largest path speed and acceleration all joints allow, shape (M,) each [1/s, 1/s^2]."""
    d = np.abs(delta)
    with np.errstate(divide="ignore"):
        v = np.min(np.asarray(limits.velocity) / d, axis=1)
        a = np.min(np.asarray(limits.acceleration) / d, axis=1)
    return v, a


def _shortest(v: FloatArray, a: FloatArray) -> FloatArray:
    """Shortest rest-to-rest time for a unit path: trapezoid, or triangle if V is never reached."""
    with np.errstate(invalid="ignore", divide="ignore"):
        triangle = v * v >= a
        t = np.where(triangle, 2.0 / np.sqrt(a), 1.0 / v + v / a)
    return np.where(np.isfinite(t), t, 0.0)


def lspb_segment(
    q0: FloatArray, q1: FloatArray, duration: float, accel: float
) -> PolynomialSegment:
    """One LSPB segment from rest to rest.

    Args:
        q0: Start joints, shape (5,) [rad].
        q1: End joints, shape (5,) [rad].
        duration: Segment duration [s].
        accel: Path acceleration of the blends [1/s^2] (``s`` runs from 0 to 1).
            If the duration is too short for it (``accel duration^2 < 4``), the
            blends take half the segment each (a triangle at ``4 / duration^2``).

    Returns:
        The piecewise-quadratic segment (two or three pieces).
    """
    t = duration
    disc = t * t - 4.0 / accel
    tb = 0.5 * (t - np.sqrt(disc)) if disc > 0.0 else 0.5 * t
    a = 1.0 / (tb * (t - tb))  # path acceleration that reaches s = 1 at t
    v = a * tb
    s_tb = 0.5 * a * tb * tb
    dq = q1 - q0
    blend_in = np.stack([q0, np.zeros(5), 0.5 * a * dq])
    cruise = np.stack([q0 + s_tb * dq, v * dq, np.zeros(5)])
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
    limits: JointLimits = DEFAULT_LIMITS,
    stretch: bool = False,
    geometry: ArmGeometry = LYNX_ARM,
) -> Trajectory:
    """Linear segments with parabolic blends, at rest at every waypoint.

    Acceleration jumps at the blend ends, so joint ranges, velocity and
    acceleration limits are checked.

    Args:
        waypoints: Poses or joints, shape (N, 5) [rad]; see :mod:`lynxsim.traj.waypoints`.
        durations: Segment durations [s]; see :mod:`lynxsim.traj.timing`.
        limits: Joint limits to respect.
        stretch: Lengthen given durations that are too short for the limits.
        geometry: The arm description.

    Returns:
        The checked :class:`Trajectory`.

    Raises:
        LimitViolationError: Given durations break a limit (names joint, time, excess).
        UnreachablePoseError: A pose has no IK solution (names the pose).
        InvalidInputError: Malformed waypoints or durations.
    """
    wp = resolve_waypoints(waypoints, geometry)
    delta = np.diff(wp.q, axis=0)
    v, a = _path_limits(delta, limits)
    times = segment_durations(durations, _shortest(v, a), wp.names, stretch=stretch)
    segments = tuple(
        lspb_segment(q0, q1, float(t), float(acc))
        for q0, q1, t, acc in zip(wp.q[:-1], wp.q[1:], times, a)
    )
    traj = Trajectory(TrajectoryKind.LSPB, segments, wp, limits)
    check_trajectory(traj, geometry, hint=DURATION_HINT)
    return traj
