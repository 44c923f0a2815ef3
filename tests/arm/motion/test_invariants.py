"""Every trajectory type over seeded random waypoint sets keeps its promises.

For each type, at least ``CASES`` random sets of 2 to 5 in-range waypoints, given
as joints or as tool poses, timed as the shortest within the limits, as given
durations stretched where needed, or as exact generous durations. Straight lines
between random poses may leave the joint ranges or need a change of
configuration; those cases must fail with a typed error and are redrawn.
"""

from __future__ import annotations

import numpy as np
import pytest

from lynxsim.arm.motion import generate
from lynxsim.errors import LimitViolationError, PathError, UnreachablePoseError
from lynxsim.traj import WAYPOINT_KINDS, Trajectory, TrajectoryKind
from tests.arm.motion.cases import (
    CASES,
    LINE_LOWER,
    LINE_UPPER,
    as_poses,
    assert_invariants,
    random_joints,
)

SEED = 20240611
MAX_ATTEMPTS = 3 * CASES


def _build(kind: TrajectoryKind, rng: np.random.Generator, case: int) -> tuple[Trajectory, bool]:
    """One random trajectory of ``kind`` and whether it passes through via points."""
    if kind is TrajectoryKind.LINE:
        q = random_joints(rng, LINE_LOWER, LINE_UPPER)
    else:
        q = random_joints(rng)
    waypoints = as_poses(q) if case % 3 == 0 else q
    pass_through = kind is TrajectoryKind.RUCKIG and case % 2 == 1
    mode = case % 4
    if mode == 0 or mode == 1:  # shortest within the limits
        return generate(kind, waypoints, pass_through=pass_through), pass_through
    if mode == 2:  # any durations, stretched where the limits need more time
        durations = rng.uniform(0.05, 3.0, len(q) - 1)
        traj = generate(kind, waypoints, durations, stretch=True, pass_through=pass_through)
        assert (traj.segment_durations >= durations * (1 - 1e-12)).all()
        return traj, pass_through
    shortest = generate(kind, waypoints, pass_through=pass_through)
    durations = shortest.segment_durations * rng.uniform(1.0, 2.0, len(q) - 1)
    traj = generate(kind, waypoints, durations, pass_through=pass_through)
    np.testing.assert_allclose(traj.segment_durations, durations, rtol=1e-12)
    return traj, pass_through


@pytest.mark.slow
@pytest.mark.parametrize("kind", WAYPOINT_KINDS, ids=lambda k: k.value)
def test_random_waypoints_keep_every_promise(kind: TrajectoryKind):
    rng = np.random.default_rng([SEED, list(TrajectoryKind).index(kind)])
    passed = 0
    refused: list[Exception] = []
    for case in range(MAX_ATTEMPTS):
        try:
            traj, pass_through = _build(kind, rng, case)
        except (LimitViolationError, PathError, UnreachablePoseError) as exc:
            refused.append(exc)
            continue
        assert_invariants(traj, rng, pass_through=pass_through)
        passed += 1
        if passed == CASES:
            break
    assert passed == CASES, f"only {passed} of {passed + len(refused)} random cases were feasible"
    # Only a straight line can be impossible between in-range waypoints, and only
    # because a joint leaves its range or the IK must jump.
    assert kind is TrajectoryKind.LINE or not refused, refused[:1]
    assert all(getattr(exc, "quantity", "position") == "position" for exc in refused)
