"""The 3-RRR's record: a 3-RRR task's motion, its platform poses timed into a path."""

from __future__ import annotations

from lynxsim.errors import InvalidInputError
from lynxsim.inputs import instance
from lynxsim.poses import PlanarPose
from lynxsim.registry import info
from lynxsim.robots.catalog import register
from lynxsim.robots.robot import Robot
from lynxsim.rrr.build import build_path
from lynxsim.rrr.modes import MODE_OPTION
from lynxsim.rrr.path import (
    DEFAULT_PLATFORM_LIMITS,
    RRR_TRAJECTORY_KINDS,
    PlatformLimits,
    PlatformPath,
)
from lynxsim.tasks import Task
from lynxsim.traj.kinds import TrajectoryKind

__all__ = ["ROBOT", "path_from_task"]


def path_from_task(
    task: Task,
    kind: TrajectoryKind | str | None = None,
    limits: PlatformLimits = DEFAULT_PLATFORM_LIMITS,
) -> PlatformPath:
    """The timed platform path of a 3-RRR task.

    Args:
        task: A task with ``robot = "rrr"`` (:func:`lynxsim.tasks.load_task`).
        kind: Trajectory type overriding the task's; only
            :data:`~lynxsim.rrr.path.RRR_TRAJECTORY_KINDS` are planned for the 3-RRR.
        limits: Task-space limits for missing or stretched durations.

    Returns:
        The :class:`~lynxsim.rrr.path.PlatformPath` (``pass_through`` gives
        one spline through the poses).

    Raises:
        InvalidInputError: ``task`` is not a :class:`~lynxsim.tasks.Task`, the
            task is not for the 3-RRR, the type is not planned for it (the
            message lists those that are), or ``limits`` is not a
            :class:`~lynxsim.rrr.path.PlatformLimits`.
        LynxsimError: Whatever :func:`~lynxsim.rrr.path.platform_path` raises
            (unreachable poses, durations out of range or too short).
    """
    task = instance(task, Task, "task")
    if not all(isinstance(p, PlanarPose) for p in task.poses):
        raise InvalidInputError(
            f"task {task.name!r} is for robot {task.robot!r}; its poses are not platform poses"
        )
    return build_path(
        task.poses,
        task.trajectory if kind is None else kind,
        task.durations,
        through=task.pass_through,
        stretch=task.stretch,
        limits=limits,
    )


ROBOT = register(
    Robot(
        info=info("rrr"),
        kinds=RRR_TRAJECTORY_KINDS,
        motion=path_from_task,
        sim="lynxsim.sim.rrr.adapter:ADAPTER",
        cameras=("top", "front"),
        run_options=(MODE_OPTION,),
    )
)
"""The 3-RRR's record (its row: :mod:`lynxsim.registry`)."""
