"""``ik_unchecked``: ``ik``'s closed form and choice without its checks, bit for bit."""

from __future__ import annotations

import numpy as np

from lynxsim.arm import LYNX_ARM, ik
from lynxsim.arm.ik import ik_unchecked


def test_ik_unchecked_gives_the_joints_and_statuses_of_ik_bit_for_bit():
    rng = np.random.default_rng(11)
    n = 5000
    position = rng.uniform([-0.35, -0.35, -0.1], [0.35, 0.35, 0.4], (n, 3))
    pitch = rng.uniform(-np.pi / 2, np.pi / 2, n)
    roll = rng.uniform(0.0, 2 * np.pi, n)
    q_ref = rng.uniform(LYNX_ARM.q_min, LYNX_ARM.q_max, (n, 5))
    full = ik(position, pitch, roll, q_ref=q_ref)
    q, status = ik_unchecked(position, pitch, roll, q_ref)
    np.testing.assert_array_equal(status, full.status)
    np.testing.assert_array_equal(q, full.q)  # NaN where there is no solution, in both
    assert {0, 1, 2} <= set(status.tolist())  # every outcome was met
