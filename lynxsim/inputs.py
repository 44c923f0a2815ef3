"""Checks of what callers pass to the library: real numbers, shapes, ranges, counts, types.

Every public function of the pure packages (:mod:`lynxsim.arm`, :mod:`lynxsim.rrr`,
:mod:`lynxsim.traj`, :mod:`lynxsim.plan`) and the environments reads its numeric
arguments through these helpers, so a string, ``None``, a complex number, a
boolean array, a ragged list or an integer beyond float64 gives
:class:`~lynxsim.errors.InvalidInputError` (a ``ValueError``) with the offending
value in the message, never a NumPy ``TypeError`` or a silent cast.

Conventions: a number may be a Python or NumPy number, a 0-d array or a
1-element 1-D array; booleans are not numbers.
"""

from __future__ import annotations

import math
from typing import TypeVar

import numpy as np
import numpy.typing as npt

from lynxsim.bounds import check_count, check_range
from lynxsim.errors import InvalidInputError, InvalidTypeError, NonFiniteInputError, short

__all__ = [
    "count",
    "finite_array",
    "flag",
    "instance",
    "number_in_range",
    "positive_number",
    "real_array",
    "real_number",
]

FloatArray = npt.NDArray[np.float64]

T = TypeVar("T")

_REAL_KINDS = "fiu"
"""NumPy dtype kinds read as real numbers: float, signed and unsigned integer."""

_KIND_WORDS = {
    "b": "booleans",
    "c": "complex numbers",
    "O": "objects (mixed types, or integers beyond float64)",
    "U": "text",
    "S": "bytes",
    "M": "dates",
    "m": "time spans",
    "V": "raw records",
}


def real_array(value: object, name: str) -> FloatArray:
    """``value`` as a float64 array, refusing what is not real numbers.

    Accepts Python and NumPy numbers, (nested) sequences of them and integer or
    float arrays. Refuses None, strings, mappings, sets, ragged sequences,
    booleans, complex numbers, object arrays (integers beyond float64, mixed
    types). Finiteness and range are the caller's to check.

    Args:
        value: What the caller passed.
        name: Its name, for the message.

    Returns:
        A float64 array of ``value``'s shape (``value`` itself when it is one:
        copy it before keeping or freezing it).

    Raises:
        InvalidTypeError: ``value`` is not real numbers (the message shows it).
    """
    if isinstance(value, np.ndarray):
        arr = value
    elif value is None or isinstance(value, str | bytes | dict | set | frozenset):
        raise InvalidTypeError(f"{name} must be real numbers, got {short(value)}")
    else:
        try:
            arr = np.asarray(value)
        except (TypeError, ValueError, OverflowError):
            raise InvalidTypeError(
                f"{name} must be real numbers in a rectangular array, got {short(value)}"
            ) from None
    if arr.dtype.kind not in _REAL_KINDS:
        words = _KIND_WORDS.get(arr.dtype.kind, f"dtype {arr.dtype}")
        raise InvalidTypeError(f"{name} must be real numbers, got {words}: {short(value)}")
    with np.errstate(over="ignore"):  # a long double beyond float64 becomes inf
        out: FloatArray = np.asarray(arr, dtype=np.float64)
    return out


def finite_array(value: object, name: str) -> FloatArray:
    """:func:`real_array`, and every element finite.

    Raises:
        InvalidInputError: Not real numbers.
        NonFiniteInputError: An element is NaN or infinite.
    """
    arr = real_array(value, name)
    if not np.isfinite(arr).all():
        raise NonFiniteInputError(f"{name} must be finite, got {short(arr.tolist())}")
    return arr


def real_number(value: object, name: str) -> float:
    """``value`` as one Python float (a number, a 0-d or a 1-element 1-D array).

    Plain floats and NumPy float64 scalars take a fast path (single-target
    kinematics call this per argument). Not checked for finiteness.

    Raises:
        InvalidInputError: Not one real number (the message shows ``value``).
    """
    kind = type(value)
    if kind is float or kind is np.float64:
        return float(value)  # type: ignore[arg-type]
    if kind is int:
        try:
            return float(value)  # type: ignore[arg-type]
        except OverflowError:
            raise InvalidInputError(
                f"{name} must be a number within float64, got {short(value)}"
            ) from None
    try:
        arr = real_array(value, name)
    except InvalidInputError:
        raise InvalidTypeError(f"{name} must be a number, got {short(value)}") from None
    if arr.size != 1 or arr.ndim > 1:
        raise InvalidInputError(
            f"{name} must be a number (or an array of one), got shape {arr.shape}"
        )
    return float(arr.reshape(()))


def count(value: object, name: str, low: int, high: int) -> int:
    """``value`` as an int in ``[low, high]`` (:func:`lynxsim.bounds.check_count` for any input).

    Raises:
        InvalidInputError: Not an integer (bools, floats and arrays of several
            numbers are not), or outside the range (the message states it).
    """
    return check_count(value, name, low, high)  # type: ignore[arg-type]


def number_in_range(value: object, name: str, low: float, high: float, unit: str = "") -> float:
    """:func:`real_number`, finite and in ``[low, high]``.

    Raises:
        InvalidInputError: Not one real number, or outside the range (states it).
        NonFiniteInputError: NaN or infinite.
    """
    return check_range(real_number(value, name), name, low, high, unit)


def positive_number(value: object, name: str, unit: str = "") -> float:
    """:func:`real_number`, finite and > 0.

    Raises:
        InvalidInputError: Not one real number, or not positive.
        NonFiniteInputError: NaN or infinite.
    """
    v = real_number(value, name)
    if not math.isfinite(v):
        raise NonFiniteInputError(f"{name} must be finite, got {v!r}")
    if v <= 0.0:
        raise InvalidInputError(f"{name} must be positive, got {v!r}{' ' + unit if unit else ''}")
    return v


def flag(value: object, name: str) -> bool:
    """``value`` as a bool if it is one (Python or NumPy), else raise.

    Raises:
        InvalidInputError: Not a boolean (``"no"``, ``0`` and ``None`` are refused).
    """
    if isinstance(value, bool | np.bool_):
        return bool(value)
    raise InvalidTypeError(f"{name} must be True or False, got {short(value)}")


def instance(value: object, cls: type[T], name: str) -> T:
    """``value`` if it is a ``cls``, else raise.

    Raises:
        InvalidInputError: ``value`` has another type (the message names both).
    """
    if isinstance(value, cls):
        return value
    raise InvalidTypeError(
        f"{name} must be of type {cls.__name__}, got {type(value).__name__}: {short(value)}"
    )
