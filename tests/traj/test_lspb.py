"""Linear segments with parabolic blends: trapezoids at the acceleration limit."""

from __future__ import annotations

import numpy as np
import pytest

from lynxsim.arm.motion import ARM_LIMITS, lspb
from lynxsim.errors import LimitViolationError
from tests.helpers import assert_close

RATE_TOL = 1e-9
"""Velocity and acceleration equal to their limits to this fraction [-]."""

HOME = np.radians([0.0, 60.0, -60.0, 0.0, 180.0])


def _base_move(angle_deg: float) -> np.ndarray:
    """Two waypoints that differ only in the base joint."""
    end = HOME.copy()
    end[0] = np.radians(angle_deg)
    return np.stack([HOME, end])


def test_long_move_is_a_trapezoid_at_the_base_limits():
    traj = lspb(_base_move(80.0))
    segment = traj.segments[0]
    assert segment.breaks.size == 4  # accelerate, cruise, decelerate
    tb = segment.breaks[1]
    v_max, a_max = ARM_LIMITS.velocity[0], ARM_LIMITS.acceleration[0]
    assert tb == pytest.approx(v_max / a_max, rel=RATE_TOL)
    states = traj.sample(np.array([0.5 * tb, 0.5 * traj.duration, traj.duration - 0.5 * tb]))
    assert_close(states.qdd[:, 0], [a_max, 0.0, -a_max], atol=RATE_TOL * a_max)
    assert states.qd[1, 0] == pytest.approx(v_max, rel=RATE_TOL)
    assert traj.duration == pytest.approx(np.radians(80.0) / v_max + v_max / a_max, rel=RATE_TOL)


def test_short_move_is_a_triangle():
    traj = lspb(_base_move(20.0))
    segment = traj.segments[0]
    assert segment.breaks.size == 3  # no cruise
    a_max = ARM_LIMITS.acceleration[0]
    assert traj.duration == pytest.approx(2.0 * np.sqrt(np.radians(20.0) / a_max), rel=RATE_TOL)
    assert (
        np.abs(traj.sample(np.linspace(0, traj.duration, 501)).qd[:, 0]).max()
        < (ARM_LIMITS.velocity[0])
    )


def test_given_duration_blends_at_the_acceleration_limit():
    traj = lspb(_base_move(60.0), durations=2.0)
    assert traj.duration == pytest.approx(2.0)
    tb = traj.segments[0].breaks[1]
    acc = traj.sample(np.array([0.5 * tb])).qdd[0, 0]
    assert acc == pytest.approx(ARM_LIMITS.acceleration[0], rel=RATE_TOL)


def test_all_joints_follow_the_straight_line_in_joint_space():
    q = np.radians([[10.0, 30.0, -100.0, 40.0, 0.0], [-50.0, 100.0, -20.0, -60.0, 90.0]])
    traj = lspb(q)
    s = (traj.sample(np.linspace(0.0, traj.duration, 101)).q - q[0]) / (q[1] - q[0])
    assert_close(s - s[:, :1], 0.0, atol=1e-12)


def test_duration_too_short_even_for_a_triangle_reports_the_acceleration():
    # 20 deg in 0.25 s: triangle peak 2.79 rad/s (fine), blends at 22.3 rad/s^2 (too much).
    with pytest.raises(
        LimitViolationError,
        match=r"^lspb trajectory: joint 1 \(base\) acceleration 22\.34 rad/s\^2 exceeds its "
        r"limit 13\.96 rad/s\^2 by 60 % at t = ",
    ) as info:
        lspb(_base_move(20.0), durations=0.25)
    assert info.value.quantity == "acceleration"
