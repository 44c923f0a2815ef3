"""Units at the command line: mm and degrees by default, SI with ``--si``."""

from __future__ import annotations

import argparse
import math

import numpy as np
import numpy.typing as npt

from lynxsim.errors import InvalidInputError

__all__ = ["Units", "add_unit_flags", "check_finite", "json_list"]


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


def check_finite(values: list[float], what: str) -> None:
    """Raise :class:`InvalidInputError` naming ``what`` if a value is NaN or infinite."""
    if not all(math.isfinite(v) for v in values):
        raise InvalidInputError(f"{what} must be finite numbers, got {values}")


def add_unit_flags(p: argparse.ArgumentParser) -> None:
    """Add ``--si`` and ``--json``."""
    p.add_argument(
        "--si", action="store_true", help="inputs and outputs in m and rad instead of mm and deg"
    )
    p.add_argument("--json", action="store_true", help="machine-readable output, units labelled")
