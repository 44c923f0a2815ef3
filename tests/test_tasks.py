"""Task files: the shipped ones load, and every malformed field is named in one line."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from lynxsim.errors import TaskFileError
from lynxsim.tasks import PlanarPose, load_task
from lynxsim.traj import ArmPose, JointPose, TrajectoryKind

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


def _write(tmp_path: Path, text: str) -> Path:
    path = tmp_path / "task.toml"
    path.write_text(text)
    return path


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


def test_arm_poses_may_be_joints_and_defaults_apply(tmp_path):
    task = load_task(_write(tmp_path, ARM_TASK))
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


def test_rrr_tasks_load_platform_poses_in_si(tmp_path):
    task = load_task(_write(tmp_path, RRR_TASK))
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
def test_malformed_field_is_named_in_one_line(tmp_path, old, new, field, problem):
    assert old in ARM_TASK
    path = _write(tmp_path, ARM_TASK.replace(old, new, 1))
    with pytest.raises(TaskFileError) as info:
        load_task(path)
    message = str(info.value)
    assert "\n" not in message
    assert message.startswith(f"{path}: {field}: ")
    assert problem in message
    assert (info.value.path, info.value.field) == (str(path), field)


def test_one_pose_is_not_a_task(tmp_path):
    text = ARM_TASK[: ARM_TASK.index("[[poses]]\nname")]
    with pytest.raises(TaskFileError, match=r"poses: must be an array of at least two"):
        load_task(_write(tmp_path, text))


def test_rrr_poses_need_their_platform_keys(tmp_path):
    text = RRR_TASK.replace("alpha_deg = 30.0\n", "", 1)
    with pytest.raises(TaskFileError, match=r": poses\[1\]\.alpha_deg: missing$"):
        load_task(_write(tmp_path, text))
    text = RRR_TASK.replace("alpha_deg = 30.0", "pitch_deg = 30.0", 1)
    with pytest.raises(
        TaskFileError,
        match=r": poses\[1\]\.pitch_deg: unknown key; expected one of: "
        r"name, x_mm, y_mm, alpha_deg$",
    ):
        load_task(_write(tmp_path, text))


def test_invalid_toml_names_the_file(tmp_path):
    path = _write(tmp_path, "robot = arm\n")
    with pytest.raises(TaskFileError, match=rf"^{path}: not valid TOML: .*line 1"):
        load_task(path)


def test_non_utf8_file_is_refused(tmp_path):
    path = tmp_path / "latin1.toml"
    path.write_bytes('name = "é"\n'.encode("latin-1"))
    with pytest.raises(TaskFileError, match="not UTF-8 text"):
        load_task(path)
