"""The planar arm's simulation side: lynxsim's generic joint robot, given its names.

The arm stands in lynxsim's table scene, so its adapter is a
:class:`lynxsim.sim.joint_sim.JointRobotSim`: the scene file, what it names, and
the kinematics. It has no gripper (the cube stays on the table) and takes the
option ``--no-obstacle`` (its record declares it).
"""

from __future__ import annotations

from pathlib import Path

from lynxsim.sim.adapter import SimAdapter
from lynxsim.sim.joint_robot import JointRobotNames
from lynxsim.sim.joint_sim import JointRobotSim
from planar_arm.kinematics import JOINT_NAMES, KINEMATICS

__all__ = ["ADAPTER", "NAMES", "SCENE_XML"]

SCENE_XML = Path(__file__).resolve().parent / "scene.xml"
"""The arm on lynxsim's table: table, obstacle class, cube, light, cameras."""

NAMES = JointRobotNames(
    root_body="base_link", joints=JOINT_NAMES, tool_site="tool", collision_group=3
)
"""What the scene names: the root body, the hinges (their actuators share their names),
the tool site and the geom group of the collision capsules."""

ADAPTER: SimAdapter = JointRobotSim(
    name="planar_arm", scene_xml=SCENE_XML, names=NAMES, kinematics=KINEMATICS
)
"""The adapter the record names (mypy checks it against :class:`SimAdapter`)."""
