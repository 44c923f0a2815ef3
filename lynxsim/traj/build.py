"""Build a trajectory of any type: from waypoints, or from a task."""

from __future__ import annotations

from typing import TYPE_CHECKING

from lynxsim.arm import LYNX_ARM, ArmGeometry
from lynxsim.errors import InvalidInputError
from lynxsim.traj.cartesian import cartesian_line
from lynxsim.traj.kinds import TrajectoryKind
from lynxsim.traj.limits import DEFAULT_LIMITS, JointLimits
from lynxsim.traj.lspb import lspb
from lynxsim.traj.polynomial import cubic, free_motion, quintic
from lynxsim.traj.ruckig_profile import ruckig_trajectory
from lynxsim.traj.timing import Durations
from lynxsim.traj.trajectory import Trajectory
from lynxsim.traj.waypoints import ArmPose, JointPose, WaypointsLike

if TYPE_CHECKING:
    from lynxsim.tasks import Task

__all__ = ["build_trajectory", "generate"]

_GENERATORS = {
    TrajectoryKind.FREE: free_motion,
    TrajectoryKind.CUBIC: cubic,
    TrajectoryKind.QUINTIC: quintic,
    TrajectoryKind.LSPB: lspb,
    TrajectoryKind.LINE: cartesian_line,
}


def _kind(kind: TrajectoryKind | str) -> TrajectoryKind:
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
        InvalidInputError: Unknown type, or ``pass_through`` for a type that stops.
        LynxsimError: Whatever the generator raises (see each generator).
    """
    kind = _kind(kind)
    if kind is TrajectoryKind.RUCKIG:
        return ruckig_trajectory(
            waypoints,
            durations,
            limits=limits,
            stretch=stretch,
            pass_through=pass_through,
            geometry=geometry,
        )
    if pass_through:
        raise InvalidInputError(f"pass_through applies to ruckig trajectories, not {kind.value}")
    return _GENERATORS[kind](
        waypoints, durations, limits=limits, stretch=stretch, geometry=geometry
    )


def build_trajectory(
    task: Task,
    kind: TrajectoryKind | str | None = None,
    limits: JointLimits | None = None,
) -> Trajectory:
    """The trajectory of a task, of its own type or another.

    Args:
        task: The task (see :func:`lynxsim.tasks.load_task`).
        kind: Trajectory type overriding the task's; ``None`` keeps it.
        limits: Joint limits; ``None`` for :data:`~lynxsim.traj.limits.DEFAULT_LIMITS`.

    Returns:
        The checked :class:`Trajectory`, with the task's poses as its targets.

    Raises:
        InvalidInputError: The task is not for the arm, or the type is unknown.
        LynxsimError: Whatever the generator raises (unreachable pose, limits).
    """
    poses = [p for p in task.poses if isinstance(p, ArmPose | JointPose)]
    if len(poses) != len(task.poses):
        raise InvalidInputError(
            f"task {task.name!r} is for robot {task.robot!r}; joint trajectories are built "
            "from arm poses only"
        )
    chosen = task.trajectory if kind is None else _kind(kind)
    return generate(
        chosen,
        poses,
        task.durations,
        limits=DEFAULT_LIMITS if limits is None else limits,
        stretch=task.stretch,
        pass_through=task.pass_through and chosen is TrajectoryKind.RUCKIG,
        geometry=LYNX_ARM,
    )
