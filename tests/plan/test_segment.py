"""One segment planned with real OMPL in fake worlds: paths, errors, determinism, shortening."""

from __future__ import annotations

import itertools

import numpy as np
import pytest

import lynxsim.plan.segment as segment_module
from lynxsim.errors import InvalidInputError, LynxsimError
from lynxsim.plan import (
    PLANNERS,
    GoalsInCollisionError,
    NoPathError,
    StartInCollisionError,
    UnknownPlannerError,
    check_path,
    path_length,
    plan_segment,
    shorten_path,
)
from tests.plan.worlds import (
    ENCLOSED_GOAL,
    LIPSCHITZ,
    LOWER_2D,
    MARGIN_M,
    UPPER_2D,
    WALL,
    dense_edge_clearance,
)

LEFT = np.array([-0.5, 0.0])
RIGHT = np.array([0.5, 0.2])


def plan(start=LEFT, goals=RIGHT, world=WALL, **kwargs):
    options = {"lipschitz": LIPSCHITZ, "margin_m": MARGIN_M, "seed": 1, **kwargs}
    return plan_segment(start, np.atleast_2d(goals), world, LOWER_2D, UPPER_2D, **options)


def test_a_path_around_the_wall_keeps_half_the_margin_on_every_edge():
    result = plan()
    path = result.path
    assert result.planner == "RRTConnect"
    assert np.array_equal(path[0], LEFT)
    assert np.array_equal(path[-1], RIGHT)
    assert path.shape[0] >= 3  # the straight line is blocked
    for a, b in itertools.pairwise(path):
        assert dense_edge_clearance(WALL, a, b) >= 0.5 * MARGIN_M
    assert result.clearance_bound_m >= 0.5 * MARGIN_M
    assert result.min_clearance_m >= MARGIN_M
    assert result.length_rad == pytest.approx(path_length(path), rel=1e-12)
    assert 0.0 < result.planning_time_s < 5.0


def test_every_edge_the_planner_accepts_is_clear_when_rechecked_densely(monkeypatch):
    accepted = []
    original = segment_module.check_edges

    def spy(starts, ends, *args, **kwargs):
        verdict = original(starts, ends, *args, **kwargs)
        accepted.extend(zip(starts[verdict.clear], ends[verdict.clear]))
        return verdict

    monkeypatch.setattr(segment_module, "check_edges", spy)
    plan(shortcuts=0)
    assert len(accepted) > 10
    worst = min(dense_edge_clearance(WALL, a, b) for a, b in accepted)
    assert worst >= 0.5 * MARGIN_M


def test_same_inputs_and_seed_give_the_same_path_bit_for_bit():
    first, second = plan(seed=7), plan(seed=7)
    assert first.path.tobytes() == second.path.tobytes()
    other = plan(seed=8)
    assert other.path.tobytes() != first.path.tobytes()


def test_a_clear_straight_edge_skips_the_search():
    result = plan(goals=[-0.5, 0.5])
    assert result.planner == "direct"
    assert result.path.shape == (2, 2)


def test_of_several_goals_one_valid_is_reached():
    goals = np.array([[0.0, 0.0], [0.5, -0.3], [0.6, 0.6]])  # the first lies in the wall
    result = plan(goals=goals)
    assert result.goal_index in (1, 2)
    assert np.array_equal(result.path[-1], goals[result.goal_index])


# The anytime planners use their whole wall-clock budget, so theirs is short; FMT* stops at its
# first solution but needs its batch of samples, which a loaded machine may not give it in 0.3 s.
@pytest.mark.parametrize(
    ("name", "time_limit_s"),
    [("RRT", 0.3), ("RRTstar", 0.3), ("BITstar", 0.3), ("AORRTC", 0.3), ("FMT", 5.0)],
)
def test_other_ompl_planners_find_a_clear_path(name, time_limit_s):
    result = plan(planner=name, time_limit_s=time_limit_s)
    assert result.planner == name
    assert check_path(
        result.path, WALL, lipschitz=LIPSCHITZ, margin_m=MARGIN_M, grasped=False
    ).clear.all()


def test_an_unknown_planner_lists_the_valid_ones():
    with pytest.raises(UnknownPlannerError, match="unknown planner 'RRTfast'; valid planners: "):
        plan(planner="RRTfast")
    assert isinstance(UnknownPlannerError("x", PLANNERS), InvalidInputError)
    with pytest.raises(UnknownPlannerError, match=r"'PRM' \(it calls the edge check from a second"):
        plan(planner="PRM")


def test_a_start_in_collision_is_refused_with_its_clearance():
    with pytest.raises(
        StartInCollisionError, match=r"segment 'reach': the start .* clearance -0\.05 m"
    ) as info:
        plan(start=[0.0, 0.0], label="reach")
    assert info.value.clearance_m == pytest.approx(-0.05)
    assert info.value.label == "reach"


def test_goals_all_in_collision_are_refused():
    with pytest.raises(GoalsInCollisionError, match="all 2 goal candidates have clearance") as info:
        plan(goals=[[0.0, 0.0], [0.0, 0.5]])
    assert info.value.clearances_m.shape == (2,)


def test_an_unreachable_goal_runs_out_of_time():
    with pytest.raises(NoPathError, match=r"segment 'into the box': RRTConnect found no .* 0\.2 s"):
        plan(goals=[0.5, 0.5], world=ENCLOSED_GOAL, time_limit_s=0.2, label="into the box")
    assert issubclass(NoPathError, LynxsimError)


def test_malformed_inputs_are_refused():
    with pytest.raises(InvalidInputError, match="outside the joint box"):
        plan(start=[2.0, 0.0])
    with pytest.raises(InvalidInputError, match=r"goals must have shape \(K, 2\)"):
        plan(goals=[[0.1, 0.2, 0.3]])
    with pytest.raises(InvalidInputError, match="seed must be an integer"):
        plan(seed=-1)
    with pytest.raises(InvalidInputError, match="lipschitz must be positive"):
        plan(lipschitz=0.0)


@pytest.mark.parametrize("seed", range(5))
def test_shortening_never_lengthens_and_stays_clear(seed):
    raw = plan(seed=seed, shortcuts=0).path
    short = shorten_path(
        raw,
        WALL,
        lipschitz=LIPSCHITZ,
        margin_m=MARGIN_M,
        grasped=False,
        rng=np.random.default_rng(seed),
    )
    assert path_length(short) <= path_length(raw)
    assert np.array_equal(short[0], raw[0])
    assert np.array_equal(short[-1], raw[-1])
    for a, b in itertools.pairwise(short):
        assert dense_edge_clearance(WALL, a, b) >= 0.5 * MARGIN_M
