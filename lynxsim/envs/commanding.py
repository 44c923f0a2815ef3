"""Where an arm env's commands may go, and what turns its actions into servo targets.

The ready pose, the box that tool targets stay in, the largest joint jump a control step
may ask for, and :func:`make_controller`, which picks the controller of the configured
action (:mod:`lynxsim.envs.control`, :mod:`lynxsim.envs.tool_action`).
"""

from __future__ import annotations

from lynxsim.envs.config import EnvConfig
from lynxsim.envs.control import ControlMode, JointSpaceController, ToolSpaceController
from lynxsim.envs.tool_action import ToolLimits, ToolRollController
from lynxsim.envs.workspace import GRIP_ROLL_RAD, TOP_DOWN_PITCH_RAD

__all__ = [
    "MAX_JOINT_JUMP_RAD",
    "READY_TOOL_POSE",
    "TARGET_BOX_LOWER",
    "TARGET_BOX_UPPER",
    "make_controller",
]

READY_TOOL_POSE = (0.18, 0.0, 0.08, TOP_DOWN_PITCH_RAD)
"""Tool point (x, y, z) [m] and pitch [rad] of the arm at reset: 18 cm in front of
the base, 8 cm above the base plane, gripper pointing down."""

TARGET_BOX_LOWER = (-0.30, -0.45, -0.004)
"""Lower corner of the tool-target box [m]; z keeps the fingertips (8 mm past the
tool point) above the table top (z = -12.5 mm) when the gripper points down."""
TARGET_BOX_UPPER = (0.45, 0.45, 0.50)
"""Upper corner of the tool-target box [m]."""
MAX_JOINT_JUMP_RAD = 0.5
"""The largest change of a joint target one control step may ask for [rad]."""


def make_controller(config: EnvConfig) -> ToolSpaceController | JointSpaceController:
    """What turns the configured actions into servo targets.

    Args:
        config: The env's checked options (its control mode and step sizes).

    Returns:
        A :class:`ToolRollController` (``"tool_roll"``), a :class:`ToolSpaceController`
        (``"tool"``) or a :class:`JointSpaceController` (``"joint"``).
    """
    if config.control is ControlMode.TOOL_ROLL:
        return ToolRollController(
            ToolLimits(
                config.position_step,
                config.pitch_step,
                config.roll_step,
                TARGET_BOX_LOWER,
                TARGET_BOX_UPPER,
                max_joint_jump=MAX_JOINT_JUMP_RAD,
            )
        )
    if config.control is ControlMode.TOOL:
        return ToolSpaceController(
            config.position_step,
            config.pitch_step,
            GRIP_ROLL_RAD,
            TARGET_BOX_LOWER,
            TARGET_BOX_UPPER,
            max_joint_jump=MAX_JOINT_JUMP_RAD,
            fallback=config.target_fallback,
        )
    return JointSpaceController(config.joint_step)
