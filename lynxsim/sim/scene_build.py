"""Putting a :class:`~lynxsim.scene.Scene` into any robot's MuJoCo scene: table, obstacles, cube.

A robot that stands in the table scene ships an MJCF scene (its robot, lights,
cameras) with these documented names, and :func:`build_scene` edits its parsed
:class:`mujoco.MjSpec` (never the XML text):

* a geom :data:`TABLE_GEOM` (``"table"``, a box): sized and placed as the scene's table;
* a default class :data:`OBSTACLE_CLASS` (``"obstacle"``): one named world geom of
  that class is added per obstacle of the scene;
* optionally a body :data:`CUBE_BODY` (``"cube"``) with a free joint and a box geom
  :data:`CUBE_GEOM` (``"cube"``): placed, sized and weighed as the scene's cube, or
  deleted for a scene without one;
* optionally a plane :data:`FLOOR_GEOM` (``"floor"``): support, as the table.

The collision groups of such a scene (:func:`lynxsim.sim.joint_robot.scene_groups`)
read the same names.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import mujoco

from lynxsim.errors import InvalidInputError
from lynxsim.scene import Box, Cylinder, Obstacle, Scene

__all__ = [
    "CUBE_BODY",
    "CUBE_GEOM",
    "FLOOR_GEOM",
    "OBSTACLE_CLASS",
    "TABLE_GEOM",
    "ObstacleGeom",
    "build_scene",
    "obstacle_geom",
    "table_top_z",
]

OBSTACLE_CLASS = "obstacle"
"""Default class of the obstacle geoms (material, contacts)."""
TABLE_GEOM = "table"
"""The table top, a box geom of the world body."""
FLOOR_GEOM = "floor"
"""The floor, a plane (optional)."""
CUBE_BODY = "cube"
"""The cube's body, with a free joint of the same name (optional)."""
CUBE_GEOM = "cube"
"""The cube's box geom."""


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


def _add_obstacle(spec: mujoco.MjSpec, obstacle: Obstacle, owner: str) -> None:
    if spec.geom(obstacle.name) is not None or spec.body(obstacle.name) is not None:
        raise InvalidInputError(
            f"obstacle name {obstacle.name!r} is taken by a part of the {owner}'s scene; rename it"
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


def build_scene(spec: mujoco.MjSpec, scene: Scene, *, owner: str = "robot") -> mujoco.MjSpec:
    """Build a scene's table, obstacles and cube into a robot's parsed scene, in place.

    Args:
        spec: The robot's scene, parsed (its table geom, obstacle class and
            optional cube named as this module says).
        scene: Obstacles, table and cube.
        owner: Names the robot in messages (``"arm"``: "the arm's scene").

    Returns:
        ``spec``, edited; ``spec.compile()`` gives the model.

    Raises:
        InvalidInputError: ``scene`` is not a Scene, the spec lacks the table or
            the obstacle class, the scene has a cube the spec has no body for,
            or an obstacle's name is already a geom or body of the spec.
    """
    if not isinstance(scene, Scene):
        raise InvalidInputError(f"scene must be a lynxsim.scene.Scene, got {scene!r}")
    table = spec.geom(TABLE_GEOM)
    if table is None or spec.find_default(OBSTACLE_CLASS) is None:
        raise InvalidInputError(
            f"the {owner}'s scene needs a geom {TABLE_GEOM!r} and a default class "
            f"{OBSTACLE_CLASS!r} to stand in the table scene"
        )
    t = scene.table
    table.size = [0.5 * t.size[0], 0.5 * t.size[1], 0.5 * t.thickness]
    table.pos = [t.center[0], t.center[1], t.top_z - 0.5 * t.thickness]
    for obstacle in scene.obstacles:
        _add_obstacle(spec, obstacle, owner)
    body = spec.body(CUBE_BODY)
    if scene.cube is None:
        if body is not None:
            spec.delete(body)
    elif body is None:
        raise InvalidInputError(
            f"the {owner}'s scene has no body {CUBE_BODY!r}, and the task's scene has a cube"
        )
    else:
        c = scene.cube
        body.pos = list(c.position)
        body.quat = [math.cos(0.5 * c.yaw), 0.0, 0.0, math.sin(0.5 * c.yaw)]
        geom = spec.geom(CUBE_GEOM)
        geom.size = [0.5 * c.size] * 3
        geom.mass = c.mass
        geom.friction = [c.friction, geom.friction[1], geom.friction[2]]
    return spec
