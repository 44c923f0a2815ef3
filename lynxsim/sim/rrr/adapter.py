"""The 3-RRR's simulation side (named by :mod:`lynxsim.robots.rrr`): a task to a played path.

The 3-RRR stands in no table scene: it has no collision checker and records no
runs for sweeps; asked for either, it raises
:class:`~lynxsim.errors.CapabilityError`. Its runs take the option
:data:`~lynxsim.rrr.modes.MODE_OPTION` (the working mode of the inverse kinematics).
"""

from __future__ import annotations

import os
from dataclasses import dataclass

import mujoco

from lynxsim.errors import CapabilityError
from lynxsim.inputs import instance
from lynxsim.registry import info
from lynxsim.rrr.modes import HOME_MODE, MODE_OPTION
from lynxsim.rrr.path import PlatformPath
from lynxsim.run_options import RunValues
from lynxsim.scene import Scene
from lynxsim.sim.adapter import SimAdapter, lacks
from lynxsim.sim.collision import CollisionChecker, CollisionGroups
from lynxsim.sim.recorded import RecordedRun
from lynxsim.sim.recording import ProgressFn
from lynxsim.sim.render import RenderSettings
from lynxsim.sim.rrr.model import load_rrr_scene
from lynxsim.sim.rrr.task import DEFAULT_RRR_RENDER, run_rrr_path
from lynxsim.sim.summary import Playback
from lynxsim.tasks import Task
from lynxsim.traj.motion import Motion

__all__ = ["ADAPTER", "RRRSim"]

_NO_SCENE = "it stands in no table scene"


@dataclass(frozen=True)
class RRRSim:
    """The 3-RRR's simulation side (:class:`~lynxsim.sim.adapter.SimAdapter`)."""

    name: str = "rrr"

    def _lacks(self, capability: str) -> CapabilityError:
        return lacks(info(self.name), capability, _NO_SCENE)

    def model(self, scene: Scene) -> mujoco.MjModel:
        """The 3-RRR's scene at its home assembly (a scene of no obstacle and no cube)."""
        if scene.obstacles or scene.cube is not None:
            raise self._lacks("obstacles or cube")
        return load_rrr_scene()

    def checker(self, scene: Scene) -> CollisionChecker:
        """Refused: the 3-RRR has no collision checker."""
        raise self._lacks("collision checker")

    def scene_model(self, scene: Scene) -> tuple[mujoco.MjModel, CollisionGroups]:
        """Refused: the 3-RRR has no table scene to sweep."""
        raise self._lacks("table scene to sweep")

    def play(
        self,
        task: Task,
        motion: Motion,
        *,
        options: RunValues | None = None,
        video: str | os.PathLike[str] | None = None,
        render: RenderSettings | None = None,
        progress: ProgressFn | None = None,
        replay: str | os.PathLike[str] | None = None,
    ) -> Playback:
        """Play a platform path through the actuated joints, IK in the option ``mode`` (0..7)."""
        path = instance(motion, PlatformPath, "motion")
        mode = HOME_MODE
        if options is not None and MODE_OPTION.name in options:
            mode = options.integer(MODE_OPTION.name)
        return run_rrr_path(
            path,
            task=task.name,
            mode=mode,
            video=video,
            render=DEFAULT_RRR_RENDER if render is None else render,
            progress=progress,
            replay=replay,
        )

    def record(self, task: Task, motion: Motion, scene: Scene) -> RecordedRun:
        """Refused: the 3-RRR records no runs for sweeps."""
        raise self._lacks("recorded runs for sweeps")


ADAPTER: SimAdapter = RRRSim()
"""The adapter the 3-RRR's record names."""
