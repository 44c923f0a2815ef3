"""Units and numbers at the command line: mm and degrees by default, SI with ``--si``."""

from __future__ import annotations

import argparse
import math

import numpy as np
import numpy.typing as npt

__all__ = ["Units", "add_unit_flags", "finite_float", "json_list", "positive_float"]


class Units:
    """Conversion between SI and the units shown at the command line."""

    def __init__(self, si: bool) -> None:
        self.si = si
        self.length = "m" if si else "mm"
        self.angle = "rad" if si else "deg"
        self._length_scale = 1.0 if si else 1e3

    def length_in(self, v: float) -> float:
        """A length typed by the user, in metres."""
        return v / self._length_scale

    def angle_in(self, v: float) -> float:
        """An angle typed by the user, in radians."""
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


def positive_float(text: str) -> float:
    """Argparse type: a finite number > 0."""
    value = finite_float(text)
    if value <= 0.0:
        raise argparse.ArgumentTypeError(f"must be a positive number, got {text!r}")
    return value


def add_unit_flags(p: argparse.ArgumentParser) -> None:
    """Add ``--si`` and ``--json``."""
    p.add_argument(
        "--si", action="store_true", help="inputs and outputs in m and rad instead of mm and deg"
    )
    p.add_argument("--json", action="store_true", help="machine-readable output, units labelled")
