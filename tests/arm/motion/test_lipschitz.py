"""The arm's Lipschitz bound holds for its kinematic chain over random joint steps."""

from __future__ import annotations

import math

import numpy as np
import pytest

from lynxsim.arm import LYNX_ARM, frame_origins
from lynxsim.arm.motion import HAND_EXTENT_M, arm_lipschitz, joint_radii
from lynxsim.errors import InvalidInputError

PAIRS = 2000
"""Random joint-vector pairs checked [-]."""


def test_the_constant_for_the_lynx_arm():
    radii = joint_radii()
    assert radii[0] == pytest.approx(0.153 + 0.153 + 0.098 + HAND_EXTENT_M, abs=1e-12)
    assert radii[4] == HAND_EXTENT_M
    assert arm_lipschitz() == pytest.approx(math.sqrt(sum(r * r for r in radii)), rel=1e-15)
    assert 0.74 < arm_lipschitz() < 0.75


def test_no_frame_of_the_chain_moves_more_than_l_times_the_joint_step():
    rng = np.random.default_rng(0)
    lower, upper = LYNX_ARM.lower, LYNX_ARM.upper
    a = rng.uniform(lower, upper, size=(PAIRS, 5))
    b = np.clip(a + rng.normal(scale=0.3, size=(PAIRS, 5)), lower, upper)
    moved = np.linalg.norm(frame_origins(b) - frame_origins(a), axis=-1).max(axis=-1)
    step = np.linalg.norm(b - a, axis=1)
    assert (moved <= arm_lipschitz(extent_m=0.0) * step).all()


def test_a_bad_extent_is_refused():
    with pytest.raises(InvalidInputError, match="extent_m"):
        arm_lipschitz(extent_m=-0.1)
