"""A bound on how far any point of the arm moves for a joint step.

For a serial arm, a point ``p`` moves with velocity ``sum_i qd_i a_i x (p - o_i)``
(joint axis ``a_i`` through ``o_i``), so ``|v| <= sum_i |qd_i| r_i``, where
``r_i`` bounds the distance of every point moved by joint ``i`` from that joint's
axis. By Cauchy-Schwarz ``|v| <= ||qd||_2 sqrt(sum_i r_i^2)``; integrated along
any joint path, no point of the robot moves more than ``L ||dq||_2`` with
``L = sqrt(sum_i r_i^2)`` [m/rad], where ``||dq||_2`` is the path's joint-space
length (the straight edge's ``||q_b - q_a||_2``).

For the Lynx arm every point moved by joint ``i`` lies within ``extent_m`` of the
kinematic chain after that joint (the polyline shoulder, elbow, wrist, tool
point), so ``r_i`` is the chain's length from joint ``i`` to the tool point plus
``extent_m``:

* base and shoulder: upper arm + forearm + tool length + extent;
* elbow: forearm + tool length + extent;
* wrist pitch: tool length + extent;
* wrist roll (the tool axis): extent.

:data:`HAND_EXTENT_M` (0.06 m) covers the model's collision geoms: the largest
servo box reaches ~0.046 m from the chain (the elbow servo's corner), the
gripper servo ~0.035 m from the tool axis, the fingers 0.008 m beyond the tool
point, and a 25 mm cube held at the tool point ~0.022 m from it. A larger payload
needs a larger extent.
"""

from __future__ import annotations

import math

from lynxsim.arm.geometry import LYNX_ARM, ArmGeometry, check_geometry
from lynxsim.bounds import check_range

__all__ = ["HAND_EXTENT_M", "arm_lipschitz", "joint_radii"]

HAND_EXTENT_M = 0.06
"""How far any collision geom of the arm, hand or a held cube lies from the arm's
kinematic chain (the polyline shoulder, elbow, wrist, tool point) [m]."""


def joint_radii(
    geometry: ArmGeometry = LYNX_ARM, extent_m: float = HAND_EXTENT_M
) -> tuple[float, ...]:
    """Bounds ``r_i`` on the distance of every point joint ``i`` moves from its axis [m], (5,).

    Args:
        geometry: The arm description.
        extent_m: How far the robot's surface (and payload) lies from the kinematic
            chain [m], 0 to 1.
    """
    geometry = check_geometry(geometry)
    extent = check_range(extent_m, "extent_m", 0.0, 1.0, "m")
    tool = geometry.tool_length
    wrist = geometry.forearm + tool
    whole = geometry.upper_arm + wrist
    return (whole + extent, whole + extent, wrist + extent, tool + extent, extent)


def arm_lipschitz(geometry: ArmGeometry = LYNX_ARM, extent_m: float = HAND_EXTENT_M) -> float:
    """The constant ``L`` [m/rad]: no point of the robot moves more than ``L ||dq||_2``.

    See the module docstring for the derivation. For :data:`~lynxsim.arm.LYNX_ARM`
    and the default extent ``L`` is about 0.745 m/rad.

    Args:
        geometry: The arm description.
        extent_m: How far the robot's surface (and payload) lies from the kinematic
            chain [m]; default :data:`HAND_EXTENT_M`.

    Returns:
        ``sqrt(sum_i r_i^2)`` of :func:`joint_radii` [m/rad].
    """
    return math.sqrt(sum(r * r for r in joint_radii(geometry, extent_m)))
