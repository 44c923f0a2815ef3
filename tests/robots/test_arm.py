"""Building trajectories from tasks: the report's tasks in every type."""

from __future__ import annotations

import dataclasses
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from lynxsim.arm import tool_pose
from lynxsim.arm.motion import ArmPose, generate
from lynxsim.errors import InvalidInputError, OutOfReachError
from lynxsim.plots.obstacles import inside_any
from lynxsim.reproduce.arm_tables import TABLE4
from lynxsim.robots.arm import build_trajectory
from lynxsim.scene import REPORT_CYLINDER
from lynxsim.tasks import PlanarPose, Task, load_task
from lynxsim.traj import WAYPOINT_KINDS, TrajectoryKind
from tests.helpers import assert_close

TASKS = Path(__file__).resolve().parents[2] / "tasks"
JOINT_TOL_DEG = 0.01
"""Table 4 prints joints to 0.01 deg."""


@pytest.fixture(scope="module")
def pick_and_place() -> Task:
    return load_task(TASKS / "pick_and_place.toml")


@pytest.fixture(scope="module")
def obstacle_avoidance() -> Task:
    return load_task(TASKS / "obstacle_avoidance.toml")


def test_pick_and_place_defaults_to_the_reports_quintic_at_1_s(pick_and_place):
    traj = build_trajectory(pick_and_place)
    assert traj.kind is TrajectoryKind.QUINTIC
    assert_close(traj.segment_durations, 1.0, atol=0.0)
    table = np.array([row.q_deg for row in TABLE4])
    assert_close(np.degrees(traj.waypoints.q[:, :4]), table, atol=JOINT_TOL_DEG)
    assert traj.waypoints.names == ("P1", "P2", "P3", "P4", "P5")


@pytest.mark.parametrize("kind", WAYPOINT_KINDS, ids=lambda k: k.value)
def test_every_type_builds_for_both_report_tasks(kind, pick_and_place, obstacle_avoidance):
    for task in (pick_and_place, obstacle_avoidance):
        traj = build_trajectory(task, kind)
        assert traj.kind is kind
        assert (traj.segment_durations >= 1.0 - 1e-12).all()  # 1 s, stretched where needed
        targets = np.array([p.position for p in task.poses if isinstance(p, ArmPose)])
        tool = tool_pose(traj.sample(traj.waypoint_times).q).position
        assert_close(tool, targets, atol=1e-8)


@pytest.mark.parametrize("kind", WAYPOINT_KINDS, ids=lambda k: k.value)
def test_plain_task_crosses_the_obstacle_in_every_type(kind, pick_and_place):
    # The report: "the plain task passes through the obstacle between P2 and P3".
    traj = build_trajectory(pick_and_place, kind)
    t = traj.times_at_rate(500.0)
    inside = inside_any(tool_pose(traj.sample(t).q).position, (REPORT_CYLINDER,))
    assert inside.any()
    assert (t[inside] > traj.waypoint_times[1]).all()
    assert (t[inside] < traj.waypoint_times[2]).all()


def test_via_points_with_straight_lines_avoid_the_obstacle(obstacle_avoidance):
    traj = build_trajectory(obstacle_avoidance)
    assert traj.kind is TrajectoryKind.LINE
    path = tool_pose(traj.sample(traj.times_at_rate(1000.0)).q).position
    assert not inside_any(path, (REPORT_CYLINDER,)).any()


def test_unknown_type_lists_the_valid_ones():
    with pytest.raises(
        InvalidInputError,
        match=r"unknown trajectory type 'spline'; expected one "
        r"of: free, cubic, quintic, lspb, line, ruckig",
    ):
        generate("spline", np.zeros((2, 5)))


def test_pass_through_is_for_ruckig_only():
    with pytest.raises(InvalidInputError, match="pass_through applies to ruckig"):
        generate(
            "quintic", np.radians([[0, 60, -60, 0, 0], [10, 60, -60, 0, 0]]), pass_through=True
        )


def test_unreachable_task_pose_names_the_pose_and_the_reason(pick_and_place):
    far = ArmPose((0.0, 0.6, 0.3), 0.0, None, "P9")
    task = dataclasses.replace(pick_and_place, poses=(*pick_and_place.poses[:2], far))
    with pytest.raises(
        OutOfReachError,
        match=r"^pose P9 \(x 0, y 600, z 300 mm, pitch 0 deg\) "
        r"is unreachable: wrist point out of the arm's reach",
    ):
        build_trajectory(task)


def test_rrr_tasks_are_not_built_yet():
    task = Task(
        "tri",
        "rrr",
        (PlanarPose(0.2, 0.15, 0.0), PlanarPose(0.3, 0.25, 0.0)),
        TrajectoryKind.QUINTIC,
    )
    with pytest.raises(InvalidInputError, match="is for robot 'rrr'"):
        build_trajectory(task)


def test_trajectories_never_import_mujoco():
    code = (
        "import sys, lynxsim.traj, lynxsim.tasks, lynxsim.plots.trajectory; "
        "sys.exit('mujoco' in sys.modules)"
    )
    assert subprocess.run([sys.executable, "-c", code], check=False).returncode == 0
