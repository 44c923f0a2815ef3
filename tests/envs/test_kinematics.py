"""The single-target IK and FK of the control loop agree with lynxsim.arm's batch versions."""

from __future__ import annotations

import numpy as np
import pytest

from lynxsim.arm import LYNX_ARM, IKStatus, ik, tool_pose
from lynxsim.envs.kinematics import ik_nearest, tool_pose_of
from tests.helpers import assert_close

JOINT_RAD = 1e-12
"""Agreement of joint angles [rad] (same operations, so equal to rounding)."""
POSE_M = 1e-12
"""Agreement of tool points [m] and pitches [rad]."""
N = 3000


@pytest.mark.parametrize("source", ["reachable", "anywhere"])
def test_ik_nearest_matches_batch_ik(source):
    rng = np.random.default_rng(7)
    q_ref = rng.uniform(LYNX_ARM.lower, LYNX_ARM.upper, (N, 5))
    if source == "reachable":  # targets of random joints: mostly solvable
        pose = tool_pose(rng.uniform(LYNX_ARM.lower, LYNX_ARM.upper, (N, 5)))
        p, pitch, roll = pose.position, pose.pitch, pose.roll
    else:  # a box around the arm: mostly out of reach or range
        p = rng.uniform([-0.5, -0.5, -0.3], [0.5, 0.5, 0.6], (N, 3))
        pitch = rng.uniform(-np.pi, np.pi, N)
        roll = rng.uniform(-1.0, 7.0, N)
    batch = ik(p, pitch, roll, q_ref=q_ref)
    for i in range(N):
        status, q = ik_nearest(*p[i].tolist(), pitch[i], roll[i], q_ref[i].tolist())
        assert status == batch.status[i], i
        if status is IKStatus.OK:
            assert_close(q, batch.q[i], atol=JOINT_RAD, err_msg=f"target {i}")
    if source == "reachable":
        assert batch.ok.mean() > 0.9


def test_ik_nearest_rejects_non_finite_targets():
    assert ik_nearest(np.nan, 0.0, 0.1, 0.0, 0.0, [0.0] * 5) == (IKStatus.NOT_FINITE, None)


def test_tool_pose_of_matches_tool_pose():
    rng = np.random.default_rng(3)
    q = rng.uniform(LYNX_ARM.lower, LYNX_ARM.upper, (500, 5))
    pose = tool_pose(q)
    got = np.array([tool_pose_of(v.tolist()) for v in q])
    assert_close(got[:, :3], pose.position, atol=POSE_M)
    assert_close(got[:, 3], pose.pitch, atol=POSE_M)
