"""Readers of a task's scene: its obstacles and its cube, put on the table."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from lynxsim.errors import InvalidInputError
from lynxsim.scene import (
    MAX_CUBE_MASS_KG,
    MAX_FRICTION,
    MIN_CUBE_MASS_KG,
    REPORT_CUBE,
    TABLE,
    Box,
    Cube,
    Cylinder,
    Obstacle,
    Scene,
    Sphere,
)
from lynxsim.tasks.reader import FieldReader, show

__all__ = ["read_scene"]

_SHAPE_KEYS: dict[str, tuple[str, ...]] = {
    "cylinder": ("name", "shape", "position_mm", "radius_mm", "height_mm"),
    "box": ("name", "shape", "position_mm", "size_mm", "yaw_deg"),
    "sphere": ("name", "shape", "position_mm", "radius_mm"),
}
_OBSTACLE_KEYS = tuple(dict.fromkeys(k for keys in _SHAPE_KEYS.values() for k in keys))
_CUBE_KEYS = ("position_mm", "size_mm", "yaw_deg", "mass_kg", "friction")


def _m(mm: float) -> float:
    """Millimetres to metres, correctly rounded (150 mm is 0.15 m exactly as a float)."""
    return mm / 1000.0


def _standing(
    r: FieldReader, field: str, position_mm: tuple[float, float, float], height_mm: float
) -> tuple[tuple[float, float, float], float]:
    """Bottom-face centre [m] and height [m] of a cylinder or box, put on the table.

    A bottom face between the table top and the base plane moves down to the
    table top; the top stays where the file puts it.
    """
    x, y, z = (_m(v) for v in position_mm)
    height = _m(height_mm)
    if z < TABLE.top_z:
        raise r.fail(
            f"{field}.position_mm[2]",
            f"the bottom face at z = {position_mm[2]:g} mm would sink into the table "
            f"(its top is at z = {TABLE.top_z * 1e3:g} mm)",
        )
    if z <= 0.0 and z != TABLE.top_z:
        height = (z + height) - TABLE.top_z
        z = TABLE.top_z
    return (x, y, z), height


def _obstacle(r: FieldReader, item: object, field: str) -> Obstacle:
    raw = r.table(item, field, _OBSTACLE_KEYS)
    shape = r.string(r.required(raw, "shape", f"{field}.shape"), f"{field}.shape")
    if shape not in _SHAPE_KEYS:
        raise r.fail(
            f"{field}.shape",
            f"unknown shape {show(shape)}; expected one of: {', '.join(_SHAPE_KEYS)}",
        )
    keys = _SHAPE_KEYS[shape]
    foreign = [k for k in raw if k not in keys]
    if foreign:
        raise r.fail(
            f"{field}.{foreign[0]}", f"not a key of a {shape}; a {shape} takes: {', '.join(keys)}"
        )
    name = r.name(r.required(raw, "name", f"{field}.name"), f"{field}.name")
    position_mm = r.position_mm(
        r.required(raw, "position_mm", f"{field}.position_mm"), f"{field}.position_mm"
    )

    def size(key: str) -> float:
        return r.size_mm(r.required(raw, key, f"{field}.{key}"), f"{field}.{key}")

    try:
        if shape == "cylinder":
            radius, height_mm = size("radius_mm"), size("height_mm")
            position, height = _standing(r, field, position_mm, height_mm)
            return Cylinder(name, position, _m(radius), height)
        if shape == "box":
            raw_size = r.required(raw, "size_mm", f"{field}.size_mm")
            if not isinstance(raw_size, list) or len(raw_size) != 3:
                raise r.fail(
                    f"{field}.size_mm", f"must be a list of 3 numbers, got {show(raw_size)}"
                )
            sx, sy, sz = (r.size_mm(v, f"{field}.size_mm[{i}]") for i, v in enumerate(raw_size))
            yaw = r.angle_deg(raw.get("yaw_deg", 0.0), f"{field}.yaw_deg")
            position, height = _standing(r, field, position_mm, sz)
            return Box(name, position, (_m(sx), _m(sy), height), yaw)
        radius = size("radius_mm")
        x, y, z = (_m(v) for v in position_mm)
        if z - _m(radius) < TABLE.top_z:
            raise r.fail(
                f"{field}.position_mm[2]",
                f"a sphere of radius {radius:g} mm centred at z = {position_mm[2]:g} mm "
                f"would reach into the table (its top is at z = {TABLE.top_z * 1e3:g} mm)",
            )
        return Sphere(name, (x, y, z), _m(radius))
    except InvalidInputError as exc:  # a value the checks above let through
        raise r.fail(field, str(exc)) from None


def _cube(r: FieldReader, item: object) -> Cube:
    """The ``[cube]`` table; a key left out keeps the report's cube's value."""
    raw = r.table(item, "cube", _CUBE_KEYS)
    position = REPORT_CUBE.position
    if "position_mm" in raw:
        x, y, z = r.position_mm(raw["position_mm"], "cube.position_mm")
        position = (_m(x), _m(y), _m(z))
    size = REPORT_CUBE.size
    if "size_mm" in raw:
        size = _m(r.size_mm(raw["size_mm"], "cube.size_mm"))
    yaw = REPORT_CUBE.yaw
    if "yaw_deg" in raw:
        yaw = r.angle_deg(raw["yaw_deg"], "cube.yaw_deg")
    mass = r.positive(raw.get("mass_kg", REPORT_CUBE.mass), "cube.mass_kg")
    if not MIN_CUBE_MASS_KG <= mass <= MAX_CUBE_MASS_KG:
        raise r.fail(
            "cube.mass_kg",
            f"must lie within {MIN_CUBE_MASS_KG:g}..{MAX_CUBE_MASS_KG:g} kg, got {mass!r}",
        )
    friction = r.positive(raw.get("friction", REPORT_CUBE.friction), "cube.friction")
    if friction > MAX_FRICTION:
        raise r.fail("cube.friction", f"must be at most {MAX_FRICTION:g}, got {friction!r}")
    if position[2] - size / 2 < TABLE.top_z:
        raise r.fail(
            "cube.position_mm[2]" if "position_mm" in raw else "cube.size_mm",
            f"a {size * 1e3:g} mm cube centred at z = {position[2] * 1e3:g} mm would reach "
            f"into the table (its top is at z = {TABLE.top_z * 1e3:g} mm)",
        )
    try:
        return Cube(position, size, yaw, mass, friction)
    except InvalidInputError as exc:  # a value the checks above let through
        raise r.fail("cube", str(exc)) from None


def read_scene(r: FieldReader, top: Mapping[str, Any]) -> Scene:
    """The scene of an arm task: its obstacles and cube."""
    cube = _cube(r, top["cube"]) if "cube" in top else REPORT_CUBE
    raw = top.get("obstacles", [])
    if not isinstance(raw, list):
        raise r.fail("obstacles", "must be an array of [[obstacles]] tables")
    obstacles: list[Obstacle] = []
    for i, item in enumerate(raw):
        field = f"obstacles[{i}]"
        obstacle = _obstacle(r, item, field)
        if any(o.name == obstacle.name for o in obstacles):
            raise r.fail(f"{field}.name", f"duplicate obstacle name {show(obstacle.name)}")
        try:  # does it enclose the base or the cube's start?
            Scene((obstacle,), TABLE, cube)
        except InvalidInputError as exc:
            raise r.fail(field, str(exc)) from None
        obstacles.append(obstacle)
    try:
        return Scene(tuple(obstacles), TABLE, cube)
    except InvalidInputError as exc:  # checked obstacle by obstacle above
        raise r.fail("obstacles", str(exc)) from None
