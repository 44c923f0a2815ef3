"""Robot names: what the task files and the commands know of each robot before importing it.

A row (:class:`RobotInfo`) gives a robot's name (a task file's ``robot``), its
title, how its task files write poses, whether it stands in the table scene,
and where its record lives (``"module:attribute"``, imported only by whoever
needs the robot's code). Reading the table imports nothing but this module, so
the task loader (:mod:`lynxsim.tasks`) can check a file's robot without
loading any robot.

The built-in robots are rows here; another robot adds its row with
:func:`register_info`.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from typing import Literal, get_args

from lynxsim.errors import InvalidInputError

__all__ = ["POSE_SCHEMAS", "PoseSchema", "RobotInfo", "info", "names", "register_info"]

PoseSchema = Literal["tool", "platform"]
"""How a task file writes a robot's poses: ``"tool"`` (``position_mm``,
``pitch_deg``, ``roll_deg`` or ``q_deg``: a serial arm's tool) or ``"platform"``
(``x_mm``, ``y_mm``, ``alpha_deg``: a planar platform)."""

POSE_SCHEMAS: tuple[PoseSchema, ...] = get_args(PoseSchema)
"""Every pose schema the task loader reads."""

_NAME = re.compile(r"^[a-z][a-z0-9_]{0,31}$")
_ENTRY = re.compile(r"^[A-Za-z_][\w.]*:[A-Za-z_]\w*$")


@dataclass(frozen=True)
class RobotInfo:
    """One robot's row.

    Attributes:
        name: The task files' ``robot`` value: lower-case letters, digits and
            ``_``, starting with a letter, at most 32 characters.
        title: Human name, for messages.
        poses: The pose schema of its task files (:data:`PoseSchema`).
        scene: Whether it stands in the table scene (obstacles and a cube).
        entry: ``"module:attribute"`` of the robot's record.

    Raises:
        InvalidInputError: A field of the wrong type or form.
    """

    name: str
    title: str
    poses: PoseSchema
    scene: bool
    entry: str

    def __post_init__(self) -> None:
        if not (isinstance(self.name, str) and _NAME.match(self.name)):
            raise InvalidInputError(
                f"robot name must be lower-case letters, digits and _, starting with a "
                f"letter, at most 32 characters, got {self.name!r}"
            )
        if not (isinstance(self.title, str) and self.title.strip()):
            raise InvalidInputError(f"robot title must be a non-empty string, got {self.title!r}")
        if self.poses not in POSE_SCHEMAS:
            raise InvalidInputError(
                f"unknown pose schema {self.poses!r}; expected one of: {', '.join(POSE_SCHEMAS)}"
            )
        if not isinstance(self.scene, bool):
            raise InvalidInputError(f"scene must be True or False, got {self.scene!r}")
        if not (isinstance(self.entry, str) and _ENTRY.match(self.entry)):
            raise InvalidInputError(f"entry must be 'module:attribute', got {self.entry!r}")


_ROBOTS: dict[str, RobotInfo] = {}


def register_info(row: RobotInfo) -> None:
    """Add a robot's row (registering the same row again changes nothing).

    Raises:
        InvalidInputError: ``row`` is not a :class:`RobotInfo`, or another row
            has its name.
    """
    if not isinstance(row, RobotInfo):
        raise InvalidInputError(f"a robot's row must be a RobotInfo, got {row!r}")
    known = _ROBOTS.get(row.name)
    if known is not None and known != row:
        raise InvalidInputError(f"robot {row.name!r} is registered already, as {known!r}")
    _ROBOTS[row.name] = row


def info(name: str) -> RobotInfo:
    """The row of a robot.

    Raises:
        InvalidInputError: Unknown name (lists the known ones).
    """
    row = _ROBOTS.get(name) if isinstance(name, str) else None
    if row is None:
        raise InvalidInputError(f"unknown robot {name!r}; expected one of: {', '.join(names())}")
    return row


def names() -> tuple[str, ...]:
    """Every registered robot's name, in registration order."""
    return tuple(_ROBOTS)


register_info(
    RobotInfo(
        name="arm",
        title="Lynxmotion 5-DOF arm",
        poses="tool",
        scene=True,
        entry="lynxsim.robots.arm:ROBOT",
    )
)
register_info(
    RobotInfo(
        name="rrr",
        title="planar 3-RRR parallel robot",
        poses="platform",
        scene=False,
        entry="lynxsim.robots.rrr:ROBOT",
    )
)
