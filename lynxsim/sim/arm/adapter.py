"""The arm's simulation side (named by :mod:`lynxsim.robots.arm`): a joint robot of the table scene.

The arm is a :class:`~lynxsim.sim.joint_sim.JointRobotSim` with its scene, its
names (:data:`~lynxsim.sim.arm.model.ARM_NAMES`), its kinematics, the
pick-and-place gripper schedule when the scene has a cube, and the tool poses
of its waypoints as the marks of its videos.
"""

from __future__ import annotations

from lynxsim.arm.motion import ARM_KINEMATICS
from lynxsim.resources import model_path
from lynxsim.sim.adapter import SimAdapter
from lynxsim.sim.arm.model import ARM_NAMES, SCENE_XML
from lynxsim.sim.arm.task import arm_targets, pick_and_place_gripper
from lynxsim.sim.joint_sim import JointRobotSim

__all__ = ["ADAPTER"]

ADAPTER: SimAdapter = JointRobotSim(
    name="arm",
    scene_xml=model_path(SCENE_XML),
    names=ARM_NAMES,
    kinematics=ARM_KINEMATICS,
    gripper=pick_and_place_gripper,
    targets=arm_targets,
)
"""The adapter the arm's record names."""
