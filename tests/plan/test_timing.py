"""A task planned through several segments and timed by Ruckig: clear, within limits, stopping."""

from __future__ import annotations

import numpy as np
import pytest

from lynxsim.arm.motion import ARM_BOUNDS, ARM_LIMITS
from lynxsim.plan import PlanProgress, plan_through, time_paths
from lynxsim.traj import JointBounds, JointLimits, TrajectoryKind
from lynxsim.traj.check import LIMIT_RTOL
from tests.plan.worlds import LIPSCHITZ, LOWER_2D, MARGIN_M, UPPER_2D, WALL, Spheres

LOWER, UPPER = ARM_BOUNDS.lower_array, ARM_BOUNDS.upper_array
MIDDLE = 0.5 * (LOWER + UPPER)
BALL = Spheres([MIDDLE], [0.5])
"""A 5-D ball in the middle of the arm's joint box; the first segment must go around it."""

START = MIDDLE - np.array([1.0, 0.0, 0.0, 0.0, 0.0])
BEYOND = MIDDLE + np.array([1.0, 0.0, 0.0, 0.0, 0.0])
LIFTED = MIDDLE + np.array([0.0, 0.9, 0.0, 0.0, 0.0])
DENSE_DT_S = 1e-4
"""Time step of the dense re-check of the timed motion [s]."""
REST_TOL = 1e-6
"""Joint speed that counts as stopped [rad/s]."""


@pytest.fixture(scope="module")
def motion():
    reports: list[PlanProgress] = []
    result = plan_through(
        [BEYOND[None], np.array([LIFTED, LIFTED + 0.05])],
        START,
        BALL,
        [False, True],
        LOWER,
        UPPER,
        lipschitz=LIPSCHITZ,
        margin_m=MARGIN_M,
        seed=3,
        labels=["carry", "lift"],
        bounds=ARM_BOUNDS,
        limits=ARM_LIMITS,
        progress=reports.append,
    )
    return result, reports


def test_the_timed_motion_passes_through_clear_space(motion):
    result, _ = motion
    traj = result.trajectory
    t = np.arange(0.0, traj.duration, DENSE_DT_S)
    clearance = BALL.clearance(traj.sample(t).q, grasped=False)
    assert clearance.min() >= 0.25 * MARGIN_M  # the guarantee between checked samples
    for timed in result.timing:
        assert timed.min_clearance_m >= 0.5 * MARGIN_M
        assert timed.clearance_bound_m >= 0.25 * MARGIN_M


def test_the_motion_starts_stops_and_ends_where_planned(motion):
    result, _ = motion
    traj = result.trajectory
    first, second = result.segments
    assert np.array_equal(first.path[-1], BEYOND)
    assert np.array_equal(second.path[0], BEYOND)
    ends = [0.0, result.timing[0].end_s, traj.duration]
    sample = traj.sample(np.array(ends))
    np.testing.assert_allclose(sample.q[0], START, atol=1e-12)
    np.testing.assert_allclose(sample.q[1], BEYOND, atol=1e-7)
    np.testing.assert_allclose(sample.q[2], second.path[-1], atol=1e-7)
    assert np.abs(sample.qd).max() <= REST_TOL


def test_the_motion_keeps_the_joint_limits(motion):
    traj = motion[0].trajectory
    assert traj.kind is TrajectoryKind.RUCKIG
    t = np.arange(0.0, traj.duration, DENSE_DT_S)
    s = traj.sample(t)
    for order, values in ((1, s.qd), (2, s.qdd), (3, s.qddd)):
        limit = ARM_LIMITS.of_order(order) * (1.0 + LIMIT_RTOL)
        assert (np.abs(values) <= limit).all()
    assert (s.q >= LOWER).all()
    assert (s.q <= UPPER).all()


def test_segments_report_their_planning_and_grasp(motion):
    result, reports = motion
    first, second = result.segments
    assert first.planner == "RRTConnect"
    assert not first.grasped
    assert second.planner == "direct"
    assert second.grasped
    assert first.length_rad <= first.raw_length_rad
    assert BALL.grasped_calls > 0
    stages = [(r.segment, r.stage) for r in reports]
    assert stages[0] == (0, "planning")
    assert (1, "planning") in stages
    assert stages[-2:] == [(2, "timing"), (2, "done")]
    assert [r.label for r in reports if r.stage == "planning"] == ["carry", "lift"]


def test_the_same_seed_gives_the_same_trajectory():
    def run():
        return plan_through(
            [BEYOND[None]],
            START,
            BALL,
            [False],
            LOWER,
            UPPER,
            lipschitz=LIPSCHITZ,
            margin_m=MARGIN_M,
            seed=11,
            bounds=ARM_BOUNDS,
            limits=ARM_LIMITS,
        ).trajectory

    a, b = run(), run()
    t = np.linspace(0.0, a.duration, 101)
    assert a.duration == b.duration
    assert a.sample(t).q.tobytes() == b.sample(t).q.tobytes()


def test_a_robot_of_two_joints_is_planned_and_timed_with_its_own_bounds_and_limits():
    """The planner knows no robot: a 2-joint world, bounds and limits given as arguments."""
    bounds = JointBounds(("x", "y"), tuple(LOWER_2D), tuple(UPPER_2D))
    limits = JointLimits.for_joints(2, 1.0, 4.0, 40.0)
    result = plan_through(
        [np.array([[0.5, 0.2]])],
        np.array([-0.5, 0.0]),
        WALL,
        [False],
        LOWER_2D,
        UPPER_2D,
        lipschitz=LIPSCHITZ,
        margin_m=MARGIN_M,
        seed=2,
        bounds=bounds,
        limits=limits,
        pose_names=["start", "goal"],
    )
    traj = result.trajectory
    assert traj.n_joints == 2
    assert traj.bounds is bounds
    assert traj.waypoints.names[0] == "start"
    assert traj.waypoints.names[-1] == "goal"
    t = np.arange(0.0, traj.duration, 1e-3)
    s = traj.sample(t)
    assert WALL.clearance(s.q, grasped=False).min() >= 0.25 * MARGIN_M
    assert (np.abs(s.qd) <= 1.0 * (1.0 + LIMIT_RTOL)).all()
    np.testing.assert_allclose(s.q[0], [-0.5, 0.0], atol=1e-12)


class _Lowered:
    """A world never above BALL: its clearance less a fixed, varying amount."""

    n_joints = 5

    def clearance(self, q: np.ndarray, *, grasped: bool) -> np.ndarray:
        exact = BALL.clearance(q, grasped=grasped)
        return exact - 0.004 * (1.0 + np.sin(7.0 * q.sum(axis=1)))


def test_a_screening_world_gives_the_same_timed_motion_for_fewer_exact_checks(motion):
    result, _ = motion
    paths = [s.path for s in result.segments]
    grasped = [s.grasped for s in result.segments]

    class Counting:
        n_joints = 5
        asked = 0

        def clearance(self, q: np.ndarray, *, grasped: bool) -> np.ndarray:
            Counting.asked += len(q)
            return BALL.clearance(q, grasped=grasped)

    plain = time_paths(paths, grasped, BALL, lipschitz=LIPSCHITZ, margin_m=MARGIN_M,
                       bounds=ARM_BOUNDS, limits=ARM_LIMITS)  # fmt: skip
    screened = time_paths(paths, grasped, Counting(), lipschitz=LIPSCHITZ, margin_m=MARGIN_M,
                          bounds=ARM_BOUNDS, limits=ARM_LIMITS, screen=_Lowered())  # fmt: skip
    assert screened.segments == plain.segments  # minimum, bound, samples, stops: all exact
    t = np.linspace(0.0, plain.trajectory.duration, 501)
    assert np.array_equal(screened.trajectory.sample(t).q, plain.trajectory.sample(t).q)
    assert 0 < Counting.asked < sum(s.samples for s in plain.segments)
