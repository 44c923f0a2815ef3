"""Actuated angles of the 3-RRR along a sampled platform path, in one working mode.

The inverse kinematics of every sample (:func:`actuated_path`), unwrapped in
time into the actuators' ranges (:func:`actuated_window`), and checked: no
parallel singularity crossed (the platform would leave its assembly mode), no
actuated angle out of range (:class:`PlatformPathError`).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import NamedTuple

import numpy as np
import numpy.typing as npt

from lynxsim.angles import wrap_angle
from lynxsim.errors import InvalidInputError, TrajectoryError, UnreachablePlatformPoseError
from lynxsim.rrr.geometry import RRR_ROBOT, RRRGeometry, as_pose_array
from lynxsim.rrr.ik import RRRIKResult, ik
from lynxsim.rrr.jacobian import singularity_measures

__all__ = [
    "ActuatedPath",
    "PlatformPathError",
    "actuated_path",
    "actuated_window",
    "reached",
    "wrap_to_window",
]

FloatArray = npt.NDArray[np.float64]


class PlatformPathError(TrajectoryError, ValueError):
    """A platform path the robot cannot follow in the chosen working mode.

    Raised when the path crosses a parallel singularity (the platform would
    leave its assembly mode) or needs an actuated angle outside the actuators'
    range.

    Attributes:
        time_s: When along the path the problem starts [s].
        pose: The platform pose there, (x, y, alpha) [m, m, rad].
    """

    def __init__(self, message: str, *, time_s: float, pose: tuple[float, float, float]) -> None:
        super().__init__(message)
        self.time_s = time_s
        self.pose = pose


def reached(poses: FloatArray, where: Callable[[int], str], geometry: RRRGeometry) -> RRRIKResult:
    """The IK of platform poses (N, 3) [m, m, rad], all reachable.

    Raises:
        UnreachablePlatformPoseError: At the first pose a leg cannot reach, its
            message prefixed with ``where(index)``.
    """
    result = ik(poses, geometry)
    if not result.ok.all():
        i = int(np.argmin(result.ok))
        try:
            result.raise_for_status(i)
        except UnreachablePlatformPoseError as exc:
            raise UnreachablePlatformPoseError(f"{where(i)}: {exc}", legs=exc.legs) from None
    return result


def actuated_window(geometry: RRRGeometry = RRR_ROBOT) -> FloatArray:
    """Centre of each actuated angle's range: direction from ``B_i`` to ``C_b``, (3,) [rad].

    Leg ``i``'s actuated angle is kept in ``[centre_i - pi, centre_i + pi]``
    (the actuators' ``ctrlrange`` in ``lynxsim/models/rrr/rrr.xml``), so that no
    command wraps.
    """
    d = np.asarray(geometry.base_centre) - geometry.base
    out: FloatArray = np.arctan2(d[:, 1], d[:, 0])
    return out


def wrap_to_window(theta: npt.ArrayLike, geometry: RRRGeometry = RRR_ROBOT) -> FloatArray:
    """Actuated angles moved by whole turns into their ranges, shape (..., 3) [rad]."""
    centre = actuated_window(geometry)
    out: FloatArray = centre + wrap_angle(np.asarray(theta, dtype=float) - centre)
    return out


class ActuatedPath(NamedTuple):
    """Actuated angles along a sampled platform path in one working mode.

    Attributes:
        theta: Actuated angles, shape (T, 3) [rad], continuous in time, in the
            actuators' ranges (:func:`actuated_window`).
        min_abs_parallel: Smallest ``|parallel measure|`` along the path [-]
            (0 at a parallel singularity; see :mod:`lynxsim.rrr.jacobian`).
        min_serial: Smallest serial measure along the path [-] (0 where a leg
            is fully stretched or folded).
    """

    theta: FloatArray
    min_abs_parallel: float
    min_serial: float


def actuated_path(
    poses: npt.ArrayLike,
    mode: int,
    *,
    times: npt.ArrayLike | None = None,
    geometry: RRRGeometry = RRR_ROBOT,
) -> ActuatedPath:
    """Inverse kinematics of every sample of a platform path in one working mode.

    Args:
        poses: Platform poses, shape (T, 3) [m, m, rad], densely sampled.
        mode: Working mode 0..7.
        times: Their times [s], (T,), for error messages (sample index if None).
        geometry: The robot description.

    Returns:
        The :class:`ActuatedPath`.

    Raises:
        UnreachablePlatformPoseError: A sample is out of reach (names the legs).
        PlatformPathError: The path crosses a parallel singularity, or an
            actuated angle would leave its range.
        InvalidInputError: Bad shape or mode.
    """
    p = as_pose_array(poses, "poses")
    if p.ndim != 2 or len(p) == 0:
        raise InvalidInputError(f"poses must have shape (T, 3), got {p.shape}")
    if not (isinstance(mode, int | np.integer) and 0 <= int(mode) <= 7):
        raise InvalidInputError(f"working mode must be an integer in 0..7, got {mode!r}")
    t = np.arange(len(p), dtype=float) if times is None else np.asarray(times, dtype=float)
    unit = "sample" if times is None else "t ="

    def where(i: int) -> str:
        return f"{unit} {t[i]:.3f}{'' if times is None else ' s'}"

    result = reached(p, lambda i: f"path leaves the workspace at {where(i)}", geometry)
    theta = np.unwrap(result.theta[:, int(mode), :], axis=0)
    theta += wrap_to_window(theta[0], geometry) - theta[0]
    centre = actuated_window(geometry)
    outside = np.abs(theta - centre) > math.pi
    if outside.any():
        i = int(np.argmax(outside.any(axis=1)))
        leg = int(np.argmax(outside[i])) + 1
        raise PlatformPathError(
            f"leg {leg}'s actuated angle leaves its range "
            f"[{math.degrees(centre[leg - 1] - math.pi):.0f}, "
            f"{math.degrees(centre[leg - 1] + math.pi):.0f}] deg at {where(i)}",
            time_s=float(t[i]),
            pose=(float(p[i, 0]), float(p[i, 1]), float(p[i, 2])),
        )
    meas = singularity_measures(p, theta, geometry)
    sign = np.sign(meas.parallel)
    if (sign != sign[0]).any() or (sign == 0).any():
        i = int(np.argmax((sign != sign[0]) | (sign == 0)))
        x, y, a = p[i]
        raise PlatformPathError(
            f"path crosses a parallel singularity of working mode {mode} at {where(i)} "
            f"(x {x * 1e3:.1f} mm, y {y * 1e3:.1f} mm, alpha {math.degrees(a):.1f} deg): "
            "the platform would leave its assembly mode",
            time_s=float(t[i]),
            pose=(float(x), float(y), float(a)),
        )
    return ActuatedPath(
        theta=theta,
        min_abs_parallel=float(np.abs(meas.parallel).min()),
        min_serial=float(meas.serial.min()),
    )
