"""What every robot's simulation side offers the commands: the :class:`SimAdapter` protocol.

A robot's record (:class:`lynxsim.robots.Robot`) names its adapter as
``"module:attribute"`` (:attr:`~lynxsim.robots.Robot.sim`), imported on demand
(:func:`lynxsim.robots.simulation`) so that the commands that need no physics
never import MuJoCo. The adapter builds the robot's MuJoCo model of a scene,
its collision checker (the planner's world), plays a task's motion (the run
report, a video, the replay data) and records a run for the sweeps. A robot
that cannot do one of these (the 3-RRR stands in no table scene: no checker,
no recorded run) raises :class:`~lynxsim.errors.CapabilityError` naming itself
and the capability (:func:`lacks`); the commands check the record's fields
first, never its name.

A robot with a real backend (:attr:`lynxsim.robots.Robot.real`) names a
:class:`RealBackend`: its calibration and its digital twin (the motion played
ideally and through the servo controller the real robot has).

An adapter module checks itself against the protocol with an annotation,
``ADAPTER: SimAdapter = MyAdapter(...)``, which strict mypy verifies.
"""

from __future__ import annotations

import os
from typing import TYPE_CHECKING, Protocol, runtime_checkable

from lynxsim.errors import CapabilityError

if TYPE_CHECKING:
    import mujoco

    from lynxsim.real.calibration import Calibration
    from lynxsim.real.stream import StreamOptions
    from lynxsim.registry import RobotInfo
    from lynxsim.run_options import RunValues
    from lynxsim.scene import Scene
    from lynxsim.sim.collision import CollisionChecker, CollisionGroups
    from lynxsim.sim.recorded import RecordedRun
    from lynxsim.sim.recording import ProgressFn
    from lynxsim.sim.render import RenderSettings
    from lynxsim.sim.summary import Playback
    from lynxsim.sim.twin import TwinRun
    from lynxsim.tasks import Task
    from lynxsim.traj.motion import Motion

__all__ = ["RealBackend", "SimAdapter", "lacks"]

Destination = str | os.PathLike[str]


@runtime_checkable
class SimAdapter(Protocol):
    """A robot's simulation side."""

    def model(self, scene: Scene) -> mujoco.MjModel:
        """The robot's MuJoCo model in ``scene``, compiled (its cameras are the record's).

        Raises:
            CapabilityError: The robot cannot stand in this scene (obstacles or a
                cube for a robot of no table scene).
        """
        ...

    def checker(self, scene: Scene) -> CollisionChecker:
        """A collision checker of the robot's joints in ``scene`` (the planner's world).

        Raises:
            CapabilityError: The robot has none.
        """
        ...

    def scene_model(self, scene: Scene) -> tuple[mujoco.MjModel, CollisionGroups]:
        """The model of ``scene`` and its collision groups (the sweep's placement judge).

        Raises:
            CapabilityError: The robot stands in no table scene.
        """
        ...

    def play(
        self,
        task: Task,
        motion: Motion,
        *,
        options: RunValues | None = None,
        video: Destination | None = None,
        render: RenderSettings | None = None,
        progress: ProgressFn | None = None,
        replay: Destination | None = None,
    ) -> Playback:
        """Play a task's motion in its scene: the run's report and log.

        Args:
            task: The task (its name, its scene).
            motion: The motion the robot's record built for it.
            options: The run's options (None: every default).
            video: MP4 to film it to, or None.
            render: Video settings (None: the robot's defaults, its first camera).
            progress: Called with the fraction done.
            replay: Where to save the run's replay data, or None.

        Raises:
            InvalidInputError: ``motion`` is not a motion of this robot.
        """
        ...

    def record(self, task: Task, motion: Motion, scene: Scene) -> RecordedRun:
        """Play a task's motion in ``scene`` as :meth:`play` does, keeping every state (sweeps).

        Raises:
            CapabilityError: The robot records no runs.
            ReplayMismatchError: The recorded hold does not join the playback.
        """
        ...


@runtime_checkable
class RealBackend(Protocol):
    """A robot's real hardware: its calibration and the digital twin of its controller.

    Attributes:
        controller: Name of its servo controller (``lynxsim play --controller``).
    """

    @property
    def controller(self) -> str:
        """Name of its servo controller, e.g. ``"ssc32"``."""
        ...

    def calibration(self, path: Destination | None) -> Calibration:
        """Read a calibration file (None: the one shipped with the robot).

        Raises:
            CalibrationFileError: The file is malformed (names file and field).
        """
        ...

    def twin(
        self,
        task: Task,
        motion: Motion,
        calibration: Calibration,
        options: StreamOptions | None = None,
        *,
        video: Destination | None = None,
        render: RenderSettings | None = None,
        progress: ProgressFn | None = None,
    ) -> TwinRun:
        """Play a task's motion ideally and through the controller, in the task's scene.

        Raises:
            InvalidInputError: ``motion`` is not a motion of this robot.
            CommandLimitError: The stream leaves the calibration or a speed limit.
        """
        ...


def lacks(row: RobotInfo, capability: str, why: str) -> CapabilityError:
    """The error of a robot that cannot do something: names the robot, the capability, why."""
    return CapabilityError(f"the {row.title} (robot {row.name!r}) has no {capability}: {why}")
