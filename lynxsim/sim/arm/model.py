"""The arm's MuJoCo scene built from a :class:`~lynxsim.scene.Scene`, and the ids of its parts.

The MJCF files in ``lynxsim/models/lynx_arm/`` are the robot, the table, the
cube, lights and cameras; this module edits the parsed :class:`mujoco.MjSpec`
(never the XML text): it adds one named geom of class ``obstacle`` per obstacle
of the scene, sets the table and the cube (or removes it), and resolves the
names the rest of lynxsim refers to.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import NamedTuple

import mujoco
import numpy as np

from lynxsim.arm import FRAME_NAMES, LYNX_ARM
from lynxsim.errors import InvalidInputError
from lynxsim.resources import model_path
from lynxsim.scene import REPORT_SCENE, Box, Cylinder, Obstacle, Scene
from lynxsim.sim.binding import RobotBinding
from lynxsim.sim.collision import CollisionGroups
from lynxsim.sim.stepping.sensors import add_recording_sensors

__all__ = [
    "ARM_ACTUATORS",
    "ARM_JOINTS",
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
OBSTACLE_CLASS = "obstacle"
"""Default class of the obstacle geoms (material, contacts)."""
TABLE_GEOM = "table"
FLOOR_GEOM = "floor"
CUBE_BODY = "cube"
CUBE_GEOM = "cube"
HOME_KEY = "home"
VISUAL_GROUP = 2
"""Geom group of the visual geoms (MuJoCo Menagerie convention)."""
COLLISION_GROUP = 3
"""Geom group of the collision geoms (MuJoCo Menagerie convention)."""


def table_top_z(spec: mujoco.MjSpec) -> float:
    """Height of the table top in the base frame [m] (negative: below z = 0).

    Raises:
        InvalidInputError: If the spec has no table geom.
    """
    table = spec.geom(TABLE_GEOM)
    if table is None:
        raise InvalidInputError(f"the spec has no geom named {TABLE_GEOM!r}")
    return float(table.pos[2] + table.size[2])


class ObstacleGeom(NamedTuple):
    """An obstacle as a MuJoCo geom: what the spec and the slots write.

    Attributes:
        type: The geom type (a :class:`mujoco.mjtGeom` value as an int).
        size: MuJoCo's size triple (half extents, radius, half height) [m].
        pos: Centre of the geom in the world (x, y, z) [m].
        quat: Orientation (w, x, y, z).
    """

    type: int
    size: tuple[float, float, float]
    pos: tuple[float, float, float]
    quat: tuple[float, float, float, float]


def obstacle_geom(obstacle: Obstacle) -> ObstacleGeom:
    """The geom of an obstacle: standing obstacles are centred half their height up."""
    x, y, z = obstacle.position
    upright = (1.0, 0.0, 0.0, 0.0)
    if isinstance(obstacle, Cylinder):
        half = 0.5 * obstacle.height
        return ObstacleGeom(
            int(mujoco.mjtGeom.mjGEOM_CYLINDER),
            (obstacle.radius, half, 0.0),
            (x, y, z + half),
            upright,
        )
    if isinstance(obstacle, Box):
        half_z = 0.5 * obstacle.size[2]
        yaw = 0.5 * obstacle.yaw
        return ObstacleGeom(
            int(mujoco.mjtGeom.mjGEOM_BOX),
            (0.5 * obstacle.size[0], 0.5 * obstacle.size[1], half_z),
            (x, y, z + half_z),
            (math.cos(yaw), 0.0, 0.0, math.sin(yaw)),
        )
    return ObstacleGeom(
        int(mujoco.mjtGeom.mjGEOM_SPHERE), (obstacle.radius, 0.0, 0.0), (x, y, z), upright
    )


def _add_obstacle(spec: mujoco.MjSpec, obstacle: Obstacle) -> None:
    if spec.geom(obstacle.name) is not None or spec.body(obstacle.name) is not None:
        raise InvalidInputError(
            f"obstacle name {obstacle.name!r} is taken by a part of the arm's scene; rename it"
        )
    geom = obstacle_geom(obstacle)
    spec.worldbody.add_geom(
        spec.find_default(OBSTACLE_CLASS),
        name=obstacle.name,
        type=mujoco.mjtGeom(geom.type),
        size=list(geom.size),
        pos=list(geom.pos),
        quat=list(geom.quat),
    )


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
    spec = mujoco.MjSpec.from_file(str(model_path(SCENE_XML)))
    table = spec.geom(TABLE_GEOM)
    t = scene.table
    table.size = [0.5 * t.size[0], 0.5 * t.size[1], 0.5 * t.thickness]
    table.pos = [t.center[0], t.center[1], t.top_z - 0.5 * t.thickness]
    for obstacle in scene.obstacles:
        _add_obstacle(spec, obstacle)
    body = spec.body(CUBE_BODY)
    if scene.cube is None:
        spec.delete(body)
    else:
        c = scene.cube
        body.pos = list(c.position)
        body.quat = [math.cos(0.5 * c.yaw), 0.0, 0.0, math.sin(0.5 * c.yaw)]
        geom = spec.geom(CUBE_GEOM)
        geom.size = [0.5 * c.size] * 3
        geom.mass = c.mass
        geom.friction = [c.friction, geom.friction[1], geom.friction[2]]
    return spec


def load_arm_scene(scene: Scene = REPORT_SCENE) -> mujoco.MjModel:
    """Compile the arm's scene (see :func:`load_arm_spec`).

    The model carries the recording sensors of its playback
    (:func:`lynxsim.sim.stepping.sensors.add_recording_sensors`), so that a run records
    natively.

    Returns:
        The compiled model (2 ms timestep, implicitfast).
    """
    spec = load_arm_spec(scene)
    plain = spec.compile()
    return add_recording_sensors(spec, plain, SceneIds.from_model(plain).binding(plain))


def load_arm_model() -> mujoco.MjModel:
    """Compile the robot alone (no table, obstacle, cube, lights or cameras)."""
    return mujoco.MjModel.from_xml_path(str(model_path(ARM_XML)))


def _id(model: mujoco.MjModel, kind: mujoco.mjtObj, name: str) -> int:
    index = int(mujoco.mj_name2id(model, kind, name))
    if index < 0:
        raise InvalidInputError(f"the model has no {kind.name[6:].lower()} named {name!r}")
    return index


def _optional_id(model: mujoco.MjModel, kind: mujoco.mjtObj, name: str) -> int | None:
    index = int(mujoco.mj_name2id(model, kind, name))
    return None if index < 0 else index


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
        joint, site, geom, actuator = (
            obj.mjOBJ_JOINT,
            obj.mjOBJ_SITE,
            obj.mjOBJ_GEOM,
            obj.mjOBJ_ACTUATOR,
        )
        arm_joints = tuple(_id(model, joint, n) for n in ARM_JOINTS)
        root = _id(model, mujoco.mjtObj.mjOBJ_BODY, ARM_ROOT_BODY)
        table = _optional_id(model, geom, TABLE_GEOM)
        floor = _optional_id(model, geom, FLOOR_GEOM)
        support = {table, floor}
        colliding = (np.asarray(model.geom_contype) != 0) | (
            np.asarray(model.geom_conaffinity) != 0
        )
        world = set(np.flatnonzero((np.asarray(model.geom_bodyid) == 0) & colliding).tolist())
        cube_joint = _optional_id(model, joint, CUBE_BODY)
        arm_geoms = tuple(
            g
            for g in range(model.ngeom)
            if model.geom_group[g] == COLLISION_GROUP
            and model.body_rootid[model.geom_bodyid[g]] == model.body_rootid[root]
        )
        return cls(
            arm_joints=arm_joints,
            arm_qpos=tuple(int(model.jnt_qposadr[j]) for j in arm_joints),
            arm_dofs=tuple(int(model.jnt_dofadr[j]) for j in arm_joints),
            arm_actuators=tuple(_id(model, actuator, n) for n in ARM_ACTUATORS),
            gripper_actuator=_id(model, actuator, GRIPPER_ACTUATOR),
            finger_joints=tuple(_id(model, joint, n) for n in FINGER_JOINTS),
            frame_sites=tuple(_id(model, site, n) for n in FRAME_SITES),
            tool_site=_id(model, site, TOOL_SITE),
            arm_collision_geoms=arm_geoms,
            obstacle_geoms=tuple(g for g in range(model.ngeom) if g in world and g not in support),
            cube_qpos=None if cube_joint is None else int(model.jnt_qposadr[cube_joint]),
            table_geom=table,
            floor_geom=floor,
            cube_geom=_optional_id(model, geom, CUBE_GEOM),
        )

    def collision_groups(self, model: mujoco.MjModel) -> CollisionGroups:
        """The collision definition of this scene (:mod:`lynxsim.sim.collision`)."""
        mask = np.zeros(model.ngeom, dtype=bool)
        robot, payload, support = mask.copy(), mask.copy(), mask.copy()
        robot[list(self.arm_collision_geoms)] = True
        if self.cube_geom is not None:
            payload[self.cube_geom] = True
        support[[g for g in (self.table_geom, self.floor_geom) if g is not None]] = True
        obstacles = np.asarray(self.obstacle_geoms, dtype=np.intp)
        return CollisionGroups(
            robot=robot,
            payload=payload,
            support=support,
            obstacle_geoms=obstacles,
            obstacle_names=tuple(model.geom(g).name for g in self.obstacle_geoms),
        )

    def binding(self, model: mujoco.MjModel) -> RobotBinding:
        """What a playback drives and watches in this scene (or the robot alone)."""
        return RobotBinding(
            actuator_ids=np.asarray(self.arm_actuators, dtype=np.intp),
            qpos_adr=np.asarray(self.arm_qpos, dtype=np.intp),
            tool_site_id=self.tool_site,
            groups=self.collision_groups(model),
            gripper_actuator_id=self.gripper_actuator,
        )
