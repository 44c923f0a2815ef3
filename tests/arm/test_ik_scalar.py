"""The single-target IK and FK in Python floats agree with the batch versions."""

from __future__ import annotations

import math
import timeit

import numpy as np
import pytest

from lynxsim.arm import (
    LYNX_ARM,
    IKStatus,
    ik,
    ik_nearest,
    ik_one,
    tool_pose,
    tool_pose_of,
)
from lynxsim.errors import InvalidInputError, JointRangeError, OutOfReachError
from tests.helpers import assert_close

JOINT_RAD = 1e-12
"""Agreement of joint angles [rad]: the same operations, but libm's atan2 and hypot
and NumPy's vectorised ones may differ in the last digit."""
POSE_M = 1e-12
"""Agreement of tool points [m] and pitches [rad]."""
N = 3000
"""Random targets per comparison."""
SPEEDUP = 10.0
"""``ik_one`` is at least this many times faster than the batch IK on one target [-]."""


def _targets(source: str, rng: np.random.Generator):
    """Tool points, pitches and rolls: of random joints (mostly solvable), or anywhere."""
    if source == "reachable":
        pose = tool_pose(rng.uniform(LYNX_ARM.lower, LYNX_ARM.upper, (N, 5)))
        return pose.position, pose.pitch, pose.roll
    p = rng.uniform([-0.5, -0.5, -0.3], [0.5, 0.5, 0.6], (N, 3))  # mostly out of reach or range
    return p, rng.uniform(-np.pi, np.pi, N), rng.uniform(-1.0, 7.0, N)


@pytest.mark.parametrize("source", ["reachable", "anywhere"])
def test_ik_nearest_matches_batch_ik(source):
    rng = np.random.default_rng(7)
    q_ref = rng.uniform(LYNX_ARM.lower, LYNX_ARM.upper, (N, 5))
    p, pitch, roll = _targets(source, rng)
    batch = ik(p, pitch, roll, q_ref=q_ref)
    for i in range(N):
        status, q = ik_nearest(*p[i].tolist(), pitch[i], roll[i], q_ref[i].tolist())
        assert status == batch.status[i], i
        if status is IKStatus.OK:
            assert_close(q, batch.q[i], atol=JOINT_RAD, err_msg=f"target {i}")
        else:
            assert q is None
    if source == "reachable":
        assert batch.ok.mean() > 0.9


@pytest.mark.parametrize("source", ["reachable", "anywhere"])
def test_ik_one_matches_batch_ik_without_reference(source):
    rng = np.random.default_rng(11)
    p, pitch, roll = _targets(source, rng)
    batch = ik(p, pitch, roll)
    for i in range(N):
        if batch.ok[i]:
            assert_close(ik_one(p[i], pitch[i], roll[i]), batch.q[i], atol=JOINT_RAD)
        else:
            status, _ = ik_nearest(*p[i].tolist(), pitch[i], roll[i], None)
            assert status == batch.status[i], i


def test_ik_one_errors_are_the_batch_ik_messages():
    rng = np.random.default_rng(5)
    p, pitch, roll = _targets("anywhere", rng)
    batch = ik(p, pitch, roll)
    errors = {IKStatus.OUT_OF_REACH: OutOfReachError, IKStatus.JOINT_RANGE: JointRangeError}
    for status, error in errors.items():
        for i in np.flatnonzero(batch.status == status)[:20]:
            with pytest.raises(error) as info:
                ik_one(p[i], pitch[i], roll[i])
            assert str(info.value) == batch.reason(int(i))


def test_ik_one_takes_the_roll_of_the_reference():
    q_ref = np.array([0.2, 1.0, -1.2, 0.3, 2.5])
    x, y, z, pitch = tool_pose_of(q_ref.tolist())
    assert_close(ik_one([x, y, z], pitch, q_ref=q_ref), q_ref, atol=1e-9)


def test_ik_nearest_ignores_a_non_finite_reference_as_the_batch_ik_does():
    p, pitch = np.array([0.2, 0.05, 0.15]), 0.3
    q_ref = [np.nan, 0.0, 0.0, 0.0, 0.0]
    status, q = ik_nearest(*p.tolist(), pitch, 0.0, q_ref)
    assert status is IKStatus.OK
    assert_close(q, ik(p, pitch, 0.0).q, atol=JOINT_RAD)


def test_ik_nearest_rejects_non_finite_targets():
    assert ik_nearest(np.nan, 0.0, 0.1, 0.0, 0.0, [0.0] * 5) == (IKStatus.NOT_FINITE, None)


@pytest.mark.parametrize(
    "pitch",
    [np.array(-1.5707963), np.array([-1.5707963]), np.float64(-1.5707963), -1.5707963],
    ids=["0-d", "1-element", "numpy-scalar", "float"],
)
def test_ik_one_accepts_a_pitch_of_one_element(pitch):
    q = ik_one([0.0, 0.3, 0.0], pitch)
    assert q.shape == (5,)
    assert_close(q, ik_one(np.array([0.0, 0.3, 0.0]), -1.5707963), atol=0.0)


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"pitch": np.zeros(2)}, r"pitch must be a number .*shape \(2,\)"),
        ({"pitch": np.zeros((1, 1))}, r"pitch must be a number .*shape \(1, 1\)"),
        ({"pitch": "steep"}, "pitch must be a number"),
        ({"pitch": None}, "not finite"),  # NumPy reads None as NaN
        ({"pitch": 0.0, "roll": np.zeros(3)}, r"roll must be a number .*shape \(3,\)"),
        ({"pitch": 0.0, "q_ref": np.zeros(4)}, r"q_ref must have shape \(5,\), got \(4,\)"),
        ({"pitch": 0.0, "q_ref": np.zeros((2, 5))}, r"q_ref must have shape \(5,\)"),
    ],
    ids=["pitch-2", "pitch-1x1", "pitch-str", "pitch-none", "roll-3", "ref-4", "ref-2x5"],
)
def test_ik_one_refuses_malformed_arguments(kwargs, match):
    with pytest.raises(InvalidInputError, match=match):
        ik_one([0.2, 0.0, 0.2], **kwargs)


def test_ik_one_refuses_a_malformed_position():
    with pytest.raises(InvalidInputError, match="position must be 3 numbers"):
        ik_one([0.2, "x", 0.2], 0.0)
    with pytest.raises(InvalidInputError, match=r"position must have shape \(3,\), got \(4,\)"):
        ik_one([0.2, 0.0, 0.2, 0.0], 0.0)


def test_tool_pose_of_matches_tool_pose():
    rng = np.random.default_rng(3)
    q = rng.uniform(LYNX_ARM.lower, LYNX_ARM.upper, (500, 5))
    pose = tool_pose(q)
    got = np.array([tool_pose_of(v.tolist()) for v in q])
    assert_close(got[:, :3], pose.position, atol=POSE_M)
    assert_close(got[:, 3], pose.pitch, atol=POSE_M)


def test_ik_one_costs_a_fraction_of_the_batch_ik_on_one_target():
    target, pitch = np.array([0.0, 0.3, 0.0]), -math.pi / 2
    q_ref = np.array([1.5, 0.3, -0.3, -1.5, 0.0])

    def best_of(fn):
        return min(timeit.repeat(fn, number=200, repeat=5)) / 200

    t_one = best_of(lambda: ik_one(target, pitch, q_ref=q_ref))
    t_batch = best_of(lambda: ik(target, pitch, q_ref=q_ref))
    # Relative, so that a loaded machine slows both alike (measured: ~5 µs against ~150 µs).
    assert t_one < t_batch / SPEEDUP
