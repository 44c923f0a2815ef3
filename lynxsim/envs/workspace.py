"""Where the envs put cubes and goals: reachable top-down, clear of the obstacle.

A point qualifies when the gripper can reach it pointing straight down (tool
pitch -pi/2, the wrist roll of the envs), also at the carry height above it, and
when the arm, turned towards it, keeps its links clear of the obstacle: seen from
above, the links lie on a strip along the ray from the base through the point,
and the obstacle's circle must stay outside that strip by a margin. Together
these are what a top-down pick, a carry at a fixed height and a place need.
:func:`work_column` gives the arm's configurations there; the envs with
randomised obstacles keep them clear, and the scripted expert
(:mod:`lynxsim.envs.expert`) plans its moves between them.

Pure NumPy on top of :func:`lynxsim.arm.ik`; sampling takes a
:class:`numpy.random.Generator` (the env's ``np_random``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from lynxsim.arm import ik, ik_nearest
from lynxsim.errors import InvalidInputError
from lynxsim.scene import Box, Obstacle

__all__ = [
    "ARM_HALF_WIDTH_M",
    "CARRY_HEIGHT_M",
    "GRIP_ROLL_RAD",
    "OBSTACLE_MARGIN_M",
    "TOP_DOWN_PITCH_RAD",
    "WORK_STEP_M",
    "PolarRegion",
    "clear_of_obstacle",
    "footprint",
    "sample_points",
    "top_down_reachable",
    "work_column",
]

FloatArray = npt.NDArray[np.float64]
BoolArray = npt.NDArray[np.bool_]

TOP_DOWN_PITCH_RAD = -math.pi / 2
"""Tool pitch of a top-down grasp: the tool axis points straight down [rad]."""
GRIP_ROLL_RAD = math.pi
"""Wrist roll the envs hold [rad]: the fingers close along the arm's radial
direction, and the roll servo sits mid-range (its range is 0..2 pi)."""
CARRY_HEIGHT_M = 0.07
"""Tool-point height at which the expert carries the cube [m] (cube 6 cm above the table)."""
WORK_STEP_M = 0.01
"""Height step between the configurations of a :func:`work_column` [m]."""
ARM_HALF_WIDTH_M = 0.025
"""Half the width of the arm seen from above [m] (the wrist bracket is 22.9 mm)."""
OBSTACLE_MARGIN_M = 0.02
"""Clearance kept between the arm's strip and the obstacle [m]."""
_BEHIND_M = 0.05
"""How far the strip reaches behind the base axis [m] (elbow, base housing)."""
_BEYOND_M = 0.035
"""How far the gripper reaches past the tool point, radially, when open [m]."""


@dataclass(frozen=True)
class PolarRegion:
    """A region in cylindrical coordinates about the base axis.

    Points are drawn uniformly over the annular sector's area, and uniformly in
    height.

    Attributes:
        radius: (min, max) horizontal distance from the base axis [m].
        azimuth: (min, max) angle from the base x axis, counter-clockwise [rad].
        height: (min, max) z of the point [m].
    """

    radius: tuple[float, float]
    azimuth: tuple[float, float]
    height: tuple[float, float]

    def __post_init__(self) -> None:
        for name in ("radius", "azimuth", "height"):
            lo, hi = getattr(self, name)
            if not (math.isfinite(lo) and math.isfinite(hi) and lo <= hi):
                raise InvalidInputError(f"region {name} must be finite (min, max), got {(lo, hi)}")
        if self.radius[0] < 0.0:
            raise InvalidInputError(f"region radius must be >= 0, got {self.radius}")


def top_down_reachable(points: npt.ArrayLike, carry_height: float = CARRY_HEIGHT_M) -> BoolArray:
    """Whether a top-down gripper reaches each point and the carry height above it.

    Args:
        points: Tool points, shape (N, 3) [m].
        carry_height: Carry height [m]; the point lifted to ``max(z, carry_height)``
            must be reachable too.

    Returns:
        Mask, shape (N,).
    """
    p = np.asarray(points, dtype=float).reshape(-1, 3)
    lifted = p.copy()
    lifted[:, 2] = np.maximum(lifted[:, 2], carry_height)
    ok: BoolArray = (
        ik(p, TOP_DOWN_PITCH_RAD, GRIP_ROLL_RAD).ok
        & ik(lifted, TOP_DOWN_PITCH_RAD, GRIP_ROLL_RAD).ok
    )
    return ok


def footprint(obstacle: Obstacle) -> tuple[tuple[float, float], float]:
    """A circle that covers an obstacle seen from above: ((x, y) centre [m], radius [m]).

    Exact for cylinders and spheres; a box's circumscribed circle (conservative).
    """
    x, y = obstacle.position[0], obstacle.position[1]
    if isinstance(obstacle, Box):
        return (x, y), 0.5 * math.hypot(obstacle.size[0], obstacle.size[1])
    return (x, y), obstacle.radius


def clear_of_obstacle(
    points: npt.ArrayLike, obstacle: Obstacle, margin: float = OBSTACLE_MARGIN_M
) -> BoolArray:
    """Whether the arm, turned towards each point, keeps clear of an obstacle seen from above.

    Seen from above the arm covers the strip of half-width :data:`ARM_HALF_WIDTH_M`
    along the segment from ``_BEHIND_M`` behind the base axis to ``_BEYOND_M`` past
    the point; the obstacle's :func:`footprint` must stay ``margin`` away from it.

    Args:
        points: Points, shape (N, 2) or (N, 3) [m] (z is ignored).
        obstacle: The obstacle (:mod:`lynxsim.scene`).
        margin: Clearance [m].

    Returns:
        Mask, shape (N,).
    """
    center, radius = footprint(obstacle)
    p = np.asarray(points, dtype=float)
    xy = p.reshape(-1, p.shape[-1])[:, :2]
    rho = np.hypot(xy[:, 0], xy[:, 1])
    u = np.where(rho[:, None] > 0.0, xy / np.maximum(rho, 1e-12)[:, None], [1.0, 0.0])
    c = np.asarray(center, dtype=float)
    t = np.clip(u @ c, -_BEHIND_M, rho + _BEYOND_M)
    nearest = u * t[:, None]
    distance = np.hypot(c[0] - nearest[:, 0], c[1] - nearest[:, 1])
    clear: BoolArray = distance >= radius + ARM_HALF_WIDTH_M + margin
    return clear


def sample_points(rng: np.random.Generator, region: PolarRegion, n: int) -> FloatArray:
    """Draw points uniformly from a region.

    Args:
        rng: The generator (an env's ``np_random``).
        region: Where.
        n: How many.

    Returns:
        Points, shape (n, 3) [m].
    """
    r0, r1 = region.radius
    radius = np.sqrt(rng.uniform(r0 * r0, r1 * r1, n))
    azimuth = rng.uniform(*region.azimuth, n)
    z = rng.uniform(*region.height, n)
    return np.stack([radius * np.cos(azimuth), radius * np.sin(azimuth), z], axis=-1)


def work_column(point: npt.ArrayLike, top_z: float, q_ref: npt.ArrayLike) -> FloatArray | None:
    """The arm's configurations with the gripper pointing down from a point up to a height.

    Where the arm works at a cube or a goal: it descends, grasps or places, and
    rises again along the vertical through the point. Each configuration is the
    IK solution nearest the one below it (the first nearest ``q_ref``), as the
    envs' tool-space controller picks them, at pitch
    :data:`TOP_DOWN_PITCH_RAD` and roll :data:`GRIP_ROLL_RAD`.

    Args:
        point: The lowest tool point, shape (3,) [m].
        top_z: Height of the highest tool point [m]; ``<= point[2]``: the point alone.
        q_ref: Reference joints, shape (5,) [rad].

    Returns:
        Joints from the bottom up, shape (K, 5) [rad], at most :data:`WORK_STEP_M`
        apart in height; None if a height is out of reach.
    """
    x, y, z = (float(v) for v in np.asarray(point, dtype=float).reshape(3))
    steps = max(0, math.ceil((top_z - z) / WORK_STEP_M - 1e-9))
    heights = np.linspace(z, max(z, top_z), steps + 1)
    ref = [float(v) for v in np.asarray(q_ref, dtype=float).reshape(5)]
    column = []
    for h in heights.tolist():
        _, q = ik_nearest(x, y, h, TOP_DOWN_PITCH_RAD, GRIP_ROLL_RAD, ref)
        if q is None:
            return None
        column.append(q)
        ref = list(q)
    return np.array(column)
