"""The one description of the Lynxmotion arm's geometry (SPEC section 1).

Everything that needs a link length, a DH parameter or a joint range reads it
from :data:`LYNX_ARM`; nothing else in lynxsim writes these numbers again.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import numpy.typing as npt

from lynxsim.errors import InvalidInputError

__all__ = ["LYNX_ARM", "ArmGeometry", "DHRow", "check_geometry"]

_MM = 1e-3


@dataclass(frozen=True)
class DHRow:
    """One row of a modified (proximal, Craig) Denavit–Hartenberg table.

    ``T_{i-1,i} = RotX(alpha) TransX(a) RotZ(theta_offset + q_i) TransZ(d)``.

    Attributes:
        a: Link length ``a_{i-1}`` [m].
        alpha: Link twist ``alpha_{i-1}`` [rad].
        d: Link offset ``d_i`` [m].
        theta_offset: Constant added to the joint angle [rad].
    """

    a: float
    alpha: float
    d: float
    theta_offset: float

    def __post_init__(self) -> None:
        for name in ("a", "alpha", "d", "theta_offset"):
            object.__setattr__(self, name, _finite_number(getattr(self, name), f"DH {name}"))


@dataclass(frozen=True)
class ArmGeometry:
    """Kinematic description of the 5-DOF arm, SI units.

    Attributes:
        dh: The five joint rows of the modified DH table.
        tool_length: Distance from the wrist (frame 5 origin) to the tool point
            along the tool axis [m].
        q_min: Lower joint limits, shape (5,) [rad].
        q_max: Upper joint limits, shape (5,) [rad].
    """

    dh: tuple[DHRow, ...]
    tool_length: float
    q_min: tuple[float, ...]
    q_max: tuple[float, ...]
    joint_names: tuple[str, ...] = field(
        default=("base", "shoulder", "elbow", "wrist_pitch", "wrist_roll")
    )

    def __post_init__(self) -> None:
        if not (
            isinstance(self.dh, tuple)
            and len(self.dh) == 5
            and all(isinstance(row, DHRow) for row in self.dh)
        ):
            raise InvalidInputError(f"dh must be a tuple of 5 DHRow, got {self.dh!r}")
        length = _finite_number(self.tool_length, "tool_length")
        if length < 0.0:
            raise InvalidInputError(f"tool_length must be >= 0 m, got {length!r}")
        object.__setattr__(self, "tool_length", length)
        for name in ("q_min", "q_max"):
            values = getattr(self, name)
            if not (isinstance(values, tuple | list) and len(values) == 5):
                raise InvalidInputError(f"{name} must be 5 joint angles [rad], got {values!r}")
            object.__setattr__(
                self, name, tuple(_finite_number(v, f"{name}[{i}]") for i, v in enumerate(values))
            )
        for i, (lo, hi) in enumerate(zip(self.q_min, self.q_max)):
            if lo > hi:
                raise InvalidInputError(f"joint {i + 1}: q_min {lo!r} > q_max {hi!r} rad")
        if self.dh[2].a <= 0.0 or self.dh[3].a <= 0.0:
            lengths = (self.dh[2].a, self.dh[3].a)
            raise InvalidInputError(f"upper arm and forearm lengths must be > 0 m, got {lengths}")

    @property
    def shoulder_height(self) -> float:
        """Height of the shoulder axis above the base [m]."""
        return self.dh[0].d

    @property
    def upper_arm(self) -> float:
        """Shoulder-to-elbow length ``l2`` [m]."""
        return self.dh[2].a

    @property
    def forearm(self) -> float:
        """Elbow-to-wrist length ``l3`` [m]."""
        return self.dh[3].a

    @property
    def lower(self) -> npt.NDArray[np.float64]:
        """Lower joint limits, shape (5,) [rad]."""
        return np.asarray(self.q_min, dtype=float)

    @property
    def upper(self) -> npt.NDArray[np.float64]:
        """Upper joint limits, shape (5,) [rad]."""
        return np.asarray(self.q_max, dtype=float)

    @property
    def max_reach(self) -> float:
        """Largest distance from the shoulder axis to the tool point [m]."""
        return self.upper_arm + self.forearm + self.tool_length


_MAX_PARAMETER = 1e3
"""Largest magnitude of a geometry parameter [m or rad]: keeps products of them finite."""


def _finite_number(value: object, name: str) -> float:
    """``value`` as a float if it is a finite real number of magnitude <= 1e3, else raise."""
    if isinstance(value, bool) or not isinstance(value, int | float | np.integer | np.floating):
        raise InvalidInputError(f"{name} must be a real number, got {value!r}")
    try:
        v = float(value)
    except OverflowError:
        v = math.inf
    if not (math.isfinite(v) and abs(v) <= _MAX_PARAMETER):
        raise InvalidInputError(f"{name} must be finite and at most {_MAX_PARAMETER:g}, got {v!r}")
    return v


def check_geometry(geometry: object) -> ArmGeometry:
    """``geometry`` if it is an :class:`ArmGeometry`, else raise InvalidInputError."""
    if geometry is LYNX_ARM or isinstance(geometry, ArmGeometry):
        return geometry
    raise InvalidInputError(f"geometry must be an ArmGeometry, got {geometry!r}")


def _deg(values: tuple[float, ...]) -> tuple[float, ...]:
    return tuple(math.radians(v) for v in values)


LYNX_ARM = ArmGeometry(
    dh=(
        DHRow(a=0.0, alpha=0.0, d=63 * _MM, theta_offset=0.0),
        DHRow(a=0.0, alpha=math.pi / 2, d=0.0, theta_offset=0.0),
        DHRow(a=153 * _MM, alpha=0.0, d=0.0, theta_offset=0.0),
        DHRow(a=153 * _MM, alpha=0.0, d=0.0, theta_offset=-math.pi / 2),
        DHRow(a=0.0, alpha=-math.pi / 2, d=0.0, theta_offset=0.0),
    ),
    tool_length=98 * _MM,
    q_min=_deg((-90.0, 0.0, -145.0, -90.0, 0.0)),
    q_max=_deg((90.0, 135.0, 0.0, 90.0, 360.0)),
)
"""The report's Lynxmotion arm (its Table 1 and joint ranges)."""
