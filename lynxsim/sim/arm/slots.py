"""Obstacle slots: obstacles placed, moved and resized at run time, without recompiling.

An environment that draws new obstacles at every reset cannot recompile its
model (ids, renderer and checkers hold it). Instead the scene is compiled with
``per_shape`` spare geoms of each obstacle shape, the *slots*, and
:meth:`ObstacleSlots.place` writes an obstacle's geom (:func:`obstacle_geom`,
the one definition the compiled scenes use too) into a slot of its shape;
unused slots are parked 5 m under the floor, invisible.

What makes this exact, checked against compiled scenes in the tests:

* the slots are compiled covering the whole region obstacles may stand in, so
  the world body's bounding-volume tree (built once, at compile time, from
  those sizes) always contains them: MuJoCo's midphase never skips a placed
  slot;
* a placed slot gets the bounding box and radius (``geom_aabb``,
  ``geom_rbound``) the compiler would give it, and ``geom_sameframe`` "none",
  so that the kinematics read its position and orientation from the model.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field

import mujoco

from lynxsim.errors import InvalidInputError
from lynxsim.scene import Box, Cylinder, Obstacle, Sphere
from lynxsim.sim.arm.model import OBSTACLE_CLASS, obstacle_geom

__all__ = [
    "PARK_POSITION_M",
    "SLOT_SHAPES",
    "ObstacleSlots",
    "add_obstacle_slots",
    "primitive_bounds",
    "slot_name",
]

SLOT_SHAPES: tuple[type[Obstacle], ...] = (Cylinder, Box, Sphere)
"""The shapes a slot can hold, in the order slots are added."""
PARK_POSITION_M = (0.0, 0.0, -5.0)
"""Where unused slots wait [m]: under the floor, out of every camera and reach."""
_REGION_CENTRE_M = (0.0, 0.0, 0.25)
"""Centre of the region obstacles may occupy [m] (the arm's reach over the table)."""
_REGION_HALF_M = (0.7, 0.7, 0.6)
"""Half extents of that region [m]; a slot compiled this large bounds any obstacle in it."""
_GEOM_TYPE = {
    Cylinder: mujoco.mjtGeom.mjGEOM_CYLINDER,
    Box: mujoco.mjtGeom.mjGEOM_BOX,
    Sphere: mujoco.mjtGeom.mjGEOM_SPHERE,
}
_SAMEFRAME_NONE = 0
"""``mjtSameFrame`` "none": the geom's own position and orientation count."""


def slot_name(shape: type[Obstacle], index: int) -> str:
    """Name of slot ``index`` (from 1) of a shape, e.g. ``slot_cylinder1``."""
    return f"slot_{shape.__name__.lower()}{index}"


def add_obstacle_slots(spec: mujoco.MjSpec, per_shape: int) -> None:
    """Add ``per_shape`` slots of each shape to the world body of an arm scene spec.

    Args:
        spec: The scene's spec (:func:`~lynxsim.sim.arm.model.load_arm_spec`).
        per_shape: Slots per shape, >= 0.
    """
    hx, hy, hz = _REGION_HALF_M
    sizes = {
        Cylinder: [math.hypot(hx, hy), hz, 0.0],
        Box: [hx, hy, hz],
        Sphere: [math.sqrt(hx * hx + hy * hy + hz * hz), 0.0, 0.0],
    }
    default = spec.find_default(OBSTACLE_CLASS)
    for shape in SLOT_SHAPES:
        for i in range(per_shape):
            spec.worldbody.add_geom(
                default,
                name=slot_name(shape, i + 1),
                type=_GEOM_TYPE[shape],
                size=sizes[shape],
                pos=list(_REGION_CENTRE_M),
            )


def primitive_bounds(geom_type: int, size: tuple[float, float, float]) -> tuple[list[float], float]:
    """Local bounding-box half extents and bounding radius of a primitive, as MuJoCo's."""
    a, b, c = size
    if geom_type == int(mujoco.mjtGeom.mjGEOM_SPHERE):
        return [a, a, a], a
    if geom_type == int(mujoco.mjtGeom.mjGEOM_CYLINDER):
        return [a, a, b], math.hypot(a, b)
    return [a, b, c], math.sqrt(a * a + b * b + c * c)


@dataclass(frozen=True)
class ObstacleSlots:
    """The slots of a compiled model, and where obstacles go.

    Attributes:
        model: The model (edited in place by :meth:`place`).
        geoms: Slot geom ids of each shape, in slot order.
        material: Material id of the slots (restored when a slot is used).
        rgba: Compiled colour of the slots (restored when a slot is used).
        sizes: Compiled ``geom_size``, ``geom_aabb`` and ``geom_rbound`` of every
            slot, by geom id (restored when a slot is parked, so that a parked
            slot does not keep the last obstacle's size).
    """

    model: mujoco.MjModel
    geoms: dict[type[Obstacle], tuple[int, ...]]
    material: int
    rgba: tuple[float, float, float, float]
    sizes: dict[int, tuple[tuple[float, ...], tuple[float, ...], float]] = field(
        default_factory=dict
    )

    @classmethod
    def from_model(cls, model: mujoco.MjModel) -> ObstacleSlots:
        """Find the slots of a model built with :func:`add_obstacle_slots`."""
        geoms: dict[type[Obstacle], tuple[int, ...]] = {}
        for shape in SLOT_SHAPES:
            ids: list[int] = []
            while True:
                name = slot_name(shape, len(ids) + 1)
                g = int(mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_GEOM, name))
                if g < 0:
                    break
                ids.append(g)
            geoms[shape] = tuple(ids)
        first = next((ids[0] for ids in geoms.values() if ids), None)
        if first is None:
            return cls(model, geoms, -1, (0.0, 0.0, 0.0, 0.0))
        red, green, blue, alpha = (float(v) for v in model.geom_rgba[first])
        sizes = {
            g: (
                tuple(model.geom_size[g].tolist()),
                tuple(model.geom_aabb[g].tolist()),
                float(model.geom_rbound[g]),
            )
            for ids in geoms.values()
            for g in ids
        }
        return cls(model, geoms, int(model.geom_matid[first]), (red, green, blue, alpha), sizes)

    @property
    def per_shape(self) -> int:
        """Slots of each shape."""
        return min(len(ids) for ids in self.geoms.values())

    def place(self, obstacles: Sequence[Obstacle]) -> None:
        """Put obstacles into the slots (in order, per shape) and park the rest.

        Every :class:`mujoco.MjData` of the model sees them after its next
        kinematics (``mj_forward``, ``mj_kinematics``, ``mj_step``).

        Args:
            obstacles: At most :attr:`per_shape` of each shape.

        Raises:
            InvalidInputError: More obstacles of a shape than slots.
        """
        m = self.model
        used = dict.fromkeys(SLOT_SHAPES, 0)
        for obstacle in obstacles:
            shape = type(obstacle)
            slots = self.geoms[shape]
            if used[shape] >= len(slots):
                raise InvalidInputError(
                    f"{len(slots)} {shape.__name__.lower()} slot(s); obstacle {obstacle.name!r} "
                    "does not fit"
                )
            g = slots[used[shape]]
            used[shape] += 1
            geom = obstacle_geom(obstacle)
            half, radius = primitive_bounds(geom.type, geom.size)
            m.geom_size[g] = geom.size
            m.geom_pos[g] = geom.pos
            m.geom_quat[g] = geom.quat
            m.geom_aabb[g] = [0.0, 0.0, 0.0, *half]
            m.geom_rbound[g] = radius
            m.geom_sameframe[g] = _SAMEFRAME_NONE
            m.geom_matid[g] = self.material
            m.geom_rgba[g] = self.rgba
        for shape, slots in self.geoms.items():
            for g in slots[used[shape] :]:
                if g in self.sizes:
                    size, aabb, rbound = self.sizes[g]
                    m.geom_size[g] = size
                    m.geom_aabb[g] = aabb
                    m.geom_rbound[g] = rbound
                m.geom_pos[g] = PARK_POSITION_M
                m.geom_quat[g] = (1.0, 0.0, 0.0, 0.0)
                m.geom_matid[g] = -1
                m.geom_rgba[g] = (0.0, 0.0, 0.0, 0.0)
                m.geom_sameframe[g] = _SAMEFRAME_NONE
