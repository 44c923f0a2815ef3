"""The one description of the planar 3-RRR parallel robot's geometry (SPEC section 2).

Everything that needs a link length or a joint position reads it from
:data:`RRR_ROBOT`; nothing else in lynxsim writes these numbers again.

Frames and conventions (all in the plane of the robot, seen from above, +z up):

* the **base frame** has its origin at base joint B1, x towards B2;
* a **pose** is ``(x, y, alpha)``: the platform centre C in the base frame [m]
  and the platform's rotation about +z, counter-clockwise positive [rad];
  pose arrays have shape (..., 3);
* leg ``i`` (1-based in text, index ``i - 1`` in arrays) runs from the
  actuated joint ``B_i`` over the proximal link (length ``proximal``) to the
  passive elbow ``E_i``, then over the distal link (length ``distal``) to the
  passive platform joint ``P_i = C + R(alpha) c_i``, where ``c_i`` is the
  platform joint's offset from the platform centre at ``alpha = 0``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from lynxsim.errors import InvalidInputError

__all__ = ["RRR_ROBOT", "RRRGeometry", "as_pose_array", "platform_joints", "rotation"]

FloatArray = npt.NDArray[np.float64]

_MM = 1e-3


def _point(p: tuple[float, ...], what: str) -> tuple[float, float]:
    if len(p) != 2 or not all(math.isfinite(v) for v in p):
        raise InvalidInputError(f"{what} must be a finite (x, y) pair, got {p!r}")
    return (float(p[0]), float(p[1]))


@dataclass(frozen=True)
class RRRGeometry:
    """Kinematic description of a planar 3-RRR robot, SI units.

    Attributes:
        base_joints: Actuated joints ``B_1..B_3`` in the base frame, three (x, y) pairs [m].
        platform_offsets: Platform joints relative to the platform centre at
            ``alpha = 0``, ``c_1..c_3``, three (x, y) pairs [m].
        proximal: Length of each proximal (actuated) link ``s_a`` [m].
        distal: Length of each distal link ``L`` [m].
        base_centre: Centre of the base-joint circle ``C_b`` [m]; used only as
            a reference point (plots, orientation range), not by the kinematics.

    Raises:
        InvalidInputError: On a wrong number of legs, non-finite points, or link
            lengths that are not positive and finite.
    """

    base_joints: tuple[tuple[float, float], ...]
    platform_offsets: tuple[tuple[float, float], ...]
    proximal: float
    distal: float
    base_centre: tuple[float, float] = (0.0, 0.0)

    def __post_init__(self) -> None:
        for name in ("base_joints", "platform_offsets"):
            points = getattr(self, name)
            if len(points) != 3:
                raise InvalidInputError(f"{name} must hold 3 points, got {len(points)}")
            object.__setattr__(
                self, name, tuple(_point(p, f"{name}[{i}]") for i, p in enumerate(points))
            )
        object.__setattr__(self, "base_centre", _point(self.base_centre, "base_centre"))
        for name in ("proximal", "distal"):
            value = getattr(self, name)
            if not (math.isfinite(value) and value > 0.0):
                raise InvalidInputError(f"{name} link length must be positive, got {value!r} m")

    @classmethod
    def symmetric(
        cls,
        *,
        base_centre: tuple[float, float],
        base_radius: float,
        platform_radius: float,
        proximal: float,
        distal: float,
        directions: tuple[float, float, float] = (
            math.radians(210.0),
            math.radians(330.0),
            math.radians(90.0),
        ),
    ) -> RRRGeometry:
        """Base joints on a circle, platform joints on a circle, same directions.

        Args:
            base_centre: Centre of the base-joint circle [m].
            base_radius: Radius of the base-joint circle [m].
            platform_radius: Radius of the platform-joint circle [m].
            proximal: Proximal link length [m].
            distal: Distal link length [m].
            directions: Direction of each base joint from ``base_centre`` and of
                each platform joint from the platform centre at ``alpha = 0`` [rad].

        Returns:
            The geometry.
        """
        for name, value in (("base_radius", base_radius), ("platform_radius", platform_radius)):
            if not (math.isfinite(value) and value > 0.0):
                raise InvalidInputError(f"{name} must be positive, got {value!r} m")
        cx, cy = base_centre
        return cls(
            base_joints=tuple(
                (cx + base_radius * math.cos(d), cy + base_radius * math.sin(d)) for d in directions
            ),
            platform_offsets=tuple(
                (platform_radius * math.cos(d), platform_radius * math.sin(d)) for d in directions
            ),
            proximal=proximal,
            distal=distal,
            base_centre=base_centre,
        )

    @property
    def base(self) -> FloatArray:
        """Base joints ``B_i``, shape (3, 2) [m]."""
        return np.asarray(self.base_joints, dtype=float)

    @property
    def platform(self) -> FloatArray:
        """Platform-joint offsets ``c_i`` at ``alpha = 0``, shape (3, 2) [m]."""
        return np.asarray(self.platform_offsets, dtype=float)

    @property
    def platform_radius(self) -> float:
        """Mean distance of the platform joints from the platform centre [m]."""
        return float(np.linalg.norm(self.platform, axis=1).mean())

    @property
    def reach_min(self) -> float:
        """Shortest base-to-platform-joint distance a leg reaches, ``|s_a - L|`` [m]."""
        return abs(self.proximal - self.distal)

    @property
    def reach_max(self) -> float:
        """Longest base-to-platform-joint distance a leg reaches, ``s_a + L`` [m]."""
        return self.proximal + self.distal


_R_B = 290 * _MM
_COS30 = math.cos(math.radians(30.0))
_SIN30 = math.sin(math.radians(30.0))

RRR_ROBOT = RRRGeometry(
    base_joints=((0.0, 0.0), (2 * _R_B * _COS30, 0.0), (_R_B * _COS30, _R_B * (1 + _SIN30))),
    platform_offsets=tuple(
        (130 * _MM * math.cos(math.radians(d)), 130 * _MM * math.sin(math.radians(d)))
        for d in (210.0, 330.0, 90.0)
    ),
    proximal=170 * _MM,
    distal=130 * _MM,
    base_centre=(_R_B * _COS30, _R_B * _SIN30),
)
"""The report's 3-RRR robot: B1 = (0, 0), B2 = (502.29, 0), B3 = (251.15, 435) mm,
C_b = (251.15, 145) mm, s_a = 170 mm, L = 130 mm, r_p = 130 mm."""


def as_pose_array(pose: npt.ArrayLike, what: str = "pose") -> FloatArray:
    """Return ``pose`` as a float array of shape (..., 3) or raise.

    Raises:
        InvalidInputError: If the last axis does not have length 3.
    """
    arr = np.asarray(pose, dtype=float)
    if arr.ndim == 0 or arr.shape[-1] != 3:
        raise InvalidInputError(f"{what} must have shape (..., 3) = (x, y, alpha), got {arr.shape}")
    return arr


def rotation(alpha: npt.ArrayLike) -> FloatArray:
    """Planar rotation matrices ``R(alpha)``, shape alpha.shape + (2, 2) (alpha [rad])."""
    a = np.asarray(alpha, dtype=float)
    c, s = np.cos(a), np.sin(a)
    return np.stack([np.stack([c, -s], axis=-1), np.stack([s, c], axis=-1)], axis=-2)


def platform_joints(pose: npt.ArrayLike, geometry: RRRGeometry = RRR_ROBOT) -> FloatArray:
    """Platform joints ``P_i = C + R(alpha) c_i`` in the base frame.

    Args:
        pose: Platform poses (x, y, alpha), shape (..., 3) [m, m, rad].
        geometry: The robot description.

    Returns:
        Shape (..., 3, 2) [m], legs in order.
    """
    p = as_pose_array(pose)
    c, s = np.cos(p[..., 2])[..., None], np.sin(p[..., 2])[..., None]
    off = geometry.platform
    out = np.empty(p.shape[:-1] + (3, 2))
    out[..., 0] = p[..., 0, None] + c * off[:, 0] - s * off[:, 1]
    out[..., 1] = p[..., 1, None] + s * off[:, 0] + c * off[:, 1]
    return out
