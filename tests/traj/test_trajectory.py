"""The trajectory type: sampling by time across segments, grids, validation."""

from __future__ import annotations

import numpy as np
import pytest

from lynxsim.arm.motion import free_motion, quintic
from lynxsim.errors import InvalidInputError, NonFiniteInputError
from lynxsim.traj import PolynomialSegment, Trajectory
from tests.helpers import assert_close

Q = np.radians(
    [
        [0.0, 60.0, -60.0, 0.0, 0.0],
        [40.0, 90.0, -30.0, 20.0, 90.0],
        [-20.0, 45.0, -90.0, -30.0, 180.0],
    ]
)


@pytest.fixture
def traj() -> Trajectory:
    return quintic(Q, durations=[1.0, 1.5])


def test_sample_shapes_follow_the_time_array(traj):
    assert traj.sample(0.5).q.shape == (5,)
    assert traj.sample(np.linspace(0, 2.5, 7)).qd.shape == (7, 5)
    assert traj.sample(np.zeros((2, 3))).qddd.shape == (2, 3, 5)
    assert traj.sample(np.array([])).q.shape == (0, 5)


def test_unsorted_times_give_the_same_states(traj):
    t = np.random.default_rng(0).uniform(0.0, traj.duration, 200)
    ordered = np.sort(t)
    a, b = traj.sample(t), traj.sample(ordered)
    position = np.searchsorted(ordered, t)
    for x, y in zip(a, b):
        assert_close(x, y[position], atol=0.0)


def test_a_waypoint_time_belongs_to_the_segment_that_starts_there():
    traj = free_motion(Q, durations=[1.0, 1.5])
    qd = traj.sample(np.array([1.0])).qd[0]
    assert_close(qd, (Q[2] - Q[1]) / 1.5, atol=1e-12)


def test_times_outside_the_trajectory_are_refused(traj):
    with pytest.raises(InvalidInputError, match=r"sample times must lie in \[0, 2\.5\] s"):
        traj.sample([0.0, 2.6])
    with pytest.raises(InvalidInputError):
        traj.sample(-0.1)
    with pytest.raises(NonFiniteInputError):
        traj.sample([0.1, np.nan])
    assert_close(traj.sample(2.5 * (1 + 1e-12)).q, Q[-1], atol=1e-12)  # rounding slack


def test_waypoint_times_and_durations(traj):
    assert_close(traj.waypoint_times, [0.0, 1.0, 2.5], atol=0.0)
    assert_close(traj.segment_durations, [1.0, 1.5], atol=0.0)
    assert traj.duration == 2.5


def test_times_at_rate_is_uniform_and_stays_within_the_duration(traj):
    t = traj.times_at_rate(500.0)
    assert t.size == 1251
    assert t[0] == 0.0
    assert t[-1] == 2.5
    assert_close(np.diff(t), 1 / 500.0, atol=1e-12)
    t = traj.times_at_rate(3.0)
    assert_close(t, [0.0, 1 / 3, 2 / 3, 1.0, 4 / 3, 5 / 3, 2.0, 7 / 3], atol=1e-12)
    with pytest.raises(
        InvalidInputError, match=r"rate_hz must be between 1 and 10000 Hz, got 0 Hz"
    ):
        traj.times_at_rate(0.0)


def test_times_per_segment_is_the_reports_grid(traj):
    t = traj.times_per_segment(10)
    assert t.size == 21
    assert_close(t[::10], traj.waypoint_times, atol=1e-12)
    assert_close(np.diff(t[:11]), 0.1, atol=1e-12)
    assert_close(np.diff(t[10:]), 0.15, atol=1e-12)
    with pytest.raises(InvalidInputError, match=r"steps must be between 1 and 4,999,999, got 0"):
        traj.times_per_segment(0)


def test_results_are_read_only(traj):
    assert not traj.waypoints.q.flags.writeable
    assert not traj.waypoint_times.flags.writeable
    with pytest.raises(AttributeError):
        traj.kind = "cubic"  # type: ignore[misc]


def test_polynomial_segment_validates_its_pieces():
    with pytest.raises(InvalidInputError, match="breaks must increase from 0"):
        PolynomialSegment(np.array([0.0, 1.0, 1.0]), np.zeros((2, 2, 5)))
    with pytest.raises(InvalidInputError, match=r"coefficients must have shape \(2, D \+ 1, n\)"):
        PolynomialSegment(np.array([0.0, 1.0, 2.0]), np.zeros((1, 2, 5)))


def test_piecewise_segment_evaluates_each_piece_in_its_own_time():
    # q = t^2 on [0, 1], then 1 + 2 (t - 1) on [1, 2], for every joint.
    c = np.zeros((2, 3, 5))
    c[0, 2] = 1.0
    c[1, 0], c[1, 1] = 1.0, 2.0
    segment = PolynomialSegment(np.array([0.0, 1.0, 2.0]), c)
    x = segment.evaluate(np.array([0.5, 1.0, 1.5, 2.0]))
    assert_close(x[0, :, 0], [0.25, 1.0, 2.0, 3.0], atol=1e-15)
    assert_close(x[1, :, 0], [1.0, 2.0, 2.0, 2.0], atol=1e-15)
    assert_close(x[2, :, 0], [2.0, 0.0, 0.0, 0.0], atol=1e-15)


def test_segment_count_must_match_the_waypoints(traj):
    with pytest.raises(InvalidInputError, match="3 waypoints need 2 segments, got 1"):
        Trajectory(traj.kind, traj.segments[:1], traj.waypoints, traj.bounds, traj.limits)
