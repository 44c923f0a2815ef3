"""Angles shared by both robots: wrapping, the slack on joint-range tests, a quaternion's yaw.

Pure NumPy and :mod:`math`; the arm (:mod:`lynxsim.arm`), the 3-RRR robot
(:mod:`lynxsim.rrr`) and the trajectories (:mod:`lynxsim.traj`) read these and
write neither again.
"""

from __future__ import annotations

import math

import numpy as np
import numpy.typing as npt

from lynxsim.inputs import real_array

__all__ = ["LIMIT_TOL", "quat_yaw", "wrap_angle", "wrap_angle_float"]

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


def wrap_angle(angle: npt.ArrayLike) -> FloatArray:
    """Wrap angles into the interval from -pi to pi [rad].

    ``angle - 2 pi rint(angle / (2 pi))``, exact for ``|angle| < 1e15``; an odd
    multiple of pi may come out as pi or -pi. Elementwise like :func:`numpy.sin`:
    NaN and infinity give NaN (silently), so that arrays marking missing values
    with NaN pass through.

    Args:
        angle: Angles, any shape [rad].

    Returns:
        A new array of the same shape (a NumPy scalar for a scalar) [rad].

    Raises:
        InvalidInputError: ``angle`` is not real numbers (:func:`lynxsim.inputs.real_array`).
    """
    a = real_array(angle, "angle")
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


def quat_yaw(w: float, x: float, y: float, z: float) -> float:
    """Yaw of a unit quaternion ``(w, x, y, z)`` (MuJoCo's order): its turn about z [rad].

    The first of its z-y-x Euler angles, in [-pi, pi]: for a rotation about z
    alone, the angle of that rotation (a planar body's heading, a cube lying on
    the table). Plain floats and :func:`math.atan2`: cheap enough to run every
    physics step.
    """
    return math.atan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z))
