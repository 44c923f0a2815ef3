"""The registered robots: :func:`register`, :func:`get`, :func:`names`, :func:`every`.

A robot is registered by its record (:class:`~lynxsim.robots.robot.Robot`);
registering adds its row to :mod:`lynxsim.registry` too, so that task files of
the robot load. The built-in robots' rows are known from the start and their
records (``lynxsim.robots.arm:ROBOT``, ``lynxsim.robots.rrr:ROBOT``) are
imported when first asked for; a robot of an installed package is found
through the entry point group :data:`lynxsim.registry.ENTRY_POINT_GROUP`.

A robot's module registers it when imported (``ROBOT = register(Robot(...))``
at module level), so that a worker process that unpickles a job naming the
record (or runs :func:`restore`) knows the robot again.
"""

from __future__ import annotations

import importlib

from lynxsim.errors import InvalidInputError
from lynxsim.inputs import instance
from lynxsim.registry import RobotInfo, discover, info, register_info, unregister_info
from lynxsim.registry import names as row_names
from lynxsim.robots.robot import Robot

__all__ = ["attribute", "every", "get", "names", "register", "restore", "rows", "unregister"]

_RECORDS: dict[str, Robot] = {}


def attribute(entry: str, what: str) -> object:
    """The object an entry ``"module:attribute"`` names (imports the module).

    Raises:
        InvalidInputError: The module does not import or lacks the attribute (names ``what``).
    """
    module, _, name = entry.partition(":")
    try:
        loaded = importlib.import_module(module)
    except ImportError as exc:
        raise InvalidInputError(f"{what}: cannot import {module!r} ({exc})") from exc
    try:
        return getattr(loaded, name)
    except AttributeError:
        raise InvalidInputError(f"{what}: module {module!r} has no {name!r}") from None


def _check_options(robot: Robot) -> None:
    """Refuse a run option whose name another registered robot uses differently (one flag)."""
    for other in _RECORDS.values():
        theirs = {o.name: o for o in other.run_options}
        for option in robot.run_options:
            if option.name in theirs and theirs[option.name] != option:
                raise InvalidInputError(
                    f"robot {robot.name!r}: run option {option.name!r} differs from that of "
                    f"robot {other.name!r}; robots share an option's definition (one flag)"
                )


def register(robot: Robot) -> Robot:
    """Register a robot: its record, and its row (:func:`lynxsim.registry.register_info`).

    Registering an equal record again changes nothing, so a module that
    registers its robot when imported may be imported again (worker processes).

    Args:
        robot: Its record.

    Returns:
        The registered record (``ROBOT = register(Robot(...))``).

    Raises:
        InvalidInputError: ``robot`` is not a :class:`Robot`, another record or
            row has its name, or a run option clashes with another robot's.
    """
    robot = instance(robot, Robot, "robot")
    known = _RECORDS.get(robot.name)
    if known is not None:
        if known == robot:
            return known
        raise InvalidInputError(f"robot {robot.name!r} is registered already, with another record")
    _check_options(robot)
    register_info(robot.info)
    _RECORDS[robot.name] = robot
    return robot


def unregister(name: str) -> None:
    """Forget a robot: its record and its row (a session that used a robot for a while; tests).

    Its module, if imported, stays imported: register its record again to use it again.

    Raises:
        InvalidInputError: Unknown name (lists the known ones).
    """
    unregister_info(name)
    _RECORDS.pop(name, None)


def get(name: str) -> Robot:
    """The record of a robot (imports it on first use).

    Raises:
        InvalidInputError: Unknown name (lists the known ones), or its row's
            entry is not its record.
    """
    known = _RECORDS.get(name) if isinstance(name, str) else None
    if known is not None:
        return known
    row = info(name)
    record = attribute(row.entry, f"robot {row.name!r}")
    if not isinstance(record, Robot) or record.info != row:
        raise InvalidInputError(f"robot {row.name!r}: {row.entry} is not its Robot record")
    return _RECORDS.get(row.name) or register(record)


def names() -> tuple[str, ...]:
    """Every registered robot's name, in registration order."""
    return row_names()


def every() -> tuple[Robot, ...]:
    """Every robot's record: the registered ones and those of installed packages' entry points."""
    discover()
    return tuple(get(name) for name in names())


def rows() -> tuple[RobotInfo, ...]:
    """Every registered robot's row (what :func:`restore` needs in another process)."""
    return tuple(info(name) for name in names())


def restore(known: tuple[RobotInfo, ...]) -> None:
    """Register these rows and import their records: a worker process's start.

    Raises:
        InvalidInputError: A row clashes with one registered here, or its record
            does not import.
    """
    for row in known:
        register_info(row)
        get(row.name)
