"""The robot table: a task's ``robot`` name to its kinematics, motion builder, model and adapter.

No other module branches on a robot's name: it looks the robot up here. A row
names its parts by import path, so that reading the table imports neither
MuJoCo nor the robot's code; :func:`sim_adapter` imports the adapter on demand.

A third robot adds: its kinematics folder (``lynxsim/<robot>/``, with a
``task.py`` that turns a task into its motion), its model
(``lynxsim/models/<robot>/``), its simulation adapter (``lynxsim/sim/<robot>/``),
and one row here. Its task files reuse one of the pose schemas
(:data:`PoseSchema`); a robot with a new kind of pose adds its reader to
:mod:`lynxsim.tasks`.
"""

from __future__ import annotations

import importlib
from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Literal, Protocol

from lynxsim.errors import InvalidInputError

if TYPE_CHECKING:
    from lynxsim.tasks import Task

__all__ = [
    "ROBOTS",
    "PoseSchema",
    "PreparedRun",
    "RobotEntry",
    "SimAdapter",
    "motion_builder",
    "robot",
    "sim_adapter",
]

PoseSchema = Literal["tool", "platform"]
"""How a task file writes a robot's poses: ``"tool"`` (``position_mm``,
``pitch_deg``, ``roll_deg`` or ``q_deg``: a serial arm's tool) or ``"platform"``
(``x_mm``, ``y_mm``, ``alpha_deg``: a planar platform)."""


class PreparedRun(Protocol):
    """A task's motion, built and ready to be played.

    Attributes:
        label: Name of the motion's type, for file names and reports.
    """

    label: str

    def run(self, *, video: Any, render: Any, progress: Any, **options: Any) -> Any:
        """Play it (and film it to ``video`` unless None); returns the ``Playback``."""


class SimAdapter(Protocol):
    """What the command line and the demo ask of a robot's simulation side.

    Attributes:
        default_camera: Camera of its videos.
        options: Names of the run options it accepts (keywords of ``PreparedRun.run``).
    """

    default_camera: str
    options: frozenset[str]

    def prepare(self, task: Task, kind: str | None) -> PreparedRun:
        """Build the task's motion of type ``kind`` (None: the task's own)."""


@dataclass(frozen=True)
class RobotEntry:
    """One row of the robot table.

    Attributes:
        name: The task files' ``robot`` value.
        title: Human name.
        kinematics: Module of its pure kinematics.
        poses: The pose schema of its task files.
        scene: Whether it stands in the table scene (obstacles and a cube).
        motion: ``"module:function"`` building a task's motion, ``(task, kind) -> motion``.
        model: Its MJCF scene, relative to ``lynxsim/models``.
        adapter: ``"module:attribute"`` of its :class:`SimAdapter`.
    """

    name: str
    title: str
    kinematics: str
    poses: PoseSchema
    scene: bool
    motion: str
    model: str
    adapter: str


ROBOTS: dict[str, RobotEntry] = {
    "arm": RobotEntry(
        name="arm",
        title="Lynxmotion 5-DOF arm",
        kinematics="lynxsim.arm",
        poses="tool",
        scene=True,
        motion="lynxsim.arm.task:build_trajectory",
        model="lynx_arm/scene.xml",
        adapter="lynxsim.sim.arm.adapter:ADAPTER",
    ),
    "rrr": RobotEntry(
        name="rrr",
        title="planar 3-RRR parallel robot",
        kinematics="lynxsim.rrr",
        poses="platform",
        scene=False,
        motion="lynxsim.rrr.task:path_from_task",
        model="rrr/scene.xml",
        adapter="lynxsim.sim.rrr.adapter:ADAPTER",
    ),
}
"""Every robot lynxsim simulates, by name."""


def robot(name: str) -> RobotEntry:
    """The row of a robot.

    Raises:
        InvalidInputError: Unknown name (lists the known ones).
    """
    entry = ROBOTS.get(name)
    if entry is None:
        raise InvalidInputError(f"unknown robot {name!r}; expected one of: {', '.join(ROBOTS)}")
    return entry


def _attribute(path: str) -> Any:
    module, _, attribute = path.partition(":")
    return getattr(importlib.import_module(module), attribute)


def sim_adapter(name: str) -> SimAdapter:
    """The simulation adapter of a robot (imports MuJoCo)."""
    adapter: SimAdapter = _attribute(robot(name).adapter)
    return adapter


def motion_builder(name: str) -> Callable[[Task, str | None], Any]:
    """The function that builds a robot's task into its motion (pure: no MuJoCo).

    It takes the task and a trajectory type (None: the task's own) and returns
    the robot's motion (a joint :class:`~lynxsim.traj.Trajectory` for the arm, a
    :class:`~lynxsim.rrr.path.PlatformPath` for the 3-RRR).
    """
    builder: Callable[[Task, str | None], Any] = _attribute(robot(name).motion)
    return builder
