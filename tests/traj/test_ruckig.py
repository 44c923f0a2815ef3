"""Ruckig segments chained offline: conversion, passing through, limits, durations."""

from __future__ import annotations

import inspect

import numpy as np
import pytest
import ruckig

from lynxsim.arm import LYNX_ARM
from lynxsim.arm.motion import ARM_LIMITS, JointPose, ruckig_trajectory
from lynxsim.errors import SegmentDurationError
from lynxsim.traj import ruckig_profile
from lynxsim.traj.ruckig_profile import profile_segment
from tests.helpers import assert_close

PROFILE_TOL = 1e-9
"""The piecewise cubic against Ruckig's own ``at_time`` [rad, rad/s, rad/s^2]."""

REPORT_Q = np.radians(
    [
        [90.0, 15.89, -18.47, -87.42, 0.0],
        [90.0, 80.38, -46.11, -34.27, 0.0],
        [0.0, 80.38, -46.11, -34.27, 0.0],
        [-90.0, 80.38, -46.11, -34.27, 0.0],
        [-90.0, 15.89, -18.47, -87.42, 0.0],
    ]
)


def _random_ruckig(rng: np.random.Generator) -> ruckig.Trajectory:
    """A Ruckig segment between random in-range states, target moving."""
    inp = ruckig.InputParameter(5)
    inp.current_position = rng.uniform(LYNX_ARM.lower, LYNX_ARM.upper).tolist()
    inp.target_position = rng.uniform(LYNX_ARM.lower, LYNX_ARM.upper).tolist()
    inp.target_velocity = (rng.uniform(-0.5, 0.5, 5) * ARM_LIMITS.velocity).tolist()
    inp.max_velocity = list(ARM_LIMITS.velocity)
    inp.max_acceleration = list(ARM_LIMITS.acceleration)
    inp.max_jerk = list(ARM_LIMITS.jerk)
    out = ruckig.Trajectory(5)
    ruckig.Ruckig(5).calculate(inp, out)
    return out


def test_piecewise_cubic_equals_ruckig_at_time():
    rng = np.random.default_rng(7)
    for _ in range(50):
        plan = _random_ruckig(rng)
        segment = profile_segment(plan)
        assert segment.duration == plan.duration
        t = np.linspace(0.0, plan.duration, 400)
        ours = segment.evaluate(t)
        theirs = np.array([plan.at_time(x) for x in t])  # (n, 3, 5)
        for order in range(3):
            assert_close(ours[order], theirs[:, order], atol=PROFILE_TOL)


def test_passing_through_keeps_the_base_moving_at_p3():
    stop = ruckig_trajectory(REPORT_Q)
    through = ruckig_trajectory(REPORT_Q, pass_through=True)
    qd_p3 = through.sample(through.waypoint_times[2]).qd
    assert abs(qd_p3[0]) > 0.5  # the base sweeps from 90 to -90 deg without stopping
    assert_close(qd_p3[1:], 0.0, atol=1e-9)  # the other joints stay put around P3
    assert through.duration < stop.duration


def test_via_velocity_that_would_overshoot_a_range_is_dropped():
    # Durations too short for the limits give high via speeds; stretched, the elbow
    # would back up below its -145 deg limit for a run-up to its via speed, so it
    # stops at the via point instead while the wrist still passes through.
    q = np.radians(
        [
            [-46.0, 40.0, -143.0, 37.0, 0.0],
            [44.0, 5.0, -124.0, 88.0, 0.0],
            [-82.0, 131.0, -8.0, 88.2, 0.0],
        ]
    )
    traj = ruckig_trajectory(q, [0.088, 0.287], stretch=True, pass_through=True)
    at_via = traj.sample(traj.waypoint_times[1]).qd
    assert at_via[2] == 0.0
    assert at_via[3] > 0.0
    q_dense = traj.sample(np.linspace(0.0, traj.duration, 5001)).q
    assert (q_dense >= LYNX_ARM.lower - 1e-9).all()
    assert (q_dense <= LYNX_ARM.upper + 1e-9).all()


def test_given_durations_are_minimum_durations():
    traj = ruckig_trajectory(REPORT_Q, durations=2.0)
    assert_close(traj.segment_durations, 2.0, atol=1e-9)


def test_duration_shorter_than_time_optimal_names_segment_and_joint():
    names = ["P1", "P2", "P3", "P4", "P5"]
    poses = [JointPose(tuple(q), n) for q, n in zip(REPORT_Q, names)]
    optimal = ruckig_trajectory(poses).segment_durations
    with pytest.raises(
        SegmentDurationError,
        match=r"^ruckig trajectory: segment 1 \(P1 -> P2\) needs 0\.6525 s within the limits, "
        r"given 0\.5 s; joint 4 \(wrist_pitch\) needs the most time",
    ) as info:
        ruckig_trajectory(poses, durations=0.5)
    assert (info.value.segment, info.value.joint) == (0, 4)
    assert info.value.required == pytest.approx(optimal[0])
    stretched = ruckig_trajectory(poses, durations=0.5, stretch=True)
    assert_close(stretched.segment_durations, np.maximum(optimal, 0.5), atol=1e-9)


def test_waypoints_are_never_sent_to_ruckigs_cloud_waypoints():
    source = inspect.getsource(ruckig_profile)
    assert ".intermediate_positions" not in source.replace("``intermediate_positions``", "")


def test_move_on_a_ruckig_profile_boundary_still_plans():
    # The base's 16 deg second move lies exactly on the boundary between two of
    # Ruckig's profile types under the default limits (a/j = 0.1 s, 4 a/j = 0.4 s),
    # where Ruckig 0.19 fails to solve for some starts one ulp apart.
    q = np.radians(
        [
            [62.0, 110.0, -136.0, -16.0, 0.0],
            [-76.0, 130.0, -57.0, -57.0, 0.0],
            [-60.0, 131.0, -144.0, 61.0, 0.0],
        ]
    )
    traj = ruckig_trajectory(q)
    assert_close(traj.sample(traj.waypoint_times).q, q, atol=1e-8)
