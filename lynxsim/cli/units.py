"""Units and numbers at the command line: mm and degrees by default, SI with ``--si``."""

from __future__ import annotations

import argparse
import math
from collections.abc import Callable

import numpy as np
import numpy.typing as npt

from lynxsim.bounds import MAX_ANGLE_RAD, MAX_COORDINATE_M, check_range

__all__ = [
    "MAX_SEED",
    "Units",
    "add_unit_flags",
    "bounded_float",
    "bounded_int",
    "finite_float",
    "json_list",
    "seed_int",
]

MAX_SEED = 2**63 - 1
"""Largest seed accepted at the command line."""


class Units:
    """Conversion between SI and the units shown at the command line."""

    def __init__(self, si: bool) -> None:
        self.si = si
        self.length = "m" if si else "mm"
        self.angle = "rad" if si else "deg"
        self._length_scale = 1.0 if si else 1e3

    def length_in(self, v: float, name: str = "a length") -> float:
        """A length typed by the user, in metres.

        Raises:
            InvalidInputError: Beyond :data:`~lynxsim.bounds.MAX_COORDINATE_M`.
        """
        limit = MAX_COORDINATE_M * self._length_scale
        check_range(v, name, -limit, limit, self.length)
        return v / self._length_scale

    def angle_in(self, v: float, name: str = "an angle") -> float:
        """An angle typed by the user, in radians.

        Raises:
            InvalidInputError: Beyond :data:`~lynxsim.bounds.MAX_ANGLE_RAD` (two turns).
        """
        limit = MAX_ANGLE_RAD if self.si else math.degrees(MAX_ANGLE_RAD)
        check_range(v, name, -limit, limit, self.angle)
        return v if self.si else math.radians(v)

    def length_out(self, v: npt.ArrayLike) -> npt.NDArray[np.float64]:
        """Lengths [m] in the shown unit."""
        return np.asarray(v, dtype=float) * self._length_scale

    def angle_out(self, v: npt.ArrayLike) -> npt.NDArray[np.float64]:
        """Angles [rad] in the shown unit."""
        a = np.asarray(v, dtype=float)
        return a if self.si else np.degrees(a)

    def fmt_length(self, v: float) -> str:
        """A length already in the shown unit, as text."""
        return f"{v:.6f}" if self.si else f"{v:.2f}"

    def fmt_angle(self, v: float) -> str:
        """An angle already in the shown unit, as text."""
        return f"{v:.5f}" if self.si else f"{v:.2f}"


def json_list(a: npt.ArrayLike) -> list[float]:
    """An array as (nested) lists of floats rounded to 9 decimals, for JSON."""
    out: list[float] = np.round(np.asarray(a, dtype=float), 9).tolist()
    return out


def finite_float(text: str) -> float:
    """Argparse type: any float literal of a finite number; NaN and infinities refused."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"invalid float value: {text!r}") from None
    if not math.isfinite(value):
        raise argparse.ArgumentTypeError(f"must be a finite number, got {text!r}")
    return value


def bounded_float(low: float, high: float, unit: str = "") -> Callable[[str], float]:
    """Argparse type: a finite number in ``[low, high]``; the error states the range."""
    suffix = f" {unit}" if unit else ""

    def parse(text: str) -> float:
        value = finite_float(text)
        if not low <= value <= high:
            raise argparse.ArgumentTypeError(
                f"must be between {low:g} and {high:g}{suffix}, got {text}"
            )
        return value + 0.0  # "-0" as 0.0

    parse.__name__ = "number"
    return parse


def bounded_int(low: int, high: int) -> Callable[[str], int]:
    """Argparse type: an integer in ``[low, high]``; the error states the range."""

    def parse(text: str) -> int:
        try:
            value = int(text.replace("_", ""), 10) if len(text) <= 40 else None
        except ValueError:
            value = None
        if value is None:
            raise argparse.ArgumentTypeError(f"must be an integer, got {text[:40]!r}")
        if not low <= value <= high:
            raise argparse.ArgumentTypeError(f"must be between {low:,} and {high:,}, got {text}")
        return value

    parse.__name__ = "integer"
    return parse


def count_range(low: int, high: int) -> Callable[[str], tuple[int, int]]:
    """Argparse type: ``N`` or ``LO-HI``, integers with ``low <= LO <= HI <= high``."""
    one = bounded_int(low, high)

    def parse(text: str) -> tuple[int, int]:
        # A leading sign belongs to the first number (a negative count is out of range).
        head, dash, last = text[1:].partition("-")
        fewest = one(text[:1] + head)
        most = one(last) if dash else fewest
        if most < fewest:
            raise argparse.ArgumentTypeError(f"must be N or LO-HI with LO <= HI, got {text[:40]}")
        return fewest, most

    parse.__name__ = "count range"
    return parse


seed_int = bounded_int(0, MAX_SEED)
"""Argparse type: a random seed, 0 to 2**63 - 1."""


def add_unit_flags(p: argparse.ArgumentParser) -> None:
    """Add ``--si`` and ``--json``."""
    p.add_argument(
        "--si", action="store_true", help="inputs and outputs in m and rad instead of mm and deg"
    )
    p.add_argument("--json", action="store_true", help="machine-readable output, units labelled")
