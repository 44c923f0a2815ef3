"""Free motion, cubic and quintic: the boundary-condition matrices and the timing."""

from __future__ import annotations

import numpy as np
import pytest

from lynxsim.arm.motion import ARM_LIMITS, JointPose, cubic, free_motion, generate, quintic
from lynxsim.errors import InvalidInputError, LimitViolationError
from lynxsim.traj import TrajectoryKind, cubic_coefficients, quintic_coefficients
from lynxsim.traj.polynomial import quintic_scaling
from tests.helpers import assert_close

COEF_TOL = 1e-9
"""Boundary values reproduced by the solved coefficients [rad, rad/s, rad/s^2]."""

PEAK_RTOL = 1e-6
"""A shortest segment reaches its binding limit to this fraction [-]."""

Q0 = np.radians([90.0, 15.89, -18.47, -87.42, 0.0])  # report P1
Q1 = np.radians([90.0, 80.38, -46.11, -34.27, 0.0])  # report P2


def _poly(coefficients: np.ndarray, t: float, order: int) -> np.ndarray:
    """Derivative ``order`` of sum_k c_k t^k at ``t``."""
    poly = np.polynomial.polynomial
    return (
        poly.polyval(t, poly.polyder(coefficients, order))
        if order
        else poly.polyval(t, coefficients)
    )


def test_cubic_coefficients_meet_boundary_conditions_away_from_t0_zero():
    t0, tf = 2.0, 3.5  # the report's eq. 42 typo (3 t0^3) would break this
    q0, v0, qf, vf = 0.3, -0.2, 1.1, 0.4
    c = cubic_coefficients(t0, tf, q0, v0, qf, vf)
    got = [_poly(c, t0, 0), _poly(c, t0, 1), _poly(c, tf, 0), _poly(c, tf, 1)]
    assert_close(got, [q0, v0, qf, vf], atol=COEF_TOL)


def test_quintic_coefficients_meet_boundary_conditions_away_from_t0_zero():
    t0, tf = 1.5, 2.25  # the report's eq. 52 typos break this for t0 != 0 or af != 0
    bc = (0.2, 0.5, -1.0, -0.4, 0.1, 2.0)
    c = quintic_coefficients(t0, tf, *bc)
    got = [_poly(c, t, k) for t in (t0, tf) for k in range(3)]
    assert_close(got, bc, atol=COEF_TOL)


def test_coefficients_broadcast_over_joints():
    c = quintic_coefficients(0.0, 1.0, Q0, 0.0, 0.0, Q1, 0.0, 0.0)
    assert c.shape == (6, 5)
    u = 0.3
    closed = Q0 + (Q1 - Q0) * (10 * u**3 - 15 * u**4 + 6 * u**5)
    assert_close([_poly(c[:, j], u, 0) for j in range(5)], closed, atol=COEF_TOL)


def test_quintic_scaling_rests_at_both_ends():
    s = quintic_scaling(np.array([0.0, 1.0]))
    assert_close(s[:, 0], [0.0, 0.0, 0.0, 60.0], atol=0.0)
    assert_close(s[:, 1], [1.0, 0.0, 0.0, 60.0], atol=1e-12)


def test_quintic_scaling_derivatives_match_finite_differences():
    u = np.linspace(0.05, 0.95, 19)
    h = 1e-6
    ahead, behind = quintic_scaling(u + h), quintic_scaling(u - h)
    central = (ahead - behind) / (2 * h)
    assert_close(central[:3], quintic_scaling(u)[1:], atol=1e-6)


@pytest.mark.parametrize("kind", ["free", "cubic", "quintic"])
def test_shortest_segment_reaches_its_binding_limit(kind):
    traj = generate(kind, [Q0, Q1])
    t = np.linspace(0.0, traj.duration, 20001)
    states = traj.sample(t)
    ratios = [
        np.abs(states[order]).max(axis=0) / ARM_LIMITS.of_order(order)
        for order in TrajectoryKind(kind).limited_orders
    ]
    assert max(r.max() for r in ratios) == pytest.approx(1.0, rel=PEAK_RTOL)


def test_free_motion_moves_every_joint_at_constant_speed():
    traj = free_motion([Q0, Q1, Q0], durations=[1.0, 2.0])
    t = np.array([0.1, 0.5, 0.9, 1.1, 2.5])
    states = traj.sample(t)
    assert_close(states.qd[:3], np.tile(Q1 - Q0, (3, 1)), atol=1e-12)
    assert_close(states.qd[3:], np.tile((Q0 - Q1) / 2.0, (2, 1)), atol=1e-12)
    assert_close(states.qdd, 0.0, atol=0.0)


def test_given_durations_are_kept_exactly():
    traj = cubic([Q0, Q1, Q0], durations=[1.25, 2.5])
    assert_close(traj.waypoint_times, [0.0, 1.25, 3.75], atol=0.0)


def test_too_short_duration_names_joint_time_and_excess():
    # The wrist moves 53 deg in 0.2 s: 1.875 * 0.928 rad / 0.2 s = 8.70 rad/s at mid-segment.
    waypoints = [JointPose(tuple(Q0), "A"), JointPose(tuple(Q1), "B")]
    with pytest.raises(
        LimitViolationError,
        match=r"^quintic trajectory: joint 4 \(wrist_pitch\) velocity 8\.697 rad/s exceeds its "
        r"limit 3\.142 rad/s by 177 % at t = 0\.1000 s \(segment 1, A -> B\); give longer",
    ) as info:
        quintic(waypoints, durations=0.2)
    err = info.value
    assert (err.joint, err.quantity, err.segment) == (4, "velocity", 0)
    assert err.value == pytest.approx(8.697, abs=1e-3)
    assert err.limit == pytest.approx(ARM_LIMITS.velocity[3])
    assert err.time == pytest.approx(0.1)


def test_stretch_lengthens_only_the_segments_that_need_it():
    shortest = quintic([Q0, Q1, Q0]).segment_durations
    traj = quintic([Q0, Q1, Q0], durations=[0.1, 10.0], stretch=True)
    assert_close(traj.segment_durations, [shortest[0], 10.0], atol=1e-12)


def test_coinciding_waypoints_need_a_given_duration():
    with pytest.raises(InvalidInputError, match="waypoints P2 and P3 coincide"):
        quintic([Q0, Q1, Q1])
    traj = quintic([Q0, Q1, Q1], durations=1.0)  # a dwell
    assert_close(traj.sample(np.linspace(1.0, 2.0, 11)).q, np.tile(Q1, (11, 1)), atol=1e-12)
