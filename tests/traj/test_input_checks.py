"""Regression tests of the fuzz campaign's findings: degenerate durations, huge rates, odd types.

Every public function of :mod:`lynxsim.traj` refuses what it cannot honour with a
typed error (a :class:`~lynxsim.errors.LynxsimError` that is also a ``ValueError``)
whose message states the valid range, before any arithmetic on it.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from lynxsim.arm.motion import (
    ArmPose,
    JointPose,
    free_motion,
    generate,
    quintic,
    resolve_waypoints,
)
from lynxsim.bounds import MAX_SAMPLES, MAX_SEGMENT_S, MIN_SEGMENT_S
from lynxsim.errors import (
    InvalidInputError,
    LimitViolationError,
    LynxsimError,
    NonFiniteInputError,
    TrajectoryError,
)
from lynxsim.traj import (
    WAYPOINT_KINDS,
    JointLimits,
    PolynomialSegment,
    TrajectoryKind,
    check_trajectory,
    cubic_coefficients,
    quintic_coefficients,
)
from lynxsim.traj.ruckig_profile import _calculate
from tests.helpers import assert_close

Q = np.radians([[0.0, 60.0, -60.0, 0.0, 0.0], [40.0, 90.0, -30.0, 20.0, 90.0]])
"""Two joint waypoints every type can join."""

KINDS = list(WAYPOINT_KINDS)
DURATION_RANGE = r"segment durations must be between 0\.001 and 3600 s"
TOO_LOW = r"needs .* s within the joint limits, more than the longest segment allowed"


@pytest.mark.parametrize("kind", KINDS, ids=lambda k: k.value)
@pytest.mark.parametrize("stretch", [False, True], ids=["exact", "stretch"])
@pytest.mark.parametrize(
    "duration",
    [5e-324, 1e-300, 1e-4, -0.0, 0.0, -1.0, 3600.5, 1e60, 1e300, 6.5e306],
    ids=str,
)
def test_given_durations_outside_the_range_are_refused(kind, stretch, duration):
    # Before: a 5e-324 s line never moved, 1e-300 s raised LinAlgError/ZeroDivisionError,
    # 1e300 s OverflowError, ruckig at 1e60 s "ValueError: -101 is not a valid Result".
    with pytest.raises(InvalidInputError, match=DURATION_RANGE):
        generate(kind, Q, duration, stretch=stretch)


@pytest.mark.parametrize("kind", KINDS, ids=lambda k: k.value)
def test_durations_at_the_ends_of_the_range_are_planned(kind):
    long = generate(kind, Q, MAX_SEGMENT_S)
    assert_close(long.segment_durations, [MAX_SEGMENT_S], atol=1e-9)
    tiny = np.array([Q[0], Q[0] + 1e-9])  # a motion 1 ms keeps within the limits
    short = generate(kind, tiny, MIN_SEGMENT_S)
    assert_close(short.segment_durations, [MIN_SEGMENT_S], atol=1e-15)
    for traj in (long, short):
        states = traj.sample(np.linspace(0.0, traj.duration, 101))
        assert all(np.isfinite(x).all() for x in states)
        assert_close(states.q[-1], traj.waypoints.q[-1], atol=1e-8)


@pytest.mark.parametrize("kind", KINDS, ids=lambda k: k.value)
def test_shortest_durations_of_tiny_motions_are_one_millisecond(kind):
    traj = generate(kind, np.array([Q[0], Q[0] + 1e-12]))
    assert_close(traj.segment_durations, [MIN_SEGMENT_S], atol=1e-15)


@pytest.mark.parametrize("kind", KINDS, ids=lambda k: k.value)
@pytest.mark.parametrize("limit", [5e-324, 1e-300, 3e-4], ids=str)
def test_limits_too_low_for_an_hour_raise_clearly(kind, limit):
    limits = JointLimits.for_joints(5, limit, limit, limit)
    if kind is TrajectoryKind.RUCKIG and limit < 1e-100:
        with pytest.raises(TrajectoryError, match=r"Ruckig cannot plan segment 1: .*beyond"):
            generate(kind, Q, limits=limits)
    else:
        with pytest.raises(InvalidInputError, match=TOO_LOW):
            generate(kind, Q, limits=limits)
    with pytest.raises(LynxsimError):
        generate(kind, Q, 1.0, limits=limits, stretch=True)


@pytest.mark.parametrize("kind", [k for k in KINDS if k is not TrajectoryKind.RUCKIG])
def test_huge_limits_give_the_shortest_segment(kind):
    traj = generate(kind, Q, limits=JointLimits.for_joints(5, 1e300, 1e300, 1e300))
    assert_close(traj.segment_durations, [MIN_SEGMENT_S], atol=1e-15)


def test_ruckig_failures_are_typed_with_the_reason_in_words():
    # Ruckig 0.19's Python module has no name for result -101 (duration beyond 7600 s).
    with pytest.raises(
        TrajectoryError, match=r"longer than Ruckig can compute \(7600 s\) \(Ruckig result -101\)"
    ) as err:
        generate("ruckig", Q, limits=JointLimits.for_joints(5, 1e-4, 1.0, 1.0))
    assert "is not a valid Result" not in str(err.value)


def test_ruckig_result_codes_map_to_messages():
    import ruckig  # type: ignore[import-not-found]

    otg, inp, out = ruckig.Ruckig(1), ruckig.InputParameter(1), ruckig.Trajectory(1)
    inp.current_position, inp.target_position = [0.0], [1.0]
    inp.max_velocity, inp.max_acceleration, inp.max_jerk = [1.0], [1.0], [1.0]
    assert _calculate(otg, inp, out) == ""
    inp.minimum_duration = 1e60
    assert "(Ruckig result -101)" in _calculate(otg, inp, out)


def test_times_at_rate_is_bounded_in_rate_and_count():
    traj = quintic(Q, 1.0)
    with pytest.raises(InvalidInputError, match=r"rate_hz must be between 1 and 10000 Hz"):
        traj.times_at_rate(1e12)  # before: MemoryError (14.6 TiB)
    with pytest.raises(InvalidInputError, match=r"rate_hz must be between 1 and 10000 Hz"):
        traj.times_at_rate(0.5)
    with pytest.raises(NonFiniteInputError, match="rate_hz must be finite"):
        traj.times_at_rate(math.nan)
    long = free_motion(np.array([Q[0], Q[1], Q[0], Q[1]]), MAX_SEGMENT_S)
    with pytest.raises(InvalidInputError, match=r"108,000,001 samples, more than 10,000,000"):
        long.times_at_rate(10_000.0)
    assert long.times_at_rate(100.0).size == 1_080_001


def test_sampling_grids_and_batches_are_bounded():
    traj = quintic(Q, 1.0)
    with pytest.raises(InvalidInputError, match=r"steps must be between 1 and 9,999,999"):
        traj.times_per_segment(10**9)
    with pytest.raises(InvalidInputError, match=r"steps must be an integer"):
        traj.times_per_segment(10.0)
    with pytest.raises(InvalidInputError, match=r"at most 10,000,000 sample times"):
        traj.sample(np.broadcast_to(0.0, (MAX_SAMPLES + 1,)))


BAD_NUMBERS = [
    pytest.param("1.0", id="str"),
    pytest.param(None, id="None"),
    pytest.param({}, id="dict"),
    pytest.param(1j, id="complex"),
    pytest.param(True, id="bool"),
    pytest.param(np.array([True]), id="bool-array"),
    pytest.param(np.array([1.0], dtype=object), id="object-array"),
    pytest.param(10**400, id="10**400"),
    pytest.param([[1.0], [2.0, 3.0]], id="ragged"),
]


@pytest.mark.parametrize("value", BAD_NUMBERS)
def test_non_numbers_are_refused_everywhere(value):
    traj = quintic(Q, 1.0)
    durations = (
        []
        if value is None
        else [  # None: the shortest durations
            lambda: quintic(Q, value),
            lambda: generate("ruckig", Q, value),
        ]
    )
    calls = [
        *durations,
        lambda: traj.times_at_rate(value),
        lambda: traj.sample(value),
        lambda: JointLimits(value, 1.0, 1.0),
        lambda: ArmPose((0.2, 0.0, 0.2), value),
        lambda: ArmPose(value, 0.0),
        lambda: JointPose(value),
        lambda: resolve_waypoints(value),
        lambda: cubic_coefficients(0.0, value, 0.0, 0.0, 1.0, 0.0),
        lambda: quintic_coefficients(0.0, 1.0, value, 0.0, 0.0, 1.0, 0.0, 0.0),
        lambda: PolynomialSegment(value, np.zeros((1, 2, 5))),
    ]
    for call in calls:
        with pytest.raises(InvalidInputError):
            call()


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"limits": None}, r"limits must be of type JointLimits, got NoneType"),
        ({"stretch": "no"}, r"stretch must be True or False, got 'no'"),
        ({"pass_through": 1}, r"pass_through must be True or False, got 1"),
        ({"geometry": "arm"}, r"geometry must be of type ArmGeometry, got str"),
    ],
    ids=["limits", "stretch", "pass_through", "geometry"],
)
def test_options_of_the_wrong_type_are_refused(kwargs, message):
    for kind in ("quintic", "ruckig") if "pass_through" not in kwargs else ("ruckig",):
        with pytest.raises(InvalidInputError, match=message):
            generate(kind, Q, 1.0, **kwargs)


def test_check_trajectory_refuses_what_is_not_a_trajectory():
    with pytest.raises(InvalidInputError, match="traj must be of type Trajectory, got NoneType"):
        check_trajectory(None)  # type: ignore[arg-type]


def test_waypoint_positions_beyond_the_coordinate_bound_are_refused():
    with pytest.raises(InvalidInputError, match=r"within ±10 m"):
        ArmPose((1e300, 0.0, 0.2), 0.0)  # before: RuntimeWarning overflow in the IK
    with pytest.raises(InvalidInputError, match="a waypoint name must be a string"):
        ArmPose((0.2, 0.0, 0.2), 0.0, None, 5)  # type: ignore[arg-type]


def test_a_one_element_array_counts_as_a_number_consistently():
    traj = quintic(Q, np.array([1.0]))
    assert_close(traj.times_at_rate(np.array([50.0])), traj.times_at_rate(50.0), atol=0.0)
    assert_close(traj.times_at_rate(np.float32(50.0)), traj.times_at_rate(50.0), atol=0.0)
    pose = ArmPose((0.2, 0.0, 0.2), np.array([0.1]), np.array(0.2))
    assert (pose.pitch, pose.roll) == (0.1, 0.2)
    with pytest.raises(InvalidInputError, match=r"must be a number .* got shape \(2,\)"):
        traj.times_at_rate(np.array([50.0, 60.0]))


def test_polynomial_segments_refuse_values_that_overflow():
    c = np.zeros((1, 6, 5))
    c[0, 5] = 1e306  # 1e311 at the segment's end
    with pytest.raises(InvalidInputError, match="coefficients too large"):
        PolynomialSegment(np.array([0.0, 10.0]), c)
    with pytest.raises(InvalidInputError, match=r"segment duration must be between"):
        PolynomialSegment(np.array([0.0, 1e-300]), np.zeros((1, 2, 5)))


def test_coefficients_refuse_degenerate_times():
    with pytest.raises(InvalidInputError, match=r"tf - t0 must be between 0\.001 and 3600 s"):
        quintic_coefficients(0.0, 1e-300, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0)  # before: LinAlgError
    with pytest.raises(InvalidInputError, match=r"tf must be between -3600 and 3600 s"):
        cubic_coefficients(0.0, 1e300, 0.0, 0.0, 1.0, 0.0)  # before: OverflowError
    with pytest.raises(NonFiniteInputError, match="coefficients overflow"):
        cubic_coefficients(0.0, 1.0, -1e308, 0.0, 1e308, 0.0)


def test_too_many_waypoints_are_refused_before_any_work():
    with pytest.raises(InvalidInputError, match=r"a trajectory needs 2 to 9,757 waypoints"):
        quintic(np.zeros((20_000, 5)), 1.0)


def test_limit_violations_stay_the_error_for_valid_but_short_durations():
    with pytest.raises(LimitViolationError):
        quintic(Q, 0.1)
