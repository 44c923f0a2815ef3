"""Angles shared by both robots: wrapping and the slack on joint-range tests.

Pure NumPy and :mod:`math`; the arm (:mod:`lynxsim.arm`), the 3-RRR robot
(:mod:`lynxsim.rrr`) and the trajectories (:mod:`lynxsim.traj`) read these and
write neither again.
"""

from __future__ import annotations

import math

import numpy as np
import numpy.typing as npt

from lynxsim.bounds import check_count
from lynxsim.errors import InvalidInputError

__all__ = [
    "LIMIT_TOL",
    "as_count",
    "as_real_array",
    "as_real_number",
    "wrap_angle",
    "wrap_angle_float",
]

FloatArray = npt.NDArray[np.float64]

_TAU = 2.0 * math.pi
_INV_TAU = 1.0 / _TAU

LIMIT_TOL = 1e-7
"""Slack on joint ranges [rad] (and on the arm IK's reach test, on cos q3 [-]).

At a stretched or folded elbow (sin q3 = 0) the arm's closed-form IK loses half
the digits: a rounding of 1e-16 in cos q3 moves q3, and so q4, by ~1e-8 rad. The
slack keeps such poses on the joint limits solvable; it is 6e-6 degrees. Every
test of a joint against its range (IK, waypoints, trajectory checks) uses it, so
that a pose the IK accepts is never refused further on.
"""


_REAL_KINDS = "fiu"
"""NumPy dtype kinds read as real numbers: float, signed and unsigned integer."""


def as_real_array(value: object, name: str) -> FloatArray:
    """``value`` as a float64 array, refusing what is not real numbers.

    Accepts Python and NumPy numbers, sequences of them and integer or float
    arrays; refuses None, strings, mappings, ragged sequences, booleans,
    complex numbers, object arrays (integers beyond float64, mixed types) and
    anything else NumPy cannot read as one rectangular array of real numbers.
    Values are not checked for finiteness or range (the caller does).

    Args:
        value: What the caller passed.
        name: Its name, for the message.

    Returns:
        A float64 array (``value`` itself when it already is one).

    Raises:
        InvalidInputError: ``value`` is not real numbers (the message shows it).
    """
    if isinstance(value, np.ndarray):
        arr = value
    elif isinstance(value, str | bytes | dict | set | frozenset) or value is None:
        raise InvalidInputError(f"{name} must be real numbers, got {_short(value)}")
    else:
        try:
            arr = np.asarray(value)
        except (TypeError, ValueError, OverflowError):
            raise InvalidInputError(
                f"{name} must be real numbers in a rectangular array, got {_short(value)}"
            ) from None
    dtype = arr.dtype
    if dtype == np.float64:
        return arr
    if dtype.kind not in _REAL_KINDS:
        words = _DTYPE_WORDS.get(dtype.kind, f"dtype {dtype}")
        raise InvalidInputError(f"{name} must be real numbers, got {words}: {_short(value)}")
    with np.errstate(over="ignore"):  # a long double beyond float64 becomes inf (checked later)
        out: FloatArray = arr.astype(np.float64)
    return out


_DTYPE_WORDS = {
    "b": "booleans",
    "c": "complex numbers",
    "O": "objects (mixed types, or integers beyond float64)",
    "U": "text",
    "S": "bytes",
    "M": "dates",
    "m": "time spans",
    "V": "raw records",
}


def _short(value: object) -> str:
    """``repr(value)`` cut to 80 characters (a huge array or integer stays readable)."""
    try:
        text = repr(value)
    except ValueError:  # an integer of more than 4300 digits
        return f"a {type(value).__name__} too long to print"
    return text if len(text) <= 80 else text[:77] + "..."


def as_real_number(value: object, name: str) -> float:
    """``value`` as one Python float: a real number, or an array holding one.

    A 0-d array and a 1-element 1-D array count as one number (NumPy's
    reductions and ``x[i:i+1]`` give those); booleans, complex numbers, strings
    and integers beyond float64 do not. Not checked for finiteness.

    Raises:
        InvalidInputError: Not one real number (the message shows ``value``).
    """
    kind = type(value)
    if kind is float or kind is np.float64:  # np.float64 (a float subclass): NumPy's scalars
        return float(value)  # type: ignore[arg-type]
    if kind is int:
        try:
            return float(value)  # type: ignore[arg-type]
        except OverflowError:
            raise InvalidInputError(
                f"{name} must be a number within float64, got {_short(value)}"
            ) from None
    try:
        arr = as_real_array(value, name)
    except InvalidInputError:
        raise InvalidInputError(f"{name} must be a number, got {_short(value)}") from None
    if arr.size != 1 or arr.ndim > 1:
        raise InvalidInputError(
            f"{name} must be a number (or an array of one), got shape {arr.shape}"
        )
    return float(arr.reshape(()))


def as_count(value: object, name: str, low: int, high: int) -> int:
    """``value`` as an int in ``[low, high]``: :func:`lynxsim.bounds.check_count` for any input.

    ``check_count`` calls ``__index__``, which a NumPy array of more than one
    element answers with TypeError; here every non-integer is an
    InvalidInputError.

    Raises:
        InvalidInputError: Not an integer (bools, floats and arrays are not), or
            outside the range (the message states it).
    """
    if isinstance(value, np.ndarray):
        if value.ndim != 0 or value.dtype.kind not in "iu":
            raise InvalidInputError(f"{name} must be an integer, got an array: {_short(value)}")
        value = int(value)
    try:
        return check_count(value, name, low, high)  # type: ignore[arg-type]
    except (TypeError, ValueError, OverflowError) as exc:
        if isinstance(exc, InvalidInputError):
            raise
        raise InvalidInputError(f"{name} must be an integer, got {_short(value)}") from None


def wrap_angle(angle: npt.ArrayLike) -> FloatArray:
    """Wrap angles into [-pi, pi] [rad].

    ``angle - 2 pi rint(angle / (2 pi))``, exact for ``|angle| < 1e15``; an odd
    multiple of pi may come out as pi or -pi. Elementwise like :func:`numpy.sin`:
    NaN and infinity give NaN (silently), so that arrays marking missing values
    with NaN pass through.

    Args:
        angle: Angles, any shape [rad].

    Returns:
        A new array of the same shape (a NumPy scalar for a scalar) [rad].

    Raises:
        InvalidInputError: ``angle`` is not real numbers (:func:`as_real_array`).
    """
    a = as_real_array(angle, "angle")
    out: FloatArray = np.multiply(a, _INV_TAU, out=np.empty_like(a))  # an array when 0-d too
    np.rint(out, out=out)
    out *= -_TAU
    with np.errstate(invalid="ignore"):  # inf - inf: NaN, as documented
        out += a
    if out.ndim == 0:
        scalar: FloatArray = out[()]
        return scalar
    return out


def wrap_angle_float(angle: float) -> float:
    """:func:`wrap_angle` of one finite Python float [rad], operation for operation.

    The scalar twin for per-call code paths (~30 ns against NumPy's ~1 µs); the
    result equals :func:`wrap_angle`'s bit for bit. ``angle`` must be finite
    (the caller checks: this path skips the test).
    """
    return round(angle * _INV_TAU) * -_TAU + angle
