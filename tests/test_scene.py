"""The scene model: obstacles, table and cube validate, contain points, and combine."""

from __future__ import annotations

import math
import re
import subprocess
import sys

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import lynxsim.scene
from lynxsim.errors import InvalidInputError
from lynxsim.scene import (
    REPORT_CUBE,
    REPORT_CYLINDER,
    REPORT_SCENE,
    TABLE,
    Box,
    Cube,
    Cylinder,
    Scene,
    Sphere,
    Table,
)

MM = 1e-3
"""One millimetre [m]."""
MARGIN_M = 1e-9
"""Distance from a surface at which the property tests trust ``contains`` [m]."""

_BOTTOM = (0.2, -0.1, TABLE.top_z)
"""Bottom-face centre of the obstacles of these tests [m]."""


def test_every_name_in_all_resolves():
    assert all(hasattr(lynxsim.scene, name) for name in lynxsim.scene.__all__)


def test_scene_never_imports_mujoco():
    code = "import sys, lynxsim.scene; sys.exit('mujoco' in sys.modules)"
    assert subprocess.run([sys.executable, "-c", code], check=False).returncode == 0


def test_report_values():
    assert TABLE.top_z == -12.5 * MM
    assert Cube((0.0, 0.3, 0.0), 0.025, 0.0, 0.01, 1.0) == REPORT_CUBE
    assert REPORT_CUBE.position[2] - REPORT_CUBE.size / 2 == TABLE.top_z  # resting on the table
    c = REPORT_CYLINDER
    assert (c.name, c.position, c.radius) == ("cylinder", (0.15, 0.15, TABLE.top_z), 0.04)
    assert c.position[2] + c.height == pytest.approx(0.4, abs=1e-15)
    assert Scene((REPORT_CYLINDER,), TABLE, REPORT_CUBE) == REPORT_SCENE
    assert Scene() == Scene((), TABLE, REPORT_CUBE)
    assert (REPORT_CYLINDER.shape, Box("b", _BOTTOM, (1, 1, 1)).shape) == ("cylinder", "box")
    assert Sphere("s", (1.0, 1.0, 1.0), 0.1).shape == "sphere"


@pytest.mark.parametrize(
    ("make", "message"),
    [
        (
            lambda: Cylinder("c", _BOTTOM, 0.0, 0.4),
            r"radius must lie within 0.0001..10 m, got 0.0 m$",
        ),
        (lambda: Cylinder("c", _BOTTOM, 0.04, -0.1), "height must lie within 0.0001..10 m"),
        (lambda: Cylinder("c", _BOTTOM, 0.04, True), "height must be a number, got True"),
        (lambda: Cylinder("c", _BOTTOM, "1", 0.4), "radius must be a number"),
        (lambda: Cylinder("c", _BOTTOM, 10**400, 0.4), "radius must be finite"),
        (lambda: Cylinder("c", [0.1, 0.1, 0.0], 0.04, 0.4), "position must be a tuple of 3"),
        (lambda: Cylinder("c", (0.1, math.inf, 0.0), 0.04, 0.4), r"position\[1\] must be finite"),
        (lambda: Cylinder("", _BOTTOM, 0.04, 0.4), "name must be a non-empty printable"),
        (lambda: Cylinder("a\nb", _BOTTOM, 0.04, 0.4), "name must be a non-empty printable"),
        (lambda: Cylinder(3, _BOTTOM, 0.04, 0.4), "name must be a non-empty printable"),
        (lambda: Box("b", _BOTTOM, (0.1, 0.1)), "size must be a tuple of 3"),
        (lambda: Box("b", _BOTTOM, (0.1, 0.1, -0.1)), r"size\[2\] must lie within"),
        (lambda: Box("b", _BOTTOM, (0.1, 0.1, 0.1), math.inf), "yaw must be finite"),
        (lambda: Sphere("s", _BOTTOM, 0.0), "radius must lie within"),
        (lambda: Sphere("s", (0.1, 0.1, math.nan), 0.02), "finite"),
        (lambda: Table(top_z=math.nan), "top_z must be finite"),
        (lambda: Table(size=(0.7, 0.0)), "size_y must lie within"),
        (lambda: Table(thickness=-0.01), "thickness must lie within"),
        (lambda: Table(center=(0.1,)), "center must be a tuple of 2"),
        (lambda: Cube(size=0.0), r"size must lie within 0.0001..10 m, got 0.0 m$"),
        (lambda: Cube(mass=-1.0), r"mass must lie within 0.0001..100 kg, got -1.0 kg$"),
        (lambda: Cube(friction=0.0), r"friction must be positive, got 0.0$"),
        (lambda: Cube(yaw=math.nan), "yaw must be finite"),
        (lambda: Cube(position=(0.0, 0.3)), "position must be a tuple of 3"),
        (lambda: Cube(size=1e-5), "size must lie within 0.0001..10 m"),
        (lambda: Cube(mass=1e-15), "mass must lie within 0.0001..100 kg"),
        (lambda: Cube(mass=1e3), "mass must lie within"),
        (lambda: Cube(friction=11.0), "friction must lie within 0..10"),
        (lambda: Sphere("s", (0.0, 0.0, 2e300), 1e300), r"position\[2\] must lie within -10..10 m"),
        (lambda: Cylinder("c", (11.0, 0.0, 0.0), 0.04, 0.4), r"position\[0\] must lie within"),
        (lambda: Box("b", _BOTTOM, (0.1, 0.1, 0.1), 100.0), "yaw must lie within"),
        (lambda: Table(top_z=-20.0), "top_z must lie within"),
    ],
    ids=[
        "zero_radius",
        "negative_height",
        "bool_height",
        "string_radius",
        "huge_int_radius",
        "list_position",
        "infinite_coordinate",
        "empty_name",
        "unprintable_name",
        "int_name",
        "two_box_sizes",
        "flat_box",
        "infinite_yaw",
        "zero_sphere",
        "nan_sphere",
        "nan_table",
        "narrow_table",
        "thin_table",
        "table_centre_1d",
        "point_cube",
        "negative_mass",
        "no_friction",
        "nan_cube_yaw",
        "cube_2d",
        "dust_cube",
        "weightless_cube",
        "ton_cube",
        "sticky_cube",
        "huge_sphere",
        "far_cylinder",
        "many_turns_box",
        "deep_table",
    ],
)
def test_invalid_value_is_refused(make, message):
    with pytest.raises(InvalidInputError, match=message):
        make()


def test_cylinder_contains_points_from_its_bottom_to_its_top():
    c = Cylinder("c", (0.1, 0.2, 0.05), 0.04, 0.3)
    assert c.contains((0.1, 0.2, 0.05))  # bottom centre
    assert c.contains((0.1399, 0.2, 0.3499))  # just inside the top rim
    assert c.contains((0.1, 0.23, 0.2))
    assert not c.contains((0.1, 0.2, 0.049))  # under it
    assert not c.contains((0.1, 0.2, 0.351))  # over it
    assert not c.contains((0.13, 0.23, 0.2))  # beside it: 42 mm from the axis


def test_box_contains_points_in_its_own_turned_frame():
    turned = Box("b", (0.0, 0.0, 0.1), (0.2, 0.04, 0.1), yaw=math.pi / 2)
    assert turned.contains((0.0, 0.09, 0.15))  # along its x axis, now world y
    assert not turned.contains((0.09, 0.0, 0.15))  # along its y axis, now world x
    assert turned.contains((0.0, 0.0, 0.1))
    assert turned.contains((0.0, 0.0, 0.2))
    assert not turned.contains((0.0, 0.0, 0.0999))
    assert not turned.contains((0.0, 0.0, 0.2001))
    straight = Box("b", (0.0, 0.0, 0.1), (0.2, 0.04, 0.1))
    assert straight.contains((0.09, 0.0, 0.15))
    assert not straight.contains((0.0, 0.09, 0.15))


def test_sphere_contains_points_within_its_radius():
    s = Sphere("s", (0.2, 0.06, 0.3), 0.03)
    assert s.contains((0.2, 0.06, 0.3))
    assert s.contains((0.2, 0.06, 0.3299))
    assert s.contains((0.22, 0.08, 0.3))  # 28 mm away
    assert not s.contains((0.23, 0.08, 0.3))  # 36 mm away


_coordinate = st.floats(-1.0, 1.0)
_size = st.floats(0.001, 0.5)


@settings(max_examples=200, deadline=None)
@given(
    position=st.tuples(_coordinate, _coordinate, _coordinate),
    size=st.tuples(_size, _size, _size),
    yaw=st.floats(-10.0, 10.0),
    local=st.tuples(st.floats(-1.0, 1.0), st.floats(-1.0, 1.0), st.floats(-0.5, 1.5)),
)
def test_box_contains_exactly_the_points_within_its_extents(position, size, yaw, local):
    # A point given in the box's own frame (fractions of its half sizes, of its height).
    box = Box("b", position, size, yaw)
    u, v, w = local[0] * size[0] / 2, local[1] * size[1] / 2, local[2] * size[2]
    c, s = math.cos(yaw), math.sin(yaw)
    point = (position[0] + c * u - s * v, position[1] + s * u + c * v, position[2] + w)
    inside = abs(u) < size[0] / 2 and abs(v) < size[1] / 2 and 0.0 < w < size[2]
    gaps = (size[0] / 2 - abs(u), size[1] / 2 - abs(v), w, size[2] - w)
    if min(abs(g) for g in gaps) > MARGIN_M:
        assert box.contains(point) is inside


@settings(max_examples=200, deadline=None)
@given(
    position=st.tuples(_coordinate, _coordinate, _coordinate),
    radius=_size,
    height=_size,
    point=st.tuples(_coordinate, _coordinate, _coordinate),
)
def test_cylinder_and_sphere_contain_agrees_with_the_distance(position, radius, height, point):
    axis = math.hypot(point[0] - position[0], point[1] - position[1])
    above = point[2] - position[2]
    if min(abs(axis - radius), abs(above), abs(above - height)) > MARGIN_M:
        inside = axis < radius and 0.0 < above < height
        assert Cylinder("c", position, radius, height).contains(point) is inside
    centre = math.dist(point, position)
    if abs(centre - radius) > MARGIN_M:
        assert Sphere("s", position, radius).contains(point) is (centre < radius)


def test_scene_refuses_duplicate_names_across_shapes():
    twin = Box("cylinder", (0.2, -0.2, TABLE.top_z), (0.05, 0.05, 0.05))
    with pytest.raises(InvalidInputError, match="two obstacles are named 'cylinder'"):
        Scene((REPORT_CYLINDER, twin))


@pytest.mark.parametrize(
    ("scene", "message"),
    [
        (
            lambda: Scene((Box("b", (0.2, 0.0, -0.05), (0.1, 0.1, 0.1)),)),
            "obstacle 'b' reaches into the table: its bottom at z = -50 mm, "
            "the table top at -12.5 mm",
        ),
        (
            lambda: Scene((Sphere("s", (0.2, 0.0, 0.3), 0.35),)),
            "obstacle 's' reaches into the table: its bottom at z = -50 mm",
        ),
        (
            lambda: Scene(cube=Cube(position=(0.0, 0.3, -0.1))),
            "the cube reaches into the table: its bottom at z = -112.5 mm",
        ),
    ],
    ids=["box", "sphere", "cube"],
)
def test_scene_refuses_what_reaches_into_the_table(scene, message):
    """The one check of a scene, which task files, sweep files and code all pass."""
    with pytest.raises(InvalidInputError, match=re.escape(message)):
        scene()


@pytest.mark.parametrize(
    ("obstacle", "what"),
    [
        (Cylinder("c", (0.0, 0.0, TABLE.top_z), 0.05, 0.1), "robot's base"),
        (Box("b", (0.05, 0.0, TABLE.top_z), (0.2, 0.2, 0.1)), "robot's base"),
        (Sphere("s", (0.0, 0.0, 0.05), 0.06), "robot's base"),
        (Cylinder("c", (0.0, 0.3, TABLE.top_z), 0.02, 0.05), "cube's start"),
        (Box("b", (0.0, 0.3, TABLE.top_z), (0.1, 0.1, 0.1)), "cube's start"),
        (Sphere("s", (0.0, 0.31, 0.005), 0.015), "cube's start"),
    ],
    ids=["cylinder_base", "box_base", "sphere_base", "cylinder_cube", "box_cube", "sphere_cube"],
)
def test_scene_refuses_an_obstacle_enclosing_the_base_or_the_cube(obstacle, what):
    with pytest.raises(InvalidInputError, match=rf"obstacle '{obstacle.name}' encloses the {what}"):
        Scene((obstacle,))
    if what == "cube's start":  # without the cube, or with the cube elsewhere, it is fine
        assert Scene((obstacle,), cube=None).obstacles == (obstacle,)
        assert Scene((obstacle,), cube=Cube(position=(0.0, -0.3, 0.0))).cube is not None


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"obstacles": [REPORT_CYLINDER]}, "obstacles must be a tuple of Cylinder, Box or Sphere"),
        ({"obstacles": ("cylinder",)}, "obstacles must be a tuple of Cylinder, Box or Sphere"),
        ({"table": None}, "table must be a Table"),
        ({"cube": (0.0, 0.3, 0.0)}, "cube must be a Cube or None"),
    ],
    ids=["list", "strings", "no_table", "cube_tuple"],
)
def test_scene_refuses_parts_of_the_wrong_type(kwargs, message):
    with pytest.raises(InvalidInputError, match=message):
        Scene(**kwargs)


def test_scene_finds_obstacles_by_name_and_drops_obstacles_or_cube():
    ball = Sphere("ball", (0.2, 0.06, 0.3), 0.03)
    scene = Scene((REPORT_CYLINDER, ball))
    assert scene.obstacle("ball") is ball
    with pytest.raises(InvalidInputError, match=r"no obstacle 'box'; obstacles: cylinder, ball$"):
        scene.obstacle("box")
    with pytest.raises(InvalidInputError, match=r"obstacles: none$"):
        Scene().obstacle("ball")

    bare = scene.without_obstacles()
    assert (bare.obstacles, bare.table, bare.cube) == ((), scene.table, scene.cube)
    no_cube = scene.without_cube()
    assert (no_cube.obstacles, no_cube.table, no_cube.cube) == (scene.obstacles, TABLE, None)
    assert scene.without_cube().without_obstacles() == Scene((), TABLE, None)
    assert scene == Scene((REPORT_CYLINDER, ball))  # unchanged: scenes are immutable values
    with pytest.raises(AttributeError):
        scene.cube = None  # type: ignore[misc]
