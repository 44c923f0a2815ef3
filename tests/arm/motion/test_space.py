"""The arm's joint space: its bounds are the geometry's, its limits derive from its servos."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from lynxsim.arm import LYNX_ARM
from lynxsim.arm.motion import ARM_BOUNDS, ARM_LIMITS, joint_bounds
from lynxsim.arm.servos import ACCELERATION_RAMP_S, AL5D_SERVOS, JERK_RAMP_S, SPEED_DERATING
from lynxsim.errors import InvalidInputError
from tests.helpers import assert_close


def test_default_limits_derive_from_the_servos():
    speeds = np.array([s.no_load_speed for s in AL5D_SERVOS])
    assert_close(ARM_LIMITS.velocity, SPEED_DERATING * speeds, atol=1e-12)
    assert_close(
        ARM_LIMITS.acceleration,
        np.array(ARM_LIMITS.velocity) / ACCELERATION_RAMP_S,
        atol=1e-12,
    )
    assert_close(ARM_LIMITS.jerk, np.array(ARM_LIMITS.acceleration) / JERK_RAMP_S, atol=1e-12)
    assert_close(ARM_LIMITS.velocity, [3.49, 4.49, 2.73, 3.14, 5.71], atol=0.005)


def test_bounds_are_the_geometrys_joints():
    assert ARM_BOUNDS.names == LYNX_ARM.joint_names
    assert_close(ARM_BOUNDS.lower_array, LYNX_ARM.lower, atol=0.0)
    assert_close(ARM_BOUNDS.upper_array, LYNX_ARM.upper, atol=0.0)
    assert joint_bounds() is ARM_BOUNDS
    narrow = dataclasses.replace(LYNX_ARM, q_max=(1.0, 1.0, 0.0, 1.0, 1.0))
    assert joint_bounds(narrow).upper == (1.0, 1.0, 0.0, 1.0, 1.0)
    with pytest.raises(InvalidInputError, match="geometry must be of type ArmGeometry"):
        joint_bounds("arm")  # type: ignore[arg-type]
