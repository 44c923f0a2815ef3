"""Kinematics of the 5-DOF Lynxmotion arm: pure numpy, SI units, no MuJoCo."""

from lynxsim.arm.fk import FRAME_NAMES, ToolPose, fk, frame_origins, frame_transforms, tool_pose
from lynxsim.arm.geometry import LYNX_ARM, ArmGeometry, DHRow
from lynxsim.arm.ik import IKResult, IKStatus, ik, ik_one, wrap_angle
from lynxsim.arm.jacobian import geometric_jacobian, jacobian, manipulability
from lynxsim.arm.workspace import WorkspaceSamples, sample_workspace

__all__ = [
    "FRAME_NAMES",
    "LYNX_ARM",
    "ArmGeometry",
    "DHRow",
    "IKResult",
    "IKStatus",
    "ToolPose",
    "WorkspaceSamples",
    "fk",
    "frame_origins",
    "frame_transforms",
    "geometric_jacobian",
    "ik",
    "ik_one",
    "jacobian",
    "manipulability",
    "sample_workspace",
    "tool_pose",
    "wrap_angle",
]
