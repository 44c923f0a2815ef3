"""Task-space platform paths of the 3-RRR robot and their actuated angles."""

from __future__ import annotations

import math
import time
from pathlib import Path

import numpy as np
import pytest

from lynxsim.bounds import MIN_SEGMENT_S
from lynxsim.errors import (
    InvalidInputError,
    NonFiniteInputError,
    SegmentDurationError,
    UnreachablePlatformPoseError,
)
from lynxsim.robots.rrr import path_from_task
from lynxsim.rrr import RRR_ROBOT, ik
from lynxsim.rrr.path import (
    DEFAULT_PLATFORM_LIMITS,
    PlatformLimits,
    PlatformPathError,
    actuated_path,
    actuated_window,
    platform_path,
)
from lynxsim.sim.rrr.model import HOME_POSE
from lynxsim.tasks import load_task
from tests.helpers import assert_close
from tests.rrr_sim.conftest import FIGURE20_A, FIGURE20_D, FIGURE20_E

ROOT = Path(__file__).resolve().parents[2]
TOUR = ROOT / "tasks" / "rrr_figure20_tour.toml"
CURVE = ROOT / "tasks" / "rrr_closed_curve.toml"

WAYPOINT_TOL = 1e-12
"""Paths pass through their waypoints exactly [m, rad]."""
DERIVATIVE_RTOL = 2e-3
"""Finite differences against analytic derivatives, relative to the peak [-]."""
LIMIT_RTOL = 1e-6
"""Shortest durations keep the platform limits up to this [-]."""
ELLIPSE_TOL_M = 1e-4
"""The closed-curve task's spline stays this close to its ellipse [m]."""
ELLIPSE_ALPHA_TOL_RAD = math.radians(0.02)
"""... and to its orientation law [rad]."""

HOME = np.array(HOME_POSE)


def _tour_poses() -> np.ndarray:
    return np.array([HOME, FIGURE20_A, [0.2, 0.15, math.radians(30)], FIGURE20_D, HOME])


def _check_derivatives(path, n=4001):
    t = np.linspace(0.0, path.duration, n)
    s = path.sample(t)
    dt = t[1] - t[0]
    for value, rate in ((s.pose, s.velocity), (s.velocity, s.acceleration)):
        numeric = np.gradient(value, dt, axis=0)[2:-2]
        scale = np.abs(rate).max()
        assert np.abs(numeric - rate[2:-2]).max() <= DERIVATIVE_RTOL * scale


def test_segments_rest_at_every_pose_and_pass_through_them():
    poses = _tour_poses()
    path = platform_path(poses, 1.2, stretch=True)
    starts = np.concatenate([[0.0], np.cumsum(path.durations)])
    s = path.sample(starts)
    assert_close(s.pose, poses, atol=WAYPOINT_TOL)
    assert_close(s.velocity, np.zeros_like(poses), atol=1e-12)
    assert_close(s.acceleration, np.zeros_like(poses), atol=1e-9)
    _check_derivatives(path)
    # Between two poses the platform moves on the straight line joining them.
    mid = path.sample(np.array([0.3 * path.durations[0]])).pose[0]
    direction = (poses[1] - poses[0]) / np.linalg.norm(poses[1] - poses[0])
    offset = mid - poses[0]
    assert_close(offset - direction * (offset @ direction), np.zeros(3), atol=1e-15)


def test_spline_through_poses_is_closed_smooth_and_rests_only_at_its_ends():
    task = load_task(CURVE)
    path = path_from_task(task)
    assert path.through
    assert path.closed
    assert path.duration == pytest.approx(6.0)
    _check_derivatives(path)
    s = path.sample(np.array([0.0, path.duration / 2, path.duration]))
    assert_close(s.velocity[[0, 2]], np.zeros((2, 3)), atol=1e-12)
    assert np.linalg.norm(s.velocity[1, :2]) > 0.05
    # Periodic spline: the slope by arc length is continuous across the seam.
    _, d1, d2 = path._spline(np.array([1e-9, path.arc_length - 1e-9]))
    assert_close(d1[0], d1[1], atol=1e-6)
    assert_close(d2[0], d2[1], atol=1e-4)
    # It follows the task's ellipse and orientation law.
    cx, cy = RRR_ROBOT.base_centre
    pose = path.sample(np.linspace(0.0, path.duration, 2001)).pose
    phi = np.arctan2((pose[:, 1] - cy) / 0.05, (pose[:, 0] - cx) / 0.08)
    ellipse = np.column_stack([cx + 0.08 * np.cos(phi), cy + 0.05 * np.sin(phi)])
    assert np.hypot(*(pose[:, :2] - ellipse).T).max() < ELLIPSE_TOL_M
    assert np.abs(pose[:, 2] - math.radians(20.0) * np.sin(phi)).max() < ELLIPSE_ALPHA_TOL_RAD


@pytest.mark.parametrize("through", [False, True], ids=["segments", "spline"])
def test_shortest_durations_keep_the_platform_limits(through):
    path = platform_path(_tour_poses(), through=through)
    s = path.sample(np.linspace(0.0, path.duration, 20001))
    lim = DEFAULT_PLATFORM_LIMITS
    slack = 1.0 + LIMIT_RTOL
    assert np.hypot(s.velocity[:, 0], s.velocity[:, 1]).max() <= lim.speed * slack
    assert np.abs(s.velocity[:, 2]).max() <= lim.angular_speed * slack
    assert np.hypot(s.acceleration[:, 0], s.acceleration[:, 1]).max() <= lim.acceleration * slack
    assert np.abs(s.acceleration[:, 2]).max() <= lim.angular_acceleration * slack
    if not through:  # each segment is limited by one of the four bounds exactly
        assert np.abs(s.velocity[:, 2]).max() == pytest.approx(lim.angular_speed, rel=1e-4)


def test_short_durations_raise_unless_stretched():
    poses = np.array([HOME, [0.2, 0.15, math.radians(30)]])
    with pytest.raises(SegmentDurationError, match=r"segment P1 -> P2 needs at least") as err:
        platform_path(poses, 0.2)
    assert err.value.given == pytest.approx(0.2)
    assert err.value.required > 0.2
    assert platform_path(poses, 0.2, stretch=True).duration == pytest.approx(err.value.required)


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"waypoints": np.zeros((1, 3))}, r"shape \(N, 3\) with N >= 2"),
        ({"waypoints": np.array([HOME, HOME])}, r"'P1' and 'P2' are the same pose"),
        ({"waypoints": np.array([HOME, FIGURE20_A]), "durations": [1.0, 1.0]}, r"1 segment"),
        (
            {"waypoints": np.array([HOME, FIGURE20_A]), "durations": -1.0},
            r"durations must be between 0\.001 and 3600 s, got -1 s for segment 1 \(P1 -> P2\)",
        ),
    ],
    ids=["one-pose", "repeated", "count", "negative"],
)
def test_bad_paths_are_rejected(kwargs, message):
    with pytest.raises(InvalidInputError, match=message):
        platform_path(**kwargs)


def test_actuated_angles_are_the_ik_of_the_mode_continuous_and_in_range():
    path = path_from_task(load_task(CURVE))
    t = np.arange(0.0, path.duration, 0.002)
    pose = path.sample(t).pose
    for mode in (0, 7):
        act = actuated_path(pose, mode, times=t)
        theta_ik = ik(pose).theta[:, mode]
        assert_close(np.angle(np.exp(1j * (act.theta - theta_ik))), np.zeros_like(pose), atol=1e-12)
        assert np.abs(np.diff(act.theta, axis=0)).max() < 0.01
        assert (np.abs(act.theta - actuated_window()) <= math.pi).all()
        assert act.min_abs_parallel > 0.3
        assert act.min_serial > 0.3


def test_path_out_of_the_workspace_is_a_clear_error():
    # Figure 20 (e) is out of reach: the straight line from home leaves the workspace.
    t = np.linspace(0.0, 2.0, 201)
    poses = HOME + np.outer(t / 2.0, np.subtract(FIGURE20_E, HOME))
    with pytest.raises(
        UnreachablePlatformPoseError, match=r"leaves the workspace at t = 1\.\d+ s"
    ) as e:
        actuated_path(poses, 7, times=t)
    assert e.value.legs == (1,)


def test_unreachable_waypoint_is_refused_before_timing():
    with pytest.raises(
        UnreachablePlatformPoseError, match=r"^waypoint 'P2': platform pose .* is unreachable"
    ) as e:
        platform_path(np.array([HOME, FIGURE20_E]), 2.0)
    assert e.value.legs == (1,)


def test_path_across_a_parallel_singularity_is_rejected():
    # From home to Figure 20 (d) in working mode 1 the parallel measure changes sign.
    path = platform_path(np.array([HOME, FIGURE20_D]), 2.0)
    t = np.linspace(0.0, 2.0, 401)
    with pytest.raises(
        PlatformPathError, match=r"crosses a parallel singularity of working mode 1"
    ):
        actuated_path(path.sample(t).pose, 1, times=t)
    assert actuated_path(path.sample(t).pose, 7, times=t).min_abs_parallel > 0.3


def test_rrr_tasks_load_and_plan_and_other_types_are_refused():
    tour = load_task(TOUR)
    assert tour.robot == "rrr"
    path = path_from_task(tour)
    assert path.names == ("home", "a", "b", "c", "d", "home_again")
    assert path.closed
    assert not path.through
    assert path.durations[2] > 1.5, "b -> c is stretched to keep 1 rad/s"
    with pytest.raises(InvalidInputError, match=r"'line' is not planned for the 3-RRR robot"):
        path_from_task(tour, "line")
    with pytest.raises(InvalidInputError, match=r"is for robot 'arm'"):
        path_from_task(load_task(ROOT / "tasks" / "pick_and_place.toml"))


# Fuzz findings: platform_path returned NaN or infinite durations, or timed an
# unreachable pose 1e9 mm away into a path whose sampling asked for 46 GiB.

QUICK_S = 0.5
"""A refused path is refused at once, before any timing or sampling [s]."""


@pytest.mark.parametrize("through", [False, True], ids=["segments", "spline"])
def test_far_or_unreachable_waypoints_are_refused_quickly(through):
    start = time.perf_counter()
    with pytest.raises(InvalidInputError, match=r"waypoint 2: x and y must be within ±10 m"):
        platform_path(np.array([HOME, [1e6, 0.0, 0.0]]), through=through)  # x = 1e9 mm
    with pytest.raises(UnreachablePlatformPoseError, match=r"^waypoint 'P2': platform pose"):
        platform_path(np.array([HOME, [2.0, 0.0, 0.0], HOME]), through=through)
    assert time.perf_counter() - start < QUICK_S


@pytest.mark.parametrize("through", [False, True], ids=["segments", "spline"])
@pytest.mark.parametrize("limit", [5e-324, 1e-300, 1e-6], ids=str)
def test_limits_too_low_for_an_hour_raise_instead_of_timing(through, limit):
    limits = PlatformLimits(limit, limit, limit, limit)
    with pytest.raises(InvalidInputError, match=r"needs .* s within the platform limits, more"):
        platform_path(_tour_poses(), through=through, limits=limits)
    with pytest.raises(InvalidInputError, match=r"within the platform limits, more"):
        platform_path(_tour_poses(), 1.0, through=through, limits=limits, stretch=True)


@pytest.mark.parametrize("through", [False, True], ids=["segments", "spline"])
def test_huge_limits_give_segments_of_the_shortest_duration(through):
    path = platform_path(_tour_poses(), through=through, limits=PlatformLimits(*[1e300] * 4))
    assert_close(path.durations, np.full(4, MIN_SEGMENT_S), atol=1e-15)
    assert np.isfinite(path.sample(np.linspace(0.0, path.duration, 11)).pose).all()


@pytest.mark.parametrize("duration", [5e-324, 1e-300, 1e-4, 3600.5, 1e60, 1e300], ids=str)
@pytest.mark.parametrize("through", [False, True], ids=["segments", "spline"])
def test_durations_outside_the_range_are_refused(duration, through):
    with pytest.raises(InvalidInputError, match=r"durations must be between 0\.001 and 3600 s"):
        platform_path(_tour_poses(), duration, through=through, stretch=True)


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"waypoints": "home"}, r"waypoints must be real numbers, got 'home'"),
        ({"waypoints": [[0.2, 0.1, 0.0], [0.3]]}, r"rectangular array"),
        ({"waypoints": np.array([HOME, FIGURE20_A]) + 0j}, r"complex numbers"),
        ({"waypoints": [[0.25, 0.15, 0.0], [0.3, 10**400, 0.0]]}, r"integers beyond float64"),
        ({"durations": "1"}, r"segment durations must be real numbers"),
        ({"durations": True}, r"segment durations must be real numbers, got booleans"),
        ({"names": "ab"}, r"names must be a sequence of strings"),
        ({"through": "yes"}, r"through must be True or False"),
        ({"limits": None}, r"limits must be of type PlatformLimits"),
        ({"geometry": 1}, r"geometry must be of type RRRGeometry"),
    ],
    ids=[
        "str",
        "ragged",
        "complex",
        "10**400",
        "duration-str",
        "bool",
        "names",
        "flag",
        "limits",
        "geometry",
    ],
)
def test_arguments_of_the_wrong_type_are_typed_errors(kwargs, message):
    args = {"waypoints": np.array([HOME, FIGURE20_A])} | kwargs
    with pytest.raises(InvalidInputError, match=message):
        platform_path(**args)


def test_platform_limits_and_samples_refuse_non_numbers():
    with pytest.raises(InvalidInputError, match="platform limit speed must be a number, got"):
        PlatformLimits("fast")  # type: ignore[arg-type]
    path = platform_path(np.array([HOME, FIGURE20_A]), 2.0)
    with pytest.raises(NonFiniteInputError, match="sample times must be finite"):
        path.sample([0.0, math.nan])
    with pytest.raises(InvalidInputError, match=r"sample times must have shape \(T,\)"):
        path.sample(np.zeros((2, 2)))


def test_an_orientation_beyond_two_turns_is_refused():
    home = np.array(HOME_POSE)
    far = home + np.array([0.0, 0.0, 4.0 * math.pi + 1e-6])
    with pytest.raises(InvalidInputError, match=r"waypoint 2: alpha must be within ±720 deg"):
        platform_path(np.stack([home, far]), 1.0)
