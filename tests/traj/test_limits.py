"""The limit and bound types: n joints, validated, no robot's defaults."""

from __future__ import annotations

import numpy as np
import pytest

from lynxsim.errors import InvalidInputError, NonFiniteInputError
from lynxsim.traj import JointBounds, JointLimits
from tests.helpers import assert_close


def test_limits_accept_a_scalar_for_every_joint():
    limits = JointLimits(velocity=1.0, acceleration=[1, 2, 3, 4, 5], jerk=np.full(5, 9.0))
    assert limits.velocity == (1.0,) * 5
    assert_close(limits.of_order(2), [1, 2, 3, 4, 5], atol=0.0)


@pytest.mark.parametrize(
    ("kwargs", "error", "message"),
    [
        (
            {"velocity": np.ones((2, 2))},
            InvalidInputError,
            r"velocity limits must be a number or have shape",
        ),
        ({"acceleration": 0.0}, InvalidInputError, r"acceleration limits must be positive"),
        ({"jerk": np.inf}, NonFiniteInputError, r"jerk limits must be finite"),
    ],
    ids=["shape", "zero", "infinite"],
)
def test_malformed_limits_are_refused(kwargs, error, message):
    values = {"velocity": [1.0, 1.0], "acceleration": 1.0, "jerk": 1.0} | kwargs
    with pytest.raises(error, match=message):
        JointLimits(**values)


@pytest.mark.parametrize("n", [1, 2, 7])
def test_limits_of_any_number_of_joints(n):
    limits = JointLimits(velocity=np.arange(1.0, n + 1), acceleration=2.0, jerk=3.0)
    assert limits.n_joints == n
    assert limits.jerk == (3.0,) * n
    assert JointLimits.for_joints(n, 1.0, 2.0, 3.0).of_order(2).tolist() == [2.0] * n


def test_limits_need_a_number_of_joints_and_agree_on_it():
    with pytest.raises(InvalidInputError, match="joint limits need the number of joints"):
        JointLimits(1.0, 2.0, 3.0)  # type: ignore[arg-type]
    with pytest.raises(
        InvalidInputError,
        match=r"acceleration limits must be a number or have shape \(3,\) as the velocity "
        r"limits, got \(2,\)",
    ):
        JointLimits(velocity=[1, 2, 3], acceleration=[1, 2], jerk=1.0)  # type: ignore[arg-type]
    with pytest.raises(InvalidInputError, match="n_joints must be a positive integer"):
        JointLimits.for_joints(0, 1.0, 1.0, 1.0)


def test_bounds_name_and_range_every_joint():
    bounds = JointBounds(("a", "b"), (-1.0, 0.0), (1.0, 2))
    assert bounds.n_joints == 2
    assert bounds.upper == (1.0, 2.0)
    assert_close(bounds.lower_array, [-1.0, 0.0], atol=0.0)


@pytest.mark.parametrize(
    ("names", "lower", "upper", "error", "message"),
    [
        ((), (), (), InvalidInputError, "joint names must be non-empty strings"),
        (("a", ""), (0, 0), (1, 1), InvalidInputError, "joint names must be non-empty strings"),
        (("a", "a"), (0, 0), (1, 1), InvalidInputError, "joint names must be distinct"),
        (("a",), (0, 0), (1,), InvalidInputError, r"1 joints need 1 lower and upper bounds"),
        (("a",), (2.0,), (1.0,), InvalidInputError, r"joint 1 \(a\): lower bound 2\.0 > upper"),
        (("a",), (np.nan,), (1.0,), NonFiniteInputError, "lower joint bounds must be finite"),
        (("a",), ("x",), (1.0,), InvalidInputError, "lower joint bounds"),
    ],
    ids=["none", "empty-name", "duplicate", "count", "order", "nan", "text"],
)
def test_malformed_bounds_are_refused(names, lower, upper, error, message):
    with pytest.raises(error, match=message):
        JointBounds(names, lower, upper)
