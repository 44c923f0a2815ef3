"""The check every generator runs before it returns a trajectory.

Each segment is evaluated on a dense grid (``CHECK_POINTS`` equally spaced
local times, the ends and every interior breakpoint included); around the
grid's largest values of every joint and derivative order, a golden-section
search finds the true extremes between grid points. The grid is fixed in the
segment's normalised time, so a shape scaled to its shortest duration meets
its limits exactly.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, NamedTuple, NoReturn

import numpy as np
import numpy.typing as npt

from lynxsim.angles import LIMIT_TOL
from lynxsim.errors import InvalidInputError, LimitViolationError
from lynxsim.inputs import instance

if TYPE_CHECKING:  # trajectory.py imports the waypoints, which import CHECK_POINTS from here
    from lynxsim.traj.trajectory import Segment, Trajectory

__all__ = [
    "CHECK_POINTS",
    "LIMIT_RTOL",
    "Extremes",
    "check_grid",
    "check_trajectory",
    "segment_extremes",
]

FloatArray = npt.NDArray[np.float64]

CHECK_POINTS = 1025
"""Equally spaced samples per segment on which extremes are searched [-]."""

LIMIT_RTOL = 1e-9
"""Relative slack on the velocity, acceleration and jerk limits [-]."""

_CANDIDATES = 2
"""Local grid maxima refined per joint, order and sign [-]."""

_GOLDEN_STEPS = 12
"""Golden-section steps: the bracket of two grid steps shrinks by 0.618^12 ~ 3e-3, so a
smooth peak's residual error is ~1e-4 of the grid's (itself ~1e-6 relative) [-]."""

_NEAR = 1e-3
"""The checker refines only extremes within this fraction of their bound [-]."""

_GOLDEN = (math.sqrt(5.0) - 1.0) / 2.0

_QUANTITIES = ("position", "velocity", "acceleration", "jerk")
_UNITS = ("rad", "rad/s", "rad/s^2", "rad/s^3")


def check_grid(segment: Segment) -> FloatArray:
    """Local times at which a segment is checked, increasing, shape (n,) [s]."""
    grid = np.linspace(0.0, segment.duration, CHECK_POINTS)
    return np.union1d(grid, segment.breakpoints)


class Extremes(NamedTuple):
    """Largest values over a segment of each joint derivative, both signs.

    Attributes:
        value: ``max(+x)`` and ``max(-x)`` of derivative order 0..3 (position,
            velocity, acceleration, jerk) per joint, shape (4, 2, n)
            [rad/s^order].
        tau: Local times where they occur, shape (4, 2, n) [s].
    """

    value: FloatArray
    tau: FloatArray

    def peak(self, order: int) -> FloatArray:
        """Largest magnitude of derivative ``order`` per joint, shape (n,)."""
        return np.asarray(self.value[order].max(axis=0))

    def time_scaled(self, duration: float) -> Extremes:
        """The extremes of the same motion stretched from 1 s to ``duration`` [s]."""
        scale = duration ** -np.arange(4.0)
        return Extremes(self.value * scale[:, None, None], self.tau * duration)


def segment_extremes(
    segment: Segment,
    tau: FloatArray,
    states: FloatArray,
    refine: npt.NDArray[np.bool_] | None = None,
) -> Extremes:
    """Refine the grid's extremes of the joint derivatives of a segment.

    Args:
        segment: The segment.
        tau: Its check grid, shape (n,) [s] (see :func:`check_grid`).
        states: ``segment.evaluate(tau)``, shape (4, len(tau), n), all finite.
        refine: Which extremes to refine, shape (4, 2, n) as :attr:`Extremes.value`;
            the others keep the grid's value. Default: all.

    Returns:
        The :class:`Extremes`, never below the grid's values.
    """
    n, joints = tau.size, states.shape[2]
    f = np.stack([states, -states], axis=1).transpose(0, 1, 3, 2).reshape(-1, n)  # (8 * joints, n)
    arg = f.argmax(axis=1)  # channel = (order, sign, joint)
    best = f[np.arange(f.shape[0]), arg]
    best_tau = tau[arg]
    selected = np.flatnonzero(np.ones(f.shape[0], bool) if refine is None else refine.ravel())
    g = f[selected]
    left = np.concatenate([np.full((g.shape[0], 1), -np.inf), g[:, :-1]], axis=1)
    right = np.concatenate([g[:, 1:], np.full((g.shape[0], 1), -np.inf)], axis=1)
    peak = ((g > left) & (g >= right)) | ((g >= left) & (g > right))
    score = np.where(peak, g, -np.inf)
    score[np.arange(g.shape[0]), arg[selected]] = best[selected]
    top = np.argpartition(score, -_CANDIDATES, axis=1)[:, -_CANDIDATES:]
    rows, idx = np.nonzero(np.isfinite(np.take_along_axis(score, top, axis=1)))
    chan = selected[rows]
    grid_index = top[rows, idx]
    order, side, joint = np.unravel_index(chan, (4, 2, joints))
    sign = np.where(side == 0, 1.0, -1.0)
    a = tau[np.maximum(grid_index - 1, 0)]
    b = tau[np.minimum(grid_index + 1, n - 1)]

    def value(*points: FloatArray) -> list[FloatArray]:
        """The candidates' channel values at one point per candidate, for each array given."""
        x = segment.evaluate(np.concatenate(points))
        rows = np.arange(chan.size)
        return [sign * x[order, rows + k * chan.size, joint] for k in range(len(points))]

    for _ in range(_GOLDEN_STEPS):
        c = b - _GOLDEN * (b - a)
        d = a + _GOLDEN * (b - a)
        fc, fd = value(c, d)
        upper = fc > fd
        b = np.where(upper, d, b)
        a = np.where(upper, a, c)
    mid = 0.5 * (a + b)
    (found,) = value(mid)
    # The best candidate of each channel replaces the grid's value if higher.
    channel_best = np.full(best.shape, -np.inf)
    np.maximum.at(channel_best, chan, found)
    winners = np.flatnonzero(found == channel_best[chan])
    first = winners[np.unique(chan[winners], return_index=True)[1]]
    higher = first[found[first] > best[chan[first]]]
    best[chan[higher]] = found[higher]
    best_tau[chan[higher]] = mid[higher]
    return Extremes(best.reshape(4, 2, joints), best_tau.reshape(4, 2, joints))


def _where(traj: Trajectory, segment: int, tau: float) -> str:
    names = traj.waypoints.names
    t = traj.waypoint_times[segment] + tau
    return f"at t = {t:.4f} s (segment {segment + 1}, {names[segment]} -> {names[segment + 1]})"


def check_trajectory(
    traj: Trajectory,
    *,
    hint: str = "",
    extremes: list[Extremes] | None = None,
) -> None:
    """Check joint ranges and limits; raise at the worst violation.

    The joint ranges come first, then every derivative order in
    ``traj.kind.limited_orders`` (velocity, acceleration, jerk); within one
    quantity the largest violation is reported.

    Args:
        traj: The trajectory; its ``bounds`` (joint ranges and names) and
            ``limits`` are what it is held to.
        hint: Advice appended to velocity, acceleration and jerk messages (e.g. how
            to lengthen segments).
        extremes: Every segment's :class:`Extremes`, all refined and finite, when
            the caller has them already; default: computed here.

    Raises:
        LimitViolationError: Names the joint, the time, the segment, the value,
            the bound and by how much it is broken.
        InvalidInputError: ``traj`` is not a :class:`Trajectory`, ``hint`` not a
            string, or ``extremes`` not one :class:`Extremes` per segment.
    """
    from lynxsim.traj.trajectory import Trajectory  # not at the top: an import cycle (see there)

    traj = instance(traj, Trajectory, "traj")
    joints = traj.bounds
    lower, upper = joints.lower_array, joints.upper_array
    hint = instance(hint, str, "hint")
    if extremes is not None and not (
        isinstance(extremes, list)
        and len(extremes) == len(traj.segments)
        and all(isinstance(e, Extremes) for e in extremes)
    ):
        raise InvalidInputError(f"extremes must be a list of {len(traj.segments)} Extremes")
    orders = (0, *traj.kind.limited_orders)
    kind = traj.kind.value
    bounds = _bounds(traj)

    def fail(
        order: int, k: int, tau: float, j: int, message: str, value: float, side: int | None
    ) -> NoReturn:
        """Raise for joint ``j`` at local time ``tau`` of segment ``k``; ``side`` 0/1 bound."""
        if side is None:
            bound = math.inf
        elif order:
            bound = float(bounds[order, side, j])
        else:
            bound = float(upper[j] if side == 0 else lower[j])
        raise LimitViolationError(
            f"{kind} trajectory: joint {j + 1} ({joints.names[j]}) {message} "
            f"{_where(traj, k, tau)}{f'; {hint}' if hint and order else ''}",
            joint=j + 1,
            quantity=_QUANTITIES[order],
            time=float(traj.waypoint_times[k] + tau),
            segment=k,
            value=value,
            limit=bound,
        )

    if extremes is None:
        extremes = []
        for k, segment in enumerate(traj.segments):
            tau = check_grid(segment)
            states = segment.evaluate(tau)
            bad = np.argwhere(~np.isfinite(states[list(orders)]))
            if bad.size:
                o, i, j = (int(v) for v in bad[0])
                fail(
                    orders[o],
                    k,
                    float(tau[i]),
                    j,
                    f"{_QUANTITIES[orders[o]]} is not finite (a singularity)",
                    float(states[orders[o], i, j]),
                    None,
                )
            grid = np.stack([states.max(axis=1), -states.min(axis=1)], axis=1)  # (4, 2, n)
            near = grid >= bounds - _NEAR * np.maximum(np.abs(bounds), 1.0)
            extremes.append(segment_extremes(segment, tau, states, near))
    value = np.array([e.value for e in extremes])  # (K, 4, 2, n): segment, order, sign, joint
    where = np.array([e.tau for e in extremes])
    sign = np.array([1.0, -1.0])[:, None]

    excess = value[:, 0] - bounds[0]  # (K, 2, n) [rad]
    k, side, j = _argmax(excess)
    if excess[k, side, j] > LIMIT_TOL:
        q = float(sign[side, 0] * value[k, 0, side, j])
        lo, hi = np.degrees(lower[j]), np.degrees(upper[j])
        fail(
            0,
            k,
            float(where[k, 0, side, j]),
            j,
            f"reaches {math.degrees(q):.4g} deg, {math.degrees(excess[k, side, j]):.3g} deg "
            f"beyond its range [{lo:.4g}, {hi:.4g}] deg",
            q,
            side,
        )

    for order in orders[1:]:
        with np.errstate(over="ignore"):  # denormal limits: inf, reported as broken
            ratio = value[:, order] / bounds[order]  # (K, 2, n)
        k, side, j = _argmax(ratio)
        if ratio[k, side, j] > 1.0 + LIMIT_RTOL:
            peak = float(sign[side, 0] * value[k, order, side, j])
            excess_percent = 100.0 * (float(ratio[k, side, j]) - 1.0)  # inf: no warning
            unit = _UNITS[order]
            fail(
                order,
                k,
                float(where[k, order, side, j]),
                j,
                f"{_QUANTITIES[order]} {peak:.4g} {unit} exceeds its limit "
                f"{bounds[order, side, j]:.4g} {unit} by {excess_percent:.3g} %",
                peak,
                side,
            )


def _bounds(traj: Trajectory) -> FloatArray:
    """Bounds on ``+x`` and ``-x`` of every derivative, shape (4, 2, n) as :class:`Extremes`."""
    bounds = np.empty((4, 2, traj.n_joints))
    bounds[0] = np.stack([traj.bounds.upper_array, -traj.bounds.lower_array])
    for order in (1, 2, 3):
        bounds[order] = traj.limits.of_order(order)
    return bounds


def _argmax(a: FloatArray) -> tuple[int, int, int]:
    """Index of the largest element of a 3-D array."""
    k, side, j = np.unravel_index(int(np.argmax(a)), a.shape)
    return int(k), int(side), int(j)
