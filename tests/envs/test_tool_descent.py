"""The compiled joint-space search of the ``-v2`` tool action (:mod:`lynxsim.envs.tool_descent`)."""

from __future__ import annotations

import numpy as np

from lynxsim.arm import LYNX_ARM, jacobian, tool_pose
from lynxsim.envs.tool_action import ToolLimits
from lynxsim.envs.tool_descent import descend, kernel_jacobian, kernel_pose

LIMITS = ToolLimits(0.015, 0.1, 0.1, (-0.30, -0.45, -0.004), (0.45, 0.45, 0.50))
"""The envs' steps and target box."""
SAME = 1e-12
"""The compiled closed forms agree with NumPy's to this [m, rad] (libm's last digit)."""


def _joints(n: int, seed: int) -> np.ndarray:
    rng = np.random.default_rng(seed)
    return rng.uniform(np.array(LYNX_ARM.q_min), np.array(LYNX_ARM.q_max), (n, 5))


def test_the_kernels_pose_and_jacobian_are_the_arms():
    q = _joints(500, 1)
    pose = tool_pose(q)
    expected = np.concatenate([pose.position, pose.pitch[:, None]], axis=1)
    got = np.array([kernel_pose(row) for row in q])
    np.testing.assert_allclose(got, expected, rtol=0.0, atol=SAME)
    got_j = np.array([kernel_jacobian(row) for row in q])
    np.testing.assert_allclose(got_j, jacobian(q)[:, :, :4], rtol=0.0, atol=SAME)


def test_the_search_stays_in_its_box_and_comes_nearer_and_rows_are_alone():
    q_cmd = _joints(40, 2)
    start = tool_pose(q_cmd)
    here = np.concatenate([start.position, start.pitch[:, None], q_cmd[:, 4:]], axis=1)
    rng = np.random.default_rng(3)
    request = here + rng.uniform(-3.0, 3.0, (40, 5)) * LIMITS.steps
    q = descend(q_cmd, request, LIMITS.descent)
    jump = LIMITS.max_joint_jump
    lo = np.maximum(np.array(LYNX_ARM.q_min[:4]), q_cmd[:, :4] - jump)
    hi = np.minimum(np.array(LYNX_ARM.q_max[:4]), q_cmd[:, :4] + jump)
    assert ((q[:, :4] >= lo) & (q[:, :4] <= hi)).all()
    np.testing.assert_array_equal(q[:, 4], request[:, 4])
    end = tool_pose(q)
    w = 1.0 / LIMITS.steps[:4]

    def miss(p: np.ndarray, pitch: np.ndarray) -> np.ndarray:
        d = (np.concatenate([p, pitch[:, None]], axis=1) - request[:, :4]) * w
        return np.einsum("ij,ij->i", d, d)

    before, after = miss(start.position, start.pitch), miss(end.position, end.pitch)
    assert (after <= before).all()
    assert (after < before).any()
    for i in (0, 17, 39):
        np.testing.assert_array_equal(
            descend(q_cmd[i : i + 1], request[i : i + 1], LIMITS.descent)[0], q[i]
        )
