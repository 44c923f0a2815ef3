"""Obstacles of a :class:`~lynxsim.scene.Scene` drawn in mm: 3-D surfaces and top-view outlines."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
import numpy.typing as npt
from matplotlib.axes import Axes
from matplotlib.patches import Circle, Polygon

from lynxsim.scene import Box, Cylinder, Obstacle

__all__ = ["draw_obstacles_3d", "draw_obstacles_top", "inside_any", "obstacle_extent_mm"]

_GREY = "0.5"


def inside_any(points: npt.ArrayLike, obstacles: Sequence[Obstacle]) -> npt.NDArray[np.bool_]:
    """Which points lie inside any obstacle.

    Args:
        points: Points, shape (N, 3) [m].
        obstacles: The obstacles.

    Returns:
        Mask, shape (N,).
    """
    p = np.asarray(points, dtype=float).reshape(-1, 3)
    return np.array(
        [any(o.contains((float(x), float(y), float(z))) for o in obstacles) for x, y, z in p],
        dtype=bool,
    )


def _box_corners_mm(box: Box) -> npt.NDArray[np.float64]:
    """The four corners of a box's footprint, (4, 2) [mm]."""
    c, s = math.cos(box.yaw), math.sin(box.yaw)
    hx, hy = 0.5 * box.size[0], 0.5 * box.size[1]
    local = np.array([[-hx, -hy], [hx, -hy], [hx, hy], [-hx, hy]])
    rot = np.array([[c, -s], [s, c]])
    corners: npt.NDArray[np.float64] = (local @ rot.T + np.asarray(box.position[:2])) * 1e3
    return corners


def obstacle_extent_mm(obstacles: Sequence[Obstacle]) -> npt.NDArray[np.float64]:
    """Corners of boxes bounding the obstacles, (2 * m, 3) [mm] (for axis limits)."""
    out = []
    for o in obstacles:
        x, y, z = (v * 1e3 for v in o.position)
        if isinstance(o, Box):
            xy = _box_corners_mm(o)
            out += [[*xy.min(axis=0), z], [*xy.max(axis=0), z + o.size[2] * 1e3]]
        elif isinstance(o, Cylinder):
            r = o.radius * 1e3
            out += [[x - r, y - r, z], [x + r, y + r, z + o.height * 1e3]]
        else:
            r = o.radius * 1e3
            out += [[x - r, y - r, z - r], [x + r, y + r, z + r]]
    return np.array(out, dtype=float).reshape(-1, 3)


def draw_obstacles_3d(ax: Axes, obstacles: Sequence[Obstacle]) -> None:
    """Draw each obstacle as a translucent surface (mm)."""
    theta = np.linspace(0.0, 2.0 * np.pi, 40)
    for o in obstacles:
        x, y, z = (v * 1e3 for v in o.position)
        if isinstance(o, Cylinder):
            th, zz = np.meshgrid(theta, [z, z + o.height * 1e3])
            xs, ys = x + o.radius * 1e3 * np.cos(th), y + o.radius * 1e3 * np.sin(th)
        elif isinstance(o, Box):
            corners = _box_corners_mm(o)
            ring = np.vstack([corners, corners[:1]])
            xs = np.vstack([ring[:, 0], ring[:, 0]])
            ys = np.vstack([ring[:, 1], ring[:, 1]])
            zz = np.vstack([np.full(5, z), np.full(5, z + o.size[2] * 1e3)])
        else:
            phi = np.linspace(0.0, np.pi, 20)
            th, ph = np.meshgrid(theta, phi)
            r = o.radius * 1e3
            xs, ys = x + r * np.sin(ph) * np.cos(th), y + r * np.sin(ph) * np.sin(th)
            zz = z + r * np.cos(ph)
        ax.plot_surface(xs, ys, zz, color=_GREY, alpha=0.35, linewidth=0)  # type: ignore[attr-defined]


def draw_obstacles_top(ax: Axes, obstacles: Sequence[Obstacle]) -> None:
    """Draw each obstacle's outline seen from above, filled grey (mm)."""
    for o in obstacles:
        if isinstance(o, Box):
            ax.add_patch(Polygon(_box_corners_mm(o), closed=True, color=_GREY, alpha=0.4))
        else:
            centre = (o.position[0] * 1e3, o.position[1] * 1e3)
            ax.add_patch(Circle(centre, o.radius * 1e3, color=_GREY, alpha=0.4))
