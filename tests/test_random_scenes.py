"""Random obstacles: seeded, in reach, never on the points kept free or the base axis."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from lynxsim.errors import InvalidInputError
from lynxsim.random_scenes import REACH_ANNULUS_M, random_obstacles
from lynxsim.scene import TABLE, Scene

FREE = ((0.0, 0.3, 0.0), (0.25, 0.0, 0.3))


@settings(max_examples=200)
@given(seed=st.integers(0, 2**32 - 1), number=st.integers(0, 3))
def test_obstacles_keep_the_free_points_and_the_base_clear(seed, number):
    obstacles = random_obstacles(np.random.default_rng(seed), number, keep_free=FREE)
    assert [o.name for o in obstacles] == [f"obstacle{i + 1}" for i in range(number)]
    Scene(obstacles, TABLE, cube=None)  # refuses one that encloses the base
    for o in obstacles:
        assert REACH_ANNULUS_M[0] <= np.hypot(*o.position[:2]) <= REACH_ANNULUS_M[1]
        for point in FREE:
            assert o.distance(point) >= 0.06  # the default gap


def test_same_generator_state_gives_the_same_obstacles():
    a = random_obstacles(np.random.default_rng(7), 3)
    b = random_obstacles(np.random.default_rng(7), 3)
    assert a == b
    assert a != random_obstacles(np.random.default_rng(8), 3)


def test_number_is_bounded():
    with pytest.raises(InvalidInputError, match="number must be between 0 and 8, got 9"):
        random_obstacles(np.random.default_rng(0), 9)
