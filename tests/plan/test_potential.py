"""The potential-field baseline: fine in the open, stuck in a U where RRTConnect succeeds."""

from __future__ import annotations

import numpy as np
import pytest

from lynxsim.plan import LocalMinimumError, plan_segment, potential_field_segment
from tests.plan.worlds import (
    LIPSCHITZ,
    LOWER_2D,
    MARGIN_M,
    U_TRAP,
    UPPER_2D,
    WALL,
    dense_edge_clearance,
)

INSIDE_U = np.array([0.0, 0.0])
BEHIND_U = np.array([0.8, 0.0])


def test_the_field_reaches_a_goal_in_the_open():
    result = potential_field_segment(
        [-0.5, 0.9], [[0.5, 0.9]], WALL, LOWER_2D, UPPER_2D, lipschitz=LIPSCHITZ, margin_m=MARGIN_M
    )
    assert result.planner == "potential"
    assert np.array_equal(result.path[-1], [0.5, 0.9])
    for a, b in zip(result.path[:-1], result.path[1:]):
        assert dense_edge_clearance(WALL, a, b) >= 0.5 * MARGIN_M


def test_the_field_gets_stuck_in_a_u_where_rrtconnect_succeeds():
    with pytest.raises(LocalMinimumError, match="segment 'trap': potential field stuck") as info:
        potential_field_segment(
            INSIDE_U,
            [BEHIND_U],
            U_TRAP,
            LOWER_2D,
            UPPER_2D,
            lipschitz=LIPSCHITZ,
            margin_m=MARGIN_M,
            label="trap",
        )
    assert info.value.q[0] < 0.25  # in front of the U's bottom, inside it
    assert info.value.distance_rad > 0.5
    result = plan_segment(
        INSIDE_U,
        [BEHIND_U],
        U_TRAP,
        LOWER_2D,
        UPPER_2D,
        lipschitz=LIPSCHITZ,
        margin_m=MARGIN_M,
        seed=0,
    )
    assert np.array_equal(result.path[-1], BEHIND_U)
    for a, b in zip(result.path[:-1], result.path[1:]):
        assert dense_edge_clearance(U_TRAP, a, b) >= 0.5 * MARGIN_M
