"""The limit type, and the arm's default limits derived from its servos (lynxsim.arm.servos)."""

from __future__ import annotations

import numpy as np
import pytest

from lynxsim.arm.servos import ACCELERATION_RAMP_S, AL5D_SERVOS, JERK_RAMP_S, SPEED_DERATING
from lynxsim.errors import InvalidInputError, NonFiniteInputError
from lynxsim.traj import DEFAULT_LIMITS, JointLimits
from tests.helpers import assert_close


def test_default_limits_derive_from_the_servos():
    speeds = np.array([s.no_load_speed for s in AL5D_SERVOS])
    assert_close(DEFAULT_LIMITS.velocity, SPEED_DERATING * speeds, atol=1e-12)
    assert_close(
        DEFAULT_LIMITS.acceleration,
        np.array(DEFAULT_LIMITS.velocity) / ACCELERATION_RAMP_S,
        atol=1e-12,
    )
    assert_close(
        DEFAULT_LIMITS.jerk, np.array(DEFAULT_LIMITS.acceleration) / JERK_RAMP_S, atol=1e-12
    )
    assert_close(DEFAULT_LIMITS.velocity, [3.49, 4.49, 2.73, 3.14, 5.71], atol=0.005)


def test_limits_accept_a_scalar_for_every_joint():
    limits = JointLimits(velocity=1.0, acceleration=[1, 2, 3, 4, 5], jerk=np.full(5, 9.0))
    assert limits.velocity == (1.0,) * 5
    assert_close(limits.of_order(2), [1, 2, 3, 4, 5], atol=0.0)


@pytest.mark.parametrize(
    ("kwargs", "error", "message"),
    [
        (
            {"velocity": [1, 2, 3]},
            InvalidInputError,
            r"velocity limits must be a number or have shape",
        ),
        ({"acceleration": 0.0}, InvalidInputError, r"acceleration limits must be positive"),
        ({"jerk": np.inf}, NonFiniteInputError, r"jerk limits must be finite"),
    ],
    ids=["shape", "zero", "infinite"],
)
def test_malformed_limits_are_refused(kwargs, error, message):
    values = {"velocity": 1.0, "acceleration": 1.0, "jerk": 1.0} | kwargs
    with pytest.raises(error, match=message):
        JointLimits(**values)
