"""The certified edge check: accepted edges keep half the margin everywhere."""

from __future__ import annotations

import numpy as np
from hypothesis import given
from hypothesis import strategies as st

from lynxsim.plan import check_edges, check_path
from tests.plan.worlds import DENSE_POINTS, LIPSCHITZ, MARGIN_M, WALL, Boxes, Spheres

EDGE_POINTS = st.lists(st.floats(-1.0, 1.0), min_size=4, max_size=4)


@given(st.lists(EDGE_POINTS, min_size=1, max_size=20))
def test_accepted_edges_keep_half_the_margin_everywhere(rows):
    e = np.array(rows)
    world = Spheres([[0.1, 0.0], [-0.4, 0.5]], [0.3, 0.2])
    verdict = check_edges(
        e[:, :2], e[:, 2:], world, lipschitz=LIPSCHITZ, margin_m=MARGIN_M, grasped=False
    )
    u = np.linspace(0.0, 1.0, DENSE_POINTS)[:, None, None]
    dense = world.clearance(
        (e[None, :, :2] + u * (e[None, :, 2:] - e[None, :, :2])).reshape(-1, 2), grasped=False
    ).reshape(DENSE_POINTS, -1)
    for k in np.flatnonzero(verdict.clear):
        assert dense[:, k].min() >= 0.5 * MARGIN_M
        assert verdict.bound_m[k] >= 0.5 * MARGIN_M
        assert dense[:, k].min() >= verdict.bound_m[k]
    # An edge that touches an obstacle is never accepted.
    crossing = dense.min(axis=0) <= 0.0
    assert not (verdict.clear & crossing).any()


def test_an_edge_through_a_wall_is_refused_and_one_beside_it_accepted():
    starts = np.array([[-0.5, 0.0], [-0.5, 0.9]])
    ends = np.array([[0.5, 0.0], [0.5, 0.9]])
    verdict = check_edges(starts, ends, WALL, lipschitz=LIPSCHITZ, margin_m=MARGIN_M, grasped=False)
    assert verdict.clear.tolist() == [False, True]
    assert verdict.bound_m[0] == -np.inf
    assert verdict.min_clearance_m[0] < MARGIN_M


def test_a_free_edge_needs_few_points_and_a_tight_one_many():
    far = Boxes([[5.0, 5.0]], [[0.1, 0.1]])
    free = check_edges(
        np.array([[-1.0, -1.0]]),
        np.array([[1.0, 1.0]]),
        far,
        lipschitz=LIPSCHITZ,
        margin_m=MARGIN_M,
        grasped=False,
    )
    assert free.clear[0]
    assert free.queries <= 4  # ends plus at most two rounds
    tight = check_edges(
        np.array([[-0.5, 0.8 + 2 * MARGIN_M]]),
        np.array([[0.5, 0.8 + 2 * MARGIN_M]]),
        WALL,
        lipschitz=LIPSCHITZ,
        margin_m=MARGIN_M,
        grasped=False,
    )
    assert tight.clear[0]
    assert tight.queries > 10


def test_a_zero_length_edge_is_its_point():
    q = np.array([[0.5, 0.5]])
    verdict = check_path(q, WALL, lipschitz=LIPSCHITZ, margin_m=MARGIN_M, grasped=False)
    assert verdict.clear.tolist() == [True]
    inside = np.array([[0.0, 0.0]])
    verdict = check_path(inside, WALL, lipschitz=LIPSCHITZ, margin_m=MARGIN_M, grasped=False)
    assert verdict.clear.tolist() == [False]
