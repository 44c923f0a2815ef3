"""Straight tool lines in Cartesian space, joints from the IK at every sample.

Between consecutive waypoints the tool point moves on the straight line
``p(tau) = p0 + (p1 - p0) s(tau / T)``; pitch and roll move by the same
fraction. ``s`` is the rest-to-rest quintic, so the tool stops at every
waypoint and joint velocity and acceleration are continuous everywhere (the
report's straight line, sampled at constant speed, jumps in velocity).

Joints come from the closed-form IK, :func:`lynxsim.arm.ik`, for all samples
in one vectorised call: its candidate of the solution branch of the segment's
first waypoint (so the arm never changes configuration mid-line). Joint
velocity, acceleration and jerk are exact: the chain rule through the IK
(``q1`` from ``log(x + i y)``, the planar two-link arm solved as a complex
linear system for each derivative order).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import numpy.typing as npt

from lynxsim.angles import wrap_angle
from lynxsim.arm.geometry import LYNX_ARM, ArmGeometry
from lynxsim.arm.ik import ik, ik_candidates
from lynxsim.arm.motion.space import ARM_LIMITS, joint_bounds
from lynxsim.arm.motion.waypoints import ArmWaypointsLike, resolve_waypoints
from lynxsim.bounds import MAX_SEGMENT_S, MIN_SEGMENT_S
from lynxsim.errors import InvalidInputError, JointRangeError, OutOfReachError, PathError
from lynxsim.inputs import instance, number_in_range
from lynxsim.poses import ArmPose
from lynxsim.traj.check import Extremes, check_grid, check_trajectory, segment_extremes
from lynxsim.traj.kinds import TrajectoryKind
from lynxsim.traj.limits import JointLimits
from lynxsim.traj.polynomial import DURATION_HINT, check_options, quintic_scaling
from lynxsim.traj.timing import Durations, scaled_shortest, segment_durations
from lynxsim.traj.trajectory import Trajectory

__all__ = ["LineSegment", "cartesian_line"]

FloatArray = npt.NDArray[np.float64]

JUMP_FACTOR = 2.0
"""A grid step moving a joint more than this many times its rate allows is a jump [-]."""

JUMP_TOL = 1e-6
"""Absolute slack of the jump test [rad]."""


@dataclass(frozen=True)
class LineSegment:
    """The tool on a straight line between two poses, one IK branch throughout.

    Attributes:
        start: Pose at the start (``roll`` set).
        end: Pose at the end (``roll`` set).
        duration: Segment duration [s].
        branch: IK candidate slot (0..3, see :mod:`lynxsim.arm.ik`): bit 1 the
            base side (0: as the target's heading, 1: turned by pi), bit 0 the
            elbow (0: ``q3 <= 0``, 1: ``q3 >= 0``).
        geometry: The arm description.

    Raises:
        InvalidInputError: A pose is not an :class:`ArmPose` with its roll set,
            the duration is not in [0.001, 3600] s, the branch not 0..3, or the
            geometry not an :class:`~lynxsim.arm.ArmGeometry`.
    """

    start: ArmPose
    end: ArmPose
    duration: float
    branch: int
    geometry: ArmGeometry = LYNX_ARM
    _rolls: tuple[float, float] = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        start = instance(self.start, ArmPose, "start")
        end = instance(self.end, ArmPose, "end")
        if start.roll is None or end.roll is None:
            raise InvalidInputError("line segment poses need their roll set")
        duration = number_in_range(self.duration, "duration", MIN_SEGMENT_S, MAX_SEGMENT_S, "s")
        object.__setattr__(self, "duration", duration)
        branch = self.branch
        if (
            isinstance(branch, bool)
            or not isinstance(branch, int | np.integer)
            or branch not in range(4)
        ):
            raise InvalidInputError(f"branch must be 0..3, got {self.branch!r}")
        object.__setattr__(self, "branch", int(branch))
        instance(self.geometry, ArmGeometry, "geometry")
        object.__setattr__(self, "_rolls", (start.roll, end.roll))

    @property
    def n_joints(self) -> int:
        """The arm's five joints."""
        return 5

    @property
    def breakpoints(self) -> FloatArray:
        """None: one formula over the whole line, shape (0,) [s]."""
        return np.empty(0)

    def evaluate(self, tau: FloatArray) -> FloatArray:
        """Joint states at local times ``tau``, shape (4, n, 5); see :class:`Segment`."""
        return self.states(tau)[0]

    def states(self, tau: FloatArray) -> tuple[FloatArray, npt.NDArray[np.bool_]]:
        """Joint states and the reach test at local times.

        Args:
            tau: Local times, shape (n,) [s].

        Returns:
            ``(states, in_reach)``: states of shape (4, n, 5) as :meth:`evaluate`
            (a view), and the IK's reach test of the tool's targets, shape (n,)
            (where it fails, the states are those of the nearest stretch).
        """
        with np.errstate(divide="ignore", invalid="ignore"):  # singularities give inf/NaN
            return self._states(tau)

    def _states(self, tau: FloatArray) -> tuple[FloatArray, npt.NDArray[np.bool_]]:
        g = self.geometry
        l2, l3, lt = g.upper_arm, g.forearm, g.tool_length
        duration = self.duration
        s = quintic_scaling(tau / duration)
        s[1] /= duration
        s[2] /= duration**2
        s[3] /= duration**3
        p0, p1 = np.asarray(self.start.position), np.asarray(self.end.position)
        dx, dy, dz = p1 - p0
        dpitch = self.end.pitch - self.start.pitch
        # The in-plane pitch q2 + q3 + q4 moves as the target's pitch, mirrored on side 1.
        dphi = -dpitch if self.branch >= 2 else dpitch
        roll0, roll1 = self._rolls
        droll = roll1 - roll0

        points = p0 + s[0][:, None] * (p1 - p0)
        x, y = points[:, 0], points[:, 1]
        # The joints: the IK's candidate of the segment's branch at every sample.
        candidates, in_reach = ik_candidates(points, self.start.pitch + dpitch * s[0], g)
        q = candidates[:, self.branch]  # (5, n)
        q1, q2, q3 = q[0], q[1], q[2]
        reach = x * np.cos(q1) + y * np.sin(q1)  # signed horizontal reach in the arm's plane
        e2 = np.exp(1j * q2)
        e3 = np.exp(1j * q3)
        s3 = e3.imag

        out = np.empty((4, 5, tau.size))
        out[0, :4] = q[:4]
        out[0, 4] = roll0 + droll * s[0]

        # q1 = Im log(x + i y) and ln|reach| = Re log(x + i y), differentiated.
        g1 = complex(dx, dy) / (x + 1j * y)
        lg1 = g1 * s[1]
        gs2 = g1 * s[2]
        lg2 = gs2 - lg1 * lg1
        lg3 = g1 * s[3] - 3.0 * lg1 * gs2 + 2.0 * lg1**3
        r1 = reach * lg1.real
        r2 = reach * (lg2.real + lg1.real**2)
        r3 = reach * (lg3.real + 3.0 * lg1.real * lg2.real + lg1.real**3)
        phi1, phi2, phi3 = dphi * s[1], dphi * s[2], dphi * s[3]
        # Wrist point in the arm's plane: W = l2 e^{i q2} + l3 e^{i (q2 + q3)}, differentiated.
        w1 = r1 + 1j * (dz * s[1])
        w2 = r2 + 1j * (dz * s[2])
        w3 = r3 + 1j * (dz * s[3])
        if dphi:
            e_phi = np.exp(1j * (q2 + q3 + q[3]))  # the in-plane tool direction
            w1 -= lt * (1j * phi1) * e_phi
            w2 -= lt * (1j * phi2 - phi1 * phi1) * e_phi
            w3 -= lt * (1j * phi3 - 3.0 * phi1 * phi2 - 1j * phi1**3) * e_phi
        # Solve i (P a' + Q b') = c for the absolute link angles a = q2, b = q2 + q3.
        p = l2 * e2
        qv = l3 * e2 * e3
        p_conj, q_conj = p.conjugate(), qv.conjugate()
        inv_det = 1.0 / (l2 * l3 * s3)

        def rates(c: npt.NDArray[np.complex128]) -> tuple[FloatArray, FloatArray]:
            return (c * q_conj).real * inv_det, -(c * p_conj).real * inv_det

        a1, b1 = rates(w1)
        a2, b2 = rates(w2 + p * (a1 * a1) + qv * (b1 * b1))
        a3, b3 = rates(w3 + 3.0 * (p * (a1 * a2) + qv * (b1 * b2)) + 1j * (p * a1**3 + qv * b1**3))
        for order, (lq, a, b, dphi_k, s_k) in enumerate(
            ((lg1, a1, b1, phi1, s[1]), (lg2, a2, b2, phi2, s[2]), (lg3, a3, b3, phi3, s[3])),
            start=1,
        ):
            out[order, 0] = lq.imag
            out[order, 1] = a
            out[order, 2] = b - a
            out[order, 3] = dphi_k - b
            out[order, 4] = droll * s_k
        return out.transpose(0, 2, 1), in_reach


def _branch(q: FloatArray, pose: ArmPose, name: str, geometry: ArmGeometry) -> int:
    """The IK candidate slot that reproduces the joints ``q`` of waypoint ``name``.

    Raises:
        JointRangeError: The IK has no candidate for its pose: joints within the
            ranges' slack but past a limit (a base angle a hair over 90 deg, which
            the IK reads as the arm reaching back), where no line can start.
    """
    result = ik(np.asarray(pose.position), pose.pitch, q[4], geometry=geometry)
    distance = np.linalg.norm(wrap_angle(result.candidates - q), axis=-1)
    if np.isnan(distance).all():
        excess = np.maximum(geometry.lower - q, q - geometry.upper)
        j = int(np.argmax(excess))
        limit = geometry.lower[j] if q[j] < geometry.lower[j] else geometry.upper[j]
        raise JointRangeError(
            f"waypoint {name}: joint {j + 1} ({geometry.joint_names[j]}) = "
            f"{math.degrees(q[j]):.10g} deg is at its limit {math.degrees(limit):.4g} deg, "
            "where the IK finds no solution of its pose: a straight line cannot start there "
            "(move it inside the range)",
            joint=j + 1,
        )
    return int(np.nanargmin(distance))


class _UnitPath:
    """A line evaluated at unit duration on its check grid (shapes scale with 1/T^k)."""

    def __init__(self, k: int, segment: LineSegment, names: tuple[str, ...]) -> None:
        self.k = k
        self.segment = segment
        self.u = check_grid(segment)
        self.states, self.in_reach = segment.states(self.u)
        self.label = f"straight line {names[k]} -> {names[k + 1]} (segment {k + 1})"
        self.points = np.asarray(segment.start.position) + np.outer(
            quintic_scaling(self.u)[0],
            np.subtract(segment.end.position, segment.start.position),
        )

    def at(self, i: int) -> str:
        x, y, z = (1e3 * float(v) for v in self.points[i])
        return (
            f"at {100 * self.u[i]:.1f} % of its duration (tool at ({x:.1f}, {y:.1f}, {z:.1f}) mm)"
        )

    def check_reach(self) -> None:
        """Raise if the line leaves the reach or passes a singular configuration."""
        # The IK's own reach test: a line between poses it solves is not refused at its ends.
        out = np.flatnonzero(~self.in_reach)
        if out.size:
            raise OutOfReachError(f"{self.label} leaves the arm's reach {self.at(int(out[0]))}")
        bad = np.argwhere(~np.isfinite(self.states[1:]))
        if bad.size:
            _, i, j = (int(v) for v in bad[0])
            raise PathError(
                f"{self.label} passes a singular configuration (base axis or stretched arm) "
                f"{self.at(i)}: joint {j + 1} rate is unbounded",
                segment=self.k,
                joint=j + 1,
                fraction=float(self.u[i]),
            )

    def extremes(self) -> Extremes:
        """Refined extremes of the joints and their derivatives over the unit-time line."""
        return segment_extremes(self.segment, self.u, self.states)

    def check_jumps(self) -> None:
        """Raise if a joint jumps between grid points (the IK changes configuration)."""
        step = np.abs(np.diff(self.states[0], axis=0))
        rate = np.maximum(np.abs(self.states[1, :-1]), np.abs(self.states[1, 1:]))
        allowed = JUMP_FACTOR * rate * np.diff(self.u)[:, None] + JUMP_TOL
        jump = np.argwhere(step > allowed)
        if jump.size:
            i, j = (int(v) for v in jump[0])
            raise PathError(
                f"{self.label}: joint {j + 1} jumps by {math.degrees(step[i, j]):.1f} deg "
                f"{self.at(i)}; the IK solution changes configuration there",
                segment=self.k,
                joint=j + 1,
                fraction=float(self.u[i]),
            )


def cartesian_line(
    waypoints: ArmWaypointsLike,
    durations: Durations = None,
    *,
    limits: JointLimits = ARM_LIMITS,
    stretch: bool = False,
    geometry: ArmGeometry = LYNX_ARM,
) -> Trajectory:
    """Straight tool lines between the waypoints, quintic timing per line.

    Joint ranges, velocity, acceleration and jerk limits are checked; with no
    durations given, each line takes the shortest time that keeps them.

    Args:
        waypoints: Poses or joints, shape (N, 5) [rad]; see :mod:`lynxsim.arm.motion.waypoints`.
        durations: Segment durations [s]; see :mod:`lynxsim.traj.timing`.
        limits: Joint limits to respect.
        stretch: Lengthen given durations that are too short for the limits.
        geometry: The arm description.

    Returns:
        The checked :class:`Trajectory`.

    Raises:
        OutOfReachError: A line leaves the arm's reach (names the line and the point).
        PathError: A line passes a singularity or needs a change of configuration.
        LimitViolationError: A joint leaves its range on a line, or given durations
            break a limit (names joint, time, excess).
        UnreachablePoseError: A pose has no IK solution (names the pose).
        JointRangeError: A line would start from joints a hair past a limit (within
            the ranges' slack) whose pose the IK cannot solve.
        InvalidInputError: Malformed waypoints, durations or options, or limits
            so low that a line needs more than 3600 s.
    """
    bounds, limits, stretch = check_options(joint_bounds(geometry), limits, stretch)
    wp = resolve_waypoints(waypoints, geometry)
    unit = [
        LineSegment(a, b, 1.0, _branch(q, a, name, geometry), geometry)
        for a, b, q, name in zip(wp.poses[:-1], wp.poses[1:], wp.q[:-1], wp.names)
    ]
    paths = [_UnitPath(k, seg, wp.names) for k, seg in enumerate(unit)]
    for path in paths:
        path.check_reach()
    unit_extremes = [p.extremes() for p in paths]
    peaks = np.array([[e.peak(order) for e in unit_extremes] for order in (1, 2, 3)])
    shortest = scaled_shortest(peaks, limits, TrajectoryKind.LINE.limited_orders)
    times = segment_durations(durations, shortest, wp.names, stretch=stretch)
    segments = tuple(
        LineSegment(seg.start, seg.end, float(t), seg.branch, geometry)
        for seg, t in zip(unit, times)
    )
    traj = Trajectory(TrajectoryKind.LINE, segments, wp.joints, bounds, limits)
    extremes = [e.time_scaled(float(t)) for e, t in zip(unit_extremes, times)]
    check_trajectory(traj, hint=DURATION_HINT, extremes=extremes)
    for path in paths:
        path.check_jumps()
    return traj
