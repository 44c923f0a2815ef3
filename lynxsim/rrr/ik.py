"""Inverse kinematics of the 3-RRR robot: every working mode of every pose at once.

For leg ``i`` with ``d = P_i - B_i`` and ``rho = |d|``, the proximal angle
``theta_i`` solves ``d_x cos(theta) + d_y sin(theta) = (rho² + s_a² - L²) / (2 s_a)``
(SPEC section 2). Writing ``phi = atan2(d_y, d_x)`` and ``gamma`` for the
interior angle at ``B_i`` of the triangle (B_i, E_i, P_i),

    ``theta_i = phi - sigma_i * gamma``,   ``gamma = atan2(sqrt(D), rho² + s_a² - L²)``,

with ``D = (s_a + L - rho)(rho - s_a + L)(rho + s_a - L)(rho + s_a + L)``, the
product form of ``(2 s_a rho)² - (rho² + s_a² - L²)²`` that stays accurate
near the reach limits. A leg reaches only when
``rho`` lies in ``[|s_a - L|, s_a + L]``; then both of its elbow branches
exist, so the 8 working modes of :mod:`lynxsim.rrr.modes` exist together or not
at all (pairs of them merge where a leg is fully stretched or folded).
"""

from __future__ import annotations

import enum
import math
from dataclasses import dataclass, field

import numpy as np
import numpy.typing as npt

from lynxsim.angles import wrap_angle
from lynxsim.bounds import MAX_SAMPLES
from lynxsim.errors import (
    InvalidInputError,
    NonFiniteInputError,
    UnreachablePlatformPoseError,
)
from lynxsim.rrr.geometry import (
    RRR_ROBOT,
    RRRGeometry,
    _platform_joints,
    as_pose_array,
    check_rrr_geometry,
    platform_joints,
)
from lynxsim.rrr.modes import MODE_SIGNS, N_MODES, _check_index

__all__ = [
    "REACH_TOL",
    "LegStatus",
    "PoseStatus",
    "RRRIKResult",
    "ik",
    "ik_one",
    "leg_points",
    "wrap_angle",  # re-exported from lynxsim.angles for older importers
]

FloatArray = npt.NDArray[np.float64]
BoolArray = npt.NDArray[np.bool_]

REACH_TOL = 1e-12
"""Slack on the reach annulus ``[|s_a - L|, s_a + L]`` [m]."""

_BRANCH = (MODE_SIGNS < 0).astype(np.intp)  # (8, 3): 0 for sigma = +1, 1 for sigma = -1
_LEG = np.broadcast_to(np.arange(3), (N_MODES, 3))


class PoseStatus(enum.IntEnum):
    """Outcome of the inverse kinematics for one platform pose."""

    OK = 0
    OUT_OF_REACH = 1
    NOT_FINITE = 2


class LegStatus(enum.IntEnum):
    """Outcome for one leg of one pose."""

    OK = 0
    TOO_FAR = 1
    """``|P_i - B_i| > s_a + L``: the leg cannot stretch that far."""
    TOO_NEAR = 2
    """``|P_i - B_i| < |s_a - L|``: the leg cannot fold that short."""
    NOT_FINITE = 3


def _fmt_pose(pose: FloatArray) -> str:
    x, y, a = pose
    return f"(x {x * 1e3:.2f} mm, y {y * 1e3:.2f} mm, alpha {math.degrees(a):.2f} deg)"


@dataclass(frozen=True)
class RRRIKResult:
    """Inverse kinematics of a batch of platform poses, batch shape ``B``.

    Attributes:
        pose: The poses solved, shape B + (3,) [m, m, rad].
        theta: Proximal (actuated) joint angles of every working mode, shape
            B + (8, 3) [rad] in [-pi, pi], row = mode index; NaN where the pose
            is not reachable.
        valid: Which working modes solve the pose, shape B + (8,) (all or none).
        status: :class:`PoseStatus` codes, shape B, int8.
        leg_status: :class:`LegStatus` codes per leg, shape B + (3,), int8.
        leg_span: Distance ``|P_i - B_i|`` of each leg, shape B + (3,) [m]
            (NaN for a non-finite pose).
        geometry: The robot the poses were solved for.
    """

    pose: FloatArray
    theta: FloatArray
    valid: npt.NDArray[np.bool_]
    status: npt.NDArray[np.int8]
    leg_status: npt.NDArray[np.int8]
    leg_span: FloatArray
    geometry: RRRGeometry = field(default=RRR_ROBOT, repr=False, compare=False)

    @property
    def ok(self) -> npt.NDArray[np.bool_]:
        """Mask of reachable poses, shape B."""
        out: npt.NDArray[np.bool_] = self.status == PoseStatus.OK
        return out

    @property
    def platform_joints(self) -> FloatArray:
        """Platform joints ``P_i``, shape B + (3, 2) [m]."""
        return platform_joints(self.pose, self.geometry)

    @property
    def elbows(self) -> FloatArray:
        """Elbows ``E_i`` of every working mode, shape B + (8, 3, 2) [m] (computed on access)."""
        th = self.theta
        return self.geometry.base + self.geometry.proximal * np.stack(
            [np.cos(th), np.sin(th)], axis=-1
        )

    def failing_legs(self, index: tuple[int, ...] | int = ()) -> tuple[int, ...]:
        """1-based numbers of the legs that cannot reach one pose's platform joint."""
        codes = self.leg_status[index]
        if codes.shape != (3,):
            raise InvalidInputError(f"index {index!r} does not select one pose")
        return tuple(i + 1 for i in range(3) if codes[i] != LegStatus.OK)

    def reason(self, index: tuple[int, ...] | int = ()) -> str:
        """One-line, human-readable outcome of one pose (lengths in mm)."""
        status = PoseStatus(int(self.status[index]))
        if status is PoseStatus.OK:
            return "reachable in all 8 working modes"
        if status is PoseStatus.NOT_FINITE:
            return f"platform pose {self.pose[index].tolist()} is not finite (NaN or infinity)"
        g = self.geometry
        parts = []
        for leg in self.failing_legs(index):
            span = self.leg_span[index][leg - 1] * 1e3
            if self.leg_status[index][leg - 1] == LegStatus.TOO_FAR:
                parts.append(
                    f"leg {leg} cannot stretch to it (|P{leg}-B{leg}| = {span:.2f} mm "
                    f"> s_a + L = {g.reach_max * 1e3:.2f} mm)"
                )
            else:
                parts.append(
                    f"leg {leg} cannot fold to it (|P{leg}-B{leg}| = {span:.2f} mm "
                    f"< |s_a - L| = {g.reach_min * 1e3:.2f} mm)"
                )
        return f"platform pose {_fmt_pose(self.pose[index])} is unreachable: " + "; ".join(parts)

    def raise_for_status(self, index: tuple[int, ...] | int = ()) -> None:
        """Raise the typed error matching one pose's outcome, if any.

        Raises:
            NonFiniteInputError: The pose holds NaN or infinity.
            UnreachablePlatformPoseError: A leg cannot reach; ``legs`` names them.
        """
        status = PoseStatus(int(self.status[index]))
        if status is PoseStatus.NOT_FINITE:
            raise NonFiniteInputError(self.reason(index))
        if status is PoseStatus.OUT_OF_REACH:
            raise UnreachablePlatformPoseError(self.reason(index), legs=self.failing_legs(index))


def _leg_branches(
    p_joints: FloatArray, geometry: RRRGeometry
) -> tuple[FloatArray, BoolArray, BoolArray, FloatArray]:
    """Leg spans, reach masks and both elbow branches' proximal angles.

    Args:
        p_joints: Platform joints, shape (..., 3, 2) [m], finite.
        geometry: The robot description.

    Returns:
        ``rho`` (..., 3) [m]; ``too_far`` and ``too_near`` masks (..., 3);
        ``branches`` (..., 3, 2) [rad], last axis sigma = +1, -1 (NaN where the
        leg does not reach).
    """
    d = p_joints - geometry.base
    rho = np.hypot(d[..., 0], d[..., 1])
    s_a, ell = geometry.proximal, geometry.distal
    too_far: BoolArray = np.asarray(rho > geometry.reach_max + REACH_TOL)
    too_near: BoolArray = np.asarray(rho < geometry.reach_min - REACH_TOL)
    disc = (
        np.clip(s_a + ell - rho, 0.0, None)
        * np.clip(rho - s_a + ell, 0.0, None)
        * np.clip(rho + s_a - ell, 0.0, None)
        * (rho + s_a + ell)
    )
    gamma = np.arctan2(np.sqrt(disc), rho**2 + s_a**2 - ell**2)
    phi = np.arctan2(d[..., 1], d[..., 0])
    branches = np.stack([phi - gamma, phi + gamma], axis=-1)
    branches = wrap_angle(branches)
    branches[too_far | too_near] = np.nan
    return rho, too_far, too_near, branches


def ik(pose: npt.ArrayLike, geometry: RRRGeometry = RRR_ROBOT) -> RRRIKResult:
    """Solve the inverse kinematics of a batch of platform poses in every working mode.

    Args:
        pose: Platform poses (x, y, alpha), shape B + (3,) [m, m, rad].
        geometry: The robot description.

    Returns:
        The :class:`RRRIKResult`; ``theta[..., m, :]`` are the actuated angles of
        working mode ``m``.

    Non-finite poses are not an error: their status is ``NOT_FINITE``.

    Raises:
        InvalidInputError: ``pose`` is not real numbers of shape (..., 3), a
            finite x or y exceeds :data:`~lynxsim.bounds.MAX_COORDINATE_M`, the
            batch exceeds :data:`~lynxsim.bounds.MAX_SAMPLES` poses, or
            ``geometry`` is not an :class:`~lynxsim.rrr.geometry.RRRGeometry`.
    """
    geometry = check_rrr_geometry(geometry)
    p = as_pose_array(pose)
    batch = p.shape[:-1]
    if p.size > 3 * MAX_SAMPLES:
        raise InvalidInputError(f"at most {MAX_SAMPLES:,} poses per call, got shape {p.shape}")
    finite: BoolArray = np.asarray(np.isfinite(p).all(axis=-1))
    safe = np.where(finite[..., None], p, 0.0)
    rho, too_far, too_near, branches = _leg_branches(_platform_joints(safe, geometry), geometry)
    theta = branches[..., _LEG, _BRANCH]  # (..., 8, 3)

    leg_status = np.full(batch + (3,), LegStatus.OK, dtype=np.int8)
    leg_status[too_near] = LegStatus.TOO_NEAR
    leg_status[too_far] = LegStatus.TOO_FAR
    leg_status[~finite] = LegStatus.NOT_FINITE
    reach: BoolArray = np.asarray((leg_status == LegStatus.OK).all(axis=-1))
    status = np.full(batch, PoseStatus.OK, dtype=np.int8)
    status[~reach] = PoseStatus.OUT_OF_REACH
    status[~finite] = PoseStatus.NOT_FINITE
    theta[~reach] = np.nan
    rho = np.where(finite[..., None], rho, np.nan)
    valid = np.broadcast_to(reach[..., None], batch + (N_MODES,)).copy()
    return RRRIKResult(
        pose=p,
        theta=theta,
        valid=valid,
        status=status,
        leg_status=leg_status,
        leg_span=rho,
        geometry=geometry,
    )


def ik_one(pose: npt.ArrayLike, geometry: RRRGeometry = RRR_ROBOT) -> FloatArray:
    """Solve one platform pose or raise.

    Args:
        pose: Platform pose (x, y, alpha), shape (3,) [m, m, rad].
        geometry: The robot description.

    Returns:
        Actuated angles of every working mode, shape (8, 3) [rad].

    Raises:
        InvalidInputError: ``pose`` is not a 3-vector of real numbers (as :func:`ik`).
        NonFiniteInputError: A coordinate is NaN or infinite.
        UnreachablePlatformPoseError: A leg cannot reach (``legs`` names which).
    """
    p = as_pose_array(pose)
    if p.shape != (3,):
        raise InvalidInputError(f"pose must have shape (3,), got {p.shape}")
    result = ik(p, geometry)
    result.raise_for_status()
    return result.theta


def leg_points(
    pose: npt.ArrayLike, mode: npt.ArrayLike, geometry: RRRGeometry = RRR_ROBOT
) -> FloatArray:
    """Joint positions of every leg: base joint, elbow, platform joint.

    Args:
        pose: Platform poses (x, y, alpha), shape B + (3,) [m, m, rad].
        mode: Working mode index (0..7), an int or an integer array
            broadcastable to B.
        geometry: The robot description.

    Returns:
        Shape B' + (3, 3, 2) [m]: ``[..., leg, k, :]`` with k = 0 for ``B_i``,
        1 for the elbow ``E_i``, 2 for ``P_i``; B' is B broadcast with
        ``mode``'s shape. Elbows are NaN where the pose is unreachable.

    Raises:
        InvalidInputError: On a bad pose, mode index or geometry (as :func:`ik`),
            or shapes that do not broadcast.
    """
    m = _check_index(mode)
    result = ik(pose, geometry)
    try:
        batch = np.broadcast_shapes(result.status.shape, m.shape)
    except ValueError as exc:
        raise InvalidInputError(f"pose and mode do not broadcast: {exc}") from None
    if math.prod(batch) > MAX_SAMPLES:
        raise InvalidInputError(f"at most {MAX_SAMPLES:,} poses per call, got batch {batch}")
    theta = np.take_along_axis(
        np.broadcast_to(result.theta, batch + (N_MODES, 3)),
        np.broadcast_to(m, batch)[..., None, None],
        axis=-2,
    )[..., 0, :]
    out = np.empty(batch + (3, 3, 2))  # (..., leg, k, xy)
    out[..., 0, :] = geometry.base
    out[..., 1, :] = geometry.base + geometry.proximal * np.stack(
        [np.cos(theta), np.sin(theta)], axis=-1
    )
    out[..., 2, :] = np.broadcast_to(result.platform_joints, batch + (3, 2))
    return out
