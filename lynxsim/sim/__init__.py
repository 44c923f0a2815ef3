"""Simulation layer: the only part of lynxsim that imports MuJoCo.

Importing this package defaults ``MUJOCO_GL`` to ``egl`` when no display is
present (:func:`lynxsim.sim.gl.default_gl_backend`); MuJoCo reads it once, when
``mujoco`` is first imported, so import :mod:`lynxsim.sim` before ``mujoco``.
"""

from lynxsim.sim.gl import default_gl_backend

default_gl_backend()

from lynxsim.sim.scene import (  # noqa: E402  (after the GL backend is chosen)
    ARM_ACTUATORS,
    ARM_JOINTS,
    ARM_ROOT_BODY,
    ARM_XML,
    COLLISION_GROUP,
    CUBE_BODY,
    CUBE_GEOM,
    FINGER_JOINTS,
    FLOOR_GEOM,
    FRAME_SITES,
    GRIPPER_ACTUATOR,
    GRIPPER_TENDON,
    HOME_KEY,
    OBSTACLE_GEOM,
    REPORT_OBSTACLE,
    SCENE_XML,
    TABLE_GEOM,
    TOOL_SITE,
    VISUAL_GROUP,
    ObstacleSpec,
    SceneIds,
    load_arm_model,
    load_arm_scene,
    load_arm_spec,
    table_top_z,
)

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
