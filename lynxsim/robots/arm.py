"""The arm's record: an arm task's motion, its poses through a trajectory of any type."""

from __future__ import annotations

from lynxsim.arm.motion import ARM_LIMITS
from lynxsim.arm.motion import build_trajectory as build_from_poses
from lynxsim.errors import InvalidInputError
from lynxsim.inputs import instance
from lynxsim.poses import ArmPose, JointPose
from lynxsim.robots import RobotParts
from lynxsim.tasks import Task
from lynxsim.traj.build import parse_kind
from lynxsim.traj.kinds import TrajectoryKind
from lynxsim.traj.limits import JointLimits
from lynxsim.traj.trajectory import Trajectory

__all__ = ["ROBOT", "build_trajectory"]


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
        The checked :class:`~lynxsim.traj.Trajectory`, with the task's poses as its targets.

    Raises:
        InvalidInputError: The task is not for the arm, or the type is unknown.
        LynxsimError: Whatever the generator raises (unreachable pose, limits).
    """
    task = instance(task, Task, "task")
    if not all(isinstance(p, ArmPose | JointPose) for p in task.poses):
        raise InvalidInputError(
            f"task {task.name!r} is for robot {task.robot!r}; joint trajectories are built "
            "from arm poses only"
        )
    return build_from_poses(
        task.poses,
        task.trajectory if kind is None else parse_kind(kind),
        task.durations,
        limits=ARM_LIMITS if limits is None else limits,
        stretch=task.stretch,
        pass_through=task.pass_through,
    )


ROBOT = RobotParts(
    motion=build_trajectory,
    model="lynx_arm/scene.xml",
    adapter="lynxsim.sim.arm.adapter:ADAPTER",
)
"""The arm's record (its row: :mod:`lynxsim.registry`)."""
