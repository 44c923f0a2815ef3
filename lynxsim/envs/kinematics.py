"""Single-target kinematics for the per-step control loop: pure Python floats, no MuJoCo.

:func:`lynxsim.arm.ik` solves batches; called on one target it spends ~250 µs in
NumPy's per-call overhead, about the cost of the 20 physics steps of a control
period. :func:`ik_nearest` is the same closed form (same candidates, same joint
range test, same choice of the candidate nearest a reference) written for one
target with :mod:`math`, ~10 µs. ``tests/envs/test_kinematics.py`` checks it
against :func:`lynxsim.arm.ik` on thousands of random targets; the geometry is
read from :data:`~lynxsim.arm.LYNX_ARM`, never written again here.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

from lynxsim.arm import LYNX_ARM, ArmGeometry, IKStatus
from lynxsim.arm.ik import LIMIT_TOL

__all__ = ["ik_nearest", "tool_pose_of"]

_TAU = 2.0 * math.pi
_INV_TAU = 1.0 / _TAU


def _bounds(geometry: ArmGeometry) -> tuple[float, ...]:
    """Joint limits widened by ``LIMIT_TOL``: 5 lower, then 5 upper [rad]."""
    return tuple(v - LIMIT_TOL for v in geometry.q_min) + tuple(
        v + LIMIT_TOL for v in geometry.q_max
    )


_LYNX_BOUNDS = _bounds(LYNX_ARM)


def _wrap(a: float) -> float:
    """Wrap an angle into [-pi, pi], operation for operation as :func:`lynxsim.arm.wrap_angle`."""
    return round(a * _INV_TAU) * -_TAU + a


def tool_pose_of(
    q: Sequence[float], geometry: ArmGeometry = LYNX_ARM
) -> tuple[float, float, float, float]:
    """Tool point and pitch of one joint vector (closed form of :func:`lynxsim.arm.tool_pose`).

    Args:
        q: Joint angles, 5 values [rad].
        geometry: The arm description.

    Returns:
        ``(x, y, z, pitch)`` in the base frame [m, m, m, rad].
    """
    q1, q2, q3, q4 = q[0], q[1], q[2], q[3]
    a23 = q2 + q3
    pitch = a23 + q4
    l2, l3, lt = geometry.upper_arm, geometry.forearm, geometry.tool_length
    reach = l2 * math.cos(q2) + l3 * math.cos(a23) + lt * math.cos(pitch)
    z = geometry.shoulder_height + l2 * math.sin(q2) + l3 * math.sin(a23) + lt * math.sin(pitch)
    return reach * math.cos(q1), reach * math.sin(q1), z, pitch


def ik_nearest(
    x: float,
    y: float,
    z: float,
    pitch: float,
    roll: float,
    q_ref: Sequence[float],
    geometry: ArmGeometry = LYNX_ARM,
) -> tuple[IKStatus, tuple[float, ...] | None]:
    """Solve one tool target, choosing the valid solution nearest ``q_ref``.

    The candidates, the joint-range test (with :data:`~lynxsim.arm.ik.LIMIT_TOL`)
    and the choice (smallest Euclidean norm of the wrapped joint difference) are
    those of :func:`lynxsim.arm.ik` with ``q_ref`` given.

    Args:
        x: Tool point x in the base frame [m].
        y: Tool point y [m].
        z: Tool point z [m].
        pitch: Tool pitch above the horizontal [rad].
        roll: Wrist roll ``q5`` [rad], wrapped into [0, 2 pi).
        q_ref: Reference joints, 5 values [rad].
        geometry: The arm description.

    Returns:
        ``(status, q)``: ``q`` is a tuple of 5 joint angles [rad] when the
        status is OK, else None.
    """
    if not all(map(math.isfinite, (x, y, z, pitch, roll))):
        return IKStatus.NOT_FINITE, None
    rho = math.hypot(x, y)
    heading = math.atan2(y, x) if rho != 0.0 else 0.0
    folded = abs(heading) > math.pi / 2
    q1_a = _wrap(heading + math.pi) if folded else heading
    q1_b = _wrap(q1_a + math.pi)
    reach = -rho if folded else rho

    l2, l3, lt = geometry.upper_arm, geometry.forearm, geometry.tool_length
    r_w = reach - lt * math.cos(pitch)
    z_w = z - geometry.shoulder_height - lt * math.sin(pitch)
    c3 = (r_w**2 + z_w**2 - l2**2 - l3**2) / (2 * l2 * l3)
    if abs(c3) > 1.0 + LIMIT_TOL:
        return IKStatus.OUT_OF_REACH, None
    c3 = min(1.0, max(-1.0, c3))
    s3 = math.sqrt(1.0 - c3**2)
    gamma = math.atan2(s3, c3)
    beta = math.atan2(l3 * s3, l2 + l3 * c3)
    base = math.atan2(z_w, r_w)
    q5 = math.fmod(roll, _TAU)
    if q5 < 0.0:
        q5 += _TAU
    up, down = base + beta, base - beta
    back = math.pi - pitch
    candidates = (
        (q1_a, up, -gamma, pitch - up + gamma),
        (q1_a, down, gamma, pitch - down - gamma),
        (q1_b, math.pi - down, -gamma, back - (math.pi - down) + gamma),
        (q1_b, math.pi - up, gamma, back - (math.pi - up) - gamma),
    )
    if geometry is LYNX_ARM:
        lo1, lo2, lo3, lo4, lo5, hi1, hi2, hi3, hi4, hi5 = _LYNX_BOUNDS
    else:
        lo1, lo2, lo3, lo4, lo5, hi1, hi2, hi3, hi4, hi5 = _bounds(geometry)
    if not lo5 <= q5 <= hi5:
        return IKStatus.JOINT_RANGE, None
    r1, r2, r3, r4, r5 = q_ref[0], q_ref[1], q_ref[2], q_ref[3], q_ref[4]
    d5 = _wrap(q5 - r5) ** 2
    best: tuple[float, ...] | None = None
    best_score = math.inf
    for q1, q2, q3, q4 in candidates:
        q2, q3, q4 = _wrap(q2), _wrap(q3), _wrap(q4)
        if not (lo1 <= q1 <= hi1 and lo2 <= q2 <= hi2 and lo3 <= q3 <= hi3 and lo4 <= q4 <= hi4):
            continue
        score = (
            (_wrap(q1 - r1) ** 2 + _wrap(q2 - r2) ** 2 + _wrap(q3 - r3) ** 2)
            + _wrap(q4 - r4) ** 2
            + d5
        )
        if score < best_score:
            best, best_score = (q1, q2, q3, q4, q5), score
    if best is None:
        return IKStatus.JOINT_RANGE, None
    return IKStatus.OK, best
