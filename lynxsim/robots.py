"""The robot table: a task's ``robot`` name to its kinematics, model and simulation adapter.

No other module branches on a robot's name: it looks the robot up here. A row
names its parts by import path, so that reading the table imports neither
MuJoCo nor the robot's code; :func:`sim_adapter` imports the adapter on demand.

A third robot adds: its kinematics folder (``lynxsim/<robot>/``), its model
(``lynxsim/models/<robot>/``), its simulation adapter (``lynxsim/sim/<robot>/``),
and one row here.
"""

from __future__ import annotations

import importlib
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Protocol

from lynxsim.errors import InvalidInputError

if TYPE_CHECKING:
    from lynxsim.tasks import Task

__all__ = ["ROBOTS", "PreparedRun", "RobotEntry", "SimAdapter", "robot", "sim_adapter"]


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
        model: Its MJCF scene, relative to ``lynxsim/models``.
        adapter: ``"module:attribute"`` of its :class:`SimAdapter`.
    """

    name: str
    title: str
    kinematics: str
    model: str
    adapter: str


ROBOTS: dict[str, RobotEntry] = {
    "arm": RobotEntry(
        name="arm",
        title="Lynxmotion 5-DOF arm",
        kinematics="lynxsim.arm",
        model="lynx_arm/scene.xml",
        adapter="lynxsim.sim.arm.adapter:ADAPTER",
    ),
    "rrr": RobotEntry(
        name="rrr",
        title="planar 3-RRR parallel robot",
        kinematics="lynxsim.rrr",
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


def sim_adapter(name: str) -> SimAdapter:
    """The simulation adapter of a robot (imports MuJoCo)."""
    module, _, attribute = robot(name).adapter.partition(":")
    adapter: SimAdapter = getattr(importlib.import_module(module), attribute)
    return adapter
