"""The arm's joint space for the trajectory layer: its joint ranges, limits and kinematics.

:data:`ARM_BOUNDS` are the joint ranges of :data:`~lynxsim.arm.LYNX_ARM`;
:data:`ARM_LIMITS` derive from the servos' datasheets in
:mod:`lynxsim.arm.servos` (derating and ramp times explained there):

velocity [rad/s] 3.49, 4.49, 2.73, 3.14, 5.71; acceleration = velocity / 0.25 s;
jerk = acceleration / 0.1 s. :data:`ARM_KINEMATICS` adds the tool point and pitch
(:func:`arm_tool`) for the robot-free commands.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from lynxsim.arm.fk import tool_pose
from lynxsim.arm.geometry import LYNX_ARM, ArmGeometry
from lynxsim.arm.servos import AL5D_SERVOS
from lynxsim.inputs import instance
from lynxsim.traj.kinematics import Kinematics, ToolReadout
from lynxsim.traj.limits import JointBounds, JointLimits

__all__ = ["ARM_BOUNDS", "ARM_KINEMATICS", "ARM_LIMITS", "arm_tool", "joint_bounds"]


def joint_bounds(geometry: ArmGeometry = LYNX_ARM) -> JointBounds:
    """The joints of an arm description: names and ranges.

    Raises:
        InvalidInputError: ``geometry`` is not an :class:`~lynxsim.arm.ArmGeometry`.
    """
    geometry = instance(geometry, ArmGeometry, "geometry")
    if geometry is LYNX_ARM:
        return ARM_BOUNDS
    return JointBounds(geometry.joint_names, geometry.q_min, geometry.q_max)


ARM_BOUNDS = JointBounds(LYNX_ARM.joint_names, LYNX_ARM.q_min, LYNX_ARM.q_max)
"""The report's arm's joints: :data:`~lynxsim.arm.LYNX_ARM`'s names and ranges."""

ARM_LIMITS = JointLimits(
    velocity=tuple(s.velocity_limit for s in AL5D_SERVOS),
    acceleration=tuple(s.acceleration_limit for s in AL5D_SERVOS),
    jerk=tuple(s.jerk_limit for s in AL5D_SERVOS),
)
"""The arm's default limits: :class:`~lynxsim.arm.servos.ServoSpec`'s
``velocity_limit``, ``acceleration_limit`` and ``jerk_limit`` of
:data:`~lynxsim.arm.servos.AL5D_SERVOS`."""


def arm_tool(q: npt.NDArray[np.float64]) -> ToolReadout:
    """The tool point and pitch of joint vectors, (N, 5) [rad] (the analytic FK)."""
    pose = tool_pose(q)
    return ToolReadout(position=pose.position, angles=(("pitch", pose.pitch),))


ARM_KINEMATICS = Kinematics(ARM_BOUNDS, ARM_LIMITS, arm_tool)
"""The arm's joints, servo limits and tool (point and pitch, as ``lynxsim traj`` writes them)."""
