"""Build a joint trajectory of any type generated through given joint waypoints."""

from __future__ import annotations

from lynxsim.errors import InvalidInputError
from lynxsim.inputs import flag
from lynxsim.traj.kinds import TrajectoryKind
from lynxsim.traj.limits import JointBounds, JointLimits
from lynxsim.traj.lspb import lspb
from lynxsim.traj.polynomial import cubic, free_motion, quintic
from lynxsim.traj.ruckig_profile import ruckig_trajectory
from lynxsim.traj.timing import Durations
from lynxsim.traj.trajectory import Trajectory
from lynxsim.traj.waypoints import WaypointsLike

__all__ = ["JOINT_KINDS", "generate", "parse_kind", "require_joint_kind"]

_GENERATORS = {
    TrajectoryKind.FREE: free_motion,
    TrajectoryKind.CUBIC: cubic,
    TrajectoryKind.QUINTIC: quintic,
    TrajectoryKind.LSPB: lspb,
}

JOINT_KINDS: tuple[TrajectoryKind, ...] = (*_GENERATORS, TrajectoryKind.RUCKIG)
"""The types :func:`generate` makes from joint waypoints alone (no robot needed)."""

_ELSEWHERE = {
    TrajectoryKind.LINE: "straight tool lines follow a robot's tool through its inverse "
    "kinematics, not joint waypoints: the arm's are built by lynxsim.arm.motion "
    "(cartesian_line, or generate with its poses)",
    TrajectoryKind.PLANNED: "planned trajectories are searched around a scene's obstacles, "
    "not generated through given waypoints: use lynxsim.robots.plan",
}


def parse_kind(kind: TrajectoryKind | str) -> TrajectoryKind:
    """``kind`` as a :class:`TrajectoryKind`.

    Raises:
        InvalidInputError: Not a trajectory type (the message lists them).
    """
    try:
        return TrajectoryKind(kind)
    except ValueError:
        valid = ", ".join(k.value for k in TrajectoryKind)
        raise InvalidInputError(
            f"unknown trajectory type {kind!r}; expected one of: {valid}"
        ) from None


def require_joint_kind(kind: TrajectoryKind) -> None:
    """Raise unless ``kind`` is made from joint waypoints alone (:data:`JOINT_KINDS`).

    Raises:
        InvalidInputError: ``line`` or ``planned``; the message says where they are built.
    """
    if kind in _ELSEWHERE:
        raise InvalidInputError(_ELSEWHERE[kind])


def generate(
    kind: TrajectoryKind | str,
    waypoints: WaypointsLike,
    durations: Durations = None,
    *,
    bounds: JointBounds,
    limits: JointLimits,
    stretch: bool = False,
    pass_through: bool = False,
) -> Trajectory:
    """Generate a joint trajectory of the given type through joint waypoints.

    Args:
        kind: The trajectory type (a :class:`TrajectoryKind` or its name), one of
            :data:`JOINT_KINDS`.
        waypoints: Joints, shape (N, n) [rad], or :class:`~lynxsim.traj.waypoints.Waypoints`.
        durations: Segment durations [s]; see :mod:`lynxsim.traj.timing`.
        bounds: The joints (n) and their ranges.
        limits: Joint limits to respect (n joints).
        stretch: Lengthen given durations that are too short for the limits.
        pass_through: Ruckig only: pass intermediate waypoints without stopping.

    Returns:
        The checked :class:`Trajectory`.

    Raises:
        InvalidInputError: Unknown type, a type not made from joint waypoints
            (``line``, ``planned``: the message says where they are built),
            ``pass_through`` not a bool or given for a type that stops.
        LynxsimError: Whatever the generator raises (see each generator).
    """
    kind = parse_kind(kind)
    pass_through = flag(pass_through, "pass_through")
    require_joint_kind(kind)
    if kind is TrajectoryKind.RUCKIG:
        return ruckig_trajectory(
            waypoints,
            durations,
            bounds=bounds,
            limits=limits,
            stretch=stretch,
            pass_through=pass_through,
        )
    if pass_through:
        raise InvalidInputError(f"pass_through applies to ruckig trajectories, not {kind.value}")
    return _GENERATORS[kind](waypoints, durations, bounds=bounds, limits=limits, stretch=stretch)
