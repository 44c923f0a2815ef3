"""Inverse kinematics: round trips through the forward kinematics, outcomes, bad input."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from lynxsim.errors import (
    InvalidInputError,
    NonFiniteInputError,
    UnreachablePlatformPoseError,
    UnreachablePoseError,
)
from lynxsim.rrr import (
    MODE_SIGNS,
    RRR_ROBOT,
    LegStatus,
    PoseStatus,
    fk_all,
    ik,
    ik_one,
    leg_points,
    loop_residual,
    singularity_measures,
)
from lynxsim.rrr.ik import wrap_angle
from tests.helpers import assert_close

POSE_M = 1e-9
"""Round-trip agreement of platform positions [m] and orientations [rad]."""
CLOSURE_M = 1e-12
"""Loop-closure residual of IK solutions [m]."""
MIN_PARALLEL = 1e-3
"""Poses closer than this to a parallel singularity may merge with a second
assembly mode in the forward kinematics; the round trips skip them (counted)."""

EXAMPLES = 300

cx, cy = RRR_ROBOT.base_centre
poses = st.tuples(
    st.floats(cx - 0.16, cx + 0.16),
    st.floats(cy - 0.14, cy + 0.16),
    st.floats(-math.radians(70.0), math.radians(70.0)),
).map(np.array)


def _matches(solutions: np.ndarray, pose: np.ndarray) -> np.ndarray:
    d = np.abs(solutions - pose)
    d[..., 2] = np.abs(wrap_angle(d[..., 2]))
    with np.errstate(invalid="ignore"):
        return (d < POSE_M).all(axis=-1)


@settings(max_examples=EXAMPLES, deadline=None, suppress_health_check=[HealthCheck.filter_too_much])
@given(pose=poses)
def test_round_trip_through_fk_in_every_working_mode(pose):
    result = ik(pose)
    assume(result.ok)
    assert result.valid.all()
    assert_close(loop_residual(pose, result.theta), np.zeros((8, 3)), atol=CLOSURE_M)
    near = np.abs(singularity_measures(pose, result.theta).parallel) < MIN_PARALLEL
    solutions = fk_all(result.theta)
    for m in range(8):
        if near[m]:
            continue
        hit = _matches(solutions.pose[m], pose)
        assert hit.sum() == 1, (m, solutions.pose[m])
        assert solutions.mode[m][hit][0] == m


def test_seeded_batch_round_trip_in_every_working_mode(random_poses):
    result = ik(random_poses)
    assert result.ok.all()
    theta = result.theta  # (N, 8, 3)
    near = np.abs(singularity_measures(random_poses[:, None, :], theta).parallel) < MIN_PARALLEL
    assert near.mean() < 0.01
    solutions = fk_all(theta)  # 16,000 actuated-angle triples
    hit = _matches(solutions.pose, random_poses[:, None, None, :])
    found = hit.any(axis=-1)
    assert found[~near].all(), np.argwhere(~found & ~near)[:5]
    mode_of_hit = np.where(hit, solutions.mode, -1).max(axis=-1)
    assert (mode_of_hit[~near] == np.arange(8)[None, :].repeat(len(theta), 0)[~near]).all()


def test_leg_points_have_link_lengths_and_elbow_signs(random_poses):
    for m in range(8):
        pts = leg_points(random_poses[:200], m)
        b, e, p = pts[..., 0, :], pts[..., 1, :], pts[..., 2, :]
        assert_close(b, np.broadcast_to(RRR_ROBOT.base, b.shape), atol=0.0)
        assert_close(np.linalg.norm(e - b, axis=-1), np.full(b.shape[:-1], 0.17), atol=CLOSURE_M)
        assert_close(np.linalg.norm(p - e, axis=-1), np.full(b.shape[:-1], 0.13), atol=CLOSURE_M)
        a, n = e - b, p - e
        bend = a[..., 0] * n[..., 1] - a[..., 1] * n[..., 0]
        assert (np.sign(bend) == MODE_SIGNS[m]).all()


def test_leg_points_broadcast_modes_against_poses(random_poses):
    pts = leg_points(random_poses[:5, None, :], np.arange(8))
    assert pts.shape == (5, 8, 3, 3, 2)
    assert_close(pts[2, 6], leg_points(random_poses[2], 6), atol=0.0)


def test_ik_matches_the_spec_equation(random_poses):
    # d_x cos(theta) + d_y sin(theta) = (|d|^2 + s_a^2 - L^2) / (2 s_a)
    result = ik(random_poses[:300])
    d = result.platform_joints - RRR_ROBOT.base  # (N, 3, 2)
    th = result.theta
    lhs = d[:, None, :, 0] * np.cos(th) + d[:, None, :, 1] * np.sin(th)
    rhs = ((d**2).sum(-1) + 0.17**2 - 0.13**2) / (2 * 0.17)
    assert_close(lhs, np.broadcast_to(rhs[:, None, :], lhs.shape), atol=1e-12)


def test_report_pose_a_angles():
    theta = np.degrees(ik_one([0.2, 0.15, 0.0]))
    assert_close(theta[0], [-5.406, 117.236, -154.131], atol=1e-3)
    assert_close(theta[7], [93.800, -165.505, -62.393], atol=1e-3)


def test_unreachable_pose_names_the_failing_leg():
    with pytest.raises(UnreachablePlatformPoseError, match=r"leg 1 cannot stretch") as info:
        ik_one([0.3, 0.25, math.radians(-40.0)])
    assert info.value.legs == (1,)
    assert isinstance(info.value, UnreachablePoseError)
    assert info.value.reason == "out_of_reach"
    assert "322.29 mm > s_a + L = 300.00 mm" in str(info.value)
    assert "\n" not in str(info.value)


def test_too_near_leg_is_reported_as_folding():
    # Put P1 20 mm from B1: closer than |s_a - L| = 40 mm.
    centre = np.array([0.02, 0.0]) - RRR_ROBOT.platform[0]
    result = ik([*centre, 0.0])
    assert result.status == PoseStatus.OUT_OF_REACH
    assert result.leg_status[0] == LegStatus.TOO_NEAR
    assert_close(result.leg_span[0], 0.02, atol=1e-15)
    assert "leg 1 cannot fold to it" in result.reason()
    assert np.isnan(result.theta).all()
    assert not result.valid.any()


def test_far_pose_lists_every_leg():
    with pytest.raises(UnreachablePlatformPoseError) as info:
        ik_one([0.6, 0.6, 0.0])
    assert info.value.legs == (1, 2, 3)


@pytest.mark.parametrize("limit", ["reach_max", "reach_min"], ids=["stretched", "folded"])
def test_leg_exactly_at_its_reach_limit_is_reachable_and_merges_modes(random_poses, limit):
    span = getattr(RRR_ROBOT, limit)
    checked = 0
    for pose in random_poses[:200]:
        # Slide the platform along B1 -> P1 until leg 1 spans exactly ``span``.
        p1 = ik(pose).platform_joints[0]
        d = p1 - RRR_ROBOT.base[0]
        moved = pose + [*(d / np.linalg.norm(d) * span - d), 0.0]
        result = ik(moved)
        if not result.ok:
            continue  # another leg fails there
        checked += 1
        assert_close(result.leg_span[0], span, atol=1e-15)
        # Modes that differ only in leg 1's elbow coincide.
        assert_close(result.theta[0::2, 0], result.theta[1::2, 0], atol=1e-6)
        meas = singularity_measures(moved, result.theta)
        assert_close(meas.leg[:, 0], np.zeros(8), atol=1e-6)
    assert checked >= 10


def test_stretched_leg_at_the_reach_limit_keeps_its_branches_equal():
    # Centre where leg 3 is exactly stretched and legs 1, 2 reach.
    centre = np.array(RRR_ROBOT.base_centre)
    direction = np.array([0.0, -1.0])
    p3 = RRR_ROBOT.base[2] + RRR_ROBOT.reach_max * direction
    pose = np.array([*(p3 - RRR_ROBOT.platform[2]), 0.0])
    result = ik(pose)
    assert result.ok, result.reason()
    assert_close(result.theta[:4, 2], result.theta[4:, 2], atol=1e-7)
    assert_close(np.degrees(result.theta[0, 2]), -90.0, atol=1e-5)
    assert centre[1] > pose[1]


def test_batch_keeps_shape_and_mixes_outcomes():
    pose = np.array(
        [
            [[0.2, 0.15, 0.0], [0.3, 0.25, math.radians(-40)]],
            [[np.nan, 0.1, 0.0], [0.25, 0.145, math.inf]],
        ]
    )
    result = ik(pose)
    assert result.theta.shape == (2, 2, 8, 3)
    assert result.valid.shape == (2, 2, 8)
    assert result.leg_status.shape == (2, 2, 3)
    assert result.status.tolist() == [
        [PoseStatus.OK, PoseStatus.OUT_OF_REACH],
        [PoseStatus.NOT_FINITE, PoseStatus.NOT_FINITE],
    ]
    assert (result.leg_status[1] == LegStatus.NOT_FINITE).all()
    assert np.isnan(result.leg_span[1]).all()
    assert np.isfinite(result.theta[0, 0]).all()
    assert np.isnan(result.theta[0, 1]).all()
    assert result.failing_legs((0, 1)) == (1,)
    with pytest.raises(NonFiniteInputError, match="not finite"):
        result.raise_for_status((1, 0))
    result.raise_for_status((0, 0))


def test_batch_matches_single_calls(random_poses):
    batch = ik(random_poses[:40]).theta
    for i, pose in enumerate(random_poses[:40]):
        assert_close(ik_one(pose), batch[i], atol=0.0)


def test_elbows_property_matches_leg_points(random_poses):
    result = ik(random_poses[:10])
    for m in (0, 5):
        assert_close(result.elbows[:, m], leg_points(random_poses[:10], m)[..., 1, :], atol=1e-15)


@pytest.mark.parametrize(
    ("pose", "error"),
    [
        ([0.2, 0.1], InvalidInputError),
        ([[0.2, 0.1, 0.0]], InvalidInputError),
        ([np.nan, 0.1, 0.0], NonFiniteInputError),
    ],
    ids=["two-numbers", "batch-of-one", "nan"],
)
def test_ik_one_rejects_bad_input(pose, error):
    with pytest.raises(error):
        ik_one(pose)


def test_ik_rejects_wrong_last_axis():
    with pytest.raises(InvalidInputError, match=r"shape \(\.\.\., 3\)"):
        ik(np.zeros((4, 2)))
