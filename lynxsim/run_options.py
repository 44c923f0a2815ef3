"""Options of a robot's runs: typed descriptors the command line turns into ``play``'s flags.

A robot declares the options its simulation takes (:attr:`lynxsim.robots.Robot.run_options`):
each a :class:`RunOption` with its name, help, value type (a flag or an
integer), choices and default. ``lynxsim play`` makes one flag per option name
over every registered robot and refuses, before any work, a flag that the task's
robot does not take. What a run receives is a :class:`RunValues`: every option
of its robot, given or defaulted, checked.

:data:`NO_OBSTACLE` is the option of every robot in the table scene that plays
a task without its obstacles (one definition, so that robots share one flag).
"""

from __future__ import annotations

import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

from lynxsim.errors import InvalidInputError

__all__ = ["NO_OBSTACLE", "RunOption", "RunValue", "RunValues"]

RunValue = bool | int
"""The value of a run option: a flag or an integer."""

_NAME = re.compile(r"^[a-z][a-z0-9_]{0,31}$")


@dataclass(frozen=True)
class RunOption:
    """One option of a robot's runs.

    Attributes:
        name: Its name, a Python identifier in lower case (the flag ``--no-obstacle``
            for ``no_obstacle``).
        help: One line for ``lynxsim play --help`` (the robots that take it are named
            before it).
        type: ``bool`` (a flag: given means True) or ``int``.
        default: Its value when not given.
        choices: The values an integer option accepts, or None for any integer.
        metavar: How the help writes an integer's value (e.g. ``"0..7"``), or None.

    Raises:
        InvalidInputError: A malformed field (a default of the wrong type or
            outside the choices, a flag with choices, ...).
    """

    name: str
    help: str
    type: type[bool] | type[int]
    default: RunValue
    choices: tuple[int, ...] | None = None
    metavar: str | None = None

    def __post_init__(self) -> None:
        if not (isinstance(self.name, str) and _NAME.match(self.name)):
            raise InvalidInputError(
                f"a run option's name must be lower-case letters, digits and _, got {self.name!r}"
            )
        if not (isinstance(self.help, str) and self.help.strip()):
            raise InvalidInputError(f"run option {self.name!r}: help must be a non-empty string")
        if self.type is bool:
            if not isinstance(self.default, bool):
                raise InvalidInputError(f"run option {self.name!r}: a flag's default is a bool")
            if self.choices is not None or self.metavar is not None:
                raise InvalidInputError(f"run option {self.name!r}: a flag has no choices")
            return
        if self.type is not int:
            raise InvalidInputError(
                f"run option {self.name!r}: type must be bool or int, got {self.type!r}"
            )
        if self.choices is not None and not (
            isinstance(self.choices, tuple)
            and self.choices
            and all(_is_int(c) for c in self.choices)
        ):
            raise InvalidInputError(
                f"run option {self.name!r}: choices must be a non-empty tuple of integers"
            )
        if self.metavar is not None and not (isinstance(self.metavar, str) and self.metavar):
            raise InvalidInputError(f"run option {self.name!r}: metavar must be a string")
        self.check(self.default)

    @property
    def flag(self) -> str:
        """Its command-line flag: ``--`` and the name with ``-`` for ``_``."""
        return "--" + self.name.replace("_", "-")

    def check(self, value: object) -> RunValue:
        """``value`` if this option accepts it.

        Raises:
            InvalidInputError: A value of the wrong type, or not among the choices.
        """
        if self.type is bool:
            if not isinstance(value, bool):
                raise InvalidInputError(f"{self.flag} is a flag (True or False), got {value!r}")
            return value
        if isinstance(value, bool) or not isinstance(value, int):
            raise InvalidInputError(f"{self.flag} must be an integer, got {value!r}")
        if self.choices is not None and value not in self.choices:
            shown = ", ".join(str(c) for c in self.choices)
            raise InvalidInputError(f"{self.flag} must be one of {shown}, got {value!r}")
        return value


def _is_int(value: object) -> bool:
    return isinstance(value, int) and not isinstance(value, bool)


@dataclass(frozen=True)
class RunValues:
    """Every option of one robot's run, with its value.

    Attributes:
        values: ``(name, value)`` of each option, in the robot's order.
    """

    values: tuple[tuple[str, RunValue], ...] = ()

    @classmethod
    def of(
        cls, options: Sequence[RunOption], given: Mapping[str, RunValue | None] | None = None
    ) -> RunValues:
        """The values of a robot's options: those given (None: not given), the others defaulted.

        Raises:
            InvalidInputError: A given name is no option of the robot, or a value is
                not accepted (:meth:`RunOption.check`).
        """
        given = {} if given is None else dict(given)
        known = {o.name for o in options}
        unknown = sorted(set(given) - known)
        if unknown:
            raise InvalidInputError(
                f"unknown run option {unknown[0]!r}; this robot takes: "
                f"{', '.join(sorted(known)) or 'none'}"
            )
        values = []
        for option in options:
            value = given.get(option.name)
            values.append((option.name, option.default if value is None else option.check(value)))
        return cls(tuple(values))

    def _get(self, name: str) -> RunValue:
        for key, value in self.values:
            if key == name:
                return value
        raise InvalidInputError(
            f"no run option {name!r}; the run has: {', '.join(k for k, _ in self.values) or 'none'}"
        )

    def flag(self, name: str) -> bool:
        """The value of a flag.

        Raises:
            InvalidInputError: No such option, or it is an integer.
        """
        value = self._get(name)
        if not isinstance(value, bool):
            raise InvalidInputError(f"run option {name!r} is an integer, not a flag")
        return value

    def integer(self, name: str) -> int:
        """The value of an integer option.

        Raises:
            InvalidInputError: No such option, or it is a flag.
        """
        value = self._get(name)
        if isinstance(value, bool):
            raise InvalidInputError(f"run option {name!r} is a flag, not an integer")
        return value

    def __contains__(self, name: object) -> bool:
        return any(key == name for key, _ in self.values)


NO_OBSTACLE = RunOption(
    name="no_obstacle",
    help="the scene without the task's obstacles",
    type=bool,
    default=False,
)
"""Play a task in its scene without its obstacles (robots of the table scene)."""
