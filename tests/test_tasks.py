"""Task files: the shipped ones load, and every malformed field is named in one line."""

from __future__ import annotations

import math
import tempfile
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from lynxsim.arm.fk import FRAME_NAMES, frame_origins
from lynxsim.bounds import MAX_SEGMENT_S, MIN_SEGMENT_S
from lynxsim.errors import InvalidInputError, LynxsimError, TaskFileError
from lynxsim.poses import ArmPose, JointPose
from lynxsim.robots import get
from lynxsim.robots.arm import build_trajectory
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
)
from lynxsim.tasks import PlanarPose, Task, load_task
from lynxsim.traj import TrajectoryKind
from tools.fuzz_tasks import toml_value

TASKS = Path(__file__).resolve().parents[1] / "tasks"

ARM_TASK = """\
robot = "arm"

[trajectory]
type = "quintic"

[[poses]]
position_mm = [0.0, 300.0, 0.0]
pitch_deg = -90.0

[[poses]]
name = "home"
q_deg = [0.0, 90.0, -90.0, 0.0, 180.0]
"""

RRR_TASK = """\
name = "platform"
robot = "rrr"

[trajectory]
type = "line"
segment_duration_s = [1.0, 2.0]

[[poses]]
x_mm = 200.0
y_mm = 150.0
alpha_deg = 0.0

[[poses]]
x_mm = 200.0
y_mm = 150.0
alpha_deg = 30.0

[[poses]]
name = "far"
x_mm = 300.0
y_mm = 250.0
alpha_deg = -40.0
"""


@pytest.fixture
def task_file(tmp_path: Path) -> Callable[[str], Path]:
    """Writes a task text to ``task.toml`` in the test's folder; returns its path."""

    def write(text: str) -> Path:
        path = tmp_path / "task.toml"
        path.write_text(text, encoding="utf-8")
        return path

    return write


@pytest.fixture
def load_text(task_file: Callable[[str], Path]) -> Callable[[str], Task]:
    """Loads a task text through a file (``task.toml``)."""
    return lambda text: load_task(task_file(text))


def _refused(path: Path, field: str | None, problem: str) -> TaskFileError:
    """The error loading ``path`` raises: one line naming the file and ``field``, with ``problem``.

    ``field`` None: the file as a whole.
    """
    with pytest.raises(TaskFileError) as info:
        load_task(path)
    message = str(info.value)
    assert message.isprintable()
    shown = str(path) if str(path).isprintable() else repr(str(path))
    assert message.startswith(f"{shown}: {field}: " if field else f"{shown}: ")
    assert problem in message
    assert (info.value.path, info.value.field) == (str(path), field)
    return info.value


def test_pick_and_place_file_is_the_reports_table_4():
    task = load_task(TASKS / "pick_and_place.toml")
    assert (task.name, task.robot, task.trajectory) == (
        "pick_and_place",
        "arm",
        TrajectoryKind.QUINTIC,
    )
    assert task.durations == (1.0,) * 4
    assert task.stretch
    assert not task.pass_through
    assert [p.name for p in task.poses] == ["P1", "P2", "P3", "P4", "P5"]
    p3 = task.poses[2]
    assert isinstance(p3, ArmPose)
    assert p3.position == pytest.approx((0.25, 0.0, 0.3))  # metres inside
    assert p3.pitch == 0.0
    assert p3.roll is None
    assert task.source == TASKS / "pick_and_place.toml"


def test_obstacle_avoidance_file_has_the_reports_via_points():
    task = load_task(TASKS / "obstacle_avoidance.toml")
    assert task.trajectory is TrajectoryKind.LINE
    mm = [
        tuple(round(v * 1e3, 9) for v in p.position) for p in task.poses if isinstance(p, ArmPose)
    ]
    assert mm == [
        (0, 300, 0),
        (80, 250, 300),
        (80, 0, 300),
        (250, 0, 300),
        (90, -250, 300),
        (0, -300, 0),
    ]


def test_arm_poses_may_be_joints_and_defaults_apply(load_text):
    task = load_text(ARM_TASK)
    assert task.name == "task"
    assert task.durations is None
    assert not task.stretch
    first, home = task.poses
    assert isinstance(first, ArmPose)
    assert first.name == "P1"
    assert first.pitch == pytest.approx(-math.pi / 2)
    assert isinstance(home, JointPose)
    assert home.name == "home"
    assert home.q == pytest.approx((0.0, math.pi / 2, -math.pi / 2, 0.0, math.pi))


def test_rrr_tasks_load_platform_poses_in_si(load_text):
    task = load_text(RRR_TASK)
    assert task.robot == "rrr"
    assert task.durations == (1.0, 2.0)
    assert task.poses[2] == PlanarPose(0.3, 0.25, math.radians(-40.0), "far")


@pytest.mark.parametrize(
    ("old", "new", "field", "problem"),
    [
        (
            'robot = "arm"',
            'robot = "scara"',
            "robot",
            "unknown robot 'scara'; expected one of: arm, rrr",
        ),
        ('robot = "arm"\n', "", "robot", "missing"),
        ('type = "quintic"', 'type = "spline"', "trajectory.type", "unknown type 'spline'"),
        ('type = "quintic"', "", "trajectory.type", "missing"),
        (
            'type = "quintic"',
            'type = "quintic"\nstretch = 1',
            "trajectory.stretch",
            "must be true or false",
        ),
        (
            'type = "quintic"',
            'type = "quintic"\nsegment_duration_s = -1.0',
            "trajectory.segment_duration_s",
            "must be positive",
        ),
        (
            'type = "quintic"',
            'type = "quintic"\nsegment_duration_s = [1.0, 2.0]',
            "trajectory.segment_duration_s",
            "needs 1 durations (one per segment), got 2",
        ),
        ('type = "quintic"', 'type = "quintic"\nspeed = 2', "trajectory.speed", "unknown key"),
        ("pitch_deg = -90.0", 'pitch_deg = "down"', "poses[0].pitch_deg", "must be a number"),
        ("pitch_deg = -90.0", "pitch_deg = true", "poses[0].pitch_deg", "must be a number"),
        ("pitch_deg = -90.0", "pitch_deg = nan", "poses[0].pitch_deg", "must be finite"),
        ("pitch_deg = -90.0", "", "poses[0].pitch_deg", "missing"),
        (
            "position_mm = [0.0, 300.0, 0.0]",
            "position_mm = [0.0, 300.0]",
            "poses[0].position_mm",
            "must be a list of 3 numbers",
        ),
        (
            "position_mm = [0.0, 300.0, 0.0]",
            'position_mm = [0.0, "y", 0.0]',
            "poses[0].position_mm[1]",
            "must be a number",
        ),
        ("pitch_deg = -90.0", "pitch_deg = -90.0\npitch = 3", "poses[0].pitch", "unknown key"),
        (
            "pitch_deg = -90.0",
            "pitch_deg = -90.0\nq_deg = [0, 0, 0, 0, 0]",
            "poses[0].pitch_deg",
            "either q_deg or a tool pose",
        ),
        ('name = "home"', 'name = "P1"', "poses[1].name", "duplicate pose name 'P1'"),
        (
            "q_deg = [0.0, 90.0, -90.0, 0.0, 180.0]",
            "q_deg = [0.0, 90.0]",
            "poses[1].q_deg",
            "must be a list of 5 numbers",
        ),
    ],
    ids=lambda v: v if isinstance(v, str) and "." in v and " " not in v else None,
)
def test_malformed_field_is_named_in_one_line(task_file, old, new, field, problem):
    assert old in ARM_TASK
    _refused(task_file(ARM_TASK.replace(old, new, 1)), field, problem)


def test_one_pose_is_not_a_task(task_file):
    text = ARM_TASK[: ARM_TASK.index("[[poses]]\nname")]
    _refused(task_file(text), "poses", "must be an array of at least two")


def test_rrr_poses_need_their_platform_keys(task_file):
    path = task_file(RRR_TASK.replace("alpha_deg = 30.0\n", "", 1))
    error = _refused(path, "poses[1].alpha_deg", "missing")
    assert str(error) == f"{path}: poses[1].alpha_deg: missing"
    path = task_file(RRR_TASK.replace("alpha_deg = 30.0", "pitch_deg = 30.0", 1))
    error = _refused(path, "poses[1].pitch_deg", "unknown key")
    assert str(error) == (
        f"{path}: poses[1].pitch_deg: unknown key; expected one of: name, x_mm, y_mm, alpha_deg"
    )


def test_invalid_toml_names_the_file(task_file):
    path = task_file("robot = arm\n")
    with pytest.raises(TaskFileError, match=rf"^{path}: not valid TOML: .*line 1"):
        load_task(path)


def test_non_utf8_file_is_refused(tmp_path):
    path = tmp_path / "latin1.toml"
    path.write_bytes('name = "é"\n'.encode("latin-1"))
    with pytest.raises(TaskFileError, match="not UTF-8 text"):
        load_task(path)


# ---------------------------------------------------------------- scenes

MM = 1e-3
"""One millimetre [m]."""
SCENE_TOL_M = 1e-15
"""Agreement of a loaded scene value with its mm value in metres [m]."""
HIT_TIME_STEP_S = 0.005
"""Time step at which the three-obstacle task's path is checked [s]."""

SCENE_TASK = (
    ARM_TASK
    + """
[[obstacles]]
name = "pillar"
shape = "cylinder"
position_mm = [150.0, 150.0, 0.0]
radius_mm = 40.0
height_mm = 400.0

[[obstacles]]
name = "crate"
shape = "box"
position_mm = [150.0, -150.0, 0.0]
size_mm = [100.0, 60.0, 350.0]
yaw_deg = -45.0

[[obstacles]]
name = "ball"
shape = "sphere"
position_mm = [200.0, 60.0, 300.0]
radius_mm = 30.0

[cube]
position_mm = [0.0, 300.0, 0.0]
size_mm = 25.0
"""
)


def test_shipped_arm_tasks_list_the_reports_cylinder():
    for name in ("pick_and_place", "obstacle_avoidance"):
        task = load_task(TASKS / f"{name}.toml")
        assert task.scene == REPORT_SCENE, name
        assert task.scene.obstacles[0] == REPORT_CYLINDER  # exactly, -12.5 to 400 mm


def test_shipped_rrr_tasks_have_an_empty_scene():
    for name in ("rrr_closed_curve", "rrr_figure20_tour"):
        assert load_task(TASKS / f"{name}.toml").scene == Scene((), cube=None)


def test_three_obstacles_is_the_pick_and_place_among_three_shapes():
    task = load_task(TASKS / "three_obstacles.toml")
    report = load_task(TASKS / "pick_and_place.toml")
    assert (task.name, task.robot, task.trajectory) == (
        "three_obstacles",
        "arm",
        TrajectoryKind.QUINTIC,
    )
    assert (task.poses, task.durations, task.stretch) == (report.poses, (1.0,) * 4, True)
    cylinder, box, sphere = task.scene.obstacles
    assert cylinder == REPORT_CYLINDER
    assert isinstance(box, Box)
    assert box.name == "box"
    assert isinstance(sphere, Sphere)
    assert sphere.name == "sphere"
    assert task.scene.cube == REPORT_CUBE
    points = [(0.0, 0.0, 0.0), REPORT_CUBE.position]
    points += [p.position for p in task.poses if isinstance(p, ArmPose)]
    for obstacle in task.scene.obstacles:
        assert not any(obstacle.contains(p) for p in points), obstacle.name


def test_every_obstacle_of_three_obstacles_stands_in_the_quintic_path():
    # The gripper (wrist point to tool point) passes through each obstacle; the
    # MuJoCo collision check of the whole arm lives in tests/sim.
    task = load_task(TASKS / "three_obstacles.toml")
    trajectory = build_trajectory(task)
    t = np.arange(0.0, trajectory.duration, HIT_TIME_STEP_S)
    origins = frame_origins(trajectory.sample(t).q)
    wrist, tool = origins[:, FRAME_NAMES.index("frame5")], origins[:, FRAME_NAMES.index("tool")]
    gripper = [wrist + f * (tool - wrist) for f in np.linspace(0.0, 1.0, 11)]
    for obstacle in task.scene.obstacles:
        assert any(obstacle.contains(tuple(p)) for points in gripper for p in points), obstacle.name


def test_task_without_obstacles_has_none_and_the_reports_cube(load_text):
    task = load_text(ARM_TASK)
    assert task.scene == Scene((), TABLE, REPORT_CUBE)


def test_task_built_in_code_defaults_to_an_empty_scene():
    task = Task("t", "arm", (JointPose((0.0,) * 5), JointPose((0.1,) * 5)), TrajectoryKind.CUBIC)
    assert task.scene == Scene()
    assert task.scene.obstacles == ()


def test_scene_is_read_in_si_and_stands_on_the_table(load_text):
    scene = load_text(SCENE_TASK).scene
    pillar, crate, ball = scene.obstacles
    assert pillar == Cylinder("pillar", (0.15, 0.15, TABLE.top_z), 0.04, 0.4 - TABLE.top_z)
    assert crate == Box(
        "crate", (0.15, -0.15, TABLE.top_z), (0.1, 0.06, 0.35 - TABLE.top_z), math.radians(-45.0)
    )
    assert ball == Sphere("ball", (0.2, 0.06, 0.3), 0.03)
    assert scene.cube == REPORT_CUBE
    assert scene.table == TABLE


@pytest.mark.parametrize("z_mm", [0.0, -0.0, -5.0, -12.5], ids=lambda z: f"z{z:g}")
@pytest.mark.parametrize("shape", ["cylinder", "box"])
def test_bottom_face_between_table_and_base_plane_moves_to_the_table(load_text, shape, z_mm):
    sizes = (
        "radius_mm = 40.0\nheight_mm = 100.0" if shape == "cylinder" else "size_mm = [1, 2, 100]"
    )
    text = ARM_TASK + (
        f'\n[[obstacles]]\nname = "o"\nshape = "{shape}"\n'
        f"position_mm = [150.0, 150.0, {z_mm}]\n{sizes}\n"
    )
    (obstacle,) = load_text(text).scene.obstacles
    height = obstacle.height if isinstance(obstacle, Cylinder) else obstacle.size[2]
    assert obstacle.position == (0.15, 0.15, TABLE.top_z)
    assert obstacle.position[2] + height == pytest.approx((z_mm + 100.0) * MM, abs=SCENE_TOL_M)


def test_raised_obstacles_are_kept_where_given(load_text):
    text = SCENE_TASK.replace("[150.0, 150.0, 0.0]", "[150.0, 150.0, 20.0]", 1)
    text = text.replace("[150.0, -150.0, 0.0]", "[150.0, -150.0, 0.001]", 1)
    text = text.replace("[200.0, 60.0, 300.0]", "[200.0, 60.0, 17.5]", 1)  # resting on the table
    pillar, crate, ball = load_text(text).scene.obstacles
    assert (pillar.position, pillar.height) == ((0.15, 0.15, 0.02), 0.4)
    assert (crate.position, crate.size[2]) == ((0.15, -0.15, 1e-6), 0.35)
    assert ball.position == (0.2, 0.06, 0.0175)


def test_cube_table_replaces_the_reports_cube_key_by_key(load_text):
    text = SCENE_TASK.replace(
        "size_mm = 25.0\n", "size_mm = 30.0\nyaw_deg = 90.0\nmass_kg = 0.02\nfriction = 0.5\n"
    ).replace("[0.0, 300.0, 0.0]\nsize_mm", "[50.0, 250.0, 2.5]\nsize_mm")
    cube = load_text(text).scene.cube
    assert cube == Cube((0.05, 0.25, 0.0025), 0.03, math.radians(90.0), 0.02, 0.5)
    text = ARM_TASK.replace('robot = "arm"\n', 'robot = "arm"\ncube = {size_mm = 20}\n')
    cube = load_text(text).scene.cube
    assert cube == Cube(REPORT_CUBE.position, 0.02)
    text = ARM_TASK.replace('robot = "arm"\n', 'robot = "arm"\ncube = {}\n')
    assert load_text(text).scene.cube == REPORT_CUBE


_WITHIN = "must lie within 0.1..10000 mm"
_CYLINDER_KEYS = "a cylinder takes: name, shape, position_mm, radius_mm, height_mm"


@pytest.mark.parametrize(
    ("old", "new", "field", "problem"),
    [
        ("radius_mm = 40.0", 'radius_mm = "40"', "obstacles[0].radius_mm", "must be a number"),
        ("radius_mm = 40.0", "radius_mm = true", "obstacles[0].radius_mm", "must be a number"),
        ("radius_mm = 40.0", "radius_mm = 0.0", "obstacles[0].radius_mm", "must be positive"),
        ("radius_mm = 40.0", "radius_mm = -1", "obstacles[0].radius_mm", "must be positive"),
        ("radius_mm = 40.0", "radius_mm = nan", "obstacles[0].radius_mm", "must be finite"),
        ("radius_mm = 40.0", "radius_mm = -inf", "obstacles[0].radius_mm", "must be finite"),
        ("radius_mm = 40.0", "radius_mm = 1e999", "obstacles[0].radius_mm", "must be finite"),
        (
            "radius_mm = 40.0",
            f"radius_mm = 1{'0' * 400}",
            "obstacles[0].radius_mm",
            "must be finite, got an integer beyond 1e308",
        ),
        ("radius_mm = 40.0", "radius_mm = 10000.5", "obstacles[0].radius_mm", _WITHIN),
        ("radius_mm = 40.0", "radius_mm = 0.05", "obstacles[0].radius_mm", _WITHIN),
        ("radius_mm = 40.0", "radius_mm = [40.0]", "obstacles[0].radius_mm", "must be a number"),
        ("height_mm = 400.0\n", "", "obstacles[0].height_mm", "missing"),
        ("radius_mm = 40.0\n", "", "obstacles[0].radius_mm", "missing"),
        (
            "radius_mm = 40.0",
            'radius_mm = 40.0\ncolour = "red"',
            "obstacles[0].colour",
            "unknown key; expected one of: name, shape, position_mm, radius_mm, height_mm, "
            "size_mm, yaw_deg",
        ),
        (
            "height_mm = 400.0",
            "height_mm = 400.0\nsize_mm = [1.0, 1.0, 1.0]",
            "obstacles[0].size_mm",
            f"not a key of a cylinder; {_CYLINDER_KEYS}",
        ),
        (
            "height_mm = 400.0",
            "height_mm = 400.0\nyaw_deg = 0.0",
            "obstacles[0].yaw_deg",
            "not a key of a cylinder",
        ),
        (
            "radius_mm = 30.0",
            "radius_mm = 30.0\nheight_mm = 10.0",
            "obstacles[2].height_mm",
            "not a key of a sphere; a sphere takes: name, shape, position_mm, radius_mm",
        ),
        (
            "size_mm = [100.0, 60.0, 350.0]",
            "size_mm = [100.0, 60.0, 350.0]\nradius_mm = 5.0",
            "obstacles[1].radius_mm",
            "not a key of a box; a box takes: name, shape, position_mm, size_mm, yaw_deg",
        ),
        (
            'shape = "box"',
            'shape = "cone"',
            "obstacles[1].shape",
            "unknown shape 'cone'; expected one of: cylinder, box, sphere",
        ),
        ('shape = "box"', 'shape = "Box"', "obstacles[1].shape", "unknown shape 'Box'"),
        ('shape = "box"\n', "", "obstacles[1].shape", "missing"),
        ('shape = "box"', "shape = 3", "obstacles[1].shape", "must be a string, got 3"),
        ('name = "ball"', 'name = "pillar"', "obstacles[2].name", "duplicate obstacle name"),
        ('name = "ball"', 'name = ""', "obstacles[2].name", "must be a non-empty printable"),
        ('name = "ball"', 'name = "a\\tb"', "obstacles[2].name", "must be a non-empty printable"),
        ('name = "ball"', "name = 7", "obstacles[2].name", "must be a string, got 7"),
        ('name = "ball"\n', "", "obstacles[2].name", "missing"),
        (
            "position_mm = [150.0, 150.0, 0.0]",
            "position_mm = [150.0, 150.0]",
            "obstacles[0].position_mm",
            "must be a list of 3 numbers",
        ),
        (
            "position_mm = [150.0, 150.0, 0.0]",
            'position_mm = "here"',
            "obstacles[0].position_mm",
            "must be a list of 3 numbers",
        ),
        (
            "position_mm = [150.0, 150.0, 0.0]",
            "position_mm = [150.0, true, 0.0]",
            "obstacles[0].position_mm[1]",
            "must be a number",
        ),
        (
            "position_mm = [150.0, 150.0, 0.0]",
            "position_mm = [150.0, 1e5, 0.0]",
            "obstacles[0].position_mm[1]",
            "must lie within -10000..10000 mm (+-10 m), got 100000.0",
        ),
        (
            "position_mm = [150.0, 150.0, 0.0]",
            "position_mm = [150.0, 150.0, -12.6]",
            "obstacles[0].position_mm[2]",
            "the bottom face at z = -12.6 mm would sink into the table (its top is at "
            "z = -12.5 mm)",
        ),
        ("position_mm = [150.0, 150.0, 0.0]\n", "", "obstacles[0].position_mm", "missing"),
        (
            "position_mm = [150.0, -150.0, 0.0]",
            "position_mm = [150.0, -150.0, -100.0]",
            "obstacles[1].position_mm[2]",
            "would sink into the table",
        ),
        (
            "position_mm = [200.0, 60.0, 300.0]",
            "position_mm = [200.0, 60.0, 17.4]",
            "obstacles[2].position_mm[2]",
            "a sphere of radius 30 mm centred at z = 17.4 mm would reach into the table",
        ),
        (
            "size_mm = [100.0, 60.0, 350.0]",
            "size_mm = [100.0, 60.0]",
            "obstacles[1].size_mm",
            "must be a list of 3 numbers",
        ),
        (
            "size_mm = [100.0, 60.0, 350.0]",
            "size_mm = [100.0, 0.0, 350.0]",
            "obstacles[1].size_mm[1]",
            "must be positive",
        ),
        (
            "size_mm = [100.0, 60.0, 350.0]",
            "size_mm = [100.0, 60.0, 1e6]",
            "obstacles[1].size_mm[2]",
            "must lie within 0.1..10000 mm, got 1000000.0",
        ),
        ("yaw_deg = -45.0", "yaw_deg = nan", "obstacles[1].yaw_deg", "must be finite"),
        ("yaw_deg = -45.0", 'yaw_deg = "north"', "obstacles[1].yaw_deg", "must be a number"),
        ("size_mm = 25.0", "size_mm = -1.0", "cube.size_mm", "must be positive"),
        ("size_mm = 25.0", "size_mm = 2e4", "cube.size_mm", _WITHIN),
        (
            "size_mm = 25.0",
            "size_mm = 40.0",
            "cube.position_mm[2]",
            "a 40 mm cube centred at z = 0 mm would reach into the table",
        ),
        (
            "[cube]\nposition_mm = [0.0, 300.0, 0.0]",
            "[cube]\nposition_mm = [0.0, 300.0, -1.0]",
            "cube.position_mm[2]",
            "would reach into the table",
        ),
        (
            "[cube]\nposition_mm = [0.0, 300.0, 0.0]",
            "[cube]\nposition_mm = [0.0, -2e4, 0.0]",
            "cube.position_mm[1]",
            "must lie within -10000..10000 mm (+-10 m)",
        ),
        ("size_mm = 25.0", "size_mm = 25.0\nyaw_deg = inf", "cube.yaw_deg", "must be finite"),
        ("size_mm = 25.0", "size_mm = 25.0\nmass_kg = 0", "cube.mass_kg", "must be positive"),
        (
            "size_mm = 25.0",
            "size_mm = 25.0\nmass_kg = 1e-15",
            "cube.mass_kg",
            "must lie within 0.0001..100 kg",
        ),
        (
            "size_mm = 25.0",
            "size_mm = 25.0\nmass_kg = 1000.0",
            "cube.mass_kg",
            "must lie within 0.0001..100 kg",
        ),
        ("size_mm = 25.0", "size_mm = 25.0\nfriction = -1", "cube.friction", "must be positive"),
        ("size_mm = 25.0", "size_mm = 25.0\nfriction = 11", "cube.friction", "at most 10"),
        (
            "size_mm = 25.0",
            "size_mm = 25.0\nedge_mm = 1",
            "cube.edge_mm",
            "unknown key; expected one of: position_mm, size_mm, yaw_deg, mass_kg, friction",
        ),
    ],
    ids=lambda v: v if isinstance(v, str) and "." in v and " " not in v else None,
)
def test_malformed_scene_field_is_named_in_one_line(task_file, old, new, field, problem):
    assert old in SCENE_TASK
    _refused(task_file(SCENE_TASK.replace(old, new, 1)), field, problem)


@pytest.mark.parametrize(
    ("top", "field", "problem"),
    [
        ("obstacles = 3", "obstacles", "must be an array of [[obstacles]] tables"),
        ('obstacles = {name = "o"}', "obstacles", "must be an array of [[obstacles]] tables"),
        ("obstacles = [1, 2]", "obstacles[0]", "must be a table, got int"),
        ("obstacles = [[]]", "obstacles[0]", "must be a table, got list"),
        ("cube = 3", "cube", "must be a table, got int"),
        ("cube = false", "cube", "must be a table, got bool"),
    ],
    ids=["number", "table", "numbers", "arrays", "cube_number", "cube_false"],
)
def test_scene_keys_of_the_wrong_kind_are_refused(task_file, top, field, problem):
    path = task_file(ARM_TASK.replace('robot = "arm"\n', f'robot = "arm"\n{top}\n'))
    assert str(_refused(path, field, problem)) == f"{path}: {field}: {problem}"


def test_empty_obstacle_array_means_no_obstacle(load_text):
    text = ARM_TASK.replace('robot = "arm"\n', 'robot = "arm"\nobstacles = []\n')
    assert load_text(text).scene.obstacles == ()


@pytest.mark.parametrize(
    ("old", "new", "field", "problem"),
    [
        (
            "position_mm = [200.0, 60.0, 300.0]\nradius_mm = 30.0",
            "position_mm = [0.0, 0.0, 40.0]\nradius_mm = 50.0",
            "obstacles[2]",
            "obstacle 'ball' encloses the robot's base",
        ),
        (
            "position_mm = [150.0, -150.0, 0.0]",
            "position_mm = [0.0, 300.0, 0.0]",
            "obstacles[1]",
            "obstacle 'crate' encloses the cube's start",
        ),
        (
            "position_mm = [150.0, 150.0, 0.0]\nradius_mm = 40.0",
            "position_mm = [0.0, 290.0, -10.0]\nradius_mm = 20.0",
            "obstacles[0]",
            "obstacle 'pillar' encloses the cube's start",
        ),
    ],
    ids=["base", "cube_in_box", "cube_in_cylinder"],
)
def test_obstacle_enclosing_the_base_or_the_cube_is_refused(task_file, old, new, field, problem):
    assert old in SCENE_TASK
    path = task_file(SCENE_TASK.replace(old, new, 1))
    assert str(_refused(path, field, problem)) == f"{path}: {field}: {problem}"


def test_obstacle_over_a_moved_cube_start_is_fine(load_text):
    text = SCENE_TASK.replace("[150.0, -150.0, 0.0]", "[0.0, 300.0, 0.0]", 1)
    text = text.replace(
        "[cube]\nposition_mm = [0.0, 300.0, 0.0]", "[cube]\nposition_mm = [0, 250, 0]"
    )
    scene = load_text(text).scene
    assert scene.obstacle("crate").position[:2] == (0.0, 0.3)
    assert scene.cube is not None
    assert scene.cube.position == (0.0, 0.25, 0.0)


@pytest.mark.parametrize(
    "extra",
    [
        '[[obstacles]]\nname = "c"\nshape = "sphere"\nposition_mm = [0, 0, 100]\nradius_mm = 5',
        "[cube]\nsize_mm = 25.0",
    ],
    ids=["obstacles", "cube"],
)
def test_rrr_tasks_refuse_a_scene(task_file, extra):
    key = extra.strip("[]").split("]")[0].strip("[")
    path = task_file(f"{RRR_TASK}\n{extra}\n")
    assert str(_refused(path, key, "has no obstacles or cube")) == (
        f"{path}: {key}: the planar 3-RRR parallel robot has no obstacles or cube yet; remove it"
    )


def test_rrr_task_scene_has_no_obstacle_and_no_cube(load_text):
    assert load_text(RRR_TASK).scene == Scene((), cube=None)


@pytest.mark.parametrize(
    "text",
    [f"robot = {'9' * 5000}\n", f"robot = {'[' * 5000}{']' * 5000}\n"],
    ids=["integer_of_5000_digits", "arrays_nested_5000_deep"],
)
def test_toml_the_parser_cannot_hold_is_a_task_file_error(task_file, text):
    path = task_file(text)
    with pytest.raises(TaskFileError, match=rf"^{path}: not valid TOML: "):
        load_task(path)


# ------------------------------------------ text, sanity bounds, building


def _named(field: str, value: str) -> str:
    """The scene task with ``field`` (a name or the description) set to the TOML ``value``."""
    text = SCENE_TASK.replace(
        'robot = "arm"\n', 'name = "pick"\ndescription = "Pick it up"\nrobot = "arm"\n', 1
    )
    old = {
        "name": 'name = "pick"',
        "description": 'description = "Pick it up"',
        "poses[1].name": 'name = "home"',
        "obstacles[0].name": 'name = "pillar"',
    }[field]
    key = old.split(" = ")[0]
    return text.replace(old, f"{key} = {value}", 1)


_NAME_FIELDS = ("name", "description", "poses[1].name", "obstacles[0].name")


@pytest.mark.parametrize("field", _NAME_FIELDS)
@pytest.mark.parametrize(
    ("value", "problem"),
    [
        ('"a\\u0000b"', "character U+0000 at index 1"),
        ('"a\\nb"', "character U+000A at index 1"),
        ('"x\\r"', "character U+000D at index 1"),
        ('"\\u001b[31mred"', "character U+001B at index 0"),
        ('"tab\\there"', "character U+0009 at index 3"),
        ('"\\u202eevil"', "character U+202E at index 0"),
        ('"a\\u00a0b"', "character U+00A0 at index 1"),
        ('"a\\u2028b"', "character U+2028 at index 1"),
    ],
    ids=["nul", "newline", "return", "escape", "tab", "bidi_override", "nbsp", "line_sep"],
)
def test_names_and_description_with_control_characters_are_refused(
    task_file, field, value, problem
):
    what = "printable text" if field == "description" else "a non-empty printable string"
    error = _refused(task_file(_named(field, value)), field, f"must be {what}, got ")
    assert f"({problem} is a control, format or whitespace character)" in str(error)


@pytest.mark.parametrize(
    ("field", "length"),
    [("name", 101), ("poses[1].name", 101), ("obstacles[0].name", 101), ("description", 1001)],
)
def test_names_and_description_of_absurd_length_are_refused(task_file, field, length):
    path = task_file(_named(field, f'"{"x" * length}"'))
    error = _refused(path, field, f"must be at most {length - 1} characters, got {length}: ")
    assert len(str(error)) < len(str(path)) + 200  # the value itself is shortened


@pytest.mark.parametrize("field", ["name", "poses[1].name", "obstacles[0].name"])
@pytest.mark.parametrize("value", ['""', '"   "'], ids=["empty", "blank"])
def test_names_may_not_be_empty_or_blank(task_file, field, value):
    _refused(task_file(_named(field, value)), field, "must be a non-empty printable string")


def test_names_take_any_script_punctuation_and_the_limit_lengths(load_text):
    name = "Pick & place – 置く (v2.1)! «ok» ‘ß’ é"
    text = _named("name", f'"{name}"').replace('name = "home"', f'name = "{"h" * 100}"', 1)
    text = text.replace('description = "Pick it up"', f'description = "{"d" * 1000}"', 1)
    task = load_text(text)
    assert task.name == name
    assert task.poses[1].name == "h" * 100
    assert task.description == "d" * 1000
    assert load_text(_named("description", '""')).description == ""


@pytest.mark.parametrize(
    "stem", ["tab\there", "esc\x1b[2J", "   ", "x" * 101], ids=["tab", "escape", "blank", "long"]
)
def test_a_file_stem_that_is_no_name_needs_a_name_key(tmp_path, stem):
    path = tmp_path / f"{stem}.toml"
    path.write_text(ARM_TASK, encoding="utf-8")
    _refused(path, "name", "missing, and the file's stem")
    path.write_text(f'name = "fine"\n{ARM_TASK}', encoding="utf-8")
    assert load_task(path).name == "fine"


def test_unknown_key_with_control_characters_is_named_in_one_line(task_file):
    path = task_file(ARM_TASK.replace('type = "quintic"', 'type = "quintic"\n"a\\nb" = 1', 1))
    _refused(path, "trajectory.'a\\nb'", "unknown key")


def test_huge_values_are_shortened_in_messages(task_file):
    path = task_file(ARM_TASK.replace("pitch_deg = -90.0", f'pitch_deg = "{"x" * 10_000}"', 1))
    error = _refused(path, "poses[0].pitch_deg", "must be a number, got 'xxx")
    assert len(str(error)) < len(str(path)) + 120


_DURATION_RANGE = f"must lie within {MIN_SEGMENT_S:g}..{MAX_SEGMENT_S:g} s, got "


@pytest.mark.parametrize(
    ("value", "shown"),
    [
        ("5e-324", "5e-324"),
        ("1e-300", "1e-300"),
        ("0.0009", "0.0009"),
        ("3600.5", "3600.5"),
        ("1e300", "1e+300"),
        ("6.5e306", "6.5e+306"),
        ("1" + "0" * 20, "1" + "0" * 20),
    ],
    ids=lambda v: v[:8],
)
@pytest.mark.parametrize("form", ["one", "per_segment"])
def test_segment_duration_outside_the_bounds_is_refused_with_the_range(
    task_file, value, shown, form
):
    field = "trajectory.segment_duration_s"
    if form == "one":
        new = f"segment_duration_s = {value}"
    else:
        new, field = f"segment_duration_s = [1.0, {value}]", f"{field}[1]"
    path = task_file(RRR_TASK.replace("segment_duration_s = [1.0, 2.0]", new, 1))
    assert _DURATION_RANGE == "must lie within 0.001..3600 s, got "
    _refused(path, field, _DURATION_RANGE + shown)


def test_segment_durations_at_the_bounds_load(load_text):
    new = f"segment_duration_s = [{MIN_SEGMENT_S!r}, {MAX_SEGMENT_S!r}]"
    task = load_text(RRR_TASK.replace("segment_duration_s = [1.0, 2.0]", new, 1))
    assert task.durations == (MIN_SEGMENT_S, MAX_SEGMENT_S)


_MM_RANGE = "must lie within -10000..10000 mm (+-10 m), got "
_DEG_RANGE = "must lie within -720..720 deg (two turns), got "


@pytest.mark.parametrize(
    ("text", "old", "new", "field", "problem"),
    [
        (
            ARM_TASK,
            "position_mm = [0.0, 300.0, 0.0]",
            "position_mm = [0.0, 1e300, 0.0]",
            "poses[0].position_mm[1]",
            _MM_RANGE + "1e+300",
        ),
        (
            ARM_TASK,
            "position_mm = [0.0, 300.0, 0.0]",
            "position_mm = [0.0, 300.0, -10000.001]",
            "poses[0].position_mm[2]",
            _MM_RANGE + "-10000.001",
        ),
        (ARM_TASK, "pitch_deg = -90.0", "pitch_deg = 1e300", "poses[0].pitch_deg", _DEG_RANGE),
        (
            ARM_TASK,
            "pitch_deg = -90.0",
            "pitch_deg = -90.0\nroll_deg = 6.5e306",
            "poses[0].roll_deg",
            _DEG_RANGE + "6.5e+306",
        ),
        (
            ARM_TASK,
            "q_deg = [0.0, 90.0, -90.0, 0.0, 180.0]",
            "q_deg = [0.0, 90.0, -90.0, 0.0, -720.5]",
            "poses[1].q_deg[4]",
            _DEG_RANGE + "-720.5",
        ),
        (RRR_TASK, "x_mm = 300.0", "x_mm = 6.5e306", "poses[2].x_mm", _MM_RANGE + "6.5e+306"),
        (RRR_TASK, "y_mm = 250.0", "y_mm = -1e300", "poses[2].y_mm", _MM_RANGE),
        (RRR_TASK, "alpha_deg = -40.0", "alpha_deg = 1e300", "poses[2].alpha_deg", _DEG_RANGE),
        (SCENE_TASK, "yaw_deg = -45.0", "yaw_deg = 1e300", "obstacles[1].yaw_deg", _DEG_RANGE),
        (
            SCENE_TASK,
            "size_mm = 25.0",
            "size_mm = 25.0\nyaw_deg = -1e9",
            "cube.yaw_deg",
            _DEG_RANGE + "-1000000000.0",
        ),
    ],
    ids=lambda v: v if isinstance(v, str) and "." in v and " " not in v else None,
)
def test_pose_coordinates_and_angles_are_bounded(task_file, text, old, new, field, problem):
    assert old in text
    _refused(task_file(text.replace(old, new, 1)), field, problem)


_HUGE = "1" + "0" * 400
_DEEP = "[" * 400 + "1" + "]" * 400
_TOO_DEEP = "[" * 600 + "1" + "]" * 600


@pytest.mark.parametrize(
    ("text", "old", "new", "field", "problem"),
    [
        (
            ARM_TASK,
            'type = "quintic"',
            f'type = "quintic"\nsegment_duration_s = {_HUGE}',
            "trajectory.segment_duration_s",
            "must be finite, got an integer beyond 1e308",
        ),
        (
            ARM_TASK,
            "q_deg = [0.0, 90.0, -90.0, 0.0, 180.0]",
            f"q_deg = [0.0, 90.0, -90.0, 0.0, -{_HUGE}]",
            "poses[1].q_deg[4]",
            "must be finite, got an integer beyond 1e308",
        ),
        (RRR_TASK, "x_mm = 300.0", f"x_mm = {_HUGE}", "poses[2].x_mm", "beyond 1e308"),
        (ARM_TASK, "pitch_deg = -90.0", f"pitch_deg = {_DEEP}", "poses[0].pitch_deg", "[[[[..."),
        (ARM_TASK, 'robot = "arm"', f"robot = {_DEEP}", "robot", "must be a string, got [[[["),
        (ARM_TASK, "pitch_deg = -90.0", f"pitch_deg = {_TOO_DEEP}", None, "not valid TOML: "),
    ],
    ids=["duration_400_digits", "q_400_digits", "x_400_digits", "deep", "deep_robot", "too_deep"],
)
def test_huge_integers_and_deep_nesting_are_task_file_errors(
    task_file, text, old, new, field, problem
):
    assert old in text
    error = _refused(task_file(text.replace(old, new, 1)), field, problem)
    assert len(str(error)) < 400


def _assert_finite_or_typed_error(task: Task, kind: str | None) -> None:
    """Building ``task``'s motion of ``kind`` gives finite samples or a LynxsimError."""
    try:
        motion = get(task.robot).motion(task, task.trajectory if kind is None else kind)
    except LynxsimError:
        return
    assert math.isfinite(motion.duration), (kind, motion.duration)
    sample = motion.sample(np.linspace(0.0, motion.duration, 101))
    for values in sample:
        assert np.isfinite(values).all(), (kind, values)


_P1 = "position_mm = [0.0, 300.0, 0.0]\npitch_deg = -90.0"
_P2 = "position_mm = [0.0, 250.0, 300.0]\npitch_deg = 0.0"
_Q_UP = "q_deg = [0.0, 0.0, 0.0, 0.0, 0.0]"
_A = "x_mm = 200.0\ny_mm = 150.0\nalpha_deg = 0.0"
_B = "x_mm = 210.0\ny_mm = 150.0\nalpha_deg = 0.0"
_FAR = "x_mm = 10000.0\ny_mm = -10000.0\nalpha_deg = 720.0"
_FAR2 = "x_mm = -10000.0\ny_mm = 10000.0\nalpha_deg = -720.0"


def _task_text(robot: str, trajectory: str, *poses: str) -> str:
    body = "".join(f"[[poses]]\n{p}\n" for p in poses)
    return f'robot = "{robot}"\n[trajectory]\ntype = "quintic"\n{trajectory}\n{body}'


@pytest.mark.parametrize(
    "text",
    [
        _task_text("arm", "", _P1, _P2),
        _task_text("arm", "", _Q_UP, _P1),
        _task_text("arm", "segment_duration_s = 0.001", _P1, _P2),
        _task_text("arm", "segment_duration_s = 0.001\nstretch = true", _P1, _P2, _P1),
        _task_text("arm", "segment_duration_s = 3600", _P1, _P2),
        _task_text("arm", "pass_through = true", _P1, _P2, _P1),
        _task_text("arm", "segment_duration_s = 1.0", _P1, _P1, _P2),
        _task_text("arm", "", "position_mm = [5e-324, 0.0, 0.0]\npitch_deg = 0.0", _P1),
        _task_text("arm", "", "position_mm = [10000.0, -10000.0, 10000.0]\npitch_deg = 720", _P1),
        _task_text("arm", "", "q_deg = [720.0, -720.0, 720.0, -720.0, 720.0]", _P1),
        _task_text("rrr", "", _A, _B),
        _task_text("rrr", "pass_through = true", _A, _B, _A),
        _task_text("rrr", "pass_through = true\nsegment_duration_s = 3600", _FAR, _FAR2),
        _task_text("rrr", "segment_duration_s = 0.001\nstretch = true", _FAR, _FAR2, _A),
        _task_text("rrr", "", "x_mm = 5e-324\ny_mm = 0.0\nalpha_deg = 1e-300", _A),
        _task_text("rrr", "pass_through = true", _A, _B, _A).replace(
            "x_mm = 200.0", "x_mm = 1e300"
        ),
        _task_text("rrr", "pass_through = true", _A, _B).replace("y_mm = 150.0", "y_mm = 1.8e308"),
        _task_text("rrr", "", _A, _B).replace("x_mm = 210.0", "x_mm = 6.5e306"),
        _task_text("arm", "", _P1, _P2).replace("0.0, 250.0, 300.0", "0.0, 1e300, 300.0"),
    ],
    ids=[
        "arm",
        "arm_straight_up",
        "arm_shortest_durations",
        "arm_shortest_durations_stretched",
        "arm_longest_durations",
        "arm_pass_through",
        "arm_pause",
        "arm_denormal_coordinate",
        "arm_at_the_bounds",
        "arm_joints_at_one_turn",
        "rrr",
        "rrr_closed",
        "rrr_at_the_bounds",
        "rrr_at_the_bounds_stretched",
        "rrr_denormal",
        "rrr_1e300",
        "rrr_max_float",
        "rrr_6.5e306",
        "arm_1e300",
    ],
)
def test_task_loads_and_builds_finite_of_every_type_or_raises_typed_errors(task_file, text):
    path = task_file(text)
    try:
        task = load_task(path)
    except TaskFileError as error:
        refused: TaskFileError | None = error
    else:
        refused = None
    if refused is not None:
        assert (refused.path, "\n" in str(refused)) == (str(path), False)
        return
    for kind in (None, *TrajectoryKind):
        _assert_finite_or_typed_error(task, kind)


def test_rrr_task_of_a_type_not_planned_loads_and_its_builder_lists_the_planned_ones(load_text):
    task = load_text(RRR_TASK.replace('type = "line"', 'type = "cubic"', 1))
    assert task.trajectory is TrajectoryKind.CUBIC
    with pytest.raises(InvalidInputError, match=r"'cubic' is not planned .* one of: quintic$"):
        get("rrr").motion(task, task.trajectory)


# ------------------------------------------ property test: mutated scenes

_VALID_OBSTACLES: tuple[dict[str, Any], ...] = (
    {
        "name": "cylinder",
        "shape": "cylinder",
        "position_mm": [150.0, 150.0, 0.0],
        "radius_mm": 40.0,
        "height_mm": 400.0,
    },
    {
        "name": "box",
        "shape": "box",
        "position_mm": [150.0, -150.0, 0.0],
        "size_mm": [100.0, 60.0, 350.0],
        "yaw_deg": -45.0,
    },
    {"name": "sphere", "shape": "sphere", "position_mm": [200.0, 60.0, 300.0], "radius_mm": 30.0},
)
_VALID_CUBE: dict[str, Any] = {
    "position_mm": [0.0, 300.0, 0.0],
    "size_mm": 25.0,
    "yaw_deg": 0.0,
    "mass_kg": 0.01,
    "friction": 1.0,
}
_KEYS = (
    "name",
    "shape",
    "position_mm",
    "radius_mm",
    "height_mm",
    "size_mm",
    "yaw_deg",
    "mass_kg",
    "friction",
    "colour",
    "",
)
_DELETE = object()
"""A mutation that removes the key."""

_numbers = st.one_of(
    st.floats(allow_nan=True, allow_infinity=True),
    st.floats(-500.0, 500.0),
    st.sampled_from([0.0, -0.0, -1.0, -12.5, 1e-300, 5e-324, 1e308, -1e308, 10_000.0, 10_000.5]),
    st.integers(-(10**400), 10**400),
    st.integers(-20_000, 20_000),
)
_scalars = st.one_of(
    _numbers,
    st.booleans(),
    st.text(st.characters(exclude_categories=("Cs",)), max_size=5),
    st.sampled_from(["cylinder", "box", "sphere", "cone", "", "\x01"]),
)
_values = st.recursive(
    _scalars,
    lambda inner: st.one_of(
        st.lists(inner, max_size=4),
        st.dictionaries(st.sampled_from(_KEYS), inner, max_size=3),
    ),
    max_leaves=6,
)


@st.composite
def _mutated_scenes(draw: st.DrawFn) -> dict[str, Any]:
    valid = draw(st.lists(st.sampled_from(_VALID_OBSTACLES), max_size=4))
    obstacles: Any = [{**o, "name": f"{o['name']}{i}"} for i, o in enumerate(valid)]
    cube: Any = dict(_VALID_CUBE) if draw(st.booleans()) else _DELETE
    for _ in range(draw(st.integers(0, 4))):
        target = draw(st.sampled_from(["obstacle"] * 3 + ["coordinate"] * 2 + ["cube", "whole"]))
        value = draw(st.one_of(st.just(_DELETE), _numbers, _values))
        if target == "whole":
            if draw(st.booleans()):
                obstacles = value
            else:
                cube = value
        elif target == "cube" and isinstance(cube, dict):
            key = draw(st.sampled_from((*sorted(cube) * 3, *_KEYS)))  # mostly its own keys
            cube.pop(key, None) if value is _DELETE else cube.__setitem__(key, value)
        elif isinstance(obstacles, list) and obstacles:
            item = obstacles[draw(st.integers(0, len(obstacles) - 1))]
            if not isinstance(item, dict):
                continue
            key = draw(st.sampled_from((*sorted(item) * 3, *_KEYS)))
            if target == "coordinate" and isinstance(item.get(key), list) and item[key]:
                item[key] = list(item[key])
                index = draw(st.integers(0, len(item[key]) - 1))
                item[key][index] = 0.0 if value is _DELETE else value
            elif value is _DELETE:
                item.pop(key, None)
            else:
                item[key] = value
    scene: dict[str, Any] = {}
    if obstacles is not _DELETE:
        scene["obstacles"] = obstacles
    if cube is not _DELETE:
        scene["cube"] = cube
    return scene


@settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(scene=_mutated_scenes(), robot=st.sampled_from(["arm", "arm", "arm", "rrr"]))
def test_mutated_scene_loads_or_raises_a_task_file_error(scene, robot):
    top = "".join(f"{key} = {toml_value(value)}\n" for key, value in scene.items())
    body = ARM_TASK if robot == "arm" else RRR_TASK.replace('name = "platform"\n', "")
    text = body.replace(f'robot = "{robot}"\n', f'robot = "{robot}"\n{top}', 1)
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "task.toml"
        path.write_text(text, encoding="utf-8")
        try:
            task = load_task(path)
        except TaskFileError as exc:  # any other exception fails the test
            error: TaskFileError | None = exc
        else:
            error = None
    if error is not None:
        assert "\n" not in str(error)
        assert error.path == str(path)
        assert error.field is None or error.field.startswith(("obstacles", "cube")), error
        return
    # Loaded: a valid scene within the documented bounds.
    assert isinstance(task.scene, Scene)
    for obstacle in task.scene.obstacles:
        assert all(abs(v) <= 10.0 for v in obstacle.position)
        bottom = obstacle.position[2] - (obstacle.radius if isinstance(obstacle, Sphere) else 0.0)
        assert bottom >= TABLE.top_z
        assert not obstacle.contains((0.0, 0.0, 0.0))
    if robot == "rrr":
        assert task.scene == Scene((), cube=None)
