"""Robot names: what the task files and the commands know of each robot before importing it.

A row (:class:`RobotInfo`) gives a robot's name (a task file's ``robot``), its
title, how its task files write poses, whether it stands in the table scene,
and where its record lives (``"module:attribute"``, imported only by whoever
needs the robot's code). Reading the table imports nothing but this module, so
the task loader (:mod:`lynxsim.tasks`) can check a file's robot without
loading any robot.

The built-in robots are rows here; another robot adds its row with
:func:`register_info` (:func:`lynxsim.robots.register` does, with its record).
A name no row has is looked for among the entry points of the group
:data:`ENTRY_POINT_GROUP` of the installed packages: an entry point of that
name is loaded (its module registers the robot) before the name is refused.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from importlib.metadata import entry_points
from typing import Literal, get_args

from lynxsim.errors import InvalidInputError

__all__ = [
    "ENTRY_POINT_GROUP",
    "MAX_JOINTS",
    "POSE_SCHEMAS",
    "PoseSchema",
    "RobotInfo",
    "discover",
    "info",
    "names",
    "register_info",
    "unregister_info",
]

PoseSchema = Literal["tool", "platform", "joints"]
"""How a task file writes a robot's poses: ``"tool"`` (``position_mm``,
``pitch_deg``, ``roll_deg`` or ``q_deg``: a serial arm's tool), ``"platform"``
(``x_mm``, ``y_mm``, ``alpha_deg``: a planar platform) or ``"joints"``
(``q_deg`` only: a robot that takes joint poses)."""

ENTRY_POINT_GROUP = "lynxsim.robots"
"""Entry point group of robots offered by installed packages: name = the robot's
name, value = ``"module:attribute"`` of its record."""

MAX_JOINTS = 32
"""Most joints of a robot's ``q_deg`` poses."""

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
        joints: Length of its ``q_deg`` poses (1 .. :data:`MAX_JOINTS`), or None for
            a robot without joint poses; needed by the ``"joints"`` schema.

    Raises:
        InvalidInputError: A field of the wrong type or form.
    """

    name: str
    title: str
    poses: PoseSchema
    scene: bool
    entry: str
    joints: int | None = None

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
        joints = self.joints
        if joints is not None and (
            isinstance(joints, bool) or not isinstance(joints, int) or not 1 <= joints <= MAX_JOINTS
        ):
            raise InvalidInputError(
                f"joints must be an integer from 1 to {MAX_JOINTS} or None, got {joints!r}"
            )
        if joints is None and self.poses == "joints":
            raise InvalidInputError(f"robot {self.name!r}: the 'joints' pose schema needs joints")


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


def unregister_info(name: str) -> None:
    """Forget a robot's row (a session that registered a robot for a while; tests).

    Raises:
        InvalidInputError: Unknown name (lists the known ones).
    """
    info(name)
    del _ROBOTS[name]


def discover(name: str | None = None) -> None:
    """Load the entry points of :data:`ENTRY_POINT_GROUP` named ``name`` (None: all).

    Loading one imports its module, which registers its robot
    (:func:`lynxsim.robots.register`); a loaded object with a :class:`RobotInfo`
    as its ``info`` has that row registered too. Rows already known are skipped.
    """
    for point in entry_points(group=ENTRY_POINT_GROUP):
        if (name is not None and point.name != name) or point.name in _ROBOTS:
            continue
        try:
            loaded = point.load()
        except Exception as exc:  # an installed package's import: any error, one line
            raise InvalidInputError(
                f"robot {point.name!r}: its entry point {point.value} does not load: {exc}"
            ) from exc
        row = getattr(loaded, "info", None)
        if isinstance(row, RobotInfo) and row.name not in _ROBOTS:
            register_info(row)


def info(name: str) -> RobotInfo:
    """The row of a robot (an unknown name is first looked for among the entry points).

    Raises:
        InvalidInputError: Unknown name (lists the known ones).
    """
    if isinstance(name, str) and name not in _ROBOTS and _NAME.match(name):
        discover(name)
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
        joints=5,
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
