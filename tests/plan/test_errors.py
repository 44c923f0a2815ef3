"""Planning errors read as sentences: a configuration in collision has no '-inf m' clearance."""

from __future__ import annotations

import numpy as np
import pytest

from lynxsim.plan import GoalsInCollisionError, StartInCollisionError


@pytest.mark.parametrize(
    "error",
    [
        StartInCollisionError(np.zeros(5), -np.inf, 0.01, "P1 -> P2"),
        GoalsInCollisionError(np.array([-np.inf, -np.inf]), 0.01, "P1 -> P2"),
    ],
    ids=["start", "goals"],
)
def test_a_configuration_in_collision_is_said_to_be_so(error):
    message = str(error)
    assert "inf" not in message
    assert "in collision" in message
    assert "0.01 m" in message  # the margin, as a number


def test_a_finite_clearance_is_a_number_of_metres():
    message = str(StartInCollisionError(np.zeros(5), 0.004, 0.01))
    assert "clearance 0.004 m, less than the margin 0.01 m" in message
    largest = str(GoalsInCollisionError(np.array([-np.inf, 0.002]), 0.01))
    assert "(largest 0.002 m)" in largest
