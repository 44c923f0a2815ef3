"""Velocity kinematics and singularity measures of the 3-RRR robot, closed form.

Differentiating each leg's loop closure ``|P_i - E_i|² = L²`` gives

    ``A · (dx, dy, dalpha) = B · (dtheta_1, dtheta_2, dtheta_3)``

with, for leg ``i`` (``n_i = P_i - E_i`` the distal link, ``r_i = P_i - C`` the
platform arm, ``a_i = E_i - B_i`` the proximal link, ``×`` the planar cross
product ``u × v = u_x v_y - u_y v_x``):

* row ``i`` of **A** = ``(n_ix, n_iy, r_i × n_i)`` [m, m, m²];
* **B** = ``diag(a_i × n_i)`` [m²].

``B`` is singular where a leg is fully stretched or folded (``a_i ∥ n_i``): a
**leg (serial) singularity**, on the boundary of the leg's reach annulus.
``A`` is singular where the three distal-link lines meet in one point or are
parallel: a **parallel (platform) singularity**, where the platform gains a
motion with the actuators locked.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np
import numpy.typing as npt

from lynxsim.bounds import MAX_SAMPLES
from lynxsim.errors import InvalidInputError
from lynxsim.rrr.geometry import (
    RRR_ROBOT,
    RRRGeometry,
    _platform_joints,
    as_pose_array,
    as_theta_array,
    check_rrr_geometry,
)

__all__ = [
    "PlatformJacobians",
    "SingularityMeasures",
    "constraint_jacobians",
    "forward_jacobian",
    "inverse_jacobian",
    "singularity_measures",
]

FloatArray = npt.NDArray[np.float64]


class PlatformJacobians(NamedTuple):
    """The two matrices of ``A · dpose = B · dtheta``.

    Attributes:
        a: Platform (parallel) Jacobian, shape (..., 3, 3); columns x, y
            [m] and alpha [m²].
        b: Leg (serial) Jacobian, diagonal, shape (..., 3, 3) [m²].
    """

    a: FloatArray
    b: FloatArray


class SingularityMeasures(NamedTuple):
    """Dimensionless distances from the two kinds of singularity.

    Attributes:
        leg: Signed sine of each elbow's bend, ``(a_i × n_i) / (s_a L)``,
            shape (..., 3) [-]; 0 where leg ``i`` is stretched or folded; its
            sign is the leg's elbow sign (:mod:`lynxsim.rrr.modes`).
        serial: ``min_i |leg_i|``, shape (...) [-]; 0 at a leg singularity.
        parallel: Signed determinant of ``A`` normalised by ``L`` per row and
            by the platform radius in its alpha column, shape (...) [-];
            0 at a parallel singularity, changes sign across one, and
            ``|parallel| <= 2 sqrt(2)``.
        parallel_icn: Inverse condition number of the normalised ``A``,
            shape (...) [-], in [0, 1]; 0 at a parallel singularity.
    """

    leg: FloatArray
    serial: FloatArray
    parallel: FloatArray
    parallel_icn: FloatArray


_as_theta = as_theta_array


def _cross(u: FloatArray, v: FloatArray) -> FloatArray:
    out: FloatArray = u[..., 0] * v[..., 1] - u[..., 1] * v[..., 0]
    return out


def det3(m: FloatArray) -> FloatArray:
    """Determinants of 3×3 matrices by the rule of Sarrus, shape (...) (no LAPACK)."""
    out: FloatArray = (
        m[..., 0, 0] * (m[..., 1, 1] * m[..., 2, 2] - m[..., 1, 2] * m[..., 2, 1])
        - m[..., 0, 1] * (m[..., 1, 0] * m[..., 2, 2] - m[..., 1, 2] * m[..., 2, 0])
        + m[..., 0, 2] * (m[..., 1, 0] * m[..., 2, 1] - m[..., 1, 1] * m[..., 2, 0])
    )
    return out


def _vectors(
    pose: npt.ArrayLike, theta: npt.ArrayLike, geometry: RRRGeometry
) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Proximal links ``a_i``, distal links ``n_i``, platform arms ``r_i``, each (..., 3, 2).

    Checks the arguments (shapes, types, broadcasting, batch size, geometry);
    call under ``np.errstate(invalid="ignore")``: a NaN or infinite input gives NaN.
    """
    geometry = check_rrr_geometry(geometry)
    p = as_pose_array(pose)
    th = _as_theta(theta)
    try:
        batch = np.broadcast_shapes(p.shape[:-1], th.shape[:-1])
    except ValueError as exc:
        raise InvalidInputError(f"pose and theta do not broadcast: {exc}") from None
    if math.prod(batch) > MAX_SAMPLES:
        raise InvalidInputError(f"at most {MAX_SAMPLES:,} configurations, got batch {batch}")
    p = np.broadcast_to(p, batch + (3,))
    th = np.broadcast_to(th, batch + (3,))
    joints = _platform_joints(p, geometry)
    a = geometry.proximal * np.stack([np.cos(th), np.sin(th)], axis=-1)
    n = joints - geometry.base - a
    r = joints - p[..., None, :2]
    bad = ~(np.isfinite(p).all(axis=-1) & np.isfinite(th).all(axis=-1))
    if bad.any():  # NaN, never +-inf, for a configuration with a NaN or infinite input
        a, n, r = a.copy(), n.copy(), r.copy()
        a[bad], n[bad], r[bad] = np.nan, np.nan, np.nan
    return a, n, r


def constraint_jacobians(
    pose: npt.ArrayLike, theta: npt.ArrayLike, geometry: RRRGeometry = RRR_ROBOT
) -> PlatformJacobians:
    """The matrices ``A`` and ``B`` of ``A · dpose = B · dtheta``.

    Args:
        pose: Platform poses (x, y, alpha), shape (..., 3) [m, m, rad].
        theta: Actuated angles that close the loops at ``pose`` (from
            :func:`~lynxsim.rrr.ik.ik` or :func:`~lynxsim.rrr.fk.fk_all`),
            shape (..., 3) [rad]; broadcast against ``pose``.
        geometry: The robot description.

    Returns:
        The :class:`PlatformJacobians`.

    Raises:
        InvalidInputError: ``pose`` or ``theta`` is not real numbers of shape
            (..., 3) (a finite x or y beyond :data:`~lynxsim.bounds.MAX_COORDINATE_M`),
            their batch shapes do not broadcast or exceed
            :data:`~lynxsim.bounds.MAX_SAMPLES`, or a bad ``geometry``.
    """
    with np.errstate(invalid="ignore"):
        a, n, r = _vectors(pose, theta, geometry)
        b = _cross(a, n)
    mat_a = np.stack([n[..., 0], n[..., 1], _cross(r, n)], axis=-1)
    mat_b = np.zeros(b.shape + (3,))
    idx = np.arange(3)
    mat_b[..., idx, idx] = b
    return PlatformJacobians(a=mat_a, b=mat_b)


def forward_jacobian(
    pose: npt.ArrayLike, theta: npt.ArrayLike, geometry: RRRGeometry = RRR_ROBOT
) -> FloatArray:
    """Platform velocity per actuator velocity, ``d(x, y, alpha) / d(theta)``.

    Args:
        pose: Platform poses, shape (..., 3) [m, m, rad].
        theta: Matching actuated angles, shape (..., 3) [rad].
        geometry: The robot description.

    Returns:
        ``A⁻¹ B``, shape (..., 3, 3): rows x, y [m/rad] and alpha [rad/rad];
        NaN where ``A`` is exactly singular or an input is NaN or infinite.

    Raises:
        InvalidInputError: ``pose`` or ``theta`` is not real numbers of shape
            (..., 3) (a finite x or y beyond :data:`~lynxsim.bounds.MAX_COORDINATE_M`),
            their batch shapes do not broadcast or exceed
            :data:`~lynxsim.bounds.MAX_SAMPLES`, or a bad ``geometry``.
    """
    jac = constraint_jacobians(pose, theta, geometry)
    with np.errstate(invalid="ignore"):
        return _forward(jac)


def _forward(jac: PlatformJacobians) -> FloatArray:
    """``A⁻¹ B`` by the adjugate, NaN where ``A`` is singular or not finite."""
    det = det3(jac.a)
    # Adjugate (transposed cofactors) of A, divided by det(A).
    a = jac.a
    cof = np.empty_like(a)
    for i in range(3):
        for j in range(3):
            rows = [k for k in range(3) if k != i]
            cols = [k for k in range(3) if k != j]
            minor = (
                a[..., rows[0], cols[0]] * a[..., rows[1], cols[1]]
                - a[..., rows[0], cols[1]] * a[..., rows[1], cols[0]]
            )
            cof[..., i, j] = (-1) ** (i + j) * minor
    adj = np.swapaxes(cof, -1, -2)
    safe = np.where(det == 0.0, 1.0, det)
    inv_a = adj / safe[..., None, None]
    inv_a[det == 0.0] = np.nan
    out: FloatArray = inv_a * np.diagonal(jac.b, axis1=-2, axis2=-1)[..., None, :]
    return out


def inverse_jacobian(
    pose: npt.ArrayLike, theta: npt.ArrayLike, geometry: RRRGeometry = RRR_ROBOT
) -> FloatArray:
    """Actuator velocity per platform velocity, ``d(theta) / d(x, y, alpha)``.

    Args:
        pose: Platform poses, shape (..., 3) [m, m, rad].
        theta: Matching actuated angles, shape (..., 3) [rad].
        geometry: The robot description.

    Returns:
        ``B⁻¹ A``, shape (..., 3, 3): columns x, y [rad/m] and alpha [rad/rad];
        row ``i`` is NaN where leg ``i`` is exactly stretched or folded.

    Raises:
        InvalidInputError: ``pose`` or ``theta`` is not real numbers of shape
            (..., 3) (a finite x or y beyond :data:`~lynxsim.bounds.MAX_COORDINATE_M`),
            their batch shapes do not broadcast or exceed
            :data:`~lynxsim.bounds.MAX_SAMPLES`, or a bad ``geometry``.
    """
    jac = constraint_jacobians(pose, theta, geometry)
    with np.errstate(invalid="ignore"):
        return _inverse(jac)


def _inverse(jac: PlatformJacobians) -> FloatArray:
    """``B⁻¹ A``, NaN rows where ``B``'s entry is zero or not finite."""
    b = np.diagonal(jac.b, axis1=-2, axis2=-1)
    safe = np.where(b == 0.0, 1.0, b)
    out: FloatArray = jac.a / safe[..., None]
    out[b == 0.0] = np.nan
    return out


def singularity_measures(
    pose: npt.ArrayLike, theta: npt.ArrayLike, geometry: RRRGeometry = RRR_ROBOT
) -> SingularityMeasures:
    """How far a configuration is from leg and from parallel singularities.

    Args:
        pose: Platform poses, shape (..., 3) [m, m, rad].
        theta: Matching actuated angles, shape (..., 3) [rad].
        geometry: The robot description.

    Returns:
        The :class:`SingularityMeasures`.

    Raises:
        InvalidInputError: ``pose`` or ``theta`` is not real numbers of shape
            (..., 3) (a finite x or y beyond :data:`~lynxsim.bounds.MAX_COORDINATE_M`),
            their batch shapes do not broadcast or exceed
            :data:`~lynxsim.bounds.MAX_SAMPLES`, or a bad ``geometry``.
    """
    with np.errstate(invalid="ignore"):
        a, n, r = _vectors(pose, theta, geometry)
        s_a, ell, r_p = geometry.proximal, geometry.distal, geometry.platform_radius
        leg = _cross(a, n) / (s_a * ell)
        a_hat = np.stack([n[..., 0] / ell, n[..., 1] / ell, _cross(r, n) / (ell * r_p)], axis=-1)
    finite: npt.NDArray[np.bool_] = np.asarray(np.isfinite(a_hat).all(axis=(-1, -2)))
    safe: FloatArray = np.where(finite[..., None, None], a_hat, np.eye(3))
    sv = np.asarray(np.linalg.svd(safe, compute_uv=False), dtype=np.float64)
    with np.errstate(invalid="ignore"):  # 0 / 0 when every distal link has zero length
        icn = np.where(finite & (sv[..., 0] > 0.0), sv[..., 2] / sv[..., 0], np.nan)
    return SingularityMeasures(
        leg=leg,
        serial=np.abs(leg).min(axis=-1),
        parallel=det3(a_hat),
        parallel_icn=icn,
    )
