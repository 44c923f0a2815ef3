"""One slack on the joint ranges: what the IK accepts, every generator accepts."""

from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest

from lynxsim.angles import LIMIT_TOL
from lynxsim.arm import IKStatus, ik, tool_pose
from lynxsim.arm.motion import (
    ArmPose,
    JointPose,
    cartesian_line,
    cubic,
    free_motion,
    lspb,
    quintic,
    ruckig_trajectory,
)
from lynxsim.errors import JointRangeError

GENERATORS = [free_motion, cubic, quintic, lspb, ruckig_trajectory, cartesian_line]
OTHER = ArmPose((0.2, 0.05, 0.2), 0.0)
"""A second waypoint well inside the ranges."""


def _joints_below_the_shoulder_limit(excess: float) -> np.ndarray:
    """Joints with the shoulder ``excess`` below its lower limit (0) [rad]."""
    return np.array([0.3, -excess, -1.2, 0.4, 1.0])


def _pose_of(q: np.ndarray) -> ArmPose:
    pose = tool_pose(q)
    return ArmPose(tuple(pose.position), float(pose.pitch), float(pose.roll))


@pytest.mark.parametrize("generate", GENERATORS, ids=[g.__name__ for g in GENERATORS])
@pytest.mark.parametrize("given_as", ["pose", "joints"])
def test_a_waypoint_within_the_ik_slack_is_accepted(generate, given_as):
    q = _joints_below_the_shoulder_limit(0.5 * LIMIT_TOL)
    pose = _pose_of(q)
    assert ik(np.asarray(pose.position), pose.pitch, pose.roll).status == IKStatus.OK
    first = pose if given_as == "pose" else JointPose(tuple(q))
    traj = generate([first, OTHER])
    start = traj.sample(np.array([0.0])).q[0]
    assert start[1] == pytest.approx(q[1], abs=1e-12)


@pytest.mark.parametrize("given_as", ["pose", "joints"])
def test_a_waypoint_beyond_the_slack_is_refused(given_as):
    q = _joints_below_the_shoulder_limit(2.0 * LIMIT_TOL)
    first = _pose_of(q) if given_as == "pose" else JointPose(tuple(q))
    with pytest.raises(JointRangeError, match="joint 2"):
        quintic([first, OTHER])


HAIR_DEG = (90.00000005, 90.0000001, 90.0000005, 90.000001)
"""A base angle a hair over its 90 deg limit, within the joint slack (issue 23)."""


@pytest.mark.parametrize("q1_deg", HAIR_DEG)
def test_a_line_from_joints_a_hair_over_a_limit_is_a_joint_range_error(q1_deg):
    q = (np.radians(q1_deg), 0.8, -1.2, -0.5, 0.3)
    with pytest.raises(JointRangeError, match=r"joint 1 \(base\)") as info:
        cartesian_line([JointPose(q), OTHER])
    assert info.value.joint == 1


def test_a_line_task_a_hair_over_a_limit_is_one_line(tmp_path):
    task = tmp_path / "hair.toml"
    task.write_text(
        'name = "hair"\nrobot = "arm"\n[trajectory]\ntype = "line"\nsegment_duration_s = 1.0\n'
        "[[poses]]\nq_deg = [90.0000005, 45.0, -70.0, -30.0, 20.0]\n"
        "[[poses]]\nposition_mm = [100.0, 250.0, 50.0]\npitch_deg = -90.0\n"
    )
    for command in (
        ["traj", str(task), "--out-dir", str(tmp_path)],
        ["play", str(task), "--no-video"],
    ):
        proc = subprocess.run(
            [sys.executable, "-m", "lynxsim", *command],
            capture_output=True,
            text=True,
            timeout=300,
        )
        assert proc.returncode == 1, proc.stderr
        (line,) = proc.stderr.splitlines()
        assert line.startswith(f"lynxsim: error: {task}: "), line
        assert "joint 1 (base)" in line
