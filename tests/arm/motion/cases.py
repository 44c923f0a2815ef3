"""Seeded random waypoint sets and the invariants every trajectory must keep."""

from __future__ import annotations

import numpy as np

from lynxsim.arm import LYNX_ARM, tool_pose
from lynxsim.arm.motion import tool_poses
from lynxsim.poses import ArmPose
from lynxsim.traj import Trajectory, TrajectoryKind
from tests.helpers import assert_close

CASES = 200
"""Successful random cases required per trajectory type."""

POS_TOL = 1e-9
"""Waypoints are hit to this [rad]; boundary derivatives vanish to this times their scale."""

RUCKIG_TOL = 1e-8
"""Ruckig meets its targets to this [rad] (rest to rest often to 1e-14)."""

TOOL_TOL = 1e-9
"""Tool points at waypoints and off the straight line [m]."""

LIMIT_RTOL = 1e-9
"""Relative slack on the velocity, acceleration and jerk limits [-]."""

DENSE = 3000
"""Uniform samples per trajectory, plus as many random ones [-]."""

LINE_LOWER = np.radians([-80.0, 20.0, -130.0, -70.0, 0.0])
LINE_UPPER = np.radians([80.0, 120.0, -15.0, 70.0, 360.0])
"""A joint box whose straight tool lines mostly stay feasible [rad]."""

# Derivative orders that vanish at every waypoint (ruckig: also velocity at the
# first and last waypoint, and at all of them unless it passes through).
ZERO_AT_WAYPOINTS = {
    TrajectoryKind.FREE: (),
    TrajectoryKind.CUBIC: (1,),
    TrajectoryKind.QUINTIC: (1, 2),
    TrajectoryKind.LSPB: (1,),
    TrajectoryKind.LINE: (1, 2),
    TrajectoryKind.RUCKIG: (2,),
}


def random_joints(
    rng: np.random.Generator, lower: np.ndarray = LYNX_ARM.lower, upper: np.ndarray = LYNX_ARM.upper
) -> np.ndarray:
    """2 to 5 random joint vectors in a box, shape (N, 5) [rad]."""
    return rng.uniform(lower, upper, (int(rng.integers(2, 6)), 5))


def as_poses(q: np.ndarray) -> list[ArmPose]:
    """The tool poses of joint vectors (for the IK path of the generators)."""
    pose = tool_pose(q)
    return [
        ArmPose(tuple(p), float(phi), float(r), f"W{i}")
        for i, (p, phi, r) in enumerate(zip(pose.position, pose.pitch, pose.roll))
    ]


def dense_times(traj: Trajectory, rng: np.random.Generator) -> np.ndarray:
    """Uniform and random times over the trajectory, waypoint times included [s]."""
    return np.concatenate(
        [
            np.linspace(0.0, traj.duration, DENSE),
            rng.uniform(0.0, traj.duration, DENSE),
            traj.waypoint_times,
        ]
    )


def assert_invariants(
    traj: Trajectory, rng: np.random.Generator, *, pass_through: bool = False
) -> None:
    """Waypoints hit, boundary derivatives as promised, continuity, no NaN, limits kept."""
    kind = traj.kind
    q_wp = traj.waypoints.q
    at_wp = traj.sample(traj.waypoint_times)
    tol = RUCKIG_TOL if kind is TrajectoryKind.RUCKIG else POS_TOL
    assert_close(at_wp.q, q_wp, atol=tol, err_msg="waypoint joints")
    targets = np.array([p.position for p in tool_poses(traj.waypoints)])
    assert_close(tool_pose(at_wp.q).position, targets, atol=tol, err_msg="waypoint tool")

    ends = [s.evaluate(np.array([s.duration]))[:, 0] for s in traj.segments]  # (4, 5) each
    starts = [s.evaluate(np.array([0.0]))[:, 0] for s in traj.segments]
    for k in range(1, len(traj.segments)):
        for order in range(kind.continuity + 1):
            scale = 1.0 + np.abs(starts[k][order])
            assert_close(
                ends[k - 1][order],
                starts[k][order],
                atol=POS_TOL * scale.max(),
                err_msg=f"order {order} jumps at waypoint {k}",
            )
    for order in ZERO_AT_WAYPOINTS[kind]:
        for state in starts + ends:
            assert_close(
                state[order],
                0.0,
                atol=POS_TOL * traj.limits.of_order(order).max(),
                err_msg=f"order {order} at a waypoint",
            )
    if kind is TrajectoryKind.RUCKIG:
        inner = [] if pass_through else starts[1:]
        for state in [starts[0], ends[-1], *inner]:
            assert_close(state[1], 0.0, atol=tol, err_msg="ruckig velocity at rest")

    t = dense_times(traj, rng)
    states = traj.sample(t)
    for values in states:
        assert np.isfinite(values).all()
    assert (states.q >= LYNX_ARM.lower - POS_TOL).all()
    assert (states.q <= LYNX_ARM.upper + POS_TOL).all()
    for order in kind.limited_orders:
        bound = traj.limits.of_order(order) * (1.0 + LIMIT_RTOL)
        assert (np.abs(states[order]) <= bound).all(), f"order {order} limit broken"

    if kind is TrajectoryKind.LINE:
        assert_straight(traj, t, tool_pose(states.q).position)


def assert_straight(traj: Trajectory, t: np.ndarray, p: np.ndarray) -> None:
    """Tool points at times ``t`` lie on their segment's straight line, between its ends."""
    times = traj.waypoint_times
    seg = np.clip(np.searchsorted(times, t, side="right") - 1, 0, len(traj.segments) - 1)
    targets = np.array([pose.position for pose in tool_poses(traj.waypoints)])
    a, b = targets[seg], targets[seg + 1]
    d = b - a
    length2 = np.einsum("ij,ij->i", d, d)
    s = np.einsum("ij,ij->i", p - a, d) / np.where(length2 > 0, length2, 1.0)
    off = p - a - s[:, None] * d
    assert np.abs(off).max() <= TOOL_TOL, f"tool leaves the line by {np.abs(off).max():.3g} m"
    moving = length2 > 1e-12
    assert (s[moving] >= -TOOL_TOL).all()
    assert (s[moving] <= 1 + TOOL_TOL).all()
