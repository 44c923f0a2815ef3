"""Orientation ranges of the 3-RRR platform at a fixed centre.

* :func:`orientation_range` gives, in closed form, the connected range of
  platform orientations every leg reaches at given centres around a reference
  orientation (vectorised);
* :func:`orientation_intervals` lists every reachable arc of one centre (the
  longest is the maximal orientation range there);
* :func:`orientation_range_in_mode` also stops where one working mode meets a
  parallel singularity, which a robot cannot cross in that mode.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np
import numpy.typing as npt

from lynxsim.angles import wrap_angle
from lynxsim.bounds import MAX_COORDINATE_M, MAX_SAMPLES, check_range
from lynxsim.errors import InvalidInputError, NonFiniteInputError
from lynxsim.inputs import real_array, real_number
from lynxsim.rrr.geometry import RRR_ROBOT, RRRGeometry, check_coordinates, check_rrr_geometry
from lynxsim.rrr.ik import ik
from lynxsim.rrr.jacobian import singularity_measures
from lynxsim.rrr.modes import _check_index

__all__ = [
    "OrientationRange",
    "orientation_intervals",
    "orientation_range",
    "orientation_range_in_mode",
]

FloatArray = npt.NDArray[np.float64]

MIN_STEP_RAD = 1e-5
"""Finest sampling step of :func:`orientation_range_in_mode` [rad] (~6e5 samples a side)."""


def _finite_number(value: object, name: str, unit: str = "rad") -> float:
    """``value`` as one finite float, or InvalidInputError / NonFiniteInputError."""
    v = real_number(value, name)
    if not math.isfinite(v):
        raise NonFiniteInputError(f"{name} must be finite, got {v!r} {unit}")
    return v


def _centre(x: object, y: object) -> tuple[float, float]:
    """A platform centre (x, y) [m]: finite numbers within ±MAX_COORDINATE_M."""
    cx, cy = _finite_number(x, "x", "m"), _finite_number(y, "y", "m")
    if not (abs(cx) <= MAX_COORDINATE_M and abs(cy) <= MAX_COORDINATE_M):
        raise InvalidInputError(
            f"platform centre must be within ±{MAX_COORDINATE_M:g} m, got ({cx:g}, {cy:g}) m"
        )
    return cx, cy


class OrientationRange(NamedTuple):
    """Connected range of reachable orientations around a reference, batch shape ``B``.

    Attributes:
        lower: Smallest reachable orientation of the range, shape B [rad]
            (may lie below -pi); NaN where the reference itself is unreachable.
        upper: Largest reachable orientation of the range, shape B [rad].
        full_turn: The platform can turn all the way round, shape B; then
            ``lower, upper = alpha_ref -/+ pi``.
        limiting_leg: 1-based leg whose reach ends the range at ``lower`` and
            at ``upper``, shape B + (2,), 0 where none.
    """

    lower: FloatArray
    upper: FloatArray
    full_turn: npt.NDArray[np.bool_]
    limiting_leg: npt.NDArray[np.int8]

    @property
    def width(self) -> FloatArray:
        """``upper - lower``, shape B [rad]."""
        out: FloatArray = self.upper - self.lower
        return out


def _leg_breakpoints(
    centres: FloatArray, geometry: RRRGeometry
) -> tuple[FloatArray, npt.NDArray[np.bool_]]:
    """Orientations where a leg's reach starts or ends, per leg.

    Leg ``i`` reaches when ``|C + R(alpha) c_i - B_i|² = m + 2 A cos(alpha - delta)``
    lies in ``[r_min², r_max²]``.

    Args:
        centres: Platform centres, shape (k, 2) [m].
        geometry: The robot description.

    Returns:
        Breakpoints (k, 3, 4) [rad] (NaN where absent) and a mask (k, 3) of
        legs that reach at no orientation.
    """
    w = centres[:, None, :] - geometry.base  # (k, 3, 2)
    c = geometry.platform
    # w . R(alpha) c = cos(alpha) (w . c) + sin(alpha) (c × w)
    a_cos = (w * c).sum(-1)
    a_sin = c[:, 0] * w[..., 1] - c[:, 1] * w[..., 0]
    amp = np.hypot(a_cos, a_sin)
    delta = np.arctan2(a_sin, a_cos)
    base = (w**2).sum(-1) + (c**2).sum(-1)
    safe = np.where(amp > 0.0, 2.0 * amp, 1.0)
    hi = (geometry.reach_max**2 - base) / safe
    lo = (geometry.reach_min**2 - base) / safe
    const = amp == 0.0
    never = np.where(
        const,
        (base > geometry.reach_max**2) | (base < geometry.reach_min**2),
        (hi < -1.0) | (lo > 1.0),
    )
    out = np.full(w.shape[:-1] + (4,), np.nan)
    for k, bound in enumerate((hi, lo)):
        has = ~const & (np.abs(bound) < 1.0)
        acos = np.arccos(np.clip(bound, -1.0, 1.0))
        out[..., 2 * k] = np.where(has, delta + acos, np.nan)
        out[..., 2 * k + 1] = np.where(has, delta - acos, np.nan)
    return out, never


def orientation_range(
    xy: npt.ArrayLike, alpha_ref: float = 0.0, geometry: RRRGeometry = RRR_ROBOT
) -> OrientationRange:
    """Connected range of orientations every leg reaches, around ``alpha_ref``.

    Exact (closed form): each leg's reach condition is a sinusoid in alpha, so
    the range ends at the first of its roots on either side of ``alpha_ref``.
    Parallel singularities inside the range are not considered here (see
    :func:`orientation_range_in_mode`).

    Args:
        xy: Platform centres, shape B + (2,) [m].
        alpha_ref: Reference orientation [rad].
        geometry: The robot description.

    Returns:
        The :class:`OrientationRange`.

    Raises:
        InvalidInputError: ``xy`` is not real numbers of shape (..., 2) (a
            finite coordinate beyond :data:`~lynxsim.bounds.MAX_COORDINATE_M`,
            more than :data:`~lynxsim.bounds.MAX_SAMPLES` centres), ``alpha_ref``
            not a number, or a bad ``geometry``.
        NonFiniteInputError: ``alpha_ref`` is NaN or infinite (a NaN centre
            gives a NaN range).
    """
    geometry = check_rrr_geometry(geometry)
    p = real_array(xy, "xy")
    if p.ndim == 0 or p.shape[-1] != 2:
        raise InvalidInputError(f"xy must have shape (..., 2), got {p.shape}")
    check_coordinates(p, "xy")
    if p.size > 2 * MAX_SAMPLES:
        raise InvalidInputError(f"at most {MAX_SAMPLES:,} centres per call, got shape {p.shape}")
    alpha_ref = _finite_number(alpha_ref, "alpha_ref")
    batch = p.shape[:-1]
    flat = p.reshape(-1, 2)
    n = len(flat)
    ref_pose = np.concatenate([flat, np.full((n, 1), alpha_ref)], axis=-1)
    ok = ik(ref_pose, geometry).ok
    bps, _ = _leg_breakpoints(np.where(np.isfinite(flat), flat, 0.0), geometry)
    two_pi = 2.0 * np.pi
    ccw = np.where(np.isnan(bps), np.inf, np.mod(bps - alpha_ref, two_pi)).reshape(n, 12)
    cw = np.where(np.isnan(bps), np.inf, np.mod(alpha_ref - bps, two_pi)).reshape(n, 12)
    up_i, lo_i = np.argmin(ccw, axis=-1), np.argmin(cw, axis=-1)
    up = ccw[np.arange(n), up_i]
    down = cw[np.arange(n), lo_i]
    full = ok & np.isinf(up)
    upper = np.where(full, alpha_ref + np.pi, alpha_ref + up)
    lower = np.where(full, alpha_ref - np.pi, alpha_ref - down)
    upper[~ok], lower[~ok] = np.nan, np.nan
    legs = np.stack([lo_i // 4 + 1, up_i // 4 + 1], axis=-1).astype(np.int8)
    legs[full | ~ok] = 0
    return OrientationRange(
        lower=lower.reshape(batch),
        upper=upper.reshape(batch),
        full_turn=full.reshape(batch),
        limiting_leg=legs.reshape(batch + (2,)),
    )


def orientation_intervals(
    x: float, y: float, geometry: RRRGeometry = RRR_ROBOT
) -> list[tuple[float, float]]:
    """Every arc of orientations reachable with the platform centre at (x, y).

    Args:
        x: Platform centre x [m].
        y: Platform centre y [m].
        geometry: The robot description.

    Returns:
        Arcs ``(start, end)`` [rad], ``start`` in [-pi, pi), ``end > start``
        (an arc may run past pi), longest first; ``[(-pi, pi)]`` for a full
        turn, ``[]`` when no orientation is reachable.

    Raises:
        InvalidInputError: ``x`` or ``y`` is not a number within
            :data:`~lynxsim.bounds.MAX_COORDINATE_M`, or a bad ``geometry``.
        NonFiniteInputError: ``x`` or ``y`` is NaN or infinite.
    """
    geometry = check_rrr_geometry(geometry)
    x, y = _centre(x, y)
    bps, never = _leg_breakpoints(np.array([[x, y]], dtype=float), geometry)
    if never.any():
        return []
    cuts = np.unique(wrap_angle(bps[np.isfinite(bps)]))
    if cuts.size == 0:
        ok = bool(ik([x, y, 0.0], geometry).ok)
        return [(-math.pi, math.pi)] if ok else []
    ends = np.append(cuts[1:], cuts[0] + 2.0 * np.pi)
    mids = 0.5 * (cuts + ends)
    poses = np.stack([np.full(mids.shape, x), np.full(mids.shape, y), mids], axis=-1)
    inside = ik(poses, geometry).ok
    arcs: list[tuple[float, float]] = []
    for start, end, ok in zip(cuts, ends, inside, strict=True):
        if not ok:
            continue
        if arcs and math.isclose(arcs[-1][1], start, abs_tol=1e-12):
            arcs[-1] = (arcs[-1][0], float(end))
        else:
            arcs.append((float(start), float(end)))
    # Join the last arc with the first across the cut at cuts[0] + 2 pi.
    if len(arcs) > 1 and math.isclose(arcs[-1][1], arcs[0][0] + 2 * math.pi, abs_tol=1e-12):
        first = arcs.pop(0)
        arcs[-1] = (arcs[-1][0], first[1] + 2 * math.pi)
    arcs = [(float(wrap_angle(s)), float(wrap_angle(s) + (e - s))) for s, e in arcs]
    arcs = [(s - 2 * math.pi, e - 2 * math.pi) if s >= math.pi else (s, e) for s, e in arcs]
    return sorted(arcs, key=lambda arc: arc[0] - arc[1])


def orientation_range_in_mode(
    x: float,
    y: float,
    mode: int,
    alpha_ref: float = 0.0,
    geometry: RRRGeometry = RRR_ROBOT,
    *,
    step: float = math.radians(0.1),
) -> tuple[float, float]:
    """Orientation range around ``alpha_ref`` free of singularities in one working mode.

    Starts from :func:`orientation_range` and shrinks it to the nearest
    orientations on either side where working mode ``mode`` meets a parallel
    singularity (found on a grid of ``step`` and refined by bisection to 1e-12 rad).

    Args:
        x: Platform centre x [m].
        y: Platform centre y [m].
        mode: Working mode 0..7.
        alpha_ref: Reference orientation [rad].
        geometry: The robot description.
        step: Sampling step in alpha [rad].

    Returns:
        ``(lower, upper)`` [rad]; NaN, NaN when ``alpha_ref`` is unreachable or
        singular in this mode.

    Raises:
        InvalidInputError: ``x`` or ``y`` is not a number within
            :data:`~lynxsim.bounds.MAX_COORDINATE_M`, ``mode`` not one integer in
            0..7, ``step`` not in [:data:`MIN_STEP_RAD`, pi], or a bad ``geometry``.
        NonFiniteInputError: ``x``, ``y`` or ``alpha_ref`` is NaN or infinite.
    """
    geometry = check_rrr_geometry(geometry)
    x, y = _centre(x, y)
    index = _check_index(mode)
    if index.ndim != 0:
        raise InvalidInputError(f"mode must be one integer in 0..7, got shape {index.shape}")
    m = int(index)
    alpha_ref = _finite_number(alpha_ref, "alpha_ref")
    step = check_range(real_number(step, "step"), "step", MIN_STEP_RAD, math.pi, "rad")
    rng = orientation_range(np.array([x, y]), alpha_ref, geometry)
    lower, upper = float(rng.lower), float(rng.upper)
    if not math.isfinite(lower):
        return math.nan, math.nan

    def measure(alpha: FloatArray) -> FloatArray:
        poses = np.stack([np.full(alpha.shape, x), np.full(alpha.shape, y), alpha], axis=-1)
        theta = ik(poses, geometry).theta[..., m, :]
        out: FloatArray = singularity_measures(poses, theta, geometry).parallel
        return out

    f_ref = float(measure(np.array([alpha_ref]))[0])
    if f_ref == 0.0:
        return math.nan, math.nan
    ends = []
    for limit in (lower, upper):
        span = limit - alpha_ref
        count = max(2, int(abs(span) / step) + 2)
        a = alpha_ref + span * np.linspace(0.0, 1.0, count)[1:]
        a[-1] = limit
        f = measure(a)
        flips = np.flatnonzero(np.sign(f) != np.sign(f_ref))
        if flips.size == 0 or (flips[0] == len(a) - 1 and f[-1] == 0.0):
            ends.append(limit)
            continue
        j = int(flips[0])
        near, far = (alpha_ref if j == 0 else float(a[j - 1])), float(a[j])
        for _ in range(80):
            mid = 0.5 * (near + far)
            if np.sign(measure(np.array([mid]))[0]) == np.sign(f_ref):
                near = mid
            else:
                far = mid
            if abs(far - near) < 1e-12:
                break
        ends.append(0.5 * (near + far))
    return ends[0], ends[1]
