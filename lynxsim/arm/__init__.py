"""Kinematics of the 5-DOF Lynxmotion arm: pure numpy, SI units, no MuJoCo."""

from lynxsim.angles import wrap_angle
from lynxsim.arm.fk import FRAME_NAMES, ToolPose, fk, frame_origins, frame_transforms, tool_pose
from lynxsim.arm.geometry import LYNX_ARM, ArmGeometry, DHRow
from lynxsim.arm.ik import IKResult, IKStatus, ik
from lynxsim.arm.jacobian import geometric_jacobian, jacobian, manipulability
from lynxsim.arm.scalar import ik_nearest, ik_one, tool_pose_of
from lynxsim.arm.servos import AL5D_SERVOS, GRIPPER_SERVO, ServoSpec
from lynxsim.arm.workspace import WorkspaceSamples, sample_workspace

__all__ = [
    "AL5D_SERVOS",
    "FRAME_NAMES",
    "GRIPPER_SERVO",
    "LYNX_ARM",
    "ArmGeometry",
    "DHRow",
    "IKResult",
    "IKStatus",
    "ServoSpec",
    "ToolPose",
    "WorkspaceSamples",
    "fk",
    "frame_origins",
    "frame_transforms",
    "geometric_jacobian",
    "ik",
    "ik_nearest",
    "ik_one",
    "jacobian",
    "manipulability",
    "sample_workspace",
    "tool_pose",
    "tool_pose_of",
    "wrap_angle",
]
