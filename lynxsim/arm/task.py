"""An arm task's motion: its poses through a joint trajectory of any type."""

from __future__ import annotations

from lynxsim.arm.motion.build import generate
from lynxsim.arm.motion.space import ARM_LIMITS
from lynxsim.errors import InvalidInputError
from lynxsim.poses import ArmPose, JointPose
from lynxsim.tasks import Task
from lynxsim.traj.build import parse_kind
from lynxsim.traj.kinds import TrajectoryKind
from lynxsim.traj.limits import JointLimits
from lynxsim.traj.trajectory import Trajectory

__all__ = ["build_trajectory"]


def build_trajectory(
    task: Task,
    kind: TrajectoryKind | str | None = None,
    limits: JointLimits | None = None,
) -> Trajectory:
    """The trajectory of a task, of its own type or another.

    Args:
        task: The task (see :func:`lynxsim.tasks.load_task`).
        kind: Trajectory type overriding the task's; ``None`` keeps it.
        limits: Joint limits; ``None`` for :data:`~lynxsim.arm.motion.ARM_LIMITS`.

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
    chosen = task.trajectory if kind is None else parse_kind(kind)
    return generate(
        chosen,
        poses,
        task.durations,
        limits=ARM_LIMITS if limits is None else limits,
        stretch=task.stretch,
        pass_through=task.pass_through and chosen is TrajectoryKind.RUCKIG,
    )
