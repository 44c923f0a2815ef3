"""The trajectory layer knows no robot: any number of joints, bounds and limits as arguments."""

from __future__ import annotations

import numpy as np
import pytest

from lynxsim.errors import InvalidInputError, JointRangeError, LimitViolationError
from lynxsim.traj import (
    JOINT_KINDS,
    JointBounds,
    JointLimits,
    Trajectory,
    TrajectoryKind,
    Waypoints,
    check_trajectory,
    generate,
    lspb,
    quintic,
    resolve_waypoints,
)
from lynxsim.traj.check import LIMIT_RTOL
from tests.helpers import assert_close

POS_TOL = 1e-8
"""Waypoints are hit to this [rad] (Ruckig meets its targets to ~1e-8)."""


def _robot(n: int) -> tuple[JointBounds, JointLimits]:
    names = tuple(f"j{i + 1}" for i in range(n))
    bounds = JointBounds(names, (-2.0,) * n, (2.0,) * n)
    limits = JointLimits(velocity=np.linspace(1.0, 2.0, n), acceleration=5.0, jerk=50.0)
    return bounds, limits


@pytest.mark.parametrize("n", [1, 2, 7])
@pytest.mark.parametrize("kind", JOINT_KINDS, ids=lambda k: k.value)
def test_every_joint_type_moves_any_number_of_joints_within_its_limits(kind, n):
    bounds, limits = _robot(n)
    rng = np.random.default_rng(n)
    q = rng.uniform(-1.5, 1.5, (4, n))
    traj = generate(kind, q, bounds=bounds, limits=limits)
    assert traj.n_joints == n
    assert traj.bounds is bounds
    assert traj.waypoints.names == ("P1", "P2", "P3", "P4")
    assert_close(traj.sample(traj.waypoint_times).q, q, atol=POS_TOL)
    states = traj.sample(np.linspace(0.0, traj.duration, 2001))
    assert states.q.shape == (2001, n)
    assert (states.q >= -2.0 - POS_TOL).all()
    assert (states.q <= 2.0 + POS_TOL).all()
    for order in kind.limited_orders:
        assert (np.abs(states[order]) <= limits.of_order(order) * (1 + LIMIT_RTOL)).all()


@pytest.mark.parametrize(
    ("kind", "where"),
    [("line", r"lynxsim\.arm\.motion"), ("planned", r"lynxsim\.robots\.plan")],
)
def test_types_that_need_a_robot_are_refused_with_where_they_are_built(kind, where):
    bounds, limits = _robot(2)
    with pytest.raises(InvalidInputError, match=where):
        generate(kind, np.zeros((2, 2)), 1.0, bounds=bounds, limits=limits)


def test_messages_name_the_robots_own_joints():
    bounds = JointBounds(("slide", "swing"), (-1.0, -1.0), (1.0, 1.0))
    limits = JointLimits.for_joints(2, 1.0, 1.0, 1.0)
    with pytest.raises(
        JointRangeError,
        match=r"waypoint B: joint 2 \(swing\) = 85\.94 deg is outside its range \[-57\.3, 57\.3\]",
    ):
        quintic(Waypoints(np.array([[0.0, 0.0], [0.0, 1.5]]), ("A", "B")), bounds=bounds,
                limits=limits)  # fmt: skip
    with pytest.raises(LimitViolationError, match=r"^lspb trajectory: joint 1 \(slide\) velocity"):
        lspb(np.array([[-0.9, 0.0], [0.9, 0.0]]), 0.5, bounds=bounds, limits=limits)


def test_the_check_reads_the_trajectorys_own_bounds():
    bounds, limits = _robot(3)
    traj = quintic(np.array([[0.0, 0.0, 0.0], [1.0, -1.0, 1.9]]), 2.0, bounds=bounds,
                   limits=limits)  # fmt: skip
    check_trajectory(traj)
    narrow = JointBounds(bounds.names, (-1.0,) * 3, (1.0,) * 3)
    moved = Trajectory(traj.kind, traj.segments, traj.waypoints, narrow, limits)
    with pytest.raises(LimitViolationError, match=r"joint 3 \(j3\) reaches 108\.9 deg"):
        check_trajectory(moved)


def test_parts_of_different_joint_counts_are_refused():
    bounds, limits = _robot(2)
    with pytest.raises(InvalidInputError, match="limits of 3 joints for bounds of 2 joints"):
        quintic(np.zeros((2, 2)), 1.0, bounds=bounds, limits=_robot(3)[1])
    with pytest.raises(InvalidInputError, match=r"joint waypoints must have shape \(N, 2\)"):
        quintic(np.zeros((2, 3)), 1.0, bounds=bounds, limits=limits)
    with pytest.raises(InvalidInputError, match="waypoints of 3 joints, but the bounds are for 2"):
        resolve_waypoints(Waypoints(np.zeros((2, 3)), ("a", "b")), bounds)
    traj = quintic(np.array([[0.0, 0.0], [1.0, 1.0]]), 3.0, bounds=bounds, limits=limits)
    with pytest.raises(InvalidInputError, match="bounds of 3 joints, limits of 2"):
        Trajectory(TrajectoryKind.QUINTIC, traj.segments, traj.waypoints, _robot(3)[0], limits)


def test_waypoints_validate_their_joints_and_names():
    with pytest.raises(InvalidInputError, match=r"shape \(N, n\), N >= 2"):
        Waypoints(np.zeros((1, 3)), ("a",))
    with pytest.raises(InvalidInputError, match="a tuple of 2 strings"):
        Waypoints(np.zeros((2, 3)), ("a",))
    wp = Waypoints(np.zeros((2, 3)), ("a", "b"))
    assert not wp.q.flags.writeable
    assert wp.n_joints == 3
