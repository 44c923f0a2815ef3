"""Jacobians and manipulability of the arm, closed form, vectorised."""

from __future__ import annotations

from typing import Literal

import numpy as np
import numpy.typing as npt

from lynxsim.arm.fk import as_joint_array, frame_transforms
from lynxsim.arm.geometry import LYNX_ARM, ArmGeometry, check_geometry
from lynxsim.errors import InvalidInputError

__all__ = ["geometric_jacobian", "jacobian", "manipulability"]

FloatArray = npt.NDArray[np.float64]


def jacobian(q: npt.ArrayLike, geometry: ArmGeometry = LYNX_ARM) -> FloatArray:
    """Jacobian of the tool point and pitch with respect to the joints.

    Rows: d(x, y, z)/dq [m/rad] and d(pitch)/dq [rad/rad]; columns: q1..q5.
    The roll column is zero (q5 does not move the tool point nor its pitch).

    Args:
        q: Joint angles, shape (..., 5) [rad].
        geometry: The arm description.

    Returns:
        Shape (..., 4, 5).

    Raises:
        InvalidInputError, NonFiniteInputError: As :func:`~lynxsim.arm.fk.frame_transforms`.
    """
    q = as_joint_array(q)
    geometry = check_geometry(geometry)
    q1, q2, q3, q4, _ = np.moveaxis(q, -1, 0)
    l2, l3, lt = geometry.upper_arm, geometry.forearm, geometry.tool_length
    a2, a23, a234 = q2, q2 + q3, q2 + q3 + q4
    reach = l2 * np.cos(a2) + l3 * np.cos(a23) + lt * np.cos(a234)
    # d(reach)/d(q2, q3, q4) and d(height)/d(q2, q3, q4): partial sums from the tip.
    dr = np.stack(
        [
            -(l2 * np.sin(a2) + l3 * np.sin(a23) + lt * np.sin(a234)),
            -(l3 * np.sin(a23) + lt * np.sin(a234)),
            -lt * np.sin(a234),
        ],
        axis=-1,
    )
    dz = np.stack(
        [
            l2 * np.cos(a2) + l3 * np.cos(a23) + lt * np.cos(a234),
            l3 * np.cos(a23) + lt * np.cos(a234),
            lt * np.cos(a234),
        ],
        axis=-1,
    )
    c1, s1 = np.cos(q1)[..., None], np.sin(q1)[..., None]
    out = np.zeros(q.shape[:-1] + (4, 5))
    out[..., 0, 0] = -reach * np.sin(q1)
    out[..., 1, 0] = reach * np.cos(q1)
    out[..., 0, 1:4] = dr * c1
    out[..., 1, 1:4] = dr * s1
    out[..., 2, 1:4] = dz
    out[..., 3, 1:4] = 1.0
    return out


def geometric_jacobian(q: npt.ArrayLike, geometry: ArmGeometry = LYNX_ARM) -> FloatArray:
    """Full geometric Jacobian of the tool frame (as MuJoCo's ``mj_jacSite``).

    Args:
        q: Joint angles, shape (..., 5) [rad].
        geometry: The arm description.

    Returns:
        Shape (..., 6, 5): rows 0–2 the tool point's linear velocity [m/rad],
        rows 3–5 the tool frame's angular velocity [rad/rad], in the base frame.

    Raises:
        InvalidInputError, NonFiniteInputError: As :func:`~lynxsim.arm.fk.frame_transforms`.
    """
    frames = frame_transforms(q, geometry)
    axes = frames[..., 1:6, :3, 2]  # z axis of frames 1..5, (..., 5, 3)
    origins = frames[..., 1:6, :3, 3]
    tool = frames[..., 6, :3, 3]
    linear = np.cross(axes, tool[..., None, :] - origins)
    return np.concatenate([np.swapaxes(linear, -1, -2), np.swapaxes(axes, -1, -2)], axis=-2)


def manipulability(
    q: npt.ArrayLike,
    kind: Literal["position", "position_pitch"] = "position",
    geometry: ArmGeometry = LYNX_ARM,
) -> FloatArray:
    """Yoshikawa manipulability ``sqrt(det(J J^T))``.

    Args:
        q: Joint angles, shape (..., 5) [rad].
        kind: ``"position"`` uses the 3×5 tool-point Jacobian [m^3];
            ``"position_pitch"`` the 4×5 one with the pitch row (mixed units).
        geometry: The arm description.

    Returns:
        Shape (...); zero at singular configurations.

    Raises:
        InvalidInputError: A bad ``kind`` (lists the choices), or as
            :func:`~lynxsim.arm.fk.frame_transforms`.
        NonFiniteInputError: An angle is NaN or infinite.
    """
    if not (isinstance(kind, str) and kind in ("position", "position_pitch")):
        raise InvalidInputError(f"kind must be 'position' or 'position_pitch', got {kind!r}")
    j = jacobian(q, geometry)
    if kind == "position":
        j = j[..., :3, :]
    det = np.linalg.det(j @ np.swapaxes(j, -1, -2))
    out: FloatArray = np.sqrt(np.clip(det, 0.0, None))
    return out
