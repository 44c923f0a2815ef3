"""Closed-form inverse kinematics of the arm (report eqs. 10–34, corrected).

A target is a tool point, a tool pitch and optionally a wrist roll. For every
target four candidates are computed at once, without a Python loop per target:

====  ===========================  =======================================
slot  base angle q1                elbow branch
====  ===========================  =======================================
0     ``atan2(y, x)`` folded       q3 <= 0 (the arm's "elbow up" branch)
1     same                         q3 >= 0
2     the other side, ``+pi``      q3 <= 0
3     the other side, ``+pi``      q3 >= 0
====  ===========================  =======================================

"Folded" means that a base angle outside the joint range is turned by pi and
the reach in the arm's vertical plane changes sign: the arm then leans back
over its base, which is how it reaches targets behind the base's plane (x < 0).
Candidates on the other side describe the same physical tool direction, so
their pitch, which is measured towards the direction q1 points, is
``pi - pitch``. Candidates outside the joint ranges (to
:data:`~lynxsim.angles.LIMIT_TOL`) are discarded; the outcome of each target is
an :class:`IKStatus`.

One target at a time, :func:`lynxsim.arm.scalar.ik_one` evaluates the same
closed form with :mod:`math` (NumPy's per-call overhead would cost ~30 times
more); ``tests/arm/test_ik_scalar.py`` holds the two to the same answers.
"""

from __future__ import annotations

import enum
import math
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from lynxsim.angles import LIMIT_TOL, wrap_angle
from lynxsim.arm.geometry import LYNX_ARM, ArmGeometry, check_geometry
from lynxsim.bounds import MAX_COORDINATE_M, MAX_SAMPLES
from lynxsim.errors import (
    InvalidInputError,
    JointRangeError,
    NonFiniteInputError,
    OutOfReachError,
)
from lynxsim.inputs import real_array

__all__ = ["IKResult", "IKStatus", "ik", "ik_candidates", "ik_unchecked"]

FloatArray = npt.NDArray[np.float64]


class IKStatus(enum.IntEnum):
    """Outcome of the inverse kinematics for one target."""

    OK = 0
    OUT_OF_REACH = 1
    JOINT_RANGE = 2
    NOT_FINITE = 3


@dataclass(frozen=True)
class IKResult:
    """Solutions of a batch of IK targets, batch shape ``B``.

    Attributes:
        q: Selected solution, shape B + (5,) [rad], inside the joint ranges to
            :data:`~lynxsim.angles.LIMIT_TOL`; NaN where ``status`` is not OK.
        status: :class:`IKStatus` codes, shape B, int8.
        joint: 1-based joint that blocks a JOINT_RANGE target (the least
            violated candidate's worst joint), else 0; shape B, int8.
        violation: How far that joint is out of its range, shape B [rad].
        candidates: The four geometric candidates, shape B + (4, 5) [rad]
            (NaN where the target is out of reach or not finite).
        valid: Which candidates are in reach and within the joint ranges,
            shape B + (4,).
        reach_m: Upper-arm and forearm lengths used [m] (for messages).
    """

    q: FloatArray
    status: npt.NDArray[np.int8]
    joint: npt.NDArray[np.int8]
    violation: FloatArray
    candidates: FloatArray
    valid: npt.NDArray[np.bool_]
    reach_m: tuple[float, float] = (LYNX_ARM.upper_arm, LYNX_ARM.forearm)

    @property
    def ok(self) -> npt.NDArray[np.bool_]:
        """Mask of targets with a solution, shape B."""
        ok: npt.NDArray[np.bool_] = self.status == IKStatus.OK
        return ok

    def reason(self, index: tuple[int, ...] | int = ()) -> str:
        """Human-readable outcome of one target."""
        status = IKStatus(int(self.status[index]))
        if status is IKStatus.OK:
            return "solved"
        if status is IKStatus.NOT_FINITE:
            return "target is not finite (NaN or infinity)"
        if status is IKStatus.OUT_OF_REACH:
            lo = abs(self.reach_m[0] - self.reach_m[1]) * 1e3
            hi = (self.reach_m[0] + self.reach_m[1]) * 1e3
            return (
                "wrist point out of the arm's reach (the upper arm and forearm reach "
                f"{lo:.0f} to {hi:.0f} mm from the shoulder)"
            )
        j = int(self.joint[index])
        return (
            "no solution within the joint ranges (the nearest candidate has joint "
            f"{j} out of range by {np.degrees(self.violation[index]):.2f} deg)"
        )

    def raise_for_status(self, index: tuple[int, ...] | int = (), context: str = "") -> None:
        """Raise the typed error matching one target's outcome, if any.

        Args:
            index: Which target of the batch.
            context: Prefix naming the target in the message (e.g. the pose).

        Raises:
            NonFiniteInputError: The target was not finite.
            OutOfReachError: The target lies out of the arm's reach.
            JointRangeError: No solution lies within the joint ranges.
        """
        status = IKStatus(int(self.status[index]))
        message = f"{context}: {self.reason(index)}" if context else self.reason(index)
        if status is IKStatus.NOT_FINITE:
            raise NonFiniteInputError(message)
        if status is IKStatus.OUT_OF_REACH:
            raise OutOfReachError(message)
        if status is IKStatus.JOINT_RANGE:
            raise JointRangeError(message, joint=int(self.joint[index]))


def _largest(p: FloatArray) -> float:
    """The finite coordinate of largest magnitude [m]."""
    finite = p[np.isfinite(p)]
    return float(finite[np.argmax(np.abs(finite))])


def _range_violation(q: FloatArray, geometry: ArmGeometry) -> FloatArray:
    """Per-joint distance outside the joint range, shape of ``q`` [rad]."""
    return np.maximum(geometry.lower - q, 0.0) + np.maximum(q - geometry.upper, 0.0)


def ik(
    position: npt.ArrayLike,
    pitch: npt.ArrayLike,
    roll: npt.ArrayLike | None = None,
    *,
    q_ref: npt.ArrayLike | None = None,
    geometry: ArmGeometry = LYNX_ARM,
) -> IKResult:
    """Solve the inverse kinematics for a batch of tool targets.

    Args:
        position: Tool points in the base frame, shape B + (3,) [m].
        pitch: Tool pitch above the horizontal, towards the target's side of the
            base (see :func:`~lynxsim.arm.fk.tool_pose`), shape B or broadcastable [rad].
        roll: Wrist roll ``q5``, shape B or broadcastable [rad]; wrapped into
            [0, 2 pi). Default: 0, or ``q_ref``'s roll when given.
        q_ref: Reference joints, shape B + (5,) or (5,) [rad]. When given, the
            valid candidate closest to it is selected (continuity along paths);
            otherwise the first valid slot in the order of the module table.
        geometry: The arm description.

    Returns:
        The :class:`IKResult`.

    Non-finite targets are not an error: their status is ``NOT_FINITE``.

    Raises:
        InvalidInputError: An argument is not real numbers (a string, None,
            booleans, complex numbers, a ragged sequence...), ``position`` or
            ``q_ref`` has the wrong last axis, a finite coordinate exceeds
            :data:`~lynxsim.bounds.MAX_COORDINATE_M`, the arrays do not
            broadcast, or the batch exceeds :data:`~lynxsim.bounds.MAX_SAMPLES`
            targets.
    """
    geometry = check_geometry(geometry)
    p = real_array(position, "position")
    if p.ndim == 0 or p.shape[-1] != 3:
        raise InvalidInputError(f"position must have shape (..., 3), got {p.shape}")
    far = np.abs(p) > MAX_COORDINATE_M  # NaN compares False; inf is caught below as NOT_FINITE
    if far.any() and np.isfinite(p[far]).any():
        raise InvalidInputError(
            f"position coordinates must be within ±{MAX_COORDINATE_M:g} m "
            f"(the arm reaches under 1 m), got {_largest(p):g} m"
        )
    ref = None if q_ref is None else real_array(q_ref, "q_ref")
    if ref is not None and (ref.ndim == 0 or ref.shape[-1] != 5):
        raise InvalidInputError(f"q_ref must have shape (..., 5), got {ref.shape}")
    phi_in = real_array(pitch, "pitch")
    roll_in = (0.0 if ref is None else ref[..., 4]) if roll is None else roll
    roll_arr = real_array(roll_in, "roll")
    try:
        batch = np.broadcast_shapes(p.shape[:-1], phi_in.shape, roll_arr.shape)
        if ref is not None:
            batch = np.broadcast_shapes(batch, ref.shape[:-1])
    except ValueError as exc:
        raise InvalidInputError(f"IK inputs do not broadcast: {exc}") from None
    n = math.prod(batch)
    if n > MAX_SAMPLES:
        raise InvalidInputError(
            f"IK batch of {n:,} targets (shape {batch}); at most {MAX_SAMPLES:,} per call"
        )
    p = np.broadcast_to(p, batch + (3,)).reshape(n, 3)
    phi = np.broadcast_to(phi_in, batch).reshape(n)
    q5 = np.broadcast_to(roll_arr, batch).reshape(n)

    finite = np.isfinite(p).all(axis=-1) & np.isfinite(phi) & np.isfinite(q5)
    if not finite.all():
        p = np.where(finite[:, None], p, 0.0)
        phi = np.where(finite, phi, 0.0)
    ref_flat = None if ref is None else np.broadcast_to(ref, batch + (5,)).reshape(n, 5)
    cand, in_reach, valid, q = _solve(p, phi, np.where(finite, q5, 0.0), ref_flat, geometry, finite)
    any_valid = valid.any(axis=0)
    cand_view = np.moveaxis(cand, (0, 1), (2, 1)).reshape(batch + (4, 5))  # a view

    status = np.select(
        [~finite, ~in_reach, ~any_valid],
        [IKStatus.NOT_FINITE, IKStatus.OUT_OF_REACH, IKStatus.JOINT_RANGE],
        IKStatus.OK,
    ).astype(np.int8)
    joint = np.zeros(n, dtype=np.int8)
    amount = np.zeros(n)
    blocked = np.flatnonzero(status == IKStatus.JOINT_RANGE)
    if blocked.size:
        v = _range_violation(np.moveaxis(cand[:, :, blocked], 2, 0).swapaxes(1, 2), geometry)
        least = np.argmin(v.max(axis=-1), axis=-1)
        v_least = v[np.arange(blocked.size), least]
        joint[blocked] = np.argmax(v_least, axis=-1) + 1
        amount[blocked] = v_least.max(axis=-1)
    return IKResult(
        q=q.reshape(batch + (5,)),
        status=status.reshape(batch),
        joint=joint.reshape(batch),
        violation=amount.reshape(batch),
        candidates=cand_view,
        valid=valid.T.reshape(batch + (4,)),
        reach_m=(geometry.upper_arm, geometry.forearm),
    )


def _solve(
    p: FloatArray,
    phi: FloatArray,
    q5: FloatArray,
    ref: FloatArray | None,
    geometry: ArmGeometry,
    finite: npt.NDArray[np.bool_] | None = None,
) -> tuple[FloatArray, npt.NDArray[np.bool_], npt.NDArray[np.bool_], FloatArray]:
    """The closed form and the choice among its candidates, on checked arrays.

    Returns:
        ``(candidates, in_reach, valid, q)``: candidates (5, 4, n) (NaN out of
        reach), in reach (n,), valid (4, n), the chosen joints (n, 5) (NaN where
        none is valid).
    """
    n = p.shape[0]
    cand, in_reach = ik_candidates(p, phi, geometry)
    if finite is not None:
        in_reach &= finite
    cand[4] = np.mod(q5, 2 * np.pi)

    lo = (geometry.lower - LIMIT_TOL)[:, None, None]
    hi = (geometry.upper + LIMIT_TOL)[:, None, None]
    valid = ((cand >= lo) & (cand <= hi)).all(axis=0)  # (4, n)
    valid &= in_reach
    any_valid = valid.any(axis=0)
    if ref is None:
        best = np.argmax(valid, axis=0)
    else:
        score = np.linalg.norm(wrap_angle(cand - ref.T[:, None, :]), axis=0)
        best = np.argmin(np.where(valid, score, np.inf), axis=0)
    cand[:, :, ~in_reach] = np.nan
    # Not clipped onto the limits: a solution may lie up to LIMIT_TOL outside a
    # range, which keeps the tool exactly on the target (clipping would not).
    q = cand[:, best, np.arange(n)].T
    q[~any_valid] = np.nan
    return cand, in_reach, valid, q


def ik_unchecked(
    position: FloatArray, pitch: FloatArray, roll: FloatArray, q_ref: FloatArray
) -> tuple[FloatArray, npt.NDArray[np.int8]]:
    """:func:`ik` of :data:`~lynxsim.arm.geometry.LYNX_ARM` without its input checks.

    For callers that solve many small batches of targets they made themselves
    (the envs' tool action): the same closed form and choice as :func:`ik` (the
    same joints, bit for bit), without the checks and bookkeeping that dominate
    its cost on a few targets.

    Args:
        position: Finite tool points, shape (n, 3) [m].
        pitch: Finite tool pitches, shape (n,) [rad].
        roll: Finite wrist rolls, shape (n,) [rad].
        q_ref: Reference joints, shape (n, 5) [rad]: the valid candidate nearest wins.

    Returns:
        The joints, shape (n, 5) [rad] (NaN where there are none), and the
        :class:`IKStatus` codes, shape (n,) int8 (OK, OUT_OF_REACH or JOINT_RANGE).
    """
    _, in_reach, valid, q = _solve(position, pitch, roll, q_ref, LYNX_ARM)
    status = np.where(
        in_reach,
        np.where(valid.any(axis=0), IKStatus.OK, IKStatus.JOINT_RANGE),
        IKStatus.OUT_OF_REACH,
    ).astype(np.int8)
    return q, status


def ik_candidates(
    position: FloatArray, pitch: FloatArray, geometry: ArmGeometry = LYNX_ARM
) -> tuple[FloatArray, npt.NDArray[np.bool_]]:
    """The closed form itself: the four geometric candidates of finite targets, unchecked.

    :func:`ik` validates its inputs, then calls this; so does the straight tool
    line (:mod:`lynxsim.arm.motion.cartesian`), which needs one slot's joints at
    thousands of points it has checked already.

    Args:
        position: Finite tool points, shape (n, 3) [m].
        pitch: Finite tool pitches, shape (n,) [rad].
        geometry: The arm description.

    Returns:
        ``(candidates, in_reach)``: joints of the slots of the module table,
        joint-major, shape (5, 4, n) [rad] (``q5`` row 0; not checked against
        the joint ranges), and whether each wrist point is within the reach
        (to :data:`~lynxsim.angles.LIMIT_TOL`), shape (n,).
    """
    n = position.shape[0]
    phi = pitch
    x, y, z = position[:, 0], position[:, 1], position[:, 2]

    # Side 0 folds q1 into (-pi/2, pi/2]; side 1 turns it by pi. On side 1 the
    # reach changes sign and the pitch becomes pi - pitch, so the wrist point's
    # in-plane coordinates are (-r_w, z_w): the same distance from the shoulder
    # (one reach test for both sides) and base angle pi - A.
    rho = np.hypot(x, y)
    heading = np.arctan2(y, x)
    heading[rho == 0.0] = 0.0
    folded = np.abs(heading) > np.pi / 2
    q1_side0 = np.where(folded, wrap_angle(heading + np.pi), heading)
    q1_side1 = wrap_angle(q1_side0 + np.pi)
    reach = np.where(folded, -rho, rho)

    l2, l3, lt = geometry.upper_arm, geometry.forearm, geometry.tool_length
    r_w = reach - lt * np.cos(phi)
    z_w = z - geometry.shoulder_height - lt * np.sin(phi)
    c3 = (r_w**2 + z_w**2 - l2**2 - l3**2) / (2 * l2 * l3)
    in_reach = np.abs(c3) <= 1.0 + LIMIT_TOL
    np.clip(c3, -1.0, 1.0, out=c3)
    s3 = np.sqrt(1.0 - c3**2)
    gamma = np.arctan2(s3, c3)  # |q3|, [0, pi]
    beta = np.arctan2(l3 * s3, l2 + l3 * c3)  # shoulder correction, >= 0
    base = np.arctan2(z_w, r_w)  # side 0; side 1 is pi - base
    # Slots (side, elbow): (0, q3<=0), (0, q3>=0), (1, q3<=0), (1, q3>=0).
    # Joint-major layout (5 joints, 4 slots, n targets) keeps every row contiguous.
    cand = np.empty((5, 4, n))
    cand[0, 0:2] = q1_side0
    cand[0, 2:4] = q1_side1
    q2, q3, q4 = cand[1], cand[2], cand[3]
    np.add(base, beta, out=q2[0])
    np.subtract(base, beta, out=q2[1])
    np.subtract(np.pi, q2[1], out=q2[2])
    np.subtract(np.pi, q2[0], out=q2[3])
    np.negative(gamma, out=q3[0])
    q3[1] = gamma
    q3[2] = q3[0]
    q3[3] = gamma
    q4[0:2] = phi
    np.subtract(np.pi, phi, out=q4[2])
    q4[3] = q4[2]
    q4 -= q2
    q4 -= q3
    cand[1:4] = wrap_angle(cand[1:4])
    cand[4] = 0.0
    return cand, in_reach
