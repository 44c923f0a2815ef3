"""One target at a time: the arm's closed forms in Python floats.

:func:`~lynxsim.arm.ik.ik` and :func:`~lynxsim.arm.fk.tool_pose` work on
batches; on a single target NumPy's per-call overhead dominates (~150 µs for the
IK, about the cost of the 20 physics steps of an env's control period). The
functions here evaluate the same closed forms with :mod:`math` (~5 µs): the same
four candidates in the same slot order, the same joint-range and reach tests
(with :data:`~lynxsim.angles.LIMIT_TOL`), the same choice (the first valid slot,
or the valid candidate nearest a reference in the Euclidean norm of the wrapped
joint difference). ``tests/arm/test_ik_scalar.py`` checks them against the batch
versions on thousands of random targets: statuses are equal, joints agree to
~1e-14 rad (libm's ``atan2`` and ``hypot`` differ from NumPy's vectorised ones in
the last digit). The geometry is read from :class:`~lynxsim.arm.geometry.ArmGeometry`.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
import numpy.typing as npt

from lynxsim.angles import LIMIT_TOL, wrap_angle_float
from lynxsim.arm.geometry import LYNX_ARM, ArmGeometry, check_geometry
from lynxsim.arm.ik import IKStatus, ik
from lynxsim.bounds import MAX_COORDINATE_M
from lynxsim.errors import InvalidInputError, NonFiniteInputError
from lynxsim.inputs import real_array, real_number

__all__ = ["ik_nearest", "ik_one", "tool_pose_of"]

FloatArray = npt.NDArray[np.float64]

_PI = math.pi
_HALF_PI = math.pi / 2
_TAU = 2.0 * math.pi
_isfinite = math.isfinite
_wrap = wrap_angle_float

_SEQUENCES = (list, tuple)
_MAX_M = MAX_COORDINATE_M

_Constants = tuple[float, ...]
"""``l2, l3, lt, h, l2², l3², 2 l2 l3``, then the joint limits widened by
``LIMIT_TOL``: five lower, five upper [m, m², rad]."""


def _constants(geometry: ArmGeometry) -> _Constants:
    l2, l3 = geometry.upper_arm, geometry.forearm
    # Computed as lynxsim.arm.ik does (l2**2 + ... in that order), for equal roundings.
    return (
        (l2, l3, geometry.tool_length, geometry.shoulder_height, l2**2, l3**2, 2 * l2 * l3)
        + tuple(v - LIMIT_TOL for v in geometry.q_min)
        + tuple(v + LIMIT_TOL for v in geometry.q_max)
    )


_LYNX_CONSTANTS = _constants(LYNX_ARM)


def tool_pose_of(
    q: Sequence[float], geometry: ArmGeometry = LYNX_ARM
) -> tuple[float, float, float, float]:
    """Tool point and pitch of one joint vector (the closed form of :func:`~lynxsim.arm.tool_pose`).

    Args:
        q: Joint angles, 5 values [rad].
        geometry: The arm description.

    Returns:
        ``(x, y, z, pitch)`` in the base frame [m, m, m, rad].

    Raises:
        InvalidInputError: ``q`` is not 5 real numbers (a 5-vector), or
            ``geometry`` not an :class:`~lynxsim.arm.geometry.ArmGeometry`.
        NonFiniteInputError: An angle is NaN or infinite.
    """
    if geometry is not LYNX_ARM:
        geometry = check_geometry(geometry)
    # Fast path: a list or tuple of 5 Python floats (what the envs pass); anything
    # else, and every non-finite result, goes through the checks.
    if type(q) in _SEQUENCES and len(q) == 5:
        q1, q2, q3, q4, q5 = q
        if not (
            type(q1) is float
            and type(q2) is float
            and type(q3) is float
            and type(q4) is float
            and type(q5) is float
        ):
            q1, q2, q3, q4, q5 = _joints(q)
    else:
        q1, q2, q3, q4, q5 = _joints(q)
    a23 = q2 + q3
    pitch = a23 + q4
    l2, l3, lt = geometry.upper_arm, geometry.forearm, geometry.tool_length
    try:
        reach = l2 * math.cos(q2) + l3 * math.cos(a23) + lt * math.cos(pitch)
        z = geometry.shoulder_height + l2 * math.sin(q2) + l3 * math.sin(a23) + lt * math.sin(pitch)
        check = reach + z + (pitch - pitch) + (q1 - q1) + (q5 - q5)  # x - x: 0 if finite
    except ValueError:  # math.cos(inf)
        check = math.nan
    if check - check != 0.0:  # NaN or infinity somewhere (or an overflowing pitch)
        _joints(q)
        raise InvalidInputError(f"q = {list(q)!r} [rad]: q2 + q3 + q4 overflows")
    return reach * math.cos(q1), reach * math.sin(q1), z, pitch


def ik_nearest(
    x: float,
    y: float,
    z: float,
    pitch: float,
    roll: float,
    q_ref: Sequence[float] | None,
    geometry: ArmGeometry = LYNX_ARM,
) -> tuple[IKStatus, tuple[float, ...] | None]:
    """Solve one tool target; of the valid solutions, take the one nearest ``q_ref``.

    The candidates, the tests and the choice are those of :func:`lynxsim.arm.ik`
    (module table of :mod:`lynxsim.arm.ik`).

    Args:
        x: Tool point x in the base frame [m].
        y: Tool point y [m].
        z: Tool point z [m].
        pitch: Tool pitch above the horizontal [rad].
        roll: Wrist roll ``q5`` [rad], wrapped into [0, 2 pi).
        q_ref: Reference joints, 5 values [rad]; ``None`` (or a non-finite value,
            as in :func:`lynxsim.arm.ik`) takes the first valid slot instead.
        geometry: The arm description.

    Returns:
        ``(status, q)``: ``q`` is a tuple of 5 joint angles [rad] when the
        status is OK, else None. A non-finite target is a status
        (``NOT_FINITE``), not an error.

    Raises:
        InvalidInputError: An argument is not a real number (``x`` .. ``roll``
            may also be arrays of one), ``q_ref`` not 5 of them, a finite
            coordinate exceeds :data:`~lynxsim.bounds.MAX_COORDINATE_M`, or
            ``geometry`` is not an :class:`~lynxsim.arm.geometry.ArmGeometry`.
    """
    if not (
        type(x) is float
        and type(y) is float
        and type(z) is float
        and type(pitch) is float
        and type(roll) is float
    ):
        x, y, z = _number(x, "x"), _number(y, "y"), _number(z, "z")
        pitch, roll = _number(pitch, "pitch"), _number(roll, "roll")
    if q_ref is not None:
        if type(q_ref) in _SEQUENCES and len(q_ref) == 5:
            r1, r2, r3, r4, r5 = q_ref
            if not (
                type(r1) is float
                and type(r2) is float
                and type(r3) is float
                and type(r4) is float
                and type(r5) is float
            ):
                r1, r2, r3, r4, r5 = _floats(q_ref, 5, "q_ref")
        else:
            r1, r2, r3, r4, r5 = _floats(q_ref, 5, "q_ref")
        # A non-finite reference is no reference, as in lynxsim.arm.ik.
        finite = _isfinite(r1) and _isfinite(r2) and _isfinite(r3)
        if not (finite and _isfinite(r4) and _isfinite(r5)):
            q_ref = None
    if geometry is not LYNX_ARM:
        geometry = check_geometry(geometry)
    if not (
        -_MAX_M <= x <= _MAX_M
        and -_MAX_M <= y <= _MAX_M
        and -_MAX_M <= z <= _MAX_M
        and _isfinite(pitch)
        and _isfinite(roll)
    ):
        if not (
            _isfinite(x) and _isfinite(y) and _isfinite(z) and _isfinite(pitch) and _isfinite(roll)
        ):
            return IKStatus.NOT_FINITE, None
        raise InvalidInputError(
            f"tool point coordinates must be within ±{_MAX_M:g} m, got ({x:g}, {y:g}, {z:g}) m"
        )
    l2, l3, lt, h, l2_sq, l3_sq, den, lo1, lo2, lo3, lo4, lo5, hi1, hi2, hi3, hi4, hi5 = (
        _LYNX_CONSTANTS if geometry is LYNX_ARM else _constants(geometry)
    )
    # Base angle folded into [-pi/2, pi/2] (side 0) and turned by pi (side 1).
    rho = math.hypot(x, y)
    heading = math.atan2(y, x) if rho != 0.0 else 0.0
    if heading > _HALF_PI or heading < -_HALF_PI:
        q1_a = _wrap(heading + _PI)
        reach = -rho
    else:
        q1_a = heading
        reach = rho
    q1_b = _wrap(q1_a + _PI)
    # Wrist point in the arm's plane, elbow angle and shoulder correction.
    r_w = reach - lt * math.cos(pitch)
    z_w = z - h - lt * math.sin(pitch)
    c3 = (r_w * r_w + z_w * z_w - l2_sq - l3_sq) / den
    if not abs(c3) <= 1.0 + LIMIT_TOL:
        return IKStatus.OUT_OF_REACH, None
    c3 = 1.0 if c3 > 1.0 else -1.0 if c3 < -1.0 else c3
    s3 = math.sqrt(1.0 - c3 * c3)
    gamma = math.atan2(s3, c3)  # |q3|
    beta = math.atan2(l3 * s3, l2 + l3 * c3)
    base = math.atan2(z_w, r_w)
    q5 = roll % _TAU
    if not lo5 <= q5 <= hi5:
        return IKStatus.JOINT_RANGE, None
    up = base + beta
    down = base - beta
    back = _PI - pitch
    up_b = _PI - down
    down_b = _PI - up
    candidates = (  # slots 0..3 of lynxsim.arm.ik, q4 = pitch - q2 - q3 before wrapping
        (q1_a, up, -gamma, pitch - up + gamma),
        (q1_a, down, gamma, pitch - down - gamma),
        (q1_b, up_b, -gamma, back - up_b + gamma),
        (q1_b, down_b, gamma, back - down_b - gamma),
    )
    best: tuple[float, ...] | None = None
    best_score = math.inf
    for q1, q2, q3, q4 in candidates:
        q2, q3, q4 = _wrap(q2), _wrap(q3), _wrap(q4)
        if not (lo1 <= q1 <= hi1 and lo2 <= q2 <= hi2 and lo3 <= q3 <= hi3 and lo4 <= q4 <= hi4):
            continue
        if q_ref is None:
            return IKStatus.OK, (q1, q2, q3, q4, q5)
        d1, d2, d3 = _wrap(q1 - r1), _wrap(q2 - r2), _wrap(q3 - r3)
        d4, d5 = _wrap(q4 - r4), _wrap(q5 - r5)
        score = math.sqrt(d1 * d1 + d2 * d2 + d3 * d3 + d4 * d4 + d5 * d5)
        if score < best_score:
            best, best_score = (q1, q2, q3, q4, q5), score
    if best is None:
        return IKStatus.JOINT_RANGE, None
    return IKStatus.OK, best


def _floats(value: object, n: int, name: str) -> list[float]:
    """``value`` as ``n`` Python floats (not checked for finiteness), or InvalidInputError."""
    if type(value) is np.ndarray and value.dtype == np.float64 and value.shape == (n,):
        fast: list[float] = value.tolist()  # the common case, without the general checks
        return fast
    try:
        arr = real_array(value, name)
    except InvalidInputError as exc:
        raise type(exc)(f"{name} must be {n} numbers: {exc}") from None
    if arr.shape != (n,):
        raise InvalidInputError(f"{name} must have shape ({n},), got {arr.shape}")
    values: list[float] = arr.tolist()
    return values


def _joints(q: object) -> list[float]:
    """``q`` as 5 finite Python floats, or InvalidInputError / NonFiniteInputError."""
    values = _floats(q, 5, "q")
    if not all(map(_isfinite, values)):
        raise NonFiniteInputError(f"q must be finite joint angles [rad], got {values!r}")
    return values


_number = real_number
"""``value`` as one Python float (a 0-d or 1-element array is one), or InvalidInputError."""


def ik_one(
    position: npt.ArrayLike,
    pitch: npt.ArrayLike,
    roll: npt.ArrayLike | None = None,
    *,
    q_ref: npt.ArrayLike | None = None,
    geometry: ArmGeometry = LYNX_ARM,
) -> FloatArray:
    """Solve one target or raise (:func:`ik_nearest`, ~5 µs a call).

    Args:
        position: Tool point, shape (3,) [m].
        pitch: Tool pitch [rad]: a number, or an array of one.
        roll: Wrist roll [rad] (default 0, or ``q_ref``'s): a number, or an array of one.
        q_ref: Reference joints, shape (5,) [rad], to pick among solutions.
        geometry: The arm description.

    Returns:
        Joint angles, shape (5,) [rad].

    Raises:
        NonFiniteInputError: A coordinate is NaN or infinite.
        OutOfReachError: The wrist point is outside the links' reach.
        JointRangeError: Every solution violates a joint range (names the joint).
        InvalidInputError: ``position`` is not a 3-vector (or a coordinate
            exceeds :data:`~lynxsim.bounds.MAX_COORDINATE_M`), ``q_ref`` not a
            5-vector, or ``pitch`` or ``roll`` not a number (booleans, complex
            numbers, strings and None are not).
    """
    x: float
    y: float
    z: float
    if isinstance(position, list | tuple) and len(position) == 3:
        x, y, z = position
        if not (type(x) is float and type(y) is float and type(z) is float):
            x, y, z = _floats(position, 3, "position")
    else:
        x, y, z = _floats(position, 3, "position")
    phi = _number(pitch, "pitch")
    ref = None if q_ref is None else _floats(q_ref, 5, "q_ref")
    if roll is None:
        roll = 0.0 if ref is None else ref[4]
    q5 = _number(roll, "roll")
    _, q = ik_nearest(x, y, z, phi, q5, ref, geometry)
    if q is not None:
        return np.array(q)
    # The batch IK words the error: which joint blocks, and by how much.
    if ref is not None and not all(map(math.isfinite, ref)):
        ref = None
    result = ik(np.array([x, y, z]), phi, q5, q_ref=ref, geometry=geometry)
    result.raise_for_status()
    return result.q  # pragma: no cover - a last-digit tie the batch IK solves
