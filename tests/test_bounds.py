"""The sanity bounds' checks: typed errors that state the range, for any input."""

from __future__ import annotations

import math

import gymnasium as gym
import numpy as np
import pytest

from lynxsim.bounds import check_count, check_range
from lynxsim.cli.units import bounded_float
from lynxsim.envs.noise import action_noise_std
from lynxsim.errors import InvalidInputError, NonFiniteInputError


@pytest.mark.parametrize(
    ("value", "expected"), [(3, 3), (np.int64(4), 4), (np.array(5), 5), (0, 0)]
)
def test_counts_accept_integers_of_any_kind(value, expected):
    assert check_count(value, "n", 0, 10) == expected


@pytest.mark.parametrize(
    ("value", "message"),
    [
        (np.array([1, 2]), "n must be an integer, got array([1, 2])"),
        (True, "n must be an integer, got True"),
        (2.0, "n must be an integer, got 2.0"),
        ("3", "n must be an integer, got '3'"),
        (11, "n must be between 0 and 10, got 11"),
        (10**400, "n must be between 0 and 10, got a 401-digit integer"),
    ],
    ids=["array", "bool", "float", "str", "above", "huge"],
)
def test_counts_refuse_everything_else_with_the_range(value, message):
    with pytest.raises(InvalidInputError) as info:
        check_count(value, "n", 0, 10)
    assert str(info.value) == message


def test_ranges_refuse_non_numbers_non_finite_and_outside():
    assert check_range(np.float32(0.5), "x", 0.0, 1.0) == 0.5
    with pytest.raises(InvalidInputError, match=r"^x must be a number, got 'a'$"):
        check_range("a", "x", 0.0, 1.0)  # type: ignore[arg-type]
    with pytest.raises(NonFiniteInputError, match=r"^x must be finite, got nan$"):
        check_range(math.nan, "x", 0.0, 1.0)
    with pytest.raises(InvalidInputError, match=r"^x must be between 0 and 1 s, got 2 s$"):
        check_range(2.0, "x", 0.0, 1.0, "s")
    with pytest.raises(InvalidInputError, match=r"^x must be a number"):
        check_range(10**400, "x", 0.0, 1.0)


def test_a_negative_zero_comes_back_as_zero():
    """``-0`` passes ``0 <= x`` but NumPy refuses it as a scale: ranges and the CLI return +0.0."""
    assert math.copysign(1.0, check_range(-0.0, "noise", 0.0, 1.0)) == 1.0
    assert math.copysign(1.0, bounded_float(0.0, 1.0)("-0")) == 1.0
    std = action_noise_std(gym.spaces.Box(-1.0, 1.0, (3,)), -0.0)
    assert (np.copysign(1.0, std) == 1.0).all()
    np.random.default_rng(0).normal(0.0, std)  # a scale NumPy takes
