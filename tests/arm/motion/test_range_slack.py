"""One slack on the joint ranges: what the IK accepts, every generator accepts."""

from __future__ import annotations

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
