"""The arm's MuJoCo scene built from a :class:`~lynxsim.scene.Scene`, and the ids of its parts.

The MJCF files in ``lynxsim/models/lynx_arm/`` are the robot, the table, the
cube, lights and cameras; this module edits the parsed :class:`mujoco.MjSpec`
(never the XML text): it adds one named geom of class ``obstacle`` per obstacle
of the scene, sets the table and the cube (or removes it), and resolves the
names the rest of lynxsim refers to.
"""

from __future__ import annotations

from dataclasses import dataclass

import mujoco
import numpy as np

from lynxsim.arm import FRAME_NAMES, LYNX_ARM
from lynxsim.errors import InvalidInputError
from lynxsim.resources import model_path
from lynxsim.scene import REPORT_SCENE, Scene
from lynxsim.sim.binding import RobotBinding
from lynxsim.sim.collision import CollisionGroups
from lynxsim.sim.joint_robot import (
    JointRobotNames,
    TableParts,
    load_joint_scene,
    robot_geoms,
)
from lynxsim.sim.scene_build import (
    CUBE_BODY,
    CUBE_GEOM,
    FLOOR_GEOM,
    OBSTACLE_CLASS,
    TABLE_GEOM,
    ObstacleGeom,
    build_scene,
    obstacle_geom,
    table_top_z,
)

__all__ = [
    "ARM_ACTUATORS",
    "ARM_JOINTS",
    "ARM_NAMES",
    "ARM_ROOT_BODY",
    "ARM_XML",
    "COLLISION_GROUP",
    "CUBE_BODY",
    "CUBE_GEOM",
    "FINGER_JOINTS",
    "FLOOR_GEOM",
    "FRAME_SITES",
    "GRIPPER_ACTUATOR",
    "GRIPPER_TENDON",
    "HOME_KEY",
    "OBSTACLE_CLASS",
    "SCENE_XML",
    "TABLE_GEOM",
    "TOOL_SITE",
    "VISUAL_GROUP",
    "ObstacleGeom",
    "SceneIds",
    "load_arm_model",
    "load_arm_scene",
    "load_arm_spec",
    "obstacle_geom",
    "table_top_z",
]

ARM_XML = "lynx_arm/lynx_arm.xml"
"""The robot alone, relative to the models folder."""
SCENE_XML = "lynx_arm/scene.xml"
"""The robot with table, obstacle, cube, lights and cameras."""

ARM_ROOT_BODY = "base_link"
"""Root body of the arm (welded to the world; its geoms are the arm's base)."""
ARM_JOINTS: tuple[str, ...] = LYNX_ARM.joint_names
"""Hinge joints in DH order; ``q = 0`` in MuJoCo is ``q = 0`` in :mod:`lynxsim.arm`."""
ARM_ACTUATORS: tuple[str, ...] = LYNX_ARM.joint_names
"""Position actuators of the hinges, named after their joints; ctrl in [rad]."""
FINGER_JOINTS = ("left_finger", "right_finger")
"""Slide joints of the fingers, each 0..0.015 m, coupled by an equality."""
GRIPPER_TENDON = "gripper_opening"
"""Fixed tendon whose length is the opening between the finger pads [m]."""
GRIPPER_ACTUATOR = "gripper"
"""Position actuator of the opening; ctrl in [m], 0 (closed) .. 0.03 (open)."""
FRAME_SITES: tuple[str, ...] = FRAME_NAMES
"""Sites at the origins of the DH frames, named as :data:`lynxsim.arm.FRAME_NAMES`."""
TOOL_SITE = "tool"
"""Site at the report's tool point; its z axis is the tool axis."""
HOME_KEY = "home"
VISUAL_GROUP = 2
"""Geom group of the visual geoms (MuJoCo Menagerie convention)."""
COLLISION_GROUP = 3
"""Geom group of the collision geoms (MuJoCo Menagerie convention)."""
ARM_NAMES = JointRobotNames(
    root_body=ARM_ROOT_BODY,
    joints=ARM_JOINTS,
    tool_site=TOOL_SITE,
    actuators=ARM_ACTUATORS,
    collision_group=COLLISION_GROUP,
    gripper_actuator=GRIPPER_ACTUATOR,
)
"""The arm as a joint robot of the table scene (:mod:`lynxsim.sim.joint_robot`); the
table, obstacles and cube carry the names of :mod:`lynxsim.sim.scene_build`."""


def load_arm_spec(scene: Scene = REPORT_SCENE) -> mujoco.MjSpec:
    """Parse the arm's scene and build a :class:`~lynxsim.scene.Scene` into it, uncompiled.

    Args:
        scene: Obstacles, table and cube (default: the report's cylinder and cube).

    Returns:
        The edited spec; ``spec.compile()`` gives the model.

    Raises:
        InvalidInputError: An obstacle's name is already a geom or body of the scene.
    """
    if not isinstance(scene, Scene):
        raise InvalidInputError(f"scene must be a lynxsim.scene.Scene, got {scene!r}")
    return build_scene(mujoco.MjSpec.from_file(str(model_path(SCENE_XML))), scene, owner="arm")


def load_arm_scene(scene: Scene = REPORT_SCENE) -> mujoco.MjModel:
    """Compile the arm's scene (see :func:`load_arm_spec`).

    The model carries the recording sensors of its playback
    (:func:`lynxsim.sim.stepping.sensors.add_recording_sensors`), so that a run records
    natively.

    Returns:
        The compiled model (2 ms timestep, implicitfast).

    Raises:
        InvalidInputError: See :func:`load_arm_spec`.
    """
    return load_joint_scene(model_path(SCENE_XML), ARM_NAMES, scene, owner="arm")


def load_arm_model() -> mujoco.MjModel:
    """Compile the robot alone (no table, obstacle, cube, lights or cameras)."""
    return mujoco.MjModel.from_xml_path(str(model_path(ARM_XML)))


def _id(model: mujoco.MjModel, kind: mujoco.mjtObj, name: str) -> int:
    index = int(mujoco.mj_name2id(model, kind, name))
    if index < 0:
        raise InvalidInputError(f"the model has no {kind.name[6:].lower()} named {name!r}")
    return index


@dataclass(frozen=True)
class SceneIds:
    """Ids of the model elements lynxsim refers to.

    Attributes:
        arm_joints: The five hinges, in DH order.
        arm_qpos: Their ``qpos`` addresses, shape (5,).
        arm_dofs: Their ``qvel`` addresses, shape (5,).
        arm_actuators: The five hinge actuators, in DH order.
        gripper_actuator: The opening actuator.
        finger_joints: The two finger slides.
        frame_sites: Sites of the DH frames, in the order of ``FRAME_NAMES``.
        tool_site: The tool-point site.
        arm_collision_geoms: Collision geoms of every body of the arm, its
            welded base included.
        obstacle_geoms: The obstacles: every colliding geom of the world body
            other than the table and the floor, in the scene's order.
        cube_qpos: ``qpos`` address of the cube's free joint, or None.
        table_geom: The table top, or None (robot-only model).
        floor_geom: The floor, or None (robot-only model).
        cube_geom: The cube, or None.
    """

    arm_joints: tuple[int, ...]
    arm_qpos: tuple[int, ...]
    arm_dofs: tuple[int, ...]
    arm_actuators: tuple[int, ...]
    gripper_actuator: int
    finger_joints: tuple[int, ...]
    frame_sites: tuple[int, ...]
    tool_site: int
    arm_collision_geoms: tuple[int, ...]
    obstacle_geoms: tuple[int, ...]
    cube_qpos: int | None
    table_geom: int | None
    floor_geom: int | None
    cube_geom: int | None

    @classmethod
    def from_model(cls, model: mujoco.MjModel) -> SceneIds:
        """Resolve the names of this module in a compiled model.

        Raises:
            InvalidInputError: If an arm element is missing (names it).
        """
        obj = mujoco.mjtObj
        joint, site, actuator = obj.mjOBJ_JOINT, obj.mjOBJ_SITE, obj.mjOBJ_ACTUATOR
        arm_joints = tuple(_id(model, joint, n) for n in ARM_JOINTS)
        root = _id(model, mujoco.mjtObj.mjOBJ_BODY, ARM_ROOT_BODY)
        table = TableParts.from_model(model)
        return cls(
            arm_joints=arm_joints,
            arm_qpos=tuple(int(model.jnt_qposadr[j]) for j in arm_joints),
            arm_dofs=tuple(int(model.jnt_dofadr[j]) for j in arm_joints),
            arm_actuators=tuple(_id(model, actuator, n) for n in ARM_ACTUATORS),
            gripper_actuator=_id(model, actuator, GRIPPER_ACTUATOR),
            finger_joints=tuple(_id(model, joint, n) for n in FINGER_JOINTS),
            frame_sites=tuple(_id(model, site, n) for n in FRAME_SITES),
            tool_site=_id(model, site, TOOL_SITE),
            arm_collision_geoms=robot_geoms(model, root, COLLISION_GROUP),
            obstacle_geoms=table.obstacle_geoms,
            cube_qpos=table.cube_qpos,
            table_geom=table.table_geom,
            floor_geom=table.floor_geom,
            cube_geom=table.cube_geom,
        )

    def collision_groups(self, model: mujoco.MjModel) -> CollisionGroups:
        """The collision definition of this scene (:mod:`lynxsim.sim.collision`)."""
        table = TableParts(
            self.table_geom, self.floor_geom, self.cube_geom, self.cube_qpos, self.obstacle_geoms
        )
        return table.groups(model, self.arm_collision_geoms)

    def binding(self, model: mujoco.MjModel) -> RobotBinding:
        """What a playback drives and watches in this scene (or the robot alone)."""
        return RobotBinding(
            actuator_ids=np.asarray(self.arm_actuators, dtype=np.intp),
            qpos_adr=np.asarray(self.arm_qpos, dtype=np.intp),
            tool_site_id=self.tool_site,
            groups=self.collision_groups(model),
            gripper_actuator_id=self.gripper_actuator,
        )
