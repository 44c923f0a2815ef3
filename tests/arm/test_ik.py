"""Inverse kinematics: the report's table, round trips over the joint ranges, bad input."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from lynxsim.angles import LIMIT_TOL
from lynxsim.arm import LYNX_ARM, IKStatus, fk, ik, ik_one, tool_pose, wrap_angle
from lynxsim.errors import (
    InvalidInputError,
    JointRangeError,
    LynxsimError,
    NonFiniteInputError,
    OutOfReachError,
)
from lynxsim.reproduce.arm_tables import FK_CASES, TABLE4
from tests.helpers import assert_close

POSE_M = 1e-9
"""Round-trip agreement of tool poses [m] (and of tool axes [-])."""
JOINT_RAD = 1e-7
"""Round-trip agreement of joint angles [rad]."""
REPORT_DEG = 0.01
"""Agreement with the report's printed joint angles [deg]."""
SINGLE_CALL_RAD = 2e-14
"""Agreement of ``ik_one`` (the closed form in :mod:`math`) with the batch IK (in NumPy)
[rad]: the same operations, but libm's and NumPy's atan2/acos/hypot may differ in the
last digit, and the chain of them carries it on. Measured over 20,000 random joint
vectors: at most 5.8e-15 rad (26 ulp of 1 rad); the bound leaves a factor of 3."""

EXAMPLES = 500

joint_vectors = st.tuples(
    *(
        st.floats(lo, hi, allow_nan=False, allow_infinity=False)
        for lo, hi in zip(LYNX_ARM.q_min, LYNX_ARM.q_max)
    )
).map(np.array)


@pytest.mark.parametrize("row", TABLE4, ids=[r.name for r in TABLE4])
def test_ik_reproduces_table4(row):
    q = ik_one(np.array(row.position_mm) * 1e-3, math.radians(row.pitch_deg))
    assert_close(np.degrees(q[:4]), row.q_deg, atol=REPORT_DEG)


def test_ik_recovers_figure7_case():
    case = FK_CASES[1]
    q = ik_one(np.array(case.position_mm) * 1e-3, math.radians(case.pitch_deg))
    # Inputs printed to 0.01 mm / 0.01 deg reproduce the joints to ~0.02 deg.
    assert_close(np.degrees(q[:4]), case.q_deg[:4], atol=0.02)


def _assert_same_tool_pose(q_a, q_b):
    """Same tool point and same tool axis (pitch is measured towards q1)."""
    t_a, t_b = fk(q_a), fk(q_b)
    assert_close(t_a[..., :3, 3], t_b[..., :3, 3], atol=POSE_M)
    assert_close(t_a[..., :3, 2], t_b[..., :3, 2], atol=POSE_M)


@settings(max_examples=EXAMPLES, deadline=None)
@given(q=joint_vectors)
def test_round_trip_recovers_pose_and_joints(q):
    pose = tool_pose(q)
    result = ik(pose.position, pose.pitch, pose.roll)
    assert result.status == IKStatus.OK
    _assert_same_tool_pose(result.q, q)
    # With q as the reference, the selected solution is q itself.
    chosen = ik(pose.position, pose.pitch, pose.roll, q_ref=q).q
    assert_close(wrap_angle(chosen - q), np.zeros(5), atol=JOINT_RAD)


@settings(max_examples=EXAMPLES, deadline=None)
@given(q=joint_vectors)
def test_every_valid_candidate_reaches_the_target(q):
    pose = tool_pose(q)
    result = ik(pose.position, pose.pitch, pose.roll)
    for cand in result.candidates[result.valid]:
        _assert_same_tool_pose(cand, q)
        assert (cand >= LYNX_ARM.lower - LIMIT_TOL).all()
        assert (cand <= LYNX_ARM.upper + LIMIT_TOL).all()


@settings(max_examples=EXAMPLES, deadline=None)
@given(
    q1=st.floats(-math.pi / 2, math.pi / 2),
    q2=st.floats(math.radians(95.0), math.radians(135.0)),
    q3=st.floats(math.radians(-40.0), 0.0),
    q4=st.floats(-math.pi / 2, math.pi / 2),
)
def test_lean_back_configurations_round_trip(q1, q2, q3, q4):
    q = np.array([q1, q2, q3, q4, 0.5])
    pose = tool_pose(q)
    result = ik(pose.position, pose.pitch, pose.roll, q_ref=q)
    assert result.status == IKStatus.OK
    _assert_same_tool_pose(result.q, q)
    assert_close(wrap_angle(result.q - q), np.zeros(5), atol=JOINT_RAD)


def test_about_a_tenth_of_configurations_lean_back_behind_the_base():
    q = np.random.default_rng(3).uniform(LYNX_ARM.lower, LYNX_ARM.upper, size=(200_000, 5))
    pose = tool_pose(q)
    behind = pose.position[:, 0] < 0
    assert 0.07 < behind.mean() < 0.14
    result = ik(pose.position[behind], pose.pitch[behind], pose.roll[behind])
    assert result.ok.all()
    _assert_same_tool_pose(result.q, q[behind])


def test_batch_matches_single_calls():
    q = np.random.default_rng(4).uniform(LYNX_ARM.lower, LYNX_ARM.upper, size=(50, 5))
    pose = tool_pose(q)
    batch = ik(pose.position, pose.pitch, pose.roll)
    for i in range(len(q)):
        q = ik_one(pose.position[i], pose.pitch[i], pose.roll[i])
        assert_close(q, batch.q[i], atol=SINGLE_CALL_RAD)


def test_batch_keeps_shape_and_mixes_outcomes():
    position = np.array([[[0.0, 0.3, 0.0], [0.6, 0.0, 0.0]], [[np.nan, 0.0, 0.0], [0.2, 0.0, 0.2]]])
    pitch = np.radians([[-90.0, 0.0], [0.0, 0.0]])
    result = ik(position, pitch)
    assert result.q.shape == (2, 2, 5)
    assert result.candidates.shape == (2, 2, 4, 5)
    assert result.status.tolist() == [
        [IKStatus.OK, IKStatus.OUT_OF_REACH],
        [IKStatus.NOT_FINITE, IKStatus.OK],
    ]
    assert np.isnan(result.q[~result.ok]).all()
    assert np.isfinite(result.q[result.ok]).all()


def test_out_of_reach_raises_typed_error():
    with pytest.raises(OutOfReachError, match="out of the arm's reach") as info:
        ik_one(np.array([0.6, 0.0, 0.0]), 0.0)
    assert isinstance(info.value, ValueError)
    assert isinstance(info.value, LynxsimError)


def test_joint_range_error_names_the_joint():
    # Low and close with the tool pointing straight up needs q4 far beyond 90 deg.
    with pytest.raises(JointRangeError, match=r"joint 4 out of range by 71.\d\d deg") as info:
        ik_one(np.array([0.1, 0.0, 0.05]), math.pi / 2)
    assert info.value.joint == 4


@pytest.mark.parametrize(
    ("position", "pitch", "roll"),
    [
        ([np.nan, 0.2, 0.1], 0.0, 0.0),
        ([0.2, 0.0, 0.1], np.inf, 0.0),
        ([0.2, 0.0, 0.1], 0.0, np.nan),
    ],
    ids=["nan-position", "inf-pitch", "nan-roll"],
)
def test_non_finite_targets_are_refused(position, pitch, roll):
    result = ik(np.array(position), pitch, roll)
    assert result.status == IKStatus.NOT_FINITE
    with pytest.raises(NonFiniteInputError, match="not finite"):
        ik_one(np.array(position), pitch, roll)


def test_malformed_shapes_are_refused():
    with pytest.raises(InvalidInputError, match="shape"):
        ik(np.zeros(2), 0.0)
    with pytest.raises(InvalidInputError, match="do not broadcast"):
        ik(np.zeros((3, 3)), np.zeros(2))
    with pytest.raises(InvalidInputError, match="shape"):
        ik_one(np.zeros((2, 3)), 0.0)


def test_roll_is_wrapped_into_its_range():
    q = ik_one(np.array([0.25, 0.0, 0.3]), 0.0, roll=-math.pi / 2)
    assert_close(q[4], 1.5 * math.pi, atol=1e-12)
