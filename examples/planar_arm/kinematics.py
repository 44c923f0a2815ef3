"""Kinematics of the planar three-link arm: pure NumPy, SI units, no MuJoCo.

Three hinges about the vertical turn three links in horizontal planes; the tool
point is the tip of the third link. ``planar_arm.xml`` writes the same numbers,
and the tests check its tool site against :func:`tool_points`.
:data:`KINEMATICS` is what lynxsim's commands read of it
(:class:`lynxsim.traj.Kinematics`): joints, limits, tool point and heading.
"""

from __future__ import annotations

import math

import numpy as np
import numpy.typing as npt

from lynxsim.traj import JointBounds, JointLimits, Kinematics, ToolReadout

FloatArray = npt.NDArray[np.float64]

LINK_LENGTHS_M = (0.2, 0.15, 0.1)
"""Axis-to-axis lengths of links 1 and 2 and the length of link 3 to the tool point [m]."""
TOOL_HEIGHT_M = 0.185
"""Height of the tool point above the base plane [m] (the link planes are stacked)."""
LINK_RADIUS_M = 0.016
"""Largest radius of the links' collision capsules [m]."""
JOINT_NAMES = ("j1", "j2", "j3")
Q_MIN = (-2.9, -2.6, -2.6)
"""Lower joint limits [rad]."""
Q_MAX = (2.9, 2.6, 2.6)
"""Upper joint limits [rad]."""
VELOCITY_LIMIT = (2.0, 2.5, 3.0)
"""Joint speed limits [rad/s]."""


def tool_points(q: npt.ArrayLike) -> FloatArray:
    """Tool points of joint vectors, shape (..., 3) -> (..., 3) [m].

    Args:
        q: Joint angles, shape (..., 3) [rad].
    """
    q = np.asarray(q, dtype=float)
    angles = np.cumsum(q, axis=-1)
    lengths = np.asarray(LINK_LENGTHS_M)
    x = (lengths * np.cos(angles)).sum(axis=-1)
    y = (lengths * np.sin(angles)).sum(axis=-1)
    return np.stack([x, y, np.full_like(x, TOOL_HEIGHT_M)], axis=-1)


def heading(q: npt.ArrayLike) -> FloatArray:
    """Direction of the last link in the plane, shape (...,) [rad] (not wrapped)."""
    angle: FloatArray = np.asarray(q, dtype=float).sum(axis=-1)
    return angle


def lipschitz() -> float:
    """``L`` [m/rad]: no point of the arm moves more than ``L ||dq||_2`` for a joint step ``dq``.

    A point moved by joint ``i`` lies within the links after that joint plus the
    capsules' radius from its axis (``r_i``); ``L = sqrt(sum r_i^2)`` (Cauchy-Schwarz,
    as for lynxsim's own arm).
    """
    radii = [sum(LINK_LENGTHS_M[i:]) + LINK_RADIUS_M for i in range(3)]
    return math.sqrt(sum(r * r for r in radii))


BOUNDS = JointBounds(JOINT_NAMES, Q_MIN, Q_MAX)
"""Its joints and their ranges."""
LIMITS = JointLimits.for_joints(
    3,
    VELOCITY_LIMIT,
    np.asarray(VELOCITY_LIMIT) / 0.25,  # full speed in 0.25 s
    np.asarray(VELOCITY_LIMIT) / 0.25 / 0.1,  # full acceleration in 0.1 s
)
"""Its trajectories' default limits [rad/s, rad/s^2, rad/s^3]."""


def tool(q: FloatArray) -> ToolReadout:
    """The tool point and the last link's heading of joint vectors, (N, 3) [rad]."""
    return ToolReadout(position=tool_points(q), angles=(("heading", heading(q)),))


KINEMATICS = Kinematics(BOUNDS, LIMITS, tool)
"""What lynxsim's commands read of the arm (``lynxsim traj`` writes x, y, z and heading)."""
