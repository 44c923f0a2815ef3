"""Sanity bounds on what users ask for, in one place (SI units).

Every entry point (task files, the command line, the library's public
functions, the environments) refuses values outside these ranges with a typed
error that states the range. They are not physical limits of the robots (those
live with the kinematics and the servo datasheet): they keep a typo such as
``1e12`` from asking for terabytes or hours, and keep the arithmetic away from
denormals and overflow.
"""

from __future__ import annotations

import math

from lynxsim.errors import InvalidInputError, NonFiniteInputError, short

__all__ = [
    "MAX_ANGLE_RAD",
    "MAX_CELLS",
    "MAX_CONTROL_DT_S",
    "MAX_COORDINATE_M",
    "MAX_EPISODES",
    "MAX_FPS",
    "MAX_JOBS",
    "MAX_RATE_HZ",
    "MAX_SAMPLES",
    "MAX_SEGMENT_S",
    "MAX_STEPS",
    "MIN_FPS",
    "MIN_RATE_HZ",
    "MIN_SEGMENT_S",
    "check_count",
    "check_range",
]

MIN_SEGMENT_S = 1e-3
"""Shortest segment duration [s]: half a physics step of the arm's model (2 ms)."""
MAX_SEGMENT_S = 3600.0
"""Longest segment duration [s]: one hour."""
MIN_RATE_HZ = 1.0
"""Lowest sampling rate of a trajectory written to a file [Hz]."""
MAX_RATE_HZ = 10_000.0
"""Highest sampling rate of a trajectory written to a file [Hz]."""
MAX_SAMPLES = 10_000_000
"""Most samples of one trajectory, workspace cloud or batch (about 0.4 GB of float64 x 5)."""
MAX_CELLS = 10_000_000
"""Most cells of a workspace grid."""
MIN_FPS = 1.0
"""Lowest video frame rate [frames/s]."""
MAX_FPS = 240.0
"""Highest video frame rate [frames/s]."""
MAX_COORDINATE_M = 10.0
"""Largest magnitude of a position coordinate [m]; the robots reach well under 1 m."""
MAX_ANGLE_RAD = 4.0 * math.pi
"""Largest magnitude of an angle given by a user [rad]: two turns (+-720 deg)."""
MAX_EPISODES = 1_000_000
"""Most episodes of one command."""
MAX_CONTROL_DT_S = 1.0
"""Longest control period of an environment [s]."""
MAX_RANDOM_OBSTACLES = 4
"""Most obstacles an env episode with randomised obstacles may have."""
MAX_STEPS = 100_000_000
"""Most physics steps of one run (about 55 h of simulated time at 2 ms)."""
MAX_JOBS = 256
"""Most worker processes of a sweep."""


def check_range(value: float, name: str, low: float, high: float, unit: str = "") -> float:
    """``value`` as a float if finite and in ``[low, high]``.

    Args:
        value: The number to check.
        name: What it is, for the message (e.g. ``"rate_hz"``).
        low: Smallest allowed value.
        high: Largest allowed value.
        unit: Unit shown after the numbers (e.g. ``"s"``).

    Raises:
        NonFiniteInputError: NaN or infinite.
        InvalidInputError: Outside the range, or not a real number; the message
            states the range.
    """
    try:
        v = float(value)
    except (TypeError, ValueError, OverflowError):
        raise InvalidInputError(f"{name} must be a number, got {value!r}") from None
    suffix = f" {unit}" if unit else ""
    if not math.isfinite(v):
        raise NonFiniteInputError(f"{name} must be finite, got {v!r}")
    if not low <= v <= high:
        raise InvalidInputError(
            f"{name} must be between {low:g} and {high:g}{suffix}, got {v:g}{suffix}"
        )
    return v + 0.0  # -0.0 as 0.0 (NumPy refuses a scale of -0.0, for one)


def check_count(value: int, name: str, low: int, high: int) -> int:
    """``value`` as an int if it is an integer in ``[low, high]`` (bools refused).

    Raises:
        InvalidInputError: Not an integer, or outside the range (states it).
    """
    if isinstance(value, bool) or not isinstance(value, int):
        index = getattr(value, "__index__", None)
        try:
            converted = None if isinstance(value, bool) or index is None else int(index())
        except (TypeError, ValueError):  # e.g. an array of several numbers
            converted = None
        if converted is None:
            raise InvalidInputError(f"{name} must be an integer, got {short(value)}")
        value = converted
    if not low <= value <= high:
        digits = len(str(abs(value)))
        got = f"{value:,}" if digits <= 30 else f"a {digits}-digit integer"
        raise InvalidInputError(f"{name} must be between {low:,} and {high:,}, got {got}")
    return value
