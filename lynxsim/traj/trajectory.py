"""The trajectory type: segments joined end to end, sampled at any times.

A :class:`Trajectory` runs through its waypoints one :class:`Segment` at a
time. Each segment is evaluated in its own local time ``tau`` in
``[0, duration]``; the trajectory maps global time onto the segments, so a
sample grid may cross segment joints freely. At a segment joint the later
segment answers (a waypoint time belongs to the segment that starts there).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import NamedTuple, Protocol

import numpy as np
import numpy.typing as npt

from lynxsim.errors import InvalidInputError, NonFiniteInputError
from lynxsim.traj.kinds import TrajectoryKind
from lynxsim.traj.limits import JointLimits
from lynxsim.traj.waypoints import Waypoints

__all__ = ["PolynomialSegment", "Segment", "Trajectory", "TrajectorySample"]

FloatArray = npt.NDArray[np.float64]

TIME_TOL = 1e-9
"""Relative slack on the time range accepted by :meth:`Trajectory.sample` [-]."""


class TrajectorySample(NamedTuple):
    """Joint states at a batch of times, batch shape ``B`` (the shape of ``t``).

    Attributes:
        q: Joint angles, shape B + (5,) [rad].
        qd: Joint velocities, shape B + (5,) [rad/s].
        qdd: Joint accelerations, shape B + (5,) [rad/s^2].
        qddd: Joint jerks, shape B + (5,) [rad/s^3]. Where a derivative jumps at
            a segment joint (see :attr:`TrajectoryKind.continuity`), the next
            derivative holds an impulse there that samples do not show.
    """

    q: FloatArray
    qd: FloatArray
    qdd: FloatArray
    qddd: FloatArray


class Segment(Protocol):
    """One piece of a trajectory between two consecutive waypoints."""

    @property
    def duration(self) -> float:
        """Length of the segment [s]."""
        ...

    @property
    def breakpoints(self) -> FloatArray:
        """Local times inside the segment where its formula changes, shape (K,) [s]."""
        ...

    def evaluate(self, tau: FloatArray) -> FloatArray:
        """Joint states at local times.

        Args:
            tau: Local times in ``[0, duration]``, shape (n,) [s].

        Returns:
            ``q, qd, qdd, qddd`` stacked, shape (4, n, 5) [rad, rad/s, rad/s^2, rad/s^3].
        """
        ...


def _derivative_coefficients(coefficients: FloatArray, order: int) -> FloatArray:
    """Coefficients of the ``order``-th derivative, ascending powers, axis 1."""
    degree = coefficients.shape[1] - 1
    if order > degree:
        return np.zeros(coefficients.shape[:1] + (1,) + coefficients.shape[2:])
    k = np.arange(degree + 1 - order)
    factor = np.ones(k.shape)
    for i in range(1, order + 1):
        factor *= k + i
    return coefficients[:, order:] * factor[None, :, None]


@dataclass(frozen=True)
class PolynomialSegment:
    """A piecewise polynomial in local time, one polynomial per joint and piece.

    Attributes:
        breaks: Piece boundaries, shape (P + 1,) [s], from 0 to the duration,
            increasing.
        coefficients: Shape (P, D + 1, 5): for piece ``i`` and joint ``j``,
            ``q_j(tau) = sum_k coefficients[i, k, j] * (tau - breaks[i])**k`` [rad/s^k].
    """

    breaks: FloatArray
    coefficients: FloatArray
    _derivatives: tuple[FloatArray, ...] = field(init=False, repr=False, compare=False)
    _by_power: tuple[FloatArray, ...] = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        breaks = np.array(self.breaks, dtype=float)
        coefficients = np.array(self.coefficients, dtype=float)
        pieces = breaks.size - 1
        if breaks.ndim != 1 or pieces < 1 or breaks[0] != 0.0 or (np.diff(breaks) <= 0).any():
            raise InvalidInputError(f"breaks must increase from 0, got {breaks.tolist()}")
        if coefficients.ndim != 3 or coefficients.shape[0] != pieces or coefficients.shape[2] != 5:
            raise InvalidInputError(
                f"coefficients must have shape ({pieces}, D + 1, 5), got {coefficients.shape}"
            )
        derivatives = tuple(_derivative_coefficients(coefficients, r) for r in range(4))
        # (power, piece, joint) copies: contiguous rows for the piecewise Horner scheme.
        by_power = tuple(np.ascontiguousarray(c.transpose(1, 0, 2)) for c in derivatives)
        for arr in (breaks, coefficients, *derivatives, *by_power):
            arr.setflags(write=False)
        object.__setattr__(self, "breaks", breaks)
        object.__setattr__(self, "coefficients", coefficients)
        object.__setattr__(self, "_derivatives", derivatives)
        object.__setattr__(self, "_by_power", by_power)

    @property
    def duration(self) -> float:
        """Length of the segment [s]."""
        return float(self.breaks[-1])

    @property
    def breakpoints(self) -> FloatArray:
        """Interior piece boundaries, shape (P - 1,) [s]."""
        return self.breaks[1:-1]

    def evaluate(self, tau: FloatArray) -> FloatArray:
        """Joint states at local times ``tau``, shape (4, n, 5); see :class:`Segment`."""
        out = np.empty((4, tau.size, 5))
        if self.breaks.size == 2:  # one piece: a Vandermonde matrix times the coefficients
            powers = np.vander(tau, self.coefficients.shape[1], increasing=True)
            for order, c in enumerate(self._derivatives):
                np.matmul(powers[:, : c.shape[1]], c[0], out=out[order])
            return out
        piece = np.searchsorted(self.breaks[1:-1], tau, side="right")
        u = (tau - self.breaks[piece])[:, None]
        for order, c in enumerate(self._by_power):
            acc = c[-1][piece]
            for k in range(c.shape[0] - 2, -1, -1):
                acc *= u
                acc += c[k][piece]
            out[order] = acc
        return out


@dataclass(frozen=True)
class Trajectory:
    """Joint motion through waypoints, sampled by time.

    Attributes:
        kind: The generator that made it.
        segments: One segment per pair of consecutive waypoints.
        waypoints: Joints and tool poses of the waypoints (the task's targets).
        limits: The joint limits the trajectory was checked against.
    """

    kind: TrajectoryKind
    segments: tuple[Segment, ...]
    waypoints: Waypoints
    limits: JointLimits
    _times: FloatArray = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        if len(self.segments) != len(self.waypoints.q) - 1:
            raise InvalidInputError(
                f"{len(self.waypoints.q)} waypoints need {len(self.waypoints.q) - 1} segments, "
                f"got {len(self.segments)}"
            )
        times = np.concatenate([[0.0], np.cumsum([s.duration for s in self.segments])])
        times.setflags(write=False)
        object.__setattr__(self, "_times", times)

    @property
    def duration(self) -> float:
        """Total duration [s]."""
        return float(self._times[-1])

    @property
    def waypoint_times(self) -> FloatArray:
        """When the trajectory passes each waypoint, shape (N,) [s], from 0 to the duration."""
        return self._times

    @property
    def segment_durations(self) -> FloatArray:
        """Duration of each segment, shape (N - 1,) [s]."""
        return np.diff(self._times)

    def sample(self, t: npt.ArrayLike) -> TrajectorySample:
        """Joint states at the given times.

        Args:
            t: Times from the start, any shape ``B`` [s], within ``[0, duration]``
                (up to a relative rounding slack of 1e-9), in any order.

        Returns:
            The :class:`TrajectorySample`, arrays of shape B + (5,).

        Raises:
            NonFiniteInputError: A time is NaN or infinite.
            InvalidInputError: A time lies outside the trajectory.
        """
        t_arr = np.asarray(t, dtype=float)
        flat = t_arr.ravel()
        if not np.isfinite(flat).all():
            raise NonFiniteInputError("sample times must be finite")
        end = self.duration
        slack = TIME_TOL * max(1.0, end)
        if flat.size and (flat.min() < -slack or flat.max() > end + slack):
            raise InvalidInputError(
                f"sample times must lie in [0, {end:.6g}] s, got [{flat.min():.6g}, "
                f"{flat.max():.6g}] s"
            )
        flat = np.clip(flat, 0.0, end)
        ordered = bool(np.all(flat[1:] >= flat[:-1]))
        order = None if ordered else np.argsort(flat, kind="stable")
        ts = flat if order is None else flat[order]
        bounds = np.searchsorted(ts, self._times[1:-1], side="left")
        lo = np.concatenate([[0], bounds])
        hi = np.concatenate([bounds, [ts.size]])
        out = np.empty((4, ts.size, 5))
        for k, segment in enumerate(self.segments):
            if hi[k] > lo[k]:
                out[:, lo[k] : hi[k]] = segment.evaluate(ts[lo[k] : hi[k]] - self._times[k])
        if order is not None:
            unsorted = np.empty_like(out)
            unsorted[:, order] = out
            out = unsorted
        shape = t_arr.shape + (5,)
        return TrajectorySample(*(out[i].reshape(shape) for i in range(4)))

    def times_at_rate(self, rate_hz: float) -> FloatArray:
        """A uniform time grid ``k / rate_hz`` over the trajectory, shape (n,) [s].

        The grid starts at 0 and ends at the last multiple of the period within
        the duration (the end itself only when the duration is such a multiple).

        Raises:
            InvalidInputError: ``rate_hz`` is not a positive finite number.
        """
        if not (math.isfinite(rate_hz) and rate_hz > 0.0):
            raise InvalidInputError(f"rate_hz must be positive and finite, got {rate_hz}")
        n = math.floor(self.duration * rate_hz * (1.0 + TIME_TOL)) + 1
        return np.minimum(np.arange(n) / rate_hz, self.duration)

    def times_per_segment(self, steps: int) -> FloatArray:
        """The report's grid: ``steps`` equal steps per segment plus the end, shape (N' ,) [s].

        Args:
            steps: Steps per segment (the report uses 10).

        Returns:
            ``steps * (N - 1) + 1`` increasing times, waypoint times included.

        Raises:
            InvalidInputError: ``steps`` is not a positive integer.
        """
        if isinstance(steps, bool) or not isinstance(steps, int) or steps < 1:
            raise InvalidInputError(f"steps must be a positive integer, got {steps!r}")
        frac = np.arange(steps) / steps
        starts, durations = self._times[:-1], self.segment_durations
        grid = (starts[:, None] + durations[:, None] * frac[None, :]).ravel()
        return np.append(grid, self.duration)
