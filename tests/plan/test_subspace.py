"""Planning in a subspace of the joints: held joints, tied joints, and the joint box."""

from __future__ import annotations

import itertools

import numpy as np
import pytest

from lynxsim.errors import InvalidInputError, NonFiniteInputError
from lynxsim.plan import plan_segment
from lynxsim.plan.subspace import JointSubspace
from tests.plan.worlds import LIPSCHITZ, MARGIN_M, Boxes, dense_edge_clearance

# A wall across x through the whole 3-D cube except |y| > 0.8: in a subspace of
# constant z the planner must go around it in y.
WALL_3D = Boxes([[0.0, 0.0, 0.0]], [[0.05, 0.8, 1.0]])
LOWER_3D = np.full(3, -1.0)
UPPER_3D = np.full(3, 1.0)


def test_held_joints_clearance_is_the_full_worlds_with_the_values_put_back() -> None:
    held = JointSubspace.holding(WALL_3D, [2], [0.5], LOWER_3D, UPPER_3D)
    p = np.random.default_rng(0).uniform(-1, 1, (200, 2))
    full = np.column_stack([p, np.full(200, 0.5)])
    np.testing.assert_array_equal(
        held.clearance(p, grasped=False), WALL_3D.clearance(full, grasped=False)
    )
    assert held.n_joints == 2
    assert held.stretch == 1.0
    np.testing.assert_array_equal(held.project(full), p)


def test_a_planned_path_keeps_the_held_joint_and_its_clearance() -> None:
    held = JointSubspace.holding(WALL_3D, [2], [0.5], LOWER_3D, UPPER_3D)
    start, goal = np.array([-0.5, 0.0]), np.array([0.5, 0.1])
    result = plan_segment(
        start, goal[None], held, [-1.0, -1.0], [1.0, 1.0], lipschitz=LIPSCHITZ, margin_m=MARGIN_M
    )
    path = held.full(result.path)
    assert np.all(path[:, 2] == 0.5)
    assert np.abs(path[:, 1]).max() > 0.8  # around the wall
    for a, b in itertools.pairwise(path):
        assert dense_edge_clearance(WALL_3D, a, b) >= 0.5 * MARGIN_M


def test_a_tied_joint_stays_tied_and_the_box_binds() -> None:
    """The plane z = -x - y, planned with the stretch in the Lipschitz constant."""
    basis = [[1.0, 0.0], [0.0, 1.0], [-1.0, -1.0]]
    tied = JointSubspace(WALL_3D, basis, np.zeros(3), LOWER_3D, UPPER_3D)
    assert tied.stretch == pytest.approx(np.sqrt(3.0))
    outside = tied.clearance(np.array([[0.9, 0.9]]), grasped=False)  # z = -1.8: out of the box
    assert outside[0] == -np.inf
    start, goal = np.array([-0.5, 0.0]), np.array([0.5, -0.1])
    result = plan_segment(
        start,
        goal[None],
        tied,
        [-1.0, -1.0],
        [1.0, 1.0],
        lipschitz=LIPSCHITZ * tied.stretch,
        margin_m=MARGIN_M,
    )
    path = tied.full(result.path)
    np.testing.assert_allclose(path[:, 2], -path[:, 0] - path[:, 1], atol=1e-15)
    assert (np.abs(path) <= 1.0).all()
    for a, b in itertools.pairwise(path):
        assert dense_edge_clearance(WALL_3D, a, b) >= 0.5 * MARGIN_M


@pytest.mark.parametrize(
    ("fixed", "values", "error"),
    [
        ([3], [0.0], InvalidInputError),
        ([0, 0], [0.0, 1.0], InvalidInputError),
        ([0, 1, 2], [0.0, 0.0, 0.0], InvalidInputError),
        ([0], [0.0, 1.0], InvalidInputError),
        ([0], [float("nan")], NonFiniteInputError),
    ],
)
def test_bad_holds_are_refused(
    fixed: list[int], values: list[float], error: type[Exception]
) -> None:
    with pytest.raises(error):
        JointSubspace.holding(WALL_3D, fixed, values, LOWER_3D, UPPER_3D)


@pytest.mark.parametrize(
    ("basis", "offset", "match"),
    [
        ([[1.0], [1.0]], np.zeros(3), "basis must have shape"),
        ([[1.0, 2.0], [2.0, 4.0], [0.0, 0.0]], np.zeros(3), "full column rank"),
        ([[1.0], [0.0], [0.0]], np.zeros(2), "offset must have shape"),
    ],
)
def test_bad_subspaces_are_refused(
    basis: list[list[float]], offset: np.ndarray, match: str
) -> None:
    with pytest.raises(InvalidInputError, match=match):
        JointSubspace(WALL_3D, basis, offset, LOWER_3D, UPPER_3D)
