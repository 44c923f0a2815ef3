"""The limit check's shortcut for cubic pieces: no grid search only where it cannot raise.

:func:`~lynxsim.traj.check.check_trajectory` knows the exact extremes of
piecewise polynomials of degree 3 or less and skips its grid and
golden-section search where they lie within half the tolerances. These tests
hold it to the search's verdict: on time-optimal Ruckig motions (every limit
reached exactly) and on the same motions held to limits and ranges tightened
just below, at and just beyond the tolerances, the check raises exactly when
the search (forced by passing its extremes) does, with the same message.
"""

from __future__ import annotations

import numpy as np
import pytest

from lynxsim.arm import LYNX_ARM
from lynxsim.arm.motion import ARM_BOUNDS, ARM_LIMITS
from lynxsim.errors import LimitViolationError
from lynxsim.traj.check import Extremes, check_grid, check_trajectory, segment_extremes
from lynxsim.traj.limits import JointBounds, JointLimits
from lynxsim.traj.ruckig_profile import ruckig_trajectory
from lynxsim.traj.trajectory import Trajectory


def _searched(traj: Trajectory) -> list[Extremes]:
    """Every segment's extremes by the grid and golden-section search, all refined."""
    out = []
    for segment in traj.segments:
        tau = check_grid(segment)
        out.append(segment_extremes(segment, tau, segment.evaluate(tau)))
    return out


def _verdict(traj: Trajectory, extremes: list[Extremes] | None) -> str:
    """The check's message, or an empty string when it passes."""
    try:
        check_trajectory(traj, extremes=extremes)
    except LimitViolationError as exc:
        return str(exc)
    return ""


def _held_to(traj: Trajectory, limits: JointLimits, bounds: JointBounds) -> Trajectory:
    return Trajectory(traj.kind, traj.segments, traj.waypoints, bounds, limits)


def _motions(count: int) -> list[Trajectory]:
    rng = np.random.default_rng(11)
    lower, upper = np.asarray(LYNX_ARM.lower), np.asarray(LYNX_ARM.upper)
    out = []
    for _ in range(count):
        q = rng.uniform(lower + 0.1, upper - 0.1, (int(rng.integers(2, 6)), 5))
        out.append(ruckig_trajectory(q, pass_through=True, bounds=ARM_BOUNDS, limits=ARM_LIMITS))
    return out


def test_time_optimal_motions_pass_as_the_search_passes_them() -> None:
    for traj in _motions(20):
        assert _verdict(traj, None) == "" == _verdict(traj, _searched(traj))


@pytest.mark.parametrize("scale", [1.0 - 1e-6, 1.0 - 2e-9, 1.0 - 4e-10, 1.0 - 1e-10, 1.0 + 1e-9])
def test_limits_near_the_motion_give_the_searchs_verdict(scale: float) -> None:
    raised = 0
    for traj in _motions(6):
        v, a, j = (np.asarray(x) * scale for x in (ARM_LIMITS.velocity, ARM_LIMITS.acceleration,
                                                   ARM_LIMITS.jerk))  # fmt: skip
        held = _held_to(traj, JointLimits(tuple(v), tuple(a), tuple(j)), ARM_BOUNDS)
        searched = _verdict(held, _searched(held))
        assert _verdict(held, None) == searched
        raised += searched != ""
    assert raised == (6 if scale < 1.0 - 1e-9 else 0)  # limits reached: beyond the tolerance


@pytest.mark.parametrize("shift", [-1e-6, -1.5e-7, -0.9e-7, -0.4e-7, 1e-9])
def test_ranges_near_the_motion_give_the_searchs_verdict(shift: float) -> None:
    raised = 0
    for traj in _motions(6):
        q = traj.sample(np.linspace(0.0, traj.duration, 4001)).q
        lower, upper = q.min(axis=0) - shift, q.max(axis=0) + shift
        held = _held_to(traj, ARM_LIMITS, JointBounds(ARM_BOUNDS.names, tuple(lower), tuple(upper)))
        searched = _verdict(held, _searched(held))
        assert _verdict(held, None) == searched
        raised += searched != ""
    assert raised == (6 if shift < -1e-7 else 0)
