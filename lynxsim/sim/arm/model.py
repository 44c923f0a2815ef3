"""The arm's MuJoCo scene: loading it, obstacle variants, and the ids of its parts.

The MJCF files in ``models/lynx_arm/`` are the model; this module only edits the
parsed :class:`mujoco.MjSpec` (never the XML text) to remove or move the obstacle
and to drop the cube, and resolves the names the rest of lynxsim refers to.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import mujoco

from lynxsim.arm import FRAME_NAMES, LYNX_ARM
from lynxsim.errors import InvalidInputError
from lynxsim.reproduce.arm_tables import OBSTACLE
from lynxsim.resources import model_path

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
    "OBSTACLE_GEOM",
    "REPORT_OBSTACLE",
    "SCENE_XML",
    "TABLE_GEOM",
    "TOOL_SITE",
    "VISUAL_GROUP",
    "ObstacleSpec",
    "SceneIds",
    "load_arm_model",
    "load_arm_scene",
    "load_arm_spec",
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
OBSTACLE_GEOM = "obstacle"
TABLE_GEOM = "table"
FLOOR_GEOM = "floor"
CUBE_BODY = "cube"
CUBE_GEOM = "cube"
HOME_KEY = "home"
VISUAL_GROUP = 2
"""Geom group of the visual geoms (MuJoCo Menagerie convention)."""
COLLISION_GROUP = 3
"""Geom group of the collision geoms (MuJoCo Menagerie convention)."""


@dataclass(frozen=True)
class ObstacleSpec:
    """A vertical cylinder standing on the table.

    The cylinder reaches from the table top up to ``top_z``.

    Attributes:
        center: (x, y) of its axis in the arm's base frame [m].
        radius: Radius [m], > 0.
        top_z: Height of its top face above the base plane z = 0 [m], > 0.
    """

    center: tuple[float, float]
    radius: float
    top_z: float

    def __post_init__(self) -> None:
        if len(self.center) != 2 or not all(
            math.isfinite(v) for v in (*self.center, self.radius, self.top_z)
        ):
            raise InvalidInputError(
                f"obstacle needs a finite (x, y) centre, radius and top_z, got {self!r}"
            )
        if self.radius <= 0.0:
            raise InvalidInputError(f"obstacle radius must be positive, got {self.radius} m")
        if self.top_z <= 0.0:
            raise InvalidInputError(
                f"obstacle top_z must be above the base plane z = 0, got {self.top_z} m"
            )


REPORT_OBSTACLE = ObstacleSpec(
    center=(OBSTACLE.center_mm[0] * 1e-3, OBSTACLE.center_mm[1] * 1e-3),
    radius=OBSTACLE.radius_mm * 1e-3,
    top_z=OBSTACLE.height_mm * 1e-3,
)
"""The report's obstacle: radius 40 mm, axis at (150, 150) mm, 400 mm tall."""


def table_top_z(spec: mujoco.MjSpec) -> float:
    """Height of the table top in the base frame [m] (negative: below z = 0).

    Raises:
        InvalidInputError: If the spec has no table geom.
    """
    table = spec.geom(TABLE_GEOM)
    if table is None:
        raise InvalidInputError(f"the spec has no geom named {TABLE_GEOM!r}")
    return float(table.pos[2] + table.size[2])


def load_arm_spec(
    obstacle: ObstacleSpec | None = REPORT_OBSTACLE, *, cube: bool = True
) -> mujoco.MjSpec:
    """Parse the scene and apply a variant, without compiling it.

    Args:
        obstacle: The cylinder obstacle, or None for a scene without one.
        cube: Whether the free cube at P1 stays in the scene.

    Returns:
        The edited spec; ``spec.compile()`` gives the model.
    """
    spec = mujoco.MjSpec.from_file(str(model_path(SCENE_XML)))
    geom = spec.geom(OBSTACLE_GEOM)
    if obstacle is None:
        spec.delete(geom)
    else:
        bottom = table_top_z(spec)  # below z = 0, so under any valid top_z
        half_height = 0.5 * (obstacle.top_z - bottom)
        geom.size = [obstacle.radius, half_height, 0.0]
        geom.pos = [obstacle.center[0], obstacle.center[1], bottom + half_height]
    if not cube:
        spec.delete(spec.body(CUBE_BODY))
    return spec


def load_arm_scene(
    obstacle: ObstacleSpec | None = REPORT_OBSTACLE, *, cube: bool = True
) -> mujoco.MjModel:
    """Compile the arm's scene.

    Args:
        obstacle: The cylinder obstacle, or None for a scene without one.
        cube: Whether the free cube at P1 stays in the scene.

    Returns:
        The compiled model (2 ms timestep, implicitfast).
    """
    return load_arm_spec(obstacle, cube=cube).compile()


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
        obstacle_geom: The obstacle, or None in a scene without one.
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
    obstacle_geom: int | None
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
            obstacle_geom=_optional_id(model, geom, OBSTACLE_GEOM),
            table_geom=_optional_id(model, geom, TABLE_GEOM),
            floor_geom=_optional_id(model, geom, FLOOR_GEOM),
            cube_geom=_optional_id(model, geom, CUBE_GEOM),
        )
