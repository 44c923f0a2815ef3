"""Platform paths of the 3-RRR robot in task space, timed.

The 3-RRR robot is planned in task space, ``(x, y, alpha)`` in SI units, and
converted to actuated angles by the inverse kinematics in one working mode at
every physics step (:func:`actuated_path`). Two path shapes, both timed with
the rest-to-rest quintic ``s(u) = 10 u^3 - 15 u^4 + 6 u^5`` of
:func:`lynxsim.traj.polynomial.quintic_scaling`:

* **stop at every pose** (a task's ``type = "quintic"``): a straight segment in
  ``(x, y, alpha)`` from each pose to the next, each with its own quintic time
  law, so the platform rests at every pose;
* **pass through** (``type = "quintic"`` with ``pass_through = true``): one C2
  cubic spline through all poses, parametrised by arc length in
  ``(x, y, r_p alpha)``, periodic when the last pose equals the first (a
  smooth closed curve), travelled with one quintic time law over the whole
  path (rest at its ends only).

The actuated angles along a path are :mod:`lynxsim.rrr.actuated`'s (its
names are importable from here too). Pure numpy.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import NamedTuple

import numpy as np
import numpy.typing as npt

from lynxsim.bounds import (
    MAX_ANGLE_RAD,
    MAX_COORDINATE_M,
    MAX_SAMPLES,
    MAX_SEGMENT_S,
    MIN_SEGMENT_S,
)
from lynxsim.errors import InvalidInputError, NonFiniteInputError, SegmentDurationError
from lynxsim.inputs import finite_array, flag, instance, positive_number, real_array
from lynxsim.rrr.actuated import (
    ActuatedPath,
    PlatformPathError,
    actuated_path,
    actuated_window,
    reached,
    wrap_to_window,
)
from lynxsim.rrr.geometry import RRR_ROBOT, RRRGeometry
from lynxsim.rrr.spline import spline_second_derivatives
from lynxsim.traj.kinds import TrajectoryKind
from lynxsim.traj.polynomial import quintic_scaling
from lynxsim.traj.timing import check_planned, given_durations

__all__ = [
    "DEFAULT_PLATFORM_LIMITS",
    "RRR_TRAJECTORY_KINDS",
    "ActuatedPath",
    "PathSample",
    "PlatformLimits",
    "PlatformPath",
    "PlatformPathError",
    "actuated_path",
    "actuated_window",
    "platform_path",
    "wrap_to_window",
]

FloatArray = npt.NDArray[np.float64]

RRR_TRAJECTORY_KINDS = (TrajectoryKind.QUINTIC,)
"""Trajectory types a 3-RRR task may name (planned in task space, see the module docs)."""

_QUINTIC_PEAK_VEL = 15.0 / 8.0
"""Peak of ds/du of the rest-to-rest quintic."""
_QUINTIC_PEAK_ACC = 10.0 / math.sqrt(3.0)
"""Peak of |d2s/du2| of the rest-to-rest quintic."""
_SAME_POSE_TOL = 1e-9
"""First and last pose closer than this [m, rad] make a closed (periodic) path."""


@dataclass(frozen=True)
class PlatformLimits:
    """Task-space limits used to choose segment durations that are not given.

    Attributes:
        speed: Platform-centre speed [m/s].
        angular_speed: Platform rotation rate [rad/s].
        acceleration: Platform-centre acceleration [m/s^2].
        angular_acceleration: Platform angular acceleration [rad/s^2].

    Raises:
        InvalidInputError: A limit is not a positive real number.
        NonFiniteInputError: A limit is NaN or infinite.
    """

    speed: float = 0.15
    angular_speed: float = 1.0
    acceleration: float = 1.0
    angular_acceleration: float = 6.0

    def __post_init__(self) -> None:
        for name in ("speed", "angular_speed", "acceleration", "angular_acceleration"):
            value = positive_number(getattr(self, name), f"platform limit {name}")
            object.__setattr__(self, name, value)


DEFAULT_PLATFORM_LIMITS = PlatformLimits()
"""Moderate limits: 0.15 m/s, 1 rad/s, 1 m/s^2, 6 rad/s^2 (the report gives none)."""


class PathSample(NamedTuple):
    """Platform states at a batch of times, shape (T, 3) each.

    Attributes:
        pose: Poses (x, y, alpha) [m, m, rad].
        velocity: Their time derivatives [m/s, m/s, rad/s].
        acceleration: Second derivatives [m/s^2, m/s^2, rad/s^2].
    """

    pose: FloatArray
    velocity: FloatArray
    acceleration: FloatArray


def _quintic(u: FloatArray) -> FloatArray:
    """``s, ds/du, d2s/du2`` of the rest-to-rest quintic, shape (3, n)."""
    out: FloatArray = quintic_scaling(np.clip(u, 0.0, 1.0))[:3]
    return out


def _metric(geometry: RRRGeometry) -> FloatArray:
    """Weights turning (dx, dy, dalpha) into lengths [m]: alpha counts at the platform radius."""
    return np.array([1.0, 1.0, geometry.platform_radius])


@dataclass(frozen=True, eq=False)
class PlatformPath:
    """A timed platform path through waypoints (see the module docs for its two shapes).

    Build one with :func:`platform_path`.

    Attributes:
        waypoints: The poses, shape (N, 3) [m, m, rad], N >= 2.
        names: Their names.
        durations: Time from each pose to the next, shape (N - 1,) [s]; with
            ``through`` only their sum matters.
        through: Pass through the intermediate poses without stopping (one spline).
        closed: The path ends where it started and (with ``through``) is a
            periodic spline.
        geometry: The robot (its platform radius weighs alpha in the arc length).
    """

    waypoints: FloatArray
    names: tuple[str, ...]
    durations: FloatArray
    through: bool
    closed: bool
    geometry: RRRGeometry = field(default=RRR_ROBOT, repr=False, compare=False)
    _knots: FloatArray = field(default_factory=lambda: np.zeros(0), repr=False, compare=False)
    _curvature: FloatArray = field(
        default_factory=lambda: np.zeros((0, 3)), repr=False, compare=False
    )

    @property
    def duration(self) -> float:
        """Total time [s]."""
        return float(self.durations.sum())

    @property
    def kind(self) -> TrajectoryKind:
        """The trajectory type of this path (always quintic timing)."""
        return TrajectoryKind.QUINTIC

    @property
    def label(self) -> str:
        """Short name of the path shape, e.g. ``"quintic"`` or ``"quintic-spline"``."""
        return "quintic-spline" if self.through else "quintic"

    @property
    def waypoint_names(self) -> tuple[str, ...]:
        """The poses' names (:class:`~lynxsim.traj.motion.Motion`)."""
        return self.names

    @property
    def arc_length(self) -> float:
        """Length of the path in ``(x, y, r_p alpha)`` [m] (spline: by its knots)."""
        if self.through:
            return float(self._knots[-1])
        d = np.diff(self.waypoints, axis=0) * _metric(self.geometry)
        return float(np.linalg.norm(d, axis=1).sum())

    def _spline(self, u: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
        """Spline value and first two derivatives by arc length at ``u``, each (T, 3)."""
        knots, y, m = self._knots, self.waypoints, self._curvature
        k = np.clip(np.searchsorted(knots, u, side="right") - 1, 0, len(knots) - 2)
        h = (knots[k + 1] - knots[k])[:, None]
        a = (knots[k + 1][:, None] - u[:, None]) / h
        b = 1.0 - a
        m0, m1 = m[k], m[k + 1]
        y0, y1 = y[k], y[k + 1]
        value = a * y0 + b * y1 + ((a**3 - a) * m0 + (b**3 - b) * m1) * h**2 / 6.0
        d1 = (y1 - y0) / h - (3.0 * a**2 - 1.0) * h * m0 / 6.0 + (3.0 * b**2 - 1.0) * h * m1 / 6.0
        d2 = a * m0 + b * m1
        return value, d1, d2

    def sample(self, t: npt.ArrayLike) -> PathSample:
        """Poses, velocities and accelerations at times ``t``.

        Args:
            t: Times from the path's start, shape (T,) (a scalar counts as one)
                [s]; clipped to [0, duration].

        Returns:
            The :class:`PathSample`.

        Raises:
            InvalidInputError: ``t`` is not real numbers of shape (T,), or holds
                more than :data:`~lynxsim.bounds.MAX_SAMPLES` times.
            NonFiniteInputError: A time is NaN or infinite.
        """
        times = np.atleast_1d(finite_array(t, "sample times"))
        if times.ndim != 1 or times.size > MAX_SAMPLES:
            raise InvalidInputError(
                f"sample times must have shape (T,) with T <= {MAX_SAMPLES:,}, got {times.shape}"
            )
        times = np.clip(times, 0.0, self.duration)
        if self.through:
            total = self.duration
            s, ds, dds = _quintic(times / total)
            length = self._knots[-1]
            u = s * length
            u_dot = ds * length / total
            u_ddot = dds * length / total**2
            value, d1, d2 = self._spline(u)
            return PathSample(
                pose=value,
                velocity=d1 * u_dot[:, None],
                acceleration=d2 * (u_dot**2)[:, None] + d1 * u_ddot[:, None],
            )
        starts = np.concatenate([[0.0], np.cumsum(self.durations)])
        k = np.clip(np.searchsorted(starts, times, side="right") - 1, 0, len(self.durations) - 1)
        dur = self.durations[k]
        s, ds, dds = _quintic((times - starts[k]) / dur)
        delta = self.waypoints[k + 1] - self.waypoints[k]
        return PathSample(
            pose=self.waypoints[k] + delta * s[:, None],
            velocity=delta * (ds / dur)[:, None],
            acceleration=delta * (dds / dur**2)[:, None],
        )


def _shortest_segments(waypoints: FloatArray, limits: PlatformLimits) -> FloatArray:
    """Shortest quintic duration of each straight segment within ``limits``, (N - 1,) [s]."""
    d = np.diff(waypoints, axis=0)
    dxy = np.hypot(d[:, 0], d[:, 1])
    da = np.abs(d[:, 2])
    out: FloatArray = np.max(
        [
            _QUINTIC_PEAK_VEL * dxy / limits.speed,
            _QUINTIC_PEAK_VEL * da / limits.angular_speed,
            np.sqrt(_QUINTIC_PEAK_ACC * dxy / limits.acceleration),
            np.sqrt(_QUINTIC_PEAK_ACC * da / limits.angular_acceleration),
        ],
        axis=0,
    )
    return out


def _shortest_spline(path: PlatformPath, limits: PlatformLimits) -> float:
    """Shortest total duration of a spline path within ``limits`` (a safe bound) [s]."""
    length = float(path._knots[-1])
    u = np.linspace(0.0, length, 2001)
    _, d1, d2 = path._spline(u)
    lin1, ang1 = np.hypot(d1[:, 0], d1[:, 1]).max(), np.abs(d1[:, 2]).max()
    lin2, ang2 = np.hypot(d2[:, 0], d2[:, 1]).max(), np.abs(d2[:, 2]).max()
    v = _QUINTIC_PEAK_VEL * length
    a2 = v**2
    a1 = _QUINTIC_PEAK_ACC * length
    return float(
        max(
            v * lin1 / limits.speed,
            v * ang1 / limits.angular_speed,
            math.sqrt((a2 * lin2 + a1 * lin1) / limits.acceleration),
            math.sqrt((a2 * ang2 + a1 * ang1) / limits.angular_acceleration),
        )
    )


def _check_waypoints(waypoints: object) -> FloatArray:
    """Poses of shape (N, 3), N >= 2, finite, x and y within the coordinate bound, reachable.

    Raises:
        InvalidInputError: Not real numbers, a bad shape, x or y beyond
            :data:`~lynxsim.bounds.MAX_COORDINATE_M`, or alpha beyond
            :data:`~lynxsim.bounds.MAX_ANGLE_RAD`.
        NonFiniteInputError: A value is NaN or infinite.
        UnreachablePlatformPoseError: A leg cannot reach a pose (names the pose
            and the legs).
    """
    w = real_array(waypoints, "waypoints")
    if w.ndim != 2 or w.shape[1] != 3 or len(w) < 2:
        raise InvalidInputError(f"waypoints must have shape (N, 3) with N >= 2, got {w.shape}")
    if len(w) > MAX_SAMPLES:
        raise InvalidInputError(f"at most {MAX_SAMPLES:,} waypoints, got {len(w):,}")
    if not np.isfinite(w).all():
        raise NonFiniteInputError(f"waypoints must be finite, got {w.tolist()}")
    far = np.abs(w[:, :2]) > MAX_COORDINATE_M
    if far.any():
        i = int(np.argmax(far.any(axis=1)))
        raise InvalidInputError(
            f"waypoint {i + 1}: x and y must be within ±{MAX_COORDINATE_M:g} m "
            f"(the robot spans under 1 m), got {w[i, :2].tolist()} m"
        )
    turned = np.abs(w[:, 2]) > MAX_ANGLE_RAD
    if turned.any():
        i = int(np.argmax(turned))
        raise InvalidInputError(
            f"waypoint {i + 1}: alpha must be within ±{math.degrees(MAX_ANGLE_RAD):g} deg "
            f"(two turns), got {math.degrees(w[i, 2]):g} deg"
        )
    return w


def platform_path(
    waypoints: npt.ArrayLike,
    durations: float | Sequence[float] | None = None,
    *,
    names: Sequence[str] | None = None,
    through: bool = False,
    stretch: bool = False,
    limits: PlatformLimits = DEFAULT_PLATFORM_LIMITS,
    geometry: RRRGeometry = RRR_ROBOT,
) -> PlatformPath:
    """A timed task-space path through platform poses.

    Inputs are checked before any timing: shapes, types, finiteness, the
    coordinate bound and the reach of every pose.

    Args:
        waypoints: Poses (x, y, alpha), shape (N, 3) [m, m, rad], N >= 2;
            consecutive poses must differ; x and y within
            :data:`~lynxsim.bounds.MAX_COORDINATE_M`, every pose reachable.
        durations: Time per segment [s] (one for all, or N - 1 values), each in
            [:data:`~lynxsim.bounds.MIN_SEGMENT_S`, :data:`~lynxsim.bounds.MAX_SEGMENT_S`]
            (:func:`lynxsim.traj.timing.given_durations`), or None for the
            shortest within ``limits``. With ``through`` the path takes their sum.
        names: Waypoint names (default ``P1``, ``P2``, ...).
        through: One spline through every pose instead of stopping at each.
        stretch: Lengthen durations that are too short for ``limits`` instead
            of raising.
        limits: Task-space limits for missing or stretched durations.
        geometry: The robot (platform radius for the arc length).

    Returns:
        The :class:`PlatformPath`; every segment lasts 0.001 to 3600 s (with
        ``through``: the total is at most 3600 s per segment).

    Raises:
        InvalidInputError: Bad shapes or types, a coordinate beyond the bound,
            repeated consecutive poses, bad durations, or limits so low that a
            segment needs more than 3600 s.
        NonFiniteInputError: A pose or duration is NaN or infinite.
        UnreachablePlatformPoseError: A leg cannot reach a waypoint.
        SegmentDurationError: A given duration breaks ``limits`` and ``stretch``
            is false (``joint`` is the axis 1..3 = x, y, alpha that needs longest).
    """
    geometry = instance(geometry, RRRGeometry, "geometry")
    limits = instance(limits, PlatformLimits, "limits")
    through = flag(through, "through")
    stretch = flag(stretch, "stretch")
    w = _check_waypoints(waypoints)
    n_seg = len(w) - 1
    if names is None:
        labels = tuple(f"P{i + 1}" for i in range(len(w)))
    elif (
        not isinstance(names, Sequence)
        or isinstance(names, str)
        or not all(isinstance(n, str) for n in names)
    ):
        raise InvalidInputError(f"names must be a sequence of strings, got {names!r}")
    else:
        labels = tuple(names)
    if len(labels) != len(w):
        raise InvalidInputError(f"got {len(labels)} names for {len(w)} waypoints")
    reached(w, lambda i: f"waypoint {labels[i]!r}", geometry)
    with np.errstate(over="ignore"):  # alpha beyond ±1e307: inf, refused below
        step = np.linalg.norm(np.diff(w, axis=0) * _metric(geometry), axis=1)
    if not np.isfinite(step).all():
        raise InvalidInputError("consecutive waypoints differ by more than float64 can hold")
    if (step < _SAME_POSE_TOL).any():
        i = int(np.argmax(step < _SAME_POSE_TOL))
        raise InvalidInputError(
            f"waypoints {labels[i]!r} and {labels[i + 1]!r} are the same pose; remove one"
        )
    closed = bool(np.linalg.norm((w[-1] - w[0]) * _metric(geometry)) < _SAME_POSE_TOL)
    knots = np.zeros(0)
    curvature = np.zeros((0, 3))
    if through:
        knots = np.concatenate([[0.0], np.cumsum(step)])
        curvature = spline_second_derivatives(knots, w, closed)

    given = given_durations(durations, n_seg, labels)

    def build(d: FloatArray) -> PlatformPath:
        return PlatformPath(w, labels, d, through, closed, geometry, knots, curvature)

    if through:
        with np.errstate(over="ignore"):  # tiny limits: inf, refused below
            shortest = _shortest_spline(build(np.ones(n_seg)), limits)
        if not shortest <= n_seg * MAX_SEGMENT_S:
            raise InvalidInputError(
                f"the path through {len(w)} poses needs {shortest:.4g} s within the platform "
                f"limits, more than {MAX_SEGMENT_S:g} s per segment: the limits are too low "
                "for this path"
            )
        shortest = max(shortest, n_seg * MIN_SEGMENT_S)
        if given is None:
            return build(np.full(n_seg, shortest / n_seg))
        total = float(given.sum())
        if total < shortest:
            if not stretch:
                raise SegmentDurationError(
                    f"the path through {len(w)} poses needs at least {shortest:.3f} s within "
                    f"the platform limits, got {total:.3f} s (set stretch to lengthen it)",
                    segment=0,
                    joint=1,
                    given=total,
                    required=shortest,
                )
            given = given * (shortest / total)
        return build(given)

    with np.errstate(over="ignore"):  # tiny limits: inf, refused by check_planned
        shortest_seg = _shortest_segments(w, limits)
    if given is None:
        chosen = np.maximum(shortest_seg, MIN_SEGMENT_S)
        check_planned(chosen, labels, "platform limits")
        return build(chosen)
    short = given < shortest_seg * (1.0 - 1e-12)
    if short.any() and not stretch:
        i = int(np.argmax(short))
        d = np.abs(np.diff(w, axis=0)[i])
        with np.errstate(over="ignore"):  # denormal limits: inf
            axis = int(
                np.argmax([d[0] / limits.speed, d[1] / limits.speed, d[2] / limits.angular_speed])
            )
        raise SegmentDurationError(
            f"segment {labels[i]} -> {labels[i + 1]} needs at least {shortest_seg[i]:.3f} s within "
            f"the platform limits, got {given[i]:.3f} s (set stretch to lengthen it)",
            segment=i,
            joint=axis + 1,
            given=float(given[i]),
            required=float(shortest_seg[i]),
        )
    chosen = np.maximum(given, shortest_seg)
    check_planned(chosen, labels, "platform limits")
    return build(chosen)
