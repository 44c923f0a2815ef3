"""Body poses of a replay: quantised to 16-bit integers, interpolated between frames, error bounded.

A replay keeps the poses of its moving bodies at its frames only, as ``int16``:
positions on a uniform grid over their bounding box (:func:`quantise_positions`),
quaternion components times 32767 (:func:`quantise_quaternions`). Between two
frames a page interpolates as :func:`interpolate_poses` does (positions
linearly, quaternions by normalised linear interpolation on the shorter arc);
:func:`point_error_bound` bounds how far any point of a body's geoms then lies
from where the simulation had it. Pure NumPy.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

__all__ = [
    "QUAT_SCALE",
    "dequantise_positions",
    "dequantise_quaternions",
    "interpolate_poses",
    "point_error_bound",
    "quantise_positions",
    "quantise_quaternions",
]

FloatArray = npt.NDArray[np.float64]
Int16Array = npt.NDArray[np.int16]

QUAT_SCALE = 32767.0
"""A quaternion component ``c`` in [-1, 1] is kept as ``round(c * QUAT_SCALE)``."""
_INT16_HALF = 32767.0
_MIN_STEP_M = 1e-9
"""The position grid's step when every position is the same [m]."""


def quantise_positions(p: npt.ArrayLike) -> tuple[Int16Array, FloatArray, float]:
    """Positions on a 16-bit grid over their bounding box.

    Args:
        p: Positions, (..., 3) [m], finite.

    Returns:
        ``(q, origin, step_m)``: ``q`` (..., 3) int16, the grid's centre (3,) [m]
        and its step [m]; ``origin + q * step_m`` is within ``step_m / 2`` of
        ``p`` along each axis.
    """
    a = np.asarray(p, dtype=float)
    flat = a.reshape(-1, 3)
    if len(flat) == 0:
        return np.zeros(a.shape, dtype=np.int16), np.zeros(3), _MIN_STEP_M
    lo, hi = flat.min(axis=0), flat.max(axis=0)
    origin = (lo + hi) / 2.0
    step = max(float((hi - lo).max()) / (2.0 * _INT16_HALF), _MIN_STEP_M)
    q = np.clip(np.rint((a - origin) / step), -_INT16_HALF, _INT16_HALF).astype(np.int16)
    return q, origin, step


def dequantise_positions(q: npt.ArrayLike, origin: npt.ArrayLike, step_m: float) -> FloatArray:
    """Positions from :func:`quantise_positions`, (..., 3) [m]."""
    out: FloatArray = np.asarray(origin, dtype=float) + np.asarray(q, dtype=float) * step_m
    return out


def quantise_quaternions(quat: npt.ArrayLike) -> Int16Array:
    """Unit quaternions (..., 4) (w, x, y, z) as int16 components times :data:`QUAT_SCALE`."""
    a = np.asarray(quat, dtype=float)
    return np.clip(np.rint(a * QUAT_SCALE), -QUAT_SCALE, QUAT_SCALE).astype(np.int16)


def dequantise_quaternions(q: npt.ArrayLike) -> FloatArray:
    """Unit quaternions from :func:`quantise_quaternions`, (..., 4), normalised."""
    a = np.asarray(q, dtype=float)
    norm = np.linalg.norm(a, axis=-1, keepdims=True)
    out: FloatArray = a / np.where(norm > 0.0, norm, 1.0)
    return out


def interpolate_poses(
    frame_s: npt.ArrayLike, pos: npt.ArrayLike, quat: npt.ArrayLike, t_s: npt.ArrayLike
) -> tuple[FloatArray, FloatArray]:
    """Body poses at any times from the poses at the frames (what the page draws).

    Times before the first frame or after the last hold that frame. Between
    frames ``i`` and ``i + 1`` at fraction ``u``: ``(1 - u) p_i + u p_{i+1}``,
    and ``(1 - u) q_i + u s q_{i+1}`` normalised, with ``s = ±1`` the sign that
    makes ``q_i . s q_{i+1} >= 0`` (the shorter arc).

    Args:
        frame_s: Frame times, (F,) [s], increasing, F >= 1.
        pos: Positions at the frames, (F, B, 3) [m].
        quat: Unit quaternions at the frames, (F, B, 4).
        t_s: Times, (T,) [s].

    Returns:
        Positions (T, B, 3) [m] and unit quaternions (T, B, 4).
    """
    f = np.asarray(frame_s, dtype=float)
    p, q = np.asarray(pos, dtype=float), np.asarray(quat, dtype=float)
    t = np.asarray(t_s, dtype=float).reshape(-1)
    if len(f) == 1:
        return np.repeat(p, len(t), axis=0), np.repeat(q, len(t), axis=0)
    i = np.clip(np.searchsorted(f, t, side="right") - 1, 0, len(f) - 2)
    u = np.clip((t - f[i]) / (f[i + 1] - f[i]), 0.0, 1.0)[:, None, None]
    p_out = (1.0 - u) * p[i] + u * p[i + 1]
    q0, q1 = q[i], q[i + 1]
    sign = np.where(np.sum(q0 * q1, axis=-1, keepdims=True) < 0.0, -1.0, 1.0)
    blend = (1.0 - u) * q0 + u * sign * q1
    return p_out, dequantise_quaternions(blend)


def point_error_bound(
    pos_true: npt.ArrayLike,
    quat_true: npt.ArrayLike,
    pos: npt.ArrayLike,
    quat: npt.ArrayLike,
    reach_m: npt.ArrayLike,
) -> FloatArray:
    """Largest distance any point within ``reach_m`` of a body's origin can be off.

    A point at distance ``r`` from a body's origin moves by at most
    ``|dp| + 2 r sin(theta / 2)`` when the body's pose is off by ``dp`` and by
    a rotation of angle ``theta``.

    Args:
        pos_true: The true positions, (..., B, 3) [m].
        quat_true: The true unit quaternions, (..., B, 4).
        pos: The positions shown, (..., B, 3) [m].
        quat: The unit quaternions shown, (..., B, 4).
        reach_m: Per body, the farthest point of its geoms from its origin, (B,) [m].

    Returns:
        The bound, (..., B) [m].
    """
    dp = np.linalg.norm(np.asarray(pos, dtype=float) - np.asarray(pos_true, dtype=float), axis=-1)
    q1, q2 = np.asarray(quat_true, dtype=float), np.asarray(quat, dtype=float)
    # sin(theta / 2) is the length of the vector part of conj(q1) q2 (well conditioned near 0,
    # unlike the arccos of a dot product)
    w1, v1, w2, v2 = q1[..., :1], q1[..., 1:], q2[..., :1], q2[..., 1:]
    sin_half = np.linalg.norm(w1 * v2 - w2 * v1 - np.cross(v1, v2), axis=-1)
    out: FloatArray = dp + 2.0 * np.asarray(reach_m, dtype=float) * sin_half
    return out
