"""The 3-RRR's simulation side (named by :mod:`lynxsim.robots.rrr`): a task to a played path."""

from __future__ import annotations

import os
from dataclasses import dataclass

from lynxsim.rrr.build import build_path
from lynxsim.rrr.modes import HOME_MODE
from lynxsim.rrr.path import PlatformPath
from lynxsim.sim.recording import ProgressFn
from lynxsim.sim.render import RenderSettings
from lynxsim.sim.rrr.task import run_rrr_path
from lynxsim.sim.summary import Playback
from lynxsim.tasks import Task

__all__ = ["ADAPTER", "RRRAdapter", "RRRRun"]


@dataclass(frozen=True)
class RRRRun:
    """A 3-RRR task's platform path, ready to play.

    Attributes:
        task: The task.
        path: Its timed platform path.
    """

    task: Task
    path: PlatformPath

    @property
    def label(self) -> str:
        """The path's type name."""
        return self.path.label

    def run(
        self,
        *,
        video: str | os.PathLike[str] | None,
        render: RenderSettings,
        progress: ProgressFn | None,
        mode: int = HOME_MODE,
        replay: str | os.PathLike[str] | None = None,
    ) -> Playback:
        """Play it through the actuated joints, IK in working mode ``mode`` (0..7).

        ``replay``: where to save the run's replay data, or None.
        """
        return run_rrr_path(
            self.path,
            task=self.task.name,
            mode=mode,
            video=video,
            render=render,
            progress=progress,
            replay=replay,
        )


@dataclass(frozen=True)
class RRRAdapter:
    """The 3-RRR's simulation side for the command line and the demo."""

    default_camera: str = "top"
    options: frozenset[str] = frozenset({"mode"})

    def prepare(self, task: Task, kind: str | None) -> RRRRun:
        """Plan the task's platform path of type ``kind`` (None: the task's own)."""
        path = build_path(
            task.poses,
            task.trajectory if kind is None else kind,
            task.durations,
            through=task.pass_through,
            stretch=task.stretch,
        )
        return RRRRun(task, path)


ADAPTER = RRRAdapter()
"""The adapter the 3-RRR's record names."""
