"""Robots by name, for the command line and the demo: an interim seam.

INTERIM (issue 22): what the current callers of the old robot table need, and
no more, until the typed robot interface replaces it. A robot's row
(:mod:`lynxsim.registry`) names its record, ``"module:attribute"``; the record
(:class:`RobotParts`, in ``lynxsim/robots/<robot>.py``) holds the task ->
motion builder, its model and its simulation adapter. Reading a row imports
neither MuJoCo nor the robot's code; :func:`sim_adapter` imports the adapter
on demand.
"""

from __future__ import annotations

import importlib
from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Protocol

from lynxsim.errors import InvalidInputError
from lynxsim.registry import info

if TYPE_CHECKING:
    from lynxsim.tasks import Task

__all__ = ["PreparedRun", "RobotParts", "SimAdapter", "motion_builder", "robot", "sim_adapter"]


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
class RobotParts:
    """A robot's record: its parts, by the callers that need them.

    Attributes:
        motion: Builds a task into the robot's motion, ``(task, kind) -> motion``
            (pure: no MuJoCo).
        model: Its MJCF scene, relative to ``lynxsim/models``.
        adapter: ``"module:attribute"`` of its :class:`SimAdapter`.
    """

    motion: Callable[[Task, str | None], Any]
    model: str
    adapter: str


def _attribute(path: str) -> Any:
    module, _, attribute = path.partition(":")
    return getattr(importlib.import_module(module), attribute)


def robot(name: str) -> RobotParts:
    """The record of a registered robot.

    Raises:
        InvalidInputError: Unknown name (lists the known ones), or its row's
            entry is not a :class:`RobotParts`.
    """
    parts = _attribute(info(name).entry)
    if not isinstance(parts, RobotParts):
        raise InvalidInputError(f"robot {name!r}: {info(name).entry} is no RobotParts")
    return parts


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
    return robot(name).motion
