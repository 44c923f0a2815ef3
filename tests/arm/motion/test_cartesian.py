"""Straight tool lines: IK at every sample, exact joint rates, typed failures."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pytest

from lynxsim.arm import LYNX_ARM, ik, tool_pose
from lynxsim.arm.motion import ArmPose, LineSegment, cartesian_line
from lynxsim.arm.motion.cartesian import _branch
from lynxsim.errors import LimitViolationError, OutOfReachError, PathError
from lynxsim.reproduce.arm_tables import TABLE4
from lynxsim.robots.arm import build_trajectory
from lynxsim.tasks import load_task
from lynxsim.traj import TrajectoryKind
from lynxsim.traj.polynomial import quintic_scaling
from tests.arm.motion.cases import LINE_LOWER, LINE_UPPER, as_poses, assert_straight
from tests.helpers import assert_close

TASKS = Path(__file__).resolve().parents[3] / "tasks"

IK_TOL = 1e-12
"""Joints of the line's closed form against lynxsim.arm.ik [rad]."""

FD_RTOL = 1e-5
"""Analytic joint rates against central finite differences, relative [-]."""

REPORT_POSES = [
    ArmPose(tuple(v * 1e-3 for v in row.position_mm), np.radians(row.pitch_deg), None, row.name)
    for row in TABLE4
]


def _random_segments(n: int, seed: int) -> list[LineSegment]:
    """Random lines between reachable poses that stay in reach, each 1.7 s long."""
    rng = np.random.default_rng(seed)
    out = []
    while len(out) < n:
        a, b = as_poses(rng.uniform(LINE_LOWER, LINE_UPPER, (2, 5)))
        q = ik(np.asarray(a.position), a.pitch, a.roll).q
        segment = LineSegment(a, b, 1.7, _branch(q, a, "P1", LYNX_ARM))
        if np.abs(segment.states(np.linspace(0.0, 1.7, 201))[1]).max() <= 1.0:
            out.append(segment)
    return out


def test_joints_are_the_arm_ik_of_the_branch_at_every_sample():
    for segment in _random_segments(50, seed=1):
        tau = np.linspace(0.0, segment.duration, 301)
        s = quintic_scaling(tau / segment.duration)[0]
        a, b = segment.start, segment.end
        p = np.asarray(a.position) + s[:, None] * np.subtract(b.position, a.position)
        result = ik(p, a.pitch + s * (b.pitch - a.pitch), a.roll + s * (b.roll - a.roll))
        assert_close(segment.evaluate(tau)[0], result.candidates[:, segment.branch], atol=IK_TOL)


def test_joint_rates_match_finite_differences():
    h = 1e-6
    for segment in _random_segments(50, seed=2):
        tau = np.linspace(0.05, segment.duration - 0.05, 101)
        x = segment.evaluate(tau)
        central = (segment.evaluate(tau + h) - segment.evaluate(tau - h)) / (2 * h)
        for order in (1, 2, 3):
            scale = 1.0 + np.abs(x[order])
            assert (np.abs(central[order - 1] - x[order]) <= FD_RTOL * scale).all(), order


def test_report_task_lines_are_straight_and_rest_at_every_pose():
    traj = cartesian_line(REPORT_POSES)
    t = traj.times_at_rate(1000.0)
    states = traj.sample(t)
    assert_straight(traj, t, tool_pose(states.q).position)
    at_poses = traj.sample(traj.waypoint_times)
    assert_close(at_poses.qd, 0.0, atol=1e-12)
    assert_close(at_poses.qdd, 0.0, atol=1e-9)
    assert_close(tool_pose(at_poses.q).position, [p.position for p in REPORT_POSES], atol=1e-12)


def test_line_leaving_the_reach_names_the_line_and_the_point():
    # Near the top of the workspace, the wrist of an interpolated pose is out of reach.
    poses = [
        ArmPose((-0.002, 0.002, 0.434), 2.32, 0.0, "A"),
        ArmPose((0.053, 0.043, 0.439), 1.96, 0.0, "B"),
    ]
    with pytest.raises(
        OutOfReachError,
        match=r"^straight line A -> B \(segment 1\) leaves the "
        r"arm's reach at 16\.9 % of its duration \(tool at \(0\.0, 3\.5, 434\.2\) mm\)",
    ):
        cartesian_line(poses)


def test_line_through_the_base_axis_is_singular():
    poses = [ArmPose((0.141, 0.0, 0.40), 0.8, 0.0), ArmPose((-0.141, 0.0, 0.4276), 1.735, 0.0)]
    with pytest.raises(
        PathError,
        match=r"passes a singular configuration .* at 50\.0 % of its "
        r"duration \(tool at \(0\.0, 0\.0, ",
    ) as info:
        cartesian_line(poses)
    assert info.value.fraction == 0.5


def test_line_that_needs_a_change_of_configuration_is_refused():
    q = np.radians([[73.0, 51.0, -30.0, 13.0, 0.0], [-54.0, 114.0, -41.0, 10.0, 0.0]])
    with pytest.raises(
        PathError,
        match=r"joint 1 jumps by 179\.8 deg at 83\.6 % of its "
        r"duration .*; the IK solution changes configuration there",
    ) as info:
        cartesian_line(q)
    assert (info.value.segment, info.value.joint) == (0, 1)


def test_line_leaving_a_joint_range_names_joint_and_time():
    poses = [ArmPose((0.12, -0.3, 0.12), 0.0, 0.0), ArmPose((0.09, 0.16, 0.32), 0.0, 0.0)]
    with pytest.raises(
        LimitViolationError,
        match=r"^line trajectory: joint 2 \(shoulder\) "
        r"reaches 142\.4 deg, 7\.44 deg beyond its range \[0, 135\] deg at t = ",
    ) as info:
        cartesian_line(poses)
    assert info.value.quantity == "position"


def test_given_durations_too_short_for_a_line():
    with pytest.raises(
        LimitViolationError,
        match=r"^line trajectory: joint 1 \(base\) velocity "
        r"-3\.75 rad/s exceeds its limit 3\.491 rad/s by 7\.43 % at t = 1\.5000 s "
        r"\(segment 2, P2 -> P3\)",
    ):
        cartesian_line(REPORT_POSES, durations=1.0)
    stretched = cartesian_line(REPORT_POSES, durations=1.0, stretch=True)
    assert (stretched.segment_durations >= 1.0).all()
    assert stretched.segment_durations[1] > 1.0


def test_samples_an_ulp_before_a_pose_on_the_base_axis_fold_stay_finite():
    """Samples just before P4 (heading -90 deg: the base angle's fold) are finite.

    s(u) overshooting 1 by an ulp once flipped the fold there and gave infinite
    joint rates (found by task-file fuzzing).
    """
    task = load_task(TASKS / "pick_and_place.toml")
    task = dataclasses.replace(task, durations=(43.645903116306684,) * 4)
    traj = build_trajectory(task, TrajectoryKind.LINE)
    t = np.linspace(0.0, traj.duration, 101)
    assert t[75] < traj.waypoint_times[3]  # 2.8e-14 s before P4
    for values in traj.sample(t):
        assert np.isfinite(values).all()
