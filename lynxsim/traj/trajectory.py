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

from lynxsim.bounds import (
    MAX_RATE_HZ,
    MAX_SAMPLES,
    MAX_SEGMENT_S,
    MIN_RATE_HZ,
    MIN_SEGMENT_S,
    check_count,
)
from lynxsim.errors import InvalidInputError, NonFiniteInputError
from lynxsim.inputs import instance, number_in_range, real_array
from lynxsim.traj.kinds import TrajectoryKind
from lynxsim.traj.limits import JointBounds, JointLimits
from lynxsim.traj.waypoints import Waypoints

__all__ = ["PolynomialSegment", "Segment", "Trajectory", "TrajectorySample"]

FloatArray = npt.NDArray[np.float64]

TIME_TOL = 1e-9
"""Relative slack on the time range accepted by :meth:`Trajectory.sample` [-]."""


class TrajectorySample(NamedTuple):
    """Joint states at a batch of times, batch shape ``B`` (the shape of ``t``), n joints.

    Attributes:
        q: Joint angles, shape B + (n,) [rad].
        qd: Joint velocities, shape B + (n,) [rad/s].
        qdd: Joint accelerations, shape B + (n,) [rad/s^2].
        qddd: Joint jerks, shape B + (n,) [rad/s^3]. Where a derivative jumps at
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
    def n_joints(self) -> int:
        """The number of joints n it moves."""
        ...

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
            ``q, qd, qdd, qddd`` stacked, shape (4, len(tau), n) [rad, rad/s, rad/s^2,
            rad/s^3].
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


def _check_magnitude(derivatives: tuple[FloatArray, ...], lengths: FloatArray) -> None:
    """Raise if a piecewise polynomial or a derivative can overflow float64 on its pieces.

    ``sum_k |c_k| max(1, h)^k`` bounds every partial sum of the evaluation
    (Horner's scheme and the powers of the Vandermonde matrix) on a piece of
    length ``h``.
    """
    with np.errstate(over="ignore", invalid="ignore"):
        for c in derivatives:
            powers = np.maximum(lengths, 1.0)[:, None] ** np.arange(c.shape[1])  # (P, D + 1)
            bound = np.einsum("pkj,pk->pj", np.abs(c), powers)
            if not np.isfinite(bound).all():
                raise InvalidInputError(
                    "coefficients too large: the polynomial or its derivatives overflow "
                    "float64 on the segment's pieces"
                )


@dataclass(frozen=True)
class PolynomialSegment:
    """A piecewise polynomial in local time, one polynomial per joint and piece.

    Attributes:
        breaks: Piece boundaries, shape (P + 1,) [s], from 0 to the duration,
            increasing.
        coefficients: Shape (P, D + 1, n), n >= 1 joints: for piece ``i`` and joint ``j``,
            ``q_j(tau) = sum_k coefficients[i, k, j] * (tau - breaks[i])**k`` [rad/s^k].

    Raises:
        InvalidInputError: Not real numbers, wrong shapes, breaks that do not
            increase from 0, a duration outside [0.001, 3600] s, or a polynomial
            whose values overflow float64 on its pieces.
        NonFiniteInputError: A value is NaN or infinite.
    """

    breaks: FloatArray
    coefficients: FloatArray
    _derivatives: tuple[FloatArray, ...] = field(init=False, repr=False, compare=False)
    _by_power: tuple[FloatArray, ...] = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        breaks = np.array(real_array(self.breaks, "breaks"))  # copies: frozen below
        coefficients = np.array(real_array(self.coefficients, "coefficients"))
        pieces = breaks.size - 1
        if breaks.ndim != 1 or pieces < 1:
            raise InvalidInputError(f"breaks must have shape (P + 1,), P >= 1, got {breaks.shape}")
        if not (np.isfinite(breaks).all() and np.isfinite(coefficients).all()):
            raise NonFiniteInputError("breaks and coefficients must be finite")
        if breaks[0] != 0.0 or (np.diff(breaks) <= 0).any():
            raise InvalidInputError(f"breaks must increase from 0, got {breaks.tolist()}")
        number_in_range(breaks[-1], "segment duration", MIN_SEGMENT_S, MAX_SEGMENT_S, "s")
        if coefficients.ndim != 3 or coefficients.shape[0] != pieces or coefficients.shape[2] < 1:
            raise InvalidInputError(
                f"coefficients must have shape ({pieces}, D + 1, n), got {coefficients.shape}"
            )
        with np.errstate(over="ignore"):  # inf: refused by the magnitude check
            derivatives = tuple(_derivative_coefficients(coefficients, r) for r in range(4))
        _check_magnitude(derivatives, np.diff(breaks))
        # (power, piece, joint) copies: contiguous rows for the piecewise Horner scheme.
        by_power = tuple(np.ascontiguousarray(c.transpose(1, 0, 2)) for c in derivatives)
        for arr in (breaks, coefficients, *derivatives, *by_power):
            arr.setflags(write=False)
        object.__setattr__(self, "breaks", breaks)
        object.__setattr__(self, "coefficients", coefficients)
        object.__setattr__(self, "_derivatives", derivatives)
        object.__setattr__(self, "_by_power", by_power)

    @property
    def n_joints(self) -> int:
        """The number of joints n."""
        return int(self.coefficients.shape[2])

    @property
    def duration(self) -> float:
        """Length of the segment [s]."""
        return float(self.breaks[-1])

    @property
    def breakpoints(self) -> FloatArray:
        """Interior piece boundaries, shape (P - 1,) [s]."""
        return self.breaks[1:-1]

    def evaluate(self, tau: FloatArray) -> FloatArray:
        """Joint states at local times ``tau``, shape (4, len(tau), n); see :class:`Segment`."""
        out = np.empty((4, tau.size, self.coefficients.shape[2]))
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
    """Joint motion through waypoints, sampled by time, n joints.

    Attributes:
        kind: The generator that made it.
        segments: One segment per pair of consecutive waypoints.
        waypoints: Joints and names of the waypoints (the task's targets).
        bounds: The joints and the ranges the trajectory was checked against.
        limits: The joint limits the trajectory was checked against.

    Raises:
        InvalidInputError: An unknown kind, fields of the wrong types, a segment
            count that does not match the waypoints, a segment duration out of
            range, or parts that disagree on the number of joints.
    """

    kind: TrajectoryKind
    segments: tuple[Segment, ...]
    waypoints: Waypoints
    bounds: JointBounds
    limits: JointLimits
    _times: FloatArray = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        try:
            object.__setattr__(self, "kind", TrajectoryKind(self.kind))
        except ValueError:
            raise InvalidInputError(f"unknown trajectory kind {self.kind!r}") from None
        instance(self.waypoints, Waypoints, "waypoints")
        bounds = instance(self.bounds, JointBounds, "bounds")
        instance(self.limits, JointLimits, "limits")
        instance(self.segments, tuple, "segments")
        n = bounds.n_joints
        if self.limits.n_joints != n or self.waypoints.n_joints != n:
            raise InvalidInputError(
                f"bounds of {n} joints, limits of {self.limits.n_joints} and waypoints of "
                f"{self.waypoints.n_joints}: they must agree"
            )
        for k, segment in enumerate(self.segments):
            duration = getattr(segment, "duration", None)
            if not callable(getattr(segment, "evaluate", None)) or duration is None:
                raise InvalidInputError(f"segment {k + 1} is not a Segment: {segment!r}")
            number_in_range(
                duration, f"segment {k + 1} duration", MIN_SEGMENT_S, MAX_SEGMENT_S, "s"
            )
            if getattr(segment, "n_joints", None) != n:
                raise InvalidInputError(
                    f"segment {k + 1} moves {getattr(segment, 'n_joints', None)} joints, "
                    f"the trajectory {n}"
                )
        if len(self.segments) != len(self.waypoints.q) - 1:
            raise InvalidInputError(
                f"{len(self.waypoints.q)} waypoints need {len(self.waypoints.q) - 1} segments, "
                f"got {len(self.segments)}"
            )
        times = np.concatenate([[0.0], np.cumsum([s.duration for s in self.segments])])
        times.setflags(write=False)
        object.__setattr__(self, "_times", times)

    @property
    def n_joints(self) -> int:
        """The number of joints n."""
        return self.bounds.n_joints

    @property
    def duration(self) -> float:
        """Total duration [s]."""
        return float(self._times[-1])

    @property
    def label(self) -> str:
        """The type's name (:class:`~lynxsim.traj.motion.Motion`): ``kind.value``."""
        return self.kind.value

    @property
    def waypoint_names(self) -> tuple[str, ...]:
        """The waypoints' names (:class:`~lynxsim.traj.motion.Motion`)."""
        return self.waypoints.names

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
            The :class:`TrajectorySample`, arrays of shape B + (n,).

        Raises:
            NonFiniteInputError: A time is NaN or infinite.
            InvalidInputError: A time lies outside the trajectory, ``t`` is not
                real numbers, or it holds more than
                :data:`~lynxsim.bounds.MAX_SAMPLES` times.
        """
        t_arr = real_array(t, "sample times")
        if t_arr.size > MAX_SAMPLES:
            raise InvalidInputError(
                f"at most {MAX_SAMPLES:,} sample times per call, got {t_arr.size:,}"
            )
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
        n = self.n_joints
        out = np.empty((4, ts.size, n))
        for k, segment in enumerate(self.segments):
            if hi[k] > lo[k]:
                out[:, lo[k] : hi[k]] = segment.evaluate(ts[lo[k] : hi[k]] - self._times[k])
        if order is not None:
            unsorted = np.empty_like(out)
            unsorted[:, order] = out
            out = unsorted
        shape = t_arr.shape + (n,)
        return TrajectorySample(*(out[i].reshape(shape) for i in range(4)))

    def times_at_rate(self, rate_hz: float) -> FloatArray:
        """A uniform time grid ``k / rate_hz`` over the trajectory, shape (n,) [s].

        The grid starts at 0 and ends at the last multiple of the period within
        the duration (the end itself only when the duration is such a multiple).

        Args:
            rate_hz: Sampling rate, :data:`~lynxsim.bounds.MIN_RATE_HZ` to
                :data:`~lynxsim.bounds.MAX_RATE_HZ` [Hz].

        Raises:
            InvalidInputError: ``rate_hz`` is not a number in that range, or the
                grid would hold more than :data:`~lynxsim.bounds.MAX_SAMPLES` times.
            NonFiniteInputError: ``rate_hz`` is NaN or infinite.
        """
        rate = number_in_range(rate_hz, "rate_hz", MIN_RATE_HZ, MAX_RATE_HZ, "Hz")
        n = math.floor(self.duration * rate * (1.0 + TIME_TOL)) + 1
        if n > MAX_SAMPLES:
            raise InvalidInputError(
                f"{self.duration:.6g} s at {rate:g} Hz is {n:,} samples, more than "
                f"{MAX_SAMPLES:,}: lower rate_hz"
            )
        return np.minimum(np.arange(n) / rate, self.duration)

    def times_per_segment(self, steps: int) -> FloatArray:
        """The report's grid: ``steps`` equal steps per segment plus the end, shape (N' ,) [s].

        Args:
            steps: Steps per segment (the report uses 10), a Python or NumPy integer.

        Returns:
            ``steps * (N - 1) + 1`` increasing times, waypoint times included.

        Raises:
            InvalidInputError: ``steps`` is not a positive integer, or the grid
                would hold more than :data:`~lynxsim.bounds.MAX_SAMPLES` times.
        """
        if isinstance(steps, bool) or not isinstance(steps, int | np.integer):
            raise InvalidInputError(f"steps must be an integer, got {steps!r}")
        steps = check_count(int(steps), "steps", 1, (MAX_SAMPLES - 1) // len(self.segments))
        frac = np.arange(steps) / steps
        starts, durations = self._times[:-1], self.segment_durations
        grid = (starts[:, None] + durations[:, None] * frac[None, :]).ravel()
        return np.append(grid, self.duration)
