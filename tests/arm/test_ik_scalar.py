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
from lynxsim.errors import (
    InvalidInputError,
    JointRangeError,
    NonFiniteInputError,
    OutOfReachError,
)
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
        ({"pitch": None}, "pitch must be a number, got None"),  # None is no NaN
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


# ------------------------------------------------------------ odd inputs (fuzz campaign)

_REACHABLE = ([0.2, 0.05, 0.1], -0.5)
"""A tool point [m] and pitch [rad] the arm reaches."""


@pytest.mark.parametrize(
    "as_array",
    [lambda v: np.array([v]), lambda v: np.array(v), lambda v: np.float32(v), lambda v: [v]],
    ids=["1-element", "0-d", "float32", "list-of-one"],
)
def test_one_element_arrays_are_numbers_in_every_single_target_function(as_array):
    (x, y, z), pitch = _REACHABLE
    q = ik_one([x, y, z], pitch)
    tol = 1e-6 if isinstance(as_array(0.5), np.float32) else 0.0  # float32 rounds the pitch
    assert_close(ik_one([x, y, z], as_array(pitch)), q, atol=tol)
    status, q_near = ik_nearest(x, y, z, as_array(pitch), as_array(0.0), None)
    assert status is IKStatus.OK
    assert all(type(v) is float for v in q_near)  # not 1-element arrays
    assert_close(np.array(q_near), q, atol=tol)
    status, _ = ik_nearest(as_array(x), as_array(y), as_array(z), pitch, 0.0, q.tolist())
    assert status is IKStatus.OK
    assert all(type(v) is float for v in tool_pose_of(np.asarray(q)))


@pytest.mark.parametrize(
    "bad",
    ["0.3", None, 1 + 0j, True, np.bool_(False), 10**400, np.zeros(2), {"pitch": 0.0}],
    ids=["str", "none", "complex", "bool", "numpy-bool", "int-beyond-float64", "two", "dict"],
)
def test_single_target_functions_refuse_odd_numbers_with_typed_errors(bad):
    (x, y, z), pitch = _REACHABLE
    with pytest.raises(InvalidInputError, match="pitch must be a number"):
        ik_one([x, y, z], bad)
    with pytest.raises(InvalidInputError, match="pitch must be a number"):
        ik_nearest(x, y, z, bad, 0.0, None)
    if isinstance(bad, bool | np.bool_):
        return  # inside a list of floats NumPy reads a bool as 0.0 or 1.0
    with pytest.raises(InvalidInputError, match="q_ref must be 5 numbers"):
        ik_nearest(x, y, z, pitch, 0.0, [0.0, 0.0, 0.0, 0.0, bad])
    with pytest.raises(InvalidInputError, match="q must be 5 numbers"):
        tool_pose_of([0.0, 0.0, 0.0, 0.0, bad])


@pytest.mark.parametrize(
    ("q", "error"),
    [
        ([0.0, math.inf, 0.0, 0.0, 0.0], NonFiniteInputError),
        ([0.0, 0.0, 0.0, 0.0, math.nan], NonFiniteInputError),
        ([1e308] * 5, InvalidInputError),  # q2 + q3 + q4 overflows
        ([0.0] * 4, InvalidInputError),
        ("00000", InvalidInputError),
    ],
    ids=["inf", "nan-roll", "overflow", "four", "str"],
)
def test_tool_pose_of_refuses_joints_it_cannot_evaluate(q, error):
    with pytest.raises(error):
        tool_pose_of(q)


def test_coordinates_beyond_the_sanity_bound_are_refused_not_overflowed():
    with pytest.raises(InvalidInputError, match=r"within ±10 m"):
        ik_one([1e200, 0.0, 0.0], 0.0)
    with pytest.raises(InvalidInputError, match=r"within ±10 m"):
        ik_nearest(0.0, 1e300, 0.0, 0.0, 0.0, None)
    with pytest.raises(InvalidInputError, match=r"within ±10 m"):
        ik([[0.2, 0.0, 0.1], [0.0, 0.0, -1e300]], 0.0)
    # Non-finite targets stay a status of the batch IK, as documented.
    assert ik([math.inf, 0.0, 0.0], 0.0, math.inf).status == IKStatus.NOT_FINITE


def test_infinite_roll_is_a_status_not_a_runtime_warning():
    (x, y, z), pitch = _REACHABLE
    assert ik([x, y, z], pitch, math.inf).status == IKStatus.NOT_FINITE
    with pytest.raises(NonFiniteInputError):
        ik_one([x, y, z], pitch, np.array([-math.inf]))


def test_wrap_angle_refuses_non_numbers_and_maps_non_finite_angles_to_nan():
    from lynxsim.angles import wrap_angle

    with pytest.raises(InvalidInputError, match="angle must be real numbers"):
        wrap_angle("1.0")
    with pytest.raises(InvalidInputError, match="angle must be real numbers"):
        wrap_angle(np.array([1j]))
    out = wrap_angle(np.array([math.inf, -math.inf, math.nan, 7.0]))  # no RuntimeWarning
    assert np.isnan(out[:3]).all()
    assert_close(out[3], 7.0 - 2 * math.pi, atol=1e-15)
