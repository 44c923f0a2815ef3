"""A joint robot in the table scene, by names: its ids, collision groups, binding and model.

A robot whose motions are joint trajectories names, in its MJCF scene, a root
body (its tree is the robot), its joints, their position actuators, its tool
site and, optionally, the geom group of its collision geoms and a gripper
actuator (:class:`JointRobotNames`); the table scene's parts carry the names of
:mod:`lynxsim.sim.scene_build`. From these alone come:

* :class:`TableParts`: the table, floor, cube and obstacles of a compiled scene;
* :class:`JointRobotIds`: the robot's ids, its collision groups (robot: the
  colliding geoms of the root's tree; payload: the cube; support: table and
  floor; obstacles: every other colliding world geom, in the scene's order) and
  its playback binding (:class:`~lynxsim.sim.binding.RobotBinding`);
* :func:`load_joint_scene`: the robot's scene with a :class:`~lynxsim.scene.Scene`
  built in, compiled with the recording sensors of its playback.
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from dataclasses import dataclass

import mujoco
import numpy as np

from lynxsim.errors import InvalidInputError
from lynxsim.scene import Scene
from lynxsim.sim.binding import RobotBinding, name_to_id
from lynxsim.sim.collision import CollisionGroups
from lynxsim.sim.scene_build import CUBE_BODY, CUBE_GEOM, FLOOR_GEOM, TABLE_GEOM, build_scene
from lynxsim.sim.stepping.sensors import add_recording_sensors

__all__ = [
    "JointRobotIds",
    "JointRobotNames",
    "TableParts",
    "load_joint_scene",
    "optional_id",
    "robot_geoms",
]


def optional_id(model: mujoco.MjModel, kind: mujoco.mjtObj, name: str) -> int | None:
    """Id of a named element, or None if the model has none."""
    index = int(mujoco.mj_name2id(model, kind, name))
    return None if index < 0 else index


def robot_geoms(model: mujoco.MjModel, root: int, group: int | None = None) -> tuple[int, ...]:
    """Collision geoms of the tree of body ``root`` (its welded parents' tree included).

    Args:
        model: The model.
        root: A body of the robot (its root).
        group: Only geoms of this geom group count; None: every geom that can
            collide (``contype`` or ``conaffinity`` set).
    """
    tree = model.body_rootid[root]
    colliding = (np.asarray(model.geom_contype) != 0) | (np.asarray(model.geom_conaffinity) != 0)
    return tuple(
        g
        for g in range(model.ngeom)
        if (colliding[g] if group is None else model.geom_group[g] == group)
        and model.body_rootid[model.geom_bodyid[g]] == tree
    )


@dataclass(frozen=True)
class TableParts:
    """The table scene's parts in a compiled model (a robot-only model has none).

    Attributes:
        table_geom: The table top, or None.
        floor_geom: The floor, or None.
        cube_geom: The cube, or None.
        cube_qpos: ``qpos`` address of the cube's free joint, or None.
        obstacle_geoms: Every colliding geom of the world body other than the table
            and the floor, in the scene's order.
    """

    table_geom: int | None
    floor_geom: int | None
    cube_geom: int | None
    cube_qpos: int | None
    obstacle_geoms: tuple[int, ...]

    @classmethod
    def from_model(cls, model: mujoco.MjModel) -> TableParts:
        """Find the parts by their names (:mod:`lynxsim.sim.scene_build`)."""
        geom = mujoco.mjtObj.mjOBJ_GEOM
        table = optional_id(model, geom, TABLE_GEOM)
        floor = optional_id(model, geom, FLOOR_GEOM)
        support = {table, floor}
        colliding = (np.asarray(model.geom_contype) != 0) | (
            np.asarray(model.geom_conaffinity) != 0
        )
        world = set(np.flatnonzero((np.asarray(model.geom_bodyid) == 0) & colliding).tolist())
        cube_joint = optional_id(model, mujoco.mjtObj.mjOBJ_JOINT, CUBE_BODY)
        return cls(
            table_geom=table,
            floor_geom=floor,
            cube_geom=optional_id(model, geom, CUBE_GEOM),
            cube_qpos=None if cube_joint is None else int(model.jnt_qposadr[cube_joint]),
            obstacle_geoms=tuple(g for g in range(model.ngeom) if g in world and g not in support),
        )

    def groups(self, model: mujoco.MjModel, robot: Sequence[int]) -> CollisionGroups:
        """The collision definition (:mod:`~lynxsim.sim.collision`), ``robot`` its geoms."""
        mask = np.zeros(model.ngeom, dtype=bool)
        robot_mask, payload, support = mask.copy(), mask.copy(), mask.copy()
        robot_mask[list(robot)] = True
        if self.cube_geom is not None:
            payload[self.cube_geom] = True
        support[[g for g in (self.table_geom, self.floor_geom) if g is not None]] = True
        return CollisionGroups(
            robot=robot_mask,
            payload=payload,
            support=support,
            obstacle_geoms=np.asarray(self.obstacle_geoms, dtype=np.intp),
            obstacle_names=tuple(model.geom(g).name for g in self.obstacle_geoms),
        )


@dataclass(frozen=True)
class JointRobotNames:
    """What a joint robot's MJCF scene names.

    Attributes:
        root_body: Its root body (its tree, welded base included, is the robot).
        joints: Its driven joints, in the order of its joint vectors.
        tool_site: The site whose position is its tool point.
        actuators: The position actuator of each joint (None: named as the joints).
        collision_group: Only geoms of this geom group are the robot's (None:
            every colliding geom of its tree).
        gripper_actuator: Its gripper's actuator, or None.

    Raises:
        InvalidInputError: Empty or mismatched names.
    """

    root_body: str
    joints: tuple[str, ...]
    tool_site: str
    actuators: tuple[str, ...] | None = None
    collision_group: int | None = None
    gripper_actuator: str | None = None

    def __post_init__(self) -> None:
        names = [self.root_body, self.tool_site, *self.joints, *self.actuator_names]
        if not self.joints or not all(isinstance(n, str) and n for n in names):
            raise InvalidInputError(f"a joint robot's names must be non-empty strings: {self!r}")
        if len(self.actuator_names) != len(self.joints):
            raise InvalidInputError(
                f"one actuator per joint: {len(self.joints)} joints, "
                f"{len(self.actuator_names)} actuators"
            )

    @property
    def actuator_names(self) -> tuple[str, ...]:
        """The actuators, one per joint."""
        return self.joints if self.actuators is None else self.actuators


@dataclass(frozen=True)
class JointRobotIds:
    """A joint robot's ids in a compiled scene.

    Attributes:
        qpos: ``qpos`` addresses of its joints, (n,).
        dofs: Their ``qvel`` addresses, (n,).
        actuators: Their actuators, (n,).
        tool_site: The tool site.
        gripper_actuator: The gripper's actuator, or None.
        robot_geoms: Its collision geoms.
        table: The table scene's parts.
    """

    qpos: tuple[int, ...]
    dofs: tuple[int, ...]
    actuators: tuple[int, ...]
    tool_site: int
    gripper_actuator: int | None
    robot_geoms: tuple[int, ...]
    table: TableParts

    @classmethod
    def from_model(cls, model: mujoco.MjModel, names: JointRobotNames) -> JointRobotIds:
        """Resolve the names in a compiled scene.

        Raises:
            InvalidInputError: An element is missing (names it).
        """
        obj = mujoco.mjtObj
        joints = [name_to_id(model, obj.mjOBJ_JOINT, n) for n in names.joints]
        root = name_to_id(model, obj.mjOBJ_BODY, names.root_body)
        gripper = names.gripper_actuator
        return cls(
            qpos=tuple(int(model.jnt_qposadr[j]) for j in joints),
            dofs=tuple(int(model.jnt_dofadr[j]) for j in joints),
            actuators=tuple(name_to_id(model, obj.mjOBJ_ACTUATOR, n) for n in names.actuator_names),
            tool_site=name_to_id(model, obj.mjOBJ_SITE, names.tool_site),
            gripper_actuator=None
            if gripper is None
            else name_to_id(model, obj.mjOBJ_ACTUATOR, gripper),
            robot_geoms=robot_geoms(model, root, names.collision_group),
            table=TableParts.from_model(model),
        )

    def collision_groups(self, model: mujoco.MjModel) -> CollisionGroups:
        """The collision definition of the scene (:mod:`lynxsim.sim.collision`)."""
        return self.table.groups(model, self.robot_geoms)

    def binding(self, model: mujoco.MjModel) -> RobotBinding:
        """What a playback drives and watches in the scene."""
        return RobotBinding(
            actuator_ids=np.asarray(self.actuators, dtype=np.intp),
            qpos_adr=np.asarray(self.qpos, dtype=np.intp),
            tool_site_id=self.tool_site,
            groups=self.collision_groups(model),
            gripper_actuator_id=self.gripper_actuator,
        )


def load_joint_scene(
    scene_xml: str | os.PathLike[str], names: JointRobotNames, scene: Scene, *, owner: str
) -> mujoco.MjModel:
    """A joint robot's MJCF scene with ``scene`` built in, compiled with its recording sensors.

    Args:
        scene_xml: The robot's scene file.
        names: What it names.
        scene: Obstacles, table and cube (:func:`lynxsim.sim.scene_build.build_scene`).
        owner: Names the robot in messages.

    Returns:
        The compiled model, with the sensors that let a playback record natively
        (:func:`lynxsim.sim.stepping.sensors.add_recording_sensors`).

    Raises:
        InvalidInputError: See :func:`~lynxsim.sim.scene_build.build_scene`; a
            named element is missing.
    """
    if not isinstance(scene, Scene):
        raise InvalidInputError(f"scene must be a lynxsim.scene.Scene, got {scene!r}")
    spec = build_scene(mujoco.MjSpec.from_file(str(scene_xml)), scene, owner=owner)
    plain = spec.compile()
    return add_recording_sensors(spec, plain, JointRobotIds.from_model(plain, names).binding(plain))
