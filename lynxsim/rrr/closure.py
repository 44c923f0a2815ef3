"""Loop closure of the 3-RRR: elbows, closure residuals, working modes, Newton's method.

With the actuated angles known, the elbows ``E_i`` are fixed and the platform
must put each joint ``P_i`` on the circle of radius ``L`` about ``E_i``. The
forward kinematics (:mod:`lynxsim.rrr.fk`, :mod:`lynxsim.rrr.assembly`) close
these three loops by Newton's method from a starting pose.
"""

from __future__ import annotations

import math

import numpy as np
import numpy.typing as npt

from lynxsim.angles import wrap_angle
from lynxsim.bounds import MAX_COORDINATE_M, MAX_SAMPLES
from lynxsim.errors import InvalidInputError
from lynxsim.rrr.geometry import (
    RRR_ROBOT,
    RRRGeometry,
    _platform_joints,
    as_pose_array,
    as_theta_array,
    check_rrr_geometry,
    platform_joints,
)
from lynxsim.rrr.jacobian import det3
from lynxsim.rrr.modes import mode_index

__all__ = [
    "CLOSURE_TOL",
    "batch_size",
    "elbow_points",
    "elbows_of",
    "loop_residual",
    "newton",
    "pose_modes",
]

FloatArray = npt.NDArray[np.float64]

CLOSURE_TOL = 1e-11
"""Largest loop-closure residual ``| |P_i - E_i| - L |`` of a converged pose [m]."""

_MAX_STEP = 0.02
"""Largest Newton step [m] (alpha counted as arc length at the platform radius)."""


def elbows_of(th: FloatArray, geometry: RRRGeometry) -> FloatArray:
    """Elbows of checked angles, shape (..., 3, 2) [m]; NaN for non-finite angles."""
    with np.errstate(invalid="ignore"):  # cos(inf): NaN
        return geometry.base + geometry.proximal * np.stack([np.cos(th), np.sin(th)], axis=-1)


def batch_size(batch: tuple[int, ...]) -> int:
    """Number of items of a batch shape, at most MAX_SAMPLES, or InvalidInputError."""
    n = math.prod(batch)
    if n > MAX_SAMPLES:
        raise InvalidInputError(f"batch of {n:,} items (shape {batch}); at most {MAX_SAMPLES:,}")
    return n


def elbow_points(theta: npt.ArrayLike, geometry: RRRGeometry = RRR_ROBOT) -> FloatArray:
    """Elbows ``E_i = B_i + s_a (cos theta_i, sin theta_i)``.

    Args:
        theta: Actuated angles, shape (..., 3) [rad].
        geometry: The robot description.

    Returns:
        Shape (..., 3, 2) [m]; NaN for NaN or infinite angles.

    Raises:
        InvalidInputError: ``theta`` is not real numbers of shape (..., 3), or
            ``geometry`` not an :class:`~lynxsim.rrr.geometry.RRRGeometry`.
    """
    th = as_theta_array(theta)
    return elbows_of(th, check_rrr_geometry(geometry))


def loop_residual(
    pose: npt.ArrayLike, theta: npt.ArrayLike, geometry: RRRGeometry = RRR_ROBOT
) -> FloatArray:
    """Loop-closure error of each leg, ``|P_i - E_i| - L``.

    Args:
        pose: Platform poses, shape (..., 3) [m, m, rad].
        theta: Actuated angles, shape (..., 3) [rad]; broadcast against ``pose``.
        geometry: The robot description.

    Returns:
        Shape (..., 3) [m]; zero where the pose and the angles fit together;
        NaN where an input is NaN or infinite.

    Raises:
        InvalidInputError: Bad shapes, types or geometry (as :func:`elbow_points`
            and :func:`~lynxsim.rrr.geometry.as_pose_array`), or shapes that do
            not broadcast.
    """
    geometry = check_rrr_geometry(geometry)
    p = as_pose_array(pose)
    th = as_theta_array(theta)
    try:
        batch_size(np.broadcast_shapes(p.shape[:-1], th.shape[:-1]))
    except ValueError as exc:
        raise InvalidInputError(f"pose and theta do not broadcast: {exc}") from None
    with np.errstate(invalid="ignore"):  # inf - inf: NaN
        n = platform_joints(p, geometry) - elbows_of(th, geometry)
        out: FloatArray = np.hypot(n[..., 0], n[..., 1]) - geometry.distal
    return out


def pose_modes(pose: FloatArray, elbows: FloatArray, geometry: RRRGeometry) -> npt.NDArray[np.int8]:
    """Working modes from the sign of each elbow's bend; -1 for NaN poses."""
    a = elbows - geometry.base
    n = _platform_joints(pose, geometry) - elbows
    bend = a[..., 0] * n[..., 1] - a[..., 1] * n[..., 0]
    signs = np.where(bend < 0.0, -1, 1)
    out = mode_index(signs).astype(np.int8)
    out[~np.isfinite(pose).all(axis=-1)] = -1
    return out


def newton(
    elbows: FloatArray, pose0: FloatArray, geometry: RRRGeometry, max_iter: int
) -> tuple[FloatArray, npt.NDArray[np.bool_]]:
    """Newton's method on the three closures for flat batches.

    Args:
        elbows: Shape (n, 3, 2) [m].
        pose0: Starting poses, shape (n, 3).
        geometry: The robot description.
        max_iter: Iteration limit.

    Returns:
        Poses (n, 3), NaN where not converged, and the converged mask (n,).
    """
    ell = geometry.distal
    r_p = geometry.platform_radius
    x = pose0.copy()
    # A start beyond MAX_COORDINATE_M (a huge polynomial root) is no pose of a robot
    # under 1 m across; skipping it keeps the squares below from overflowing.
    startable: npt.NDArray[np.bool_] = np.asarray(
        np.isfinite(x).all(axis=-1)
        & (np.abs(x[:, :2]) <= MAX_COORDINATE_M).all(axis=-1)
        & np.isfinite(elbows).all(axis=(-1, -2))
    )
    active = startable.copy()
    x[~active] = 0.0
    for _ in range(max_iter):
        idx = np.flatnonzero(active)
        if idx.size == 0:
            break
        xa = x[idx]
        joints = _platform_joints(xa, geometry)
        n = joints - elbows[idx]
        r = joints - xa[:, None, :2]
        f = 0.5 * (n[..., 0] ** 2 + n[..., 1] ** 2 - ell**2)  # (k, 3) [m²]
        a = np.stack([n[..., 0], n[..., 1], r[..., 0] * n[..., 1] - r[..., 1] * n[..., 0]], -1)
        det = det3(a)
        ok = np.abs(det) > 1e-30
        safe = np.where(ok, det, 1.0)
        step = np.empty_like(xa)
        for k in range(3):
            ak = a.copy()
            ak[..., k] = -f
            step[:, k] = det3(ak) / safe
        size = np.maximum(np.abs(step[:, :2]).max(axis=-1), np.abs(step[:, 2]) * r_p)
        step *= np.minimum(1.0, _MAX_STEP / np.maximum(size, 1e-300))[:, None]
        xa = xa + step
        x[idx] = xa
        done = np.abs(f).max(axis=-1) < 1e-3 * CLOSURE_TOL * ell
        active[idx[done | ~ok]] = False
    x[:, 2] = wrap_angle(x[:, 2])
    n = _platform_joints(x, geometry) - elbows
    residual = np.abs(np.hypot(n[..., 0], n[..., 1]) - ell)
    converged = (
        startable & np.isfinite(residual).all(axis=-1) & (residual.max(axis=-1) <= CLOSURE_TOL)
    )
    x[~converged] = np.nan
    return x, converged
