"""Validating readers of task-file values: each failure names the file and the field."""

from __future__ import annotations

import math
import reprlib
from collections.abc import Mapping
from typing import Any

from lynxsim.bounds import MAX_ANGLE_RAD, MAX_COORDINATE_M, MAX_SEGMENT_S, MIN_SEGMENT_S
from lynxsim.errors import TaskFileError
from lynxsim.scene import MIN_SIZE_M

__all__ = ["MAX_DESCRIPTION_CHARS", "MAX_NAME_CHARS", "FieldReader", "is_text", "show"]

_LIMIT_MM = MAX_COORDINATE_M * 1e3
"""Bound on every coordinate and scene size [mm]: :data:`lynxsim.bounds.MAX_COORDINATE_M`."""
_MAX_ANGLE_DEG = math.degrees(MAX_ANGLE_RAD)
"""Bound on every angle [deg]: :data:`lynxsim.bounds.MAX_ANGLE_RAD`, two turns either way."""
MAX_NAME_CHARS = 100
"""Longest name (task, pose, obstacle) [characters]."""
MAX_DESCRIPTION_CHARS = 1000
"""Longest description [characters]."""
_MIN_SIZE_MM = MIN_SIZE_M * 1e3
"""Smallest scene size (radius, height, edge) [mm]: :data:`lynxsim.scene.MIN_SIZE_M`."""


_SHOW = reprlib.Repr()
_SHOW.maxstring = 60
_SHOW.maxother = 60
_SHOW.maxlong = 40
_SHOW.maxlevel = 3


def show(value: object) -> str:
    """``value`` for a message: its repr, shortened (long strings, lists, integers, nesting)."""
    return _SHOW.repr(value)


class FieldReader:
    """Validating accessors that report the file and the field on failure.

    Args:
        path: The file read, for the messages.
    """

    def __init__(self, path: str) -> None:
        self.path = path

    def fail(self, field: str | None, problem: str) -> TaskFileError:
        """The error naming the file, the field (None: the whole file) and the problem."""
        return TaskFileError(self.path, field, problem)

    def table(self, value: object, field: str, keys: tuple[str, ...]) -> Mapping[str, Any]:
        """A table whose keys are all among ``keys``."""
        if not isinstance(value, Mapping):
            raise self.fail(field, f"must be a table, got {type(value).__name__}")
        unknown = sorted(set(value) - set(keys))
        if unknown:
            prefix = f"{field}." if field else ""
            key = unknown[0] if is_text(unknown[0], MAX_NAME_CHARS) else show(unknown[0])
            raise self.fail(f"{prefix}{key}", f"unknown key; expected one of: {', '.join(keys)}")
        return value

    def number(self, value: object, field: str) -> float:
        """A finite number (an integer or a float, not a bool)."""
        if isinstance(value, bool) or not isinstance(value, int | float):
            raise self.fail(field, f"must be a number, got {show(value)}")
        try:
            number = float(value)
        except OverflowError:  # an integer beyond the float range
            raise self.fail(field, "must be finite, got an integer beyond 1e308") from None
        if not math.isfinite(number):
            raise self.fail(field, f"must be finite, got {show(value)}")
        return number

    def positive(self, value: object, field: str) -> float:
        """A finite number > 0."""
        number = self.number(value, field)
        if number <= 0.0:
            raise self.fail(field, f"must be positive, got {show(value)}")
        return number

    def bounded(self, value: object, field: str, low: float, high: float, unit: str) -> float:
        """A number in [low, high], ``unit`` naming its unit in the message."""
        number = self.number(value, field)
        if not low <= number <= high:
            raise self.fail(field, f"must lie within {low:g}..{high:g} {unit}, got {show(value)}")
        return number

    def angle_deg(self, value: object, field: str) -> float:
        """An angle [deg] within +-720 deg, as radians."""
        bound = _MAX_ANGLE_DEG
        return math.radians(self.bounded(value, field, -bound, bound, "deg (two turns)"))

    def duration_s(self, value: object, field: str) -> float:
        """A segment duration [s] within the bounds of :mod:`lynxsim.bounds`."""
        self.positive(value, field)
        return self.bounded(value, field, MIN_SEGMENT_S, MAX_SEGMENT_S, "s")

    def size_mm(self, value: object, field: str, high: float = _LIMIT_MM) -> float:
        """A positive size [mm], at least 0.1 mm and at most ``high``."""
        number = self.positive(value, field)
        if not _MIN_SIZE_MM <= number <= high:
            raise self.fail(
                field, f"must lie within {_MIN_SIZE_MM:g}..{high:g} mm, got {show(value)}"
            )
        return number

    def coordinate_mm(self, value: object, field: str) -> float:
        """A coordinate [mm] within +-10000 mm (:data:`lynxsim.bounds.MAX_COORDINATE_M`)."""
        unit = f"mm (+-{MAX_COORDINATE_M:g} m)"
        return self.bounded(value, field, -_LIMIT_MM, _LIMIT_MM, unit)

    def position_mm(self, value: object, field: str) -> tuple[float, float, float]:
        """A point (x, y, z) [mm], each coordinate within +-10000 mm (10 m)."""
        if not isinstance(value, list) or len(value) != 3:
            raise self.fail(field, f"must be a list of 3 numbers, got {show(value)}")
        x, y, z = (self.coordinate_mm(v, f"{field}[{i}]") for i, v in enumerate(value))
        return x, y, z

    def string(self, value: object, field: str) -> str:
        """A string."""
        if not isinstance(value, str):
            raise self.fail(field, f"must be a string, got {show(value)}")
        return value

    def text(self, value: object, field: str, max_chars: int, *, empty: bool) -> str:
        """Printable one-line text of at most ``max_chars`` characters (empty if ``empty``)."""
        text = self.string(value, field)
        what = "printable text" if empty else "a non-empty printable string"
        if not empty and not text.strip():
            raise self.fail(field, f"must be {what}, got {show(text)}")
        bad = next((i for i, c in enumerate(text) if not c.isprintable()), None)
        if bad is not None:
            raise self.fail(
                field,
                f"must be {what}, got {show(text)} "
                f"(character U+{ord(text[bad]):04X} at index {bad} is a control, "
                "format or whitespace character)",
            )
        if len(text) > max_chars:
            raise self.fail(
                field, f"must be at most {max_chars} characters, got {len(text)}: {show(text)}"
            )
        return text

    def name(self, value: object, field: str) -> str:
        """A name: 1 to 100 printable characters."""
        return self.text(value, field, MAX_NAME_CHARS, empty=False)

    def boolean(self, value: object, field: str) -> bool:
        """``true`` or ``false``."""
        if not isinstance(value, bool):
            raise self.fail(field, f"must be true or false, got {show(value)}")
        return value

    def required(self, table: Mapping[str, Any], key: str, field: str) -> Any:
        """``table[key]``, or the error that ``field`` is missing."""
        if key not in table:
            raise self.fail(field, "missing")
        return table[key]


def is_text(value: str, max_chars: int) -> bool:
    """Whether ``value`` is printable, one line and at most ``max_chars`` long."""
    return len(value) <= max_chars and value.isprintable()
