"""The arm's simulation side (named by :mod:`lynxsim.robots.arm`): a task to a played trajectory."""

from __future__ import annotations

import os
from dataclasses import dataclass

from lynxsim.sim.arm.planning import task_trajectory
from lynxsim.sim.arm.task import run_arm_trajectory
from lynxsim.sim.recording import ProgressFn
from lynxsim.sim.render import RenderSettings
from lynxsim.sim.summary import Playback
from lynxsim.tasks import Task
from lynxsim.traj import Trajectory

__all__ = ["ADAPTER", "ArmAdapter", "ArmRun"]


@dataclass(frozen=True)
class ArmRun:
    """An arm task's trajectory, ready to play in the task's scene.

    Attributes:
        task: The task.
        trajectory: Its trajectory.
    """

    task: Task
    trajectory: Trajectory

    @property
    def label(self) -> str:
        """The trajectory type's name."""
        return self.trajectory.kind.value

    def run(
        self,
        *,
        video: str | os.PathLike[str] | None,
        render: RenderSettings,
        progress: ProgressFn | None,
        no_obstacle: bool = False,
        replay: str | os.PathLike[str] | None = None,
    ) -> Playback:
        """Play it in the task's scene (``no_obstacle``: without its obstacles).

        ``replay``: where to save the run's replay data, or None.
        """
        scene = self.task.scene.without_obstacles() if no_obstacle else self.task.scene
        return run_arm_trajectory(
            self.trajectory,
            task=self.task.name,
            scene=scene,
            video=video,
            render=render,
            progress=progress,
            replay=replay,
        )


@dataclass(frozen=True)
class ArmAdapter:
    """The arm's simulation side for the command line and the demo."""

    default_camera: str = "front"
    options: frozenset[str] = frozenset({"no_obstacle"})

    def prepare(self, task: Task, kind: str | None) -> ArmRun:
        """Build the task's trajectory of type ``kind`` (None: the task's own)."""
        return ArmRun(task, task_trajectory(task, kind))


ADAPTER = ArmAdapter()
"""The adapter the arm's record names."""
