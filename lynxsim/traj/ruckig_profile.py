"""Time-optimal, jerk-limited joint motion with Ruckig, chained offline.

Ruckig plans one point-to-point motion per segment (state to state, all joints
finishing together). Waypoints are chained here, never with Ruckig's
``intermediate_positions``, which calls a cloud service. Each segment starts in
the state the previous one ends in, so position, velocity and acceleration are
continuous (position exactly, velocity to Ruckig's precision) and jerk stays
within its limit everywhere. Ruckig meets its targets to ~1e-8 (to ~1e-14 for
time-optimal rest-to-rest segments), so a waypoint is passed to that precision.

With ``pass_through`` the arm does not stop at intermediate waypoints: a joint
that keeps its direction through a waypoint passes it at the smaller of the two
adjacent segments' mean speeds (the rest-to-rest plan's, or the given
durations'), a joint that turns back passes at rest. A via velocity that would
carry a joint beyond its range (Ruckig's ``position_extrema``) is set to zero
and the chain replanned.

Every Ruckig profile is turned into a piecewise cubic (constant jerk per phase),
so sampling is vectorised. The chained states lie within the limits, so Ruckig
never prepends a braking phase.
"""

from __future__ import annotations

import re

import numpy as np
import numpy.typing as npt
import ruckig  # type: ignore[import-not-found]  # ships no type information

from lynxsim.angles import LIMIT_TOL
from lynxsim.bounds import MIN_SEGMENT_S
from lynxsim.errors import SegmentDurationError, TrajectoryError
from lynxsim.inputs import flag
from lynxsim.traj.check import check_trajectory
from lynxsim.traj.kinds import TrajectoryKind
from lynxsim.traj.limits import JointBounds, JointLimits
from lynxsim.traj.polynomial import DURATION_HINT, check_options
from lynxsim.traj.timing import Durations, check_planned, given_durations, require_motion
from lynxsim.traj.trajectory import PolynomialSegment, Trajectory
from lynxsim.traj.waypoints import Waypoints, WaypointsLike, resolve_waypoints

__all__ = ["profile_segment", "ruckig_trajectory"]

FloatArray = npt.NDArray[np.float64]

DURATION_TOL = 1e-9
"""Relative slack when comparing Ruckig's duration with a given one [-]."""

_LIMIT_SCALES = (1.0, 1.0 - 1e-9)
"""Ruckig 0.19 fails on rare inputs that lie exactly on the boundary between two of
its profile types (round joint moves under the default limits' round ratios); such a
segment is planned again with limits tighter by 1e-9 [-]."""

_BREAK_TOL = 1e-12
"""Phase boundaries of different joints closer than this merge [s]."""

_RESULTS = {
    0: "working",
    1: "finished",
    -1: "an error",
    -100: "invalid input (limits or states Ruckig cannot read)",
    -101: "the trajectory would last longer than Ruckig can compute (7600 s)",
    -102: "a position limit cannot be kept",
    -104: "zero limits",
    -110: "the time-optimal duration could not be calculated",
    -111: "the segment's joints could not be synchronised",
}
"""Ruckig's result codes (``ruckig::Result``); the Python module names only some of them."""

_RESULT_CODE = re.compile(r"^(-?\d+) is not a valid Result")


def _calculate(otg: ruckig.Ruckig, inp: ruckig.InputParameter, out: ruckig.Trajectory) -> str:
    """Run Ruckig's offline calculation; "" on success, else why it failed (one line)."""
    try:
        result = otg.calculate(inp, out)
    except ruckig.RuckigError as exc:
        first = next((line for line in str(exc).splitlines() if line.strip()), "an error")
        reason = first.strip().rstrip(":").removesuffix(" input")
        return f"{reason} (limits or states beyond its range)"
    except ValueError as exc:  # a result code the Python module has no name for
        match = _RESULT_CODE.match(str(exc))
        if match is None:
            return str(exc)
        code = int(match.group(1))
        return f"{_RESULTS.get(code, 'an unknown error')} (Ruckig result {code})"
    code = int(result.value)
    if code not in (0, 1):
        return f"{_RESULTS.get(code, 'an unknown error')} (Ruckig result {code})"
    return ""


def profile_segment(trajectory: ruckig.Trajectory) -> PolynomialSegment:
    """Turn a single-section Ruckig trajectory into a piecewise cubic segment.

    Args:
        trajectory: A calculated Ruckig trajectory without intermediate waypoints.

    Returns:
        The segment; its pieces are the union of all joints' phases.
    """
    profiles = trajectory.profiles[0]
    duration = float(trajectory.duration)
    starts = np.array([np.concatenate([[0.0], np.cumsum(p.t)]) for p in profiles])  # (dof, 8)
    pos = np.array([p.p for p in profiles])
    vel = np.array([p.v for p in profiles])
    acc = np.array([p.a for p in profiles])
    jerk = np.array([p.j for p in profiles])
    inner = np.sort(starts.ravel())
    inner = inner[(inner > _BREAK_TOL) & (inner < duration - _BREAK_TOL)]
    inner = inner[np.diff(inner, prepend=-np.inf) > _BREAK_TOL]
    breaks = np.concatenate([[0.0], inner, [duration]])
    coefficients = np.empty((breaks.size - 1, 4, len(profiles)))
    middle = 0.5 * (breaks[:-1] + breaks[1:])  # picks the phase a piece lies in, robustly
    for j in range(len(profiles)):
        phase = np.clip(np.searchsorted(starts[j], middle, side="right") - 1, 0, 6)
        u = breaks[:-1] - starts[j, phase]
        jk = jerk[j, phase]
        ak = acc[j, phase]
        vk = vel[j, phase]
        coefficients[:, 0, j] = pos[j, phase] + u * (vk + u * (ak / 2 + u * jk / 6))
        coefficients[:, 1, j] = vk + u * (ak + u * jk / 2)
        coefficients[:, 2, j] = (ak + u * jk) / 2
        coefficients[:, 3, j] = jk / 6
    return PolynomialSegment(breaks, coefficients)


def _plan(
    q: FloatArray, via: FloatArray, limits: JointLimits, minimum: FloatArray | None
) -> list[ruckig.Trajectory]:
    """Ruckig trajectories through ``q`` (N, n) with velocities ``via`` (N, n) [rad/s].

    Each segment starts where the previous one ends, at the velocity it was asked
    to end with (Ruckig meets it to ~1e-8 rad/s) and at rest in acceleration.
    """
    dof = q.shape[1]
    otg = ruckig.Ruckig(dof)
    inp = ruckig.InputParameter(dof)
    plans = []
    position = q[0].tolist()
    for k in range(q.shape[0] - 1):
        inp.current_position = position
        inp.current_velocity = via[k].tolist()
        inp.current_acceleration = [0.0] * dof
        inp.target_position = q[k + 1].tolist()
        inp.target_velocity = via[k + 1].tolist()
        inp.target_acceleration = [0.0] * dof
        if minimum is not None:
            inp.minimum_duration = float(minimum[k])
        out = ruckig.Trajectory(dof)
        for attempt, scale in enumerate(_LIMIT_SCALES):
            inp.max_velocity = [scale * v for v in limits.velocity]
            inp.max_acceleration = [scale * a for a in limits.acceleration]
            inp.max_jerk = [scale * j for j in limits.jerk]
            reason = _calculate(otg, inp, out)
            if not reason:
                break
            if attempt == len(_LIMIT_SCALES) - 1:
                raise TrajectoryError(f"Ruckig cannot plan segment {k + 1}: {reason}")
        plans.append(out)
        # Start the next segment where this one really ends (Ruckig meets a target to
        # ~1e-8 rad), so that the positions are exactly continuous.
        position = out.at_time(out.duration)[0]
    return plans


def _via_velocities(wp: Waypoints, times: FloatArray, limits: JointLimits) -> FloatArray:
    """Velocities at the waypoints for passing through, shape (N, n) [rad/s]."""
    slope = np.diff(wp.q, axis=0) / times[:, None]  # mean speed per segment
    v_in, v_out = slope[:-1], slope[1:]
    same = np.sign(v_in) * np.sign(v_out) > 0
    speed = np.minimum(np.minimum(np.abs(v_in), np.abs(v_out)), np.asarray(limits.velocity))
    via = np.zeros_like(wp.q)
    via[1:-1] = np.where(same, np.sign(v_in) * speed, 0.0)
    return via


def _overshoots(plans: list[ruckig.Trajectory], bounds: JointBounds) -> list[tuple[int, int]]:
    """(segment, joint) pairs whose extrema leave the joint ranges."""
    found = []
    for k, plan in enumerate(plans):
        for j, ext in enumerate(plan.position_extrema):
            if ext.min < bounds.lower[j] - LIMIT_TOL or ext.max > bounds.upper[j] + LIMIT_TOL:
                found.append((k, j))
    return found


def ruckig_trajectory(
    waypoints: WaypointsLike,
    durations: Durations = None,
    *,
    bounds: JointBounds,
    limits: JointLimits,
    stretch: bool = False,
    pass_through: bool = False,
) -> Trajectory:
    """Time-optimal jerk-limited motion through the waypoints (Ruckig).

    Position, velocity and acceleration are continuous; ranges, velocity,
    acceleration and jerk limits are checked.

    Args:
        waypoints: Joints, shape (N, n) [rad], or :class:`~lynxsim.traj.waypoints.Waypoints`.
        durations: Segment durations [s]; ``None`` for time-optimal segments.
            Given durations are Ruckig's ``minimum_duration``.
        bounds: The joints (n) and their ranges.
        limits: Joint limits, n joints (velocity, acceleration and jerk are fed to Ruckig).
        stretch: Accept segments longer than given durations where the limits
            need more time, instead of raising.
        pass_through: Pass intermediate waypoints without stopping.

    Returns:
        The checked :class:`Trajectory`.

    Raises:
        SegmentDurationError: A given duration is shorter than the limits allow
            and ``stretch`` is false (names segment, joint and the time needed).
        LimitViolationError: A joint leaves its range.
        JointRangeError: A waypoint has a joint out of its range (names the waypoint).
        InvalidInputError: Malformed waypoints, durations or options, or limits
            so low that a segment needs more than 3600 s.
        TrajectoryError: Ruckig cannot plan a segment (its reason in words).
    """
    bounds, limits, stretch = check_options(bounds, limits, stretch)
    pass_through = flag(pass_through, "pass_through")
    wp = resolve_waypoints(waypoints, bounds)
    given = given_durations(durations, wp.q.shape[0] - 1, wp.names)
    via = np.zeros_like(wp.q)
    plans = _plan(wp.q, via, limits, given)
    if given is None:
        shortest = np.array([p.duration for p in plans])
        require_motion(shortest, wp.names)
        check_planned(shortest, wp.names)
        if (shortest < MIN_SEGMENT_S).any():  # tiny motions, huge limits: segments of 1 ms
            given = np.maximum(shortest, MIN_SEGMENT_S)
            plans = _plan(wp.q, via, limits, given)
    if pass_through and wp.q.shape[0] > 2:
        times = given if given is not None else np.array([p.duration for p in plans])
        via = _via_velocities(wp, times, limits)
        plans = _plan(wp.q, via, limits, given)
        while fix := [(k, j) for k, j in _overshoots(plans, bounds) if via[k : k + 2, j].any()]:
            for k, j in fix:
                via[k : k + 2, j] = 0.0
            plans = _plan(wp.q, via, limits, given)
    if given is not None and not stretch:
        for k, (plan, want) in enumerate(zip(plans, given)):
            if plan.duration > want * (1.0 + DURATION_TOL):
                j = int(np.argmax(plan.independent_min_durations))
                names = wp.names
                raise SegmentDurationError(
                    f"ruckig trajectory: segment {k + 1} ({names[k]} -> {names[k + 1]}) needs "
                    f"{plan.duration:.4g} s within the limits, given {want:.4g} s; joint {j + 1} "
                    f"({bounds.names[j]}) needs the most time; {DURATION_HINT}",
                    segment=k,
                    joint=j + 1,
                    given=float(want),
                    required=float(plan.duration),
                )
    check_planned(np.array([p.duration for p in plans]), wp.names)
    segments = tuple(profile_segment(p) for p in plans)
    traj = Trajectory(TrajectoryKind.RUCKIG, segments, wp, bounds, limits)
    check_trajectory(traj)
    return traj
