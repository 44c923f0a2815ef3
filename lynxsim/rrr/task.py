"""A 3-RRR task's motion: its platform poses timed into a :class:`PlatformPath`."""

from __future__ import annotations

import numpy as np

from lynxsim.errors import InvalidInputError
from lynxsim.inputs import instance
from lynxsim.rrr.path import (
    DEFAULT_PLATFORM_LIMITS,
    RRR_TRAJECTORY_KINDS,
    PlatformLimits,
    PlatformPath,
    platform_path,
)
from lynxsim.tasks import PlanarPose, Task
from lynxsim.traj.build import parse_kind
from lynxsim.traj.kinds import TrajectoryKind

__all__ = ["path_from_task"]


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
    poses = [p for p in task.poses if isinstance(p, PlanarPose)]
    if len(poses) != len(task.poses):
        raise InvalidInputError(
            f"task {task.name!r} is for robot {task.robot!r}; its poses are not platform poses"
        )
    chosen = task.trajectory if kind is None else parse_kind(kind)
    if chosen not in RRR_TRAJECTORY_KINDS:
        raise InvalidInputError(
            f"trajectory type {chosen.value!r} is not planned for the 3-RRR robot; "
            f"expected one of: {', '.join(k.value for k in RRR_TRAJECTORY_KINDS)}"
        )
    return platform_path(
        np.array([[p.x, p.y, p.alpha] for p in poses]),
        task.durations,
        names=[p.name for p in poses],
        through=task.pass_through,
        stretch=task.stretch,
        limits=limits,
    )
