"""Jacobians against finite differences; singularity measures where they must vanish."""

from __future__ import annotations

import numpy as np
import pytest

from lynxsim.rrr import (
    RRR_ROBOT,
    constraint_jacobians,
    fk_near,
    forward_jacobian,
    ik,
    inverse_jacobian,
    leg_points,
    orientation_range_in_mode,
    singularity_measures,
)
from lynxsim.rrr.ik import wrap_angle
from tests.helpers import assert_close

STEP = 1e-6
"""Central-difference step [m] for x, y and [rad] for alpha and theta."""
STEP_THETA = 1e-7
"""Smaller step for the forward Jacobian, whose third derivatives grow near parallel
singularities (FK converges to 1e-15 m, so rounding stays ~1e-8 relative)."""
FD_TOL = 1e-6
"""Finite differences with a 1e-6 step agree to ~1e-9 relative; margin for near-singular poses."""


@pytest.fixture
def configurations(random_poses):
    """300 poses with the angles of one working mode each, away from parallel singularities."""
    poses = random_poses[:400]
    modes = np.arange(len(poses)) % 8
    theta = ik(poses).theta[np.arange(len(poses)), modes]
    keep = np.abs(singularity_measures(poses, theta).parallel) > 0.05
    return poses[keep][:300], theta[keep][:300], modes[keep][:300]


def test_inverse_jacobian_matches_finite_differences_of_ik(configurations):
    poses, theta, modes = configurations
    cols = []
    for k in range(3):
        dp = np.zeros(3)
        dp[k] = STEP
        plus = ik(poses + dp).theta[np.arange(len(poses)), modes]
        minus = ik(poses - dp).theta[np.arange(len(poses)), modes]
        cols.append(wrap_angle(plus - minus) / (2 * STEP))
    numeric = np.stack(cols, axis=-1)
    analytic = inverse_jacobian(poses, theta)
    scale = np.maximum(1.0, np.abs(analytic).max(axis=(-1, -2)))[:, None, None]
    assert_close(analytic / scale, numeric / scale, atol=FD_TOL)


def test_forward_jacobian_matches_finite_differences_of_fk(configurations):
    poses, theta, _ = configurations
    cols = []
    for k in range(3):
        dt = np.zeros(3)
        dt[k] = STEP_THETA
        plus = fk_near(theta + dt, poses)
        minus = fk_near(theta - dt, poses)
        assert plus.converged.all()
        assert minus.converged.all()
        diff = plus.pose - minus.pose
        diff[:, 2] = wrap_angle(diff[:, 2])
        cols.append(diff / (2 * STEP_THETA))
    numeric = np.stack(cols, axis=-1)
    analytic = forward_jacobian(poses, theta)
    scale = np.maximum(1.0, np.abs(analytic).max(axis=(-1, -2)))[:, None, None]
    assert_close(analytic / scale, numeric / scale, atol=FD_TOL)


def test_forward_and_inverse_jacobians_are_inverse(configurations):
    poses, theta, _ = configurations
    product = forward_jacobian(poses, theta) @ inverse_jacobian(poses, theta)
    assert_close(product, np.broadcast_to(np.eye(3), product.shape), atol=1e-9)
    jac = constraint_jacobians(poses, theta)
    assert_close(jac.a @ forward_jacobian(poses, theta), jac.b, atol=1e-12)


def test_measures_are_bounded(configurations):
    poses, theta, modes = configurations
    m = singularity_measures(poses, theta)
    assert (np.abs(m.leg) <= 1.0 + 1e-12).all()
    assert (np.sign(m.leg) == np.where(modes[:, None] & (1 << np.arange(3)), -1, 1)).all()
    assert (np.abs(m.parallel) <= 2 * np.sqrt(2)).all()
    assert ((m.parallel_icn > 0) & (m.parallel_icn <= 1)).all()


def test_parallel_measure_vanishes_where_the_distal_lines_meet():
    # At the base centre, mode 0 meets a parallel singularity near alpha = +35.5 deg.
    cx, cy = RRR_ROBOT.base_centre
    _, upper = orientation_range_in_mode(cx, cy, 0)
    pose = np.array([cx, cy, upper])
    theta = ik(pose).theta[0]
    m = singularity_measures(pose, theta)
    assert abs(m.parallel) < 1e-9
    assert m.parallel_icn < 1e-8
    assert m.serial > 0.1  # not a leg singularity
    # The three distal-link lines pass through one point (or are parallel).
    pts = leg_points(pose, 0)
    e, p = pts[:, 1], pts[:, 2]
    n = p - e
    # Intersect lines 1 and 2, measure the distance of line 3 from that point.
    mat = np.column_stack([n[0], -n[1]])
    s = np.linalg.solve(mat, e[1] - e[0])
    meet = e[0] + s[0] * n[0]
    u = n[2] / np.linalg.norm(n[2])
    offset = meet - e[2]
    assert abs(offset[0] * u[1] - offset[1] * u[0]) < 1e-9
    # Nearby, the forward Jacobian grows without bound.
    assert np.abs(forward_jacobian(pose, theta)).max() > 1e6


def test_leg_measure_vanishes_on_the_annulus_circles():
    cx, cy = RRR_ROBOT.base_centre
    for radius in (RRR_ROBOT.reach_max, RRR_ROBOT.reach_min):
        # Leg 3 exactly stretched or folded, straight below B3.
        p3 = RRR_ROBOT.base[2] + [0.0, -radius]
        pose = np.array([*(p3 - RRR_ROBOT.platform[2]), 0.0])
        result = ik(pose)
        if not result.ok:
            assert radius == RRR_ROBOT.reach_min  # the folded pose is out of legs 1/2's reach
            continue
        m = singularity_measures(pose, result.theta)
        assert_close(m.leg[:, 2], np.zeros(8), atol=1e-7)
        assert_close(m.serial, np.zeros(8), atol=1e-7)
        assert np.isnan(inverse_jacobian(pose, result.theta)[:, 2]).all() or (
            np.abs(inverse_jacobian(pose, result.theta)[:, 2]).max() > 1e5
        )
    assert cy > 0
    assert cx > 0


def test_singularity_measures_of_unreachable_poses_are_nan():
    pose = np.array([0.6, 0.6, 0.0])
    m = singularity_measures(pose, ik(pose).theta)
    assert np.isnan(m.parallel).all()
    assert np.isnan(m.parallel_icn).all()
