"""Segment durations: given, the shortest within the limits, or given but stretched.

Every generator takes ``durations`` and ``stretch``:

* ``durations=None``: each segment takes the shortest time its joint limits allow;
* ``durations`` a number or one number per segment [s], ``stretch=False``: the
  segments take exactly that long, and the generator raises
  :class:`~lynxsim.errors.LimitViolationError` if a limit cannot be kept;
* the same with ``stretch=True``: a segment too short for the limits takes the
  shortest time they allow instead.

For motions that are one fixed shape scaled in time (``q0 + dq * s(tau / T)``),
velocity scales with ``1/T``, acceleration with ``1/T^2`` and jerk with ``1/T^3``,
so the shortest duration follows from the shape's peaks at ``T = 1``.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import numpy.typing as npt

from lynxsim.errors import InvalidInputError, NonFiniteInputError
from lynxsim.traj.limits import JointLimits

__all__ = [
    "Durations",
    "given_durations",
    "require_motion",
    "scaled_shortest",
    "segment_durations",
]

FloatArray = npt.NDArray[np.float64]

Durations = float | Sequence[float] | FloatArray | None
"""A duration for every segment [s], one for all, or ``None`` for the shortest."""


def given_durations(durations: Durations, n_segments: int) -> FloatArray | None:
    """Validate user durations; ``None`` stays ``None``.

    Returns:
        Shape (n_segments,) [s], or ``None``.

    Raises:
        InvalidInputError: Wrong count or a duration that is not positive.
        NonFiniteInputError: A duration is NaN or infinite.
    """
    if durations is None:
        return None
    arr = np.asarray(durations, dtype=float)
    if arr.ndim == 0:
        arr = np.full(n_segments, float(arr))
    if arr.shape != (n_segments,):
        raise InvalidInputError(
            f"expected one duration or {n_segments} segment durations, got shape {arr.shape}"
        )
    if not np.isfinite(arr).all():
        raise NonFiniteInputError(f"segment durations must be finite, got {arr.tolist()}")
    if (arr <= 0.0).any():
        raise InvalidInputError(f"segment durations must be positive, got {arr.tolist()}")
    return arr


def segment_durations(
    durations: Durations,
    shortest: FloatArray,
    names: Sequence[str],
    *,
    stretch: bool,
) -> FloatArray:
    """Choose every segment's duration.

    Args:
        durations: What the user asked for (see the module docs).
        shortest: Shortest duration within the limits per segment, shape (M,) [s].
        names: Waypoint names, M + 1, for messages.
        stretch: Lengthen given durations that are too short for the limits.

    Returns:
        Shape (M,) [s].

    Raises:
        InvalidInputError: Durations are left to the limits but two consecutive
            waypoints coincide (a segment without motion has no shortest
            duration), or the given durations are malformed.
    """
    given = given_durations(durations, shortest.size)
    if given is None:
        require_motion(shortest, names)
        return shortest
    return np.maximum(given, shortest) if stretch else given


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
            each segment when the segment lasts 1 s, shape (3, M, 5)
            [rad/s, rad/s^2, rad/s^3].
        limits: The joint limits.
        orders: The derivative orders held to their limits.

    Returns:
        Shape (M,) [s]; 0 for a segment without motion.
    """
    needed = np.zeros(peaks.shape[1:])
    for order in orders:
        ratio = np.abs(peaks[order - 1]) / limits.of_order(order)
        needed = np.maximum(needed, ratio ** (1.0 / order))
    return np.asarray(needed.max(axis=1), dtype=float)
