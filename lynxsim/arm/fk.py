"""Forward kinematics of the arm, vectorised over any leading batch shape.

Two routes to the same numbers, tested against each other:

* :func:`frame_transforms` multiplies the modified-DH chain of
  :data:`~lynxsim.arm.geometry.LYNX_ARM` (the definition);
* :func:`tool_pose` evaluates the closed form of the tool point and pitch in the
  arm's vertical plane (the fast path used by sampling and by the IK checks).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
import numpy.typing as npt

from lynxsim.arm.geometry import LYNX_ARM, ArmGeometry, check_geometry
from lynxsim.errors import InvalidInputError, NonFiniteInputError
from lynxsim.inputs import real_array

__all__ = [
    "FRAME_NAMES",
    "ToolPose",
    "fk",
    "frame_origins",
    "frame_transforms",
    "tool_pose",
]

FloatArray = npt.NDArray[np.float64]

FRAME_NAMES = ("base", "frame1", "frame2", "frame3", "frame4", "frame5", "tool")
"""Names of the frames returned by :func:`frame_transforms`, in order.

frame1 is the base rotation axis at shoulder height, frame2 the shoulder,
frame3 the elbow, frame4 the wrist-pitch axis, frame5 the wrist-roll axis (the
wrist point, which coincides with frame4's origin) and ``tool`` the tool point.
"""


class ToolPose(NamedTuple):
    """Tool point and tool-axis angles.

    Attributes:
        position: Tool point in the base frame, shape (..., 3) [m].
        pitch: Angle of the wrist→tool line above the horizontal, measured in
            the arm's vertical plane towards the direction ``q1`` points,
            ``q2 + q3 + q4``, shape (...) [rad].
        roll: Wrist roll ``q5``, shape (...) [rad].
    """

    position: FloatArray
    pitch: FloatArray
    roll: FloatArray


def as_joint_array(q: npt.ArrayLike, name: str = "q") -> FloatArray:
    """Return ``q`` as a finite float array of shape (..., 5) [rad] or raise.

    Raises:
        InvalidInputError: Not real numbers, or the last axis does not have length 5.
        NonFiniteInputError: An angle is NaN or infinite.
    """
    arr = real_array(q, name)
    if arr.ndim == 0 or arr.shape[-1] != 5:
        raise InvalidInputError(f"{name} must have shape (..., 5), got {arr.shape}")
    if not np.isfinite(arr).all():
        raise NonFiniteInputError(f"{name} must be finite joint angles [rad], got NaN or infinity")
    return arr


def _dh_matrices(a: float, alpha: float, d: float, theta: FloatArray) -> FloatArray:
    """``RotX(alpha) TransX(a) RotZ(theta) TransZ(d)``, shape theta.shape + (4, 4)."""
    ct, st = np.cos(theta), np.sin(theta)
    ca, sa = np.cos(alpha), np.sin(alpha)
    out = np.zeros(theta.shape + (4, 4))
    out[..., 0, 0] = ct
    out[..., 0, 1] = -st
    out[..., 0, 3] = a
    out[..., 1, 0] = st * ca
    out[..., 1, 1] = ct * ca
    out[..., 1, 2] = -sa
    out[..., 1, 3] = -sa * d
    out[..., 2, 0] = st * sa
    out[..., 2, 1] = ct * sa
    out[..., 2, 2] = ca
    out[..., 2, 3] = ca * d
    out[..., 3, 3] = 1.0
    return out


def frame_transforms(q: npt.ArrayLike, geometry: ArmGeometry = LYNX_ARM) -> FloatArray:
    """Poses of every frame of the chain in the base frame.

    Args:
        q: Joint angles, shape (..., 5) [rad].
        geometry: The arm description.

    Returns:
        ``T_base_frame``, shape (..., 7, 4, 4) [m], frames in the order of
        :data:`FRAME_NAMES`.

    Raises:
        InvalidInputError: ``q`` is not real numbers of shape (..., 5), or
            ``geometry`` not an :class:`~lynxsim.arm.geometry.ArmGeometry`.
        NonFiniteInputError: An angle is NaN or infinite.
    """
    q = as_joint_array(q)
    geometry = check_geometry(geometry)
    batch = q.shape[:-1]
    out = np.empty(batch + (7, 4, 4))
    current = np.broadcast_to(np.eye(4), batch + (4, 4))
    out[..., 0, :, :] = current
    for i, row in enumerate(geometry.dh):
        current = current @ _dh_matrices(row.a, row.alpha, row.d, q[..., i] + row.theta_offset)
        out[..., i + 1, :, :] = current
    tool = np.eye(4)
    tool[2, 3] = geometry.tool_length
    out[..., 6, :, :] = current @ tool
    return out


def fk(q: npt.ArrayLike, geometry: ArmGeometry = LYNX_ARM) -> FloatArray:
    """Tool pose for joint angles.

    Args:
        q: Joint angles, shape (..., 5) [rad].
        geometry: The arm description.

    Returns:
        ``T_base_tool``, shape (..., 4, 4) [m]; its z axis is the tool axis.

    Raises:
        InvalidInputError, NonFiniteInputError: As :func:`frame_transforms`.
    """
    return frame_transforms(q, geometry)[..., 6, :, :]


def frame_origins(q: npt.ArrayLike, geometry: ArmGeometry = LYNX_ARM) -> FloatArray:
    """Origins of every frame (for plots, collision reasoning and tests).

    Args:
        q: Joint angles, shape (..., 5) [rad].
        geometry: The arm description.

    Returns:
        Positions in the base frame, shape (..., 7, 3) [m], in the order of
        :data:`FRAME_NAMES`.

    Raises:
        InvalidInputError, NonFiniteInputError: As :func:`frame_transforms`.
    """
    return frame_transforms(q, geometry)[..., :3, 3]


def tool_pose(q: npt.ArrayLike, geometry: ArmGeometry = LYNX_ARM) -> ToolPose:
    """Closed-form tool point, pitch and roll (fast path, no matrices).

    Args:
        q: Joint angles, shape (..., 5) [rad].
        geometry: The arm description.

    Returns:
        The :class:`ToolPose`, batch shape ``q.shape[:-1]``.

    Raises:
        InvalidInputError, NonFiniteInputError: As :func:`frame_transforms`.
    """
    q = as_joint_array(q)
    geometry = check_geometry(geometry)
    q1, q2, q3, q4, q5 = np.moveaxis(q, -1, 0)
    a23 = q2 + q3
    pitch = a23 + q4
    l2, l3, lt = geometry.upper_arm, geometry.forearm, geometry.tool_length
    reach = l2 * np.cos(q2) + l3 * np.cos(a23) + lt * np.cos(pitch)
    height = geometry.shoulder_height + l2 * np.sin(q2) + l3 * np.sin(a23) + lt * np.sin(pitch)
    position = np.stack([reach * np.cos(q1), reach * np.sin(q1), height], axis=-1)
    return ToolPose(position=position, pitch=pitch, roll=np.asarray(q5, dtype=float))
