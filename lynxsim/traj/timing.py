"""Segment durations: given, the shortest within the limits, or given but stretched.

Every generator takes ``durations`` and ``stretch``:

* ``durations=None``: each segment takes the shortest time its joint limits allow;
* ``durations`` a number or one number per segment [s], ``stretch=False``: the
  segments take exactly that long, and the generator raises
  :class:`~lynxsim.errors.LimitViolationError` if a limit cannot be kept;
* the same with ``stretch=True``: a segment too short for the limits takes the
  shortest time they allow instead.

Every segment lasts between :data:`~lynxsim.bounds.MIN_SEGMENT_S` and
:data:`~lynxsim.bounds.MAX_SEGMENT_S` (1 ms to 1 h): given durations outside are
refused, shortest durations below 1 ms become 1 ms, and limits that need more
than an hour for a segment raise :class:`~lynxsim.errors.InvalidInputError`.

For motions that are one fixed shape scaled in time (``q0 + dq * s(tau / T)``),
velocity scales with ``1/T``, acceleration with ``1/T^2`` and jerk with ``1/T^3``,
so the shortest duration follows from the shape's peaks at ``T = 1``.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import numpy.typing as npt

from lynxsim.bounds import MAX_SEGMENT_S, MIN_SEGMENT_S
from lynxsim.errors import InvalidInputError, NonFiniteInputError
from lynxsim.inputs import real_array
from lynxsim.traj.limits import JointLimits

__all__ = [
    "Durations",
    "check_planned",
    "given_durations",
    "require_motion",
    "scaled_shortest",
    "segment_durations",
]

FloatArray = npt.NDArray[np.float64]

Durations = float | Sequence[float] | FloatArray | None
"""A duration for every segment [s], one for all, or ``None`` for the shortest."""


def _segment(k: int, names: Sequence[str] | None) -> str:
    """``segment 2 (P2 -> P3)`` for messages (``segment 2`` without names)."""
    where = f" ({names[k]} -> {names[k + 1]})" if names is not None and len(names) > k + 1 else ""
    return f"segment {k + 1}{where}"


def given_durations(
    durations: object, n_segments: int, names: Sequence[str] | None = None
) -> FloatArray | None:
    """Validate user durations; ``None`` stays ``None``.

    Every generator (and :func:`lynxsim.rrr.path.platform_path`) reads its
    durations here, so all of them accept the same range:
    [:data:`~lynxsim.bounds.MIN_SEGMENT_S`, :data:`~lynxsim.bounds.MAX_SEGMENT_S`]
    per segment.

    Args:
        durations: One duration for all segments, or one per segment [s].
        n_segments: Number of segments M.
        names: Waypoint names, M + 1, for messages (optional).

    Returns:
        Shape (M,) [s], or ``None``.

    Raises:
        InvalidInputError: Not real numbers, wrong count, or a duration outside
            [0.001, 3600] s (the message states the range).
        NonFiniteInputError: A duration is NaN or infinite.
    """
    if durations is None:
        return None
    arr = real_array(durations, "segment durations")
    if arr.ndim == 0:
        arr = np.full(n_segments, float(arr))
    if arr.shape != (n_segments,):
        raise InvalidInputError(
            f"expected one duration or {n_segments} segment durations, got shape {arr.shape}"
        )
    if not np.isfinite(arr).all():
        raise NonFiniteInputError(f"segment durations must be finite, got {arr.tolist()}")
    bad = np.flatnonzero((arr < MIN_SEGMENT_S) | (arr > MAX_SEGMENT_S))
    if bad.size:
        k = int(bad[0])
        raise InvalidInputError(
            f"segment durations must be between {MIN_SEGMENT_S:g} and {MAX_SEGMENT_S:g} s, "
            f"got {arr[k]:g} s for {_segment(k, names)}"
        )
    return arr


def check_planned(durations: FloatArray, names: Sequence[str], what: str = "joint limits") -> None:
    """Raise if a duration chosen from the limits exceeds :data:`~lynxsim.bounds.MAX_SEGMENT_S`.

    Args:
        durations: Shortest (or stretched) durations per segment, shape (M,) [s].
        names: Waypoint names, M + 1.
        what: The limits the durations come from, for the message.

    Raises:
        InvalidInputError: A segment needs longer than 3600 s (or has no finite
            shortest duration) within the limits: they are too low for the motion.
    """
    bad = np.flatnonzero(~(durations <= MAX_SEGMENT_S))  # NaN included
    if bad.size:
        k = int(bad[0])
        raise InvalidInputError(
            f"{_segment(k, names)} needs {durations[k]:.4g} s within the {what}, more than "
            f"the longest segment allowed (segments last {MIN_SEGMENT_S:g} to "
            f"{MAX_SEGMENT_S:g} s): the {what} are too low for this motion"
        )


def segment_durations(
    durations: Durations,
    shortest: FloatArray,
    names: Sequence[str],
    *,
    stretch: bool,
) -> FloatArray:
    """Choose every segment's duration.

    Shortest durations below :data:`~lynxsim.bounds.MIN_SEGMENT_S` (tiny motions,
    huge limits) become that: a longer time-scaled motion keeps the limits.

    Args:
        durations: What the user asked for (see the module docs).
        shortest: Shortest duration within the limits per segment, shape (M,) [s].
        names: Waypoint names, M + 1, for messages.
        stretch: Lengthen given durations that are too short for the limits.

    Returns:
        Shape (M,) [s], each in [0.001, 3600] s.

    Raises:
        InvalidInputError: Durations are left to the limits but two consecutive
            waypoints coincide (a segment without motion has no shortest
            duration), the given durations are malformed or out of range, or the
            limits need a segment longer than 3600 s.
    """
    given = given_durations(durations, shortest.size, names)
    if given is None:
        require_motion(shortest, names)
        chosen = np.maximum(shortest, MIN_SEGMENT_S)
    elif stretch:
        chosen = np.maximum(given, shortest)
    else:
        return given
    check_planned(chosen, names)
    return chosen


def require_motion(shortest: FloatArray, names: Sequence[str]) -> None:
    """Raise if a segment left to the limits has nothing to do.

    Args:
        shortest: Shortest duration per segment, shape (M,) [s].
        names: Waypoint names, M + 1.

    Raises:
        InvalidInputError: Two consecutive waypoints coincide (a segment without
            motion has no shortest duration).
    """
    still = np.flatnonzero(shortest <= 0.0)
    if still.size:
        k = int(still[0])
        raise InvalidInputError(
            f"waypoints {names[k]} and {names[k + 1]} coincide: a segment without motion "
            "needs a given duration"
        )


def scaled_shortest(peaks: FloatArray, limits: JointLimits, orders: Sequence[int]) -> FloatArray:
    """Shortest durations of time-scaled shapes.

    Args:
        peaks: Peak magnitude of each joint's derivative of order 1, 2, 3 over
            each segment when the segment lasts 1 s, shape (3, M, n)
            [rad/s, rad/s^2, rad/s^3].
        limits: The joint limits.
        orders: The derivative orders held to their limits.

    Returns:
        Shape (M,) [s]; 0 for a segment without motion, inf where the limits
        are too low for float64.
    """
    needed = np.zeros(peaks.shape[1:])
    with np.errstate(over="ignore"):  # tiny limits: inf, refused by check_planned
        for order in orders:
            ratio = np.abs(peaks[order - 1]) / limits.of_order(order)
            needed = np.maximum(needed, ratio ** (1.0 / order))
    return np.asarray(needed.max(axis=1), dtype=float)
