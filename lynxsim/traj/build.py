"""Build a trajectory of any type from waypoints."""

from __future__ import annotations

from lynxsim.arm import LYNX_ARM, ArmGeometry
from lynxsim.errors import InvalidInputError
from lynxsim.inputs import flag
from lynxsim.traj.cartesian import cartesian_line
from lynxsim.traj.kinds import TrajectoryKind
from lynxsim.traj.limits import DEFAULT_LIMITS, JointLimits
from lynxsim.traj.lspb import lspb
from lynxsim.traj.polynomial import cubic, free_motion, quintic
from lynxsim.traj.ruckig_profile import ruckig_trajectory
from lynxsim.traj.timing import Durations
from lynxsim.traj.trajectory import Trajectory
from lynxsim.traj.waypoints import WaypointsLike

__all__ = ["generate"]

_GENERATORS = {
    TrajectoryKind.FREE: free_motion,
    TrajectoryKind.CUBIC: cubic,
    TrajectoryKind.QUINTIC: quintic,
    TrajectoryKind.LSPB: lspb,
    TrajectoryKind.LINE: cartesian_line,
}


def parse_kind(kind: TrajectoryKind | str) -> TrajectoryKind:
    try:
        return TrajectoryKind(kind)
    except ValueError:
        valid = ", ".join(k.value for k in TrajectoryKind)
        raise InvalidInputError(
            f"unknown trajectory type {kind!r}; expected one of: {valid}"
        ) from None


def generate(
    kind: TrajectoryKind | str,
    waypoints: WaypointsLike,
    durations: Durations = None,
    *,
    limits: JointLimits = DEFAULT_LIMITS,
    stretch: bool = False,
    pass_through: bool = False,
    geometry: ArmGeometry = LYNX_ARM,
) -> Trajectory:
    """Generate a trajectory of the given type through waypoints.

    Args:
        kind: The trajectory type (a :class:`TrajectoryKind` or its name).
        waypoints: Poses or joints, shape (N, 5) [rad]; see :mod:`lynxsim.traj.waypoints`.
        durations: Segment durations [s]; see :mod:`lynxsim.traj.timing`.
        limits: Joint limits to respect.
        stretch: Lengthen given durations that are too short for the limits.
        pass_through: Ruckig only: pass intermediate waypoints without stopping.
        geometry: The arm description.

    Returns:
        The checked :class:`Trajectory`.

    Raises:
        InvalidInputError: Unknown type, ``pass_through`` not a bool or given
            for a type that stops.
        LynxsimError: Whatever the generator raises (see each generator).
    """
    kind = parse_kind(kind)
    pass_through = flag(pass_through, "pass_through")
    if kind is TrajectoryKind.RUCKIG:
        return ruckig_trajectory(
            waypoints,
            durations,
            limits=limits,
            stretch=stretch,
            pass_through=pass_through,
            geometry=geometry,
        )
    if kind is TrajectoryKind.PLANNED:
        raise InvalidInputError(
            "planned trajectories are searched around a scene's obstacles, not generated "
            "through given waypoints: use lynxsim.sim.arm.planning.plan_task"
        )
    if pass_through:
        raise InvalidInputError(f"pass_through applies to ruckig trajectories, not {kind.value}")
    return _GENERATORS[kind](
        waypoints, durations, limits=limits, stretch=stretch, geometry=geometry
    )
