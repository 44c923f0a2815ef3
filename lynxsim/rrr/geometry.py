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

from lynxsim.bounds import MAX_COORDINATE_M
from lynxsim.errors import InvalidInputError
from lynxsim.inputs import real_array

__all__ = [
    "RRR_ROBOT",
    "RRRGeometry",
    "as_pose_array",
    "as_theta_array",
    "check_coordinates",
    "check_rrr_geometry",
    "platform_joints",
    "rotation",
]

FloatArray = npt.NDArray[np.float64]

_MM = 1e-3


def _real(value: object, what: str) -> float:
    """``value`` as a float if it is a finite real number within ±MAX_COORDINATE_M, else raise."""
    if isinstance(value, bool) or not isinstance(value, int | float | np.integer | np.floating):
        raise InvalidInputError(f"{what} must be a real number, got {value!r}")
    try:
        v = float(value)
    except OverflowError:  # an int beyond float64
        v = math.inf
    if not (math.isfinite(v) and abs(v) <= MAX_COORDINATE_M):
        raise InvalidInputError(
            f"{what} must be finite and within ±{MAX_COORDINATE_M:g} m, got {value!r}"
        )
    return v


def _point(p: object, what: str) -> tuple[float, float]:
    if not (isinstance(p, tuple | list | np.ndarray) and len(p) == 2):
        raise InvalidInputError(f"{what} must be a finite (x, y) pair, got {p!r}")
    try:
        return (_real(p[0], what), _real(p[1], what))
    except InvalidInputError:
        raise InvalidInputError(f"{what} must be a finite (x, y) pair, got {p!r}") from None


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
            if not isinstance(points, tuple | list) or len(points) != 3:
                raise InvalidInputError(f"{name} must hold 3 points (x, y), got {points!r}")
            object.__setattr__(
                self, name, tuple(_point(p, f"{name}[{i}]") for i, p in enumerate(points))
            )
        object.__setattr__(self, "base_centre", _point(self.base_centre, "base_centre"))
        for name in ("proximal", "distal"):
            value = getattr(self, name)
            try:
                length = _real(value, name)
            except InvalidInputError:
                length = math.nan
            if not length > 0.0:
                raise InvalidInputError(
                    f"{name} link length must be positive, at most {MAX_COORDINATE_M:g} m, "
                    f"got {value!r} m"
                )
            object.__setattr__(self, name, length)

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
            try:
                radius = _real(value, name)
            except InvalidInputError:
                radius = math.nan
            if not radius > 0.0:
                raise InvalidInputError(
                    f"{name} must be positive, at most {MAX_COORDINATE_M:g} m, got {value!r} m"
                )
        base_radius, platform_radius = float(base_radius), float(platform_radius)
        cx, cy = _point(base_centre, "base_centre")
        if not (isinstance(directions, tuple | list) and len(directions) == 3):
            raise InvalidInputError(f"directions must be 3 angles [rad], got {directions!r}")
        directions = tuple(_real(d, "direction") for d in directions)  # type: ignore[assignment]
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


def check_rrr_geometry(geometry: object) -> RRRGeometry:
    """``geometry`` if it is an :class:`RRRGeometry`, else raise InvalidInputError."""
    if geometry is RRR_ROBOT or isinstance(geometry, RRRGeometry):
        return geometry
    raise InvalidInputError(f"geometry must be an RRRGeometry, got {geometry!r}")


def as_pose_array(pose: npt.ArrayLike, what: str = "pose") -> FloatArray:
    """Return ``pose`` as a float array of shape (..., 3) or raise.

    NaN and infinity pass (the kinematics report them per pose); finite x and y
    must lie within :data:`~lynxsim.bounds.MAX_COORDINATE_M`.

    Raises:
        InvalidInputError: Not real numbers, the last axis does not have length
            3, or a finite x or y beyond the bound.
    """
    arr = real_array(pose, what)
    if arr.ndim == 0 or arr.shape[-1] != 3:
        raise InvalidInputError(f"{what} must have shape (..., 3) = (x, y, alpha), got {arr.shape}")
    check_coordinates(arr[..., :2], f"{what} x, y")
    return arr


def as_theta_array(theta: npt.ArrayLike, what: str = "theta") -> FloatArray:
    """Return actuated angles as a float array of shape (..., 3) [rad] or raise.

    NaN and infinity pass (the kinematics report them per triple).

    Raises:
        InvalidInputError: Not real numbers, or the last axis does not have length 3.
    """
    arr = real_array(theta, what)
    if arr.ndim == 0 or arr.shape[-1] != 3:
        raise InvalidInputError(f"{what} must have shape (..., 3), got {arr.shape}")
    return arr


def check_coordinates(xy: FloatArray, what: str) -> None:
    """Raise InvalidInputError if a finite coordinate exceeds ±MAX_COORDINATE_M [m]."""
    far = np.abs(xy) > MAX_COORDINATE_M  # NaN compares False
    if far.any() and np.isfinite(xy[far]).any():
        worst = xy[far & np.isfinite(xy)]
        raise InvalidInputError(
            f"{what} must be within ±{MAX_COORDINATE_M:g} m (the robot spans under 1 m), "
            f"got {float(worst[0]):g} m"
        )


def rotation(alpha: npt.ArrayLike) -> FloatArray:
    """Planar rotation matrices ``R(alpha)``, shape alpha.shape + (2, 2) (alpha [rad]).

    NaN or infinite angles give NaN matrices.

    Raises:
        InvalidInputError: ``alpha`` is not real numbers.
    """
    a = real_array(alpha, "alpha")
    with np.errstate(invalid="ignore"):  # cos(inf): NaN
        c, s = np.cos(a), np.sin(a)
    return np.stack([np.stack([c, -s], axis=-1), np.stack([s, c], axis=-1)], axis=-2)


def platform_joints(pose: npt.ArrayLike, geometry: RRRGeometry = RRR_ROBOT) -> FloatArray:
    """Platform joints ``P_i = C + R(alpha) c_i`` in the base frame.

    Args:
        pose: Platform poses (x, y, alpha), shape (..., 3) [m, m, rad].
        geometry: The robot description.

    Returns:
        Shape (..., 3, 2) [m], legs in order; NaN for a pose with NaN or infinity.

    Raises:
        InvalidInputError: As :func:`as_pose_array`, or a bad ``geometry``.
    """
    p = as_pose_array(pose)
    geometry = check_rrr_geometry(geometry)
    with np.errstate(invalid="ignore"):  # cos(inf), inf - inf: NaN
        out = _platform_joints(p, geometry)
    out[~np.isfinite(p).all(axis=-1)] = np.nan  # not +-inf from an infinite x or y
    return out


def _platform_joints(p: FloatArray, geometry: RRRGeometry) -> FloatArray:
    """:func:`platform_joints` of a checked pose array."""
    c, s = np.cos(p[..., 2])[..., None], np.sin(p[..., 2])[..., None]
    off = geometry.platform
    out = np.empty(p.shape[:-1] + (3, 2))
    out[..., 0] = p[..., 0, None] + c * off[:, 0] - s * off[:, 1]
    out[..., 1] = p[..., 1, None] + s * off[:, 0] + c * off[:, 1]
    return out
