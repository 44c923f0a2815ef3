"""The task: a robot, its poses and how to move through them (what a task file holds)."""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from pathlib import Path

from lynxsim.poses import ArmPose, JointPose, PlanarPose
from lynxsim.scene import Scene
from lynxsim.traj.kinds import TrajectoryKind

__all__ = ["Task", "TaskPose"]

TaskPose = ArmPose | JointPose | PlanarPose
"""A pose of a task: :class:`ArmPose` or :class:`JointPose` (arm), :class:`PlanarPose` (rrr)."""


@dataclass(frozen=True)
class Task:
    """A task: a robot, its poses and how to move through them.

    Attributes:
        name: Task name.
        robot: A registered robot's name (:func:`lynxsim.registry.names`): ``"arm"``, ``"rrr"``, ...
        poses: The poses in order, SI units (at least two).
        trajectory: The default trajectory type.
        durations: Duration of every segment [s], or ``None`` for the shortest
            within the joint limits.
        stretch: Lengthen given durations that are too short for the limits.
        pass_through: Ruckig: pass intermediate poses without stopping.
        description: Free text.
        source: The file the task was read from, if any.
        scene: Obstacles, table and cube (:class:`~lynxsim.scene.Scene`, SI units,
            the arm's base frame; default: no obstacle, the report's cube).
    """

    name: str
    robot: str
    poses: tuple[TaskPose, ...]
    trajectory: TrajectoryKind
    durations: tuple[float, ...] | None = None
    stretch: bool = False
    pass_through: bool = False
    description: str = ""
    source: Path | None = None
    scene: Scene = dataclasses.field(default_factory=Scene)
