"""Lower bounds of robot-obstacle distances for the sweep judge, over states and placements.

Spheres that cover each robot or payload geom (:func:`cover`, in its own
frame) bound its distance to an obstacle at any placement from below
(:func:`distance_bound`); against a vertical cylinder, each geom seen from
above (:class:`Prisms`, :func:`prisms_of`) gives a tighter bound. Bounds only
skip work: the judge's verdicts and distances are MuJoCo's
(:mod:`lynxsim.sim.sweep_judge`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import mujoco
import numpy as np
import numpy.typing as npt

from lynxsim.scene import Cylinder, Obstacle, Sphere

__all__ = ["BLOCK_STATES", "COVER_SPHERE_M", "Prisms", "cover", "distance_bound", "prisms_of"]

FloatArray = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.intp]

BLOCK_STATES = 16
"""Consecutive states bounded together."""
COVER_SPHERE_M = 0.012
"""Target half size of the pieces a geom is cut into for its covering spheres [m]."""


def cover(geom_type: int, size: FloatArray, rbound: float) -> tuple[FloatArray, FloatArray]:
    """Spheres covering a geom, in its frame: centres (k, 3) [m] and radii (k,) [m].

    A capsule or cylinder is cut along its axis, a box along each of its axes,
    into pieces of about :data:`COVER_SPHERE_M` half size (capsules half that:
    their spheres add the capsule's radius); each piece's sphere covers it.
    """
    t = mujoco.mjtGeom
    if geom_type == t.mjGEOM_SPHERE:
        return np.zeros((1, 3)), np.array([float(size[0])])
    if geom_type in (t.mjGEOM_CAPSULE, t.mjGEOM_CYLINDER):
        r, h = float(size[0]), float(size[1])
        capsule = geom_type == t.mjGEOM_CAPSULE
        n = max(1, math.ceil(h / (0.5 * COVER_SPHERE_M if capsule else COVER_SPHERE_M)))
        half = h / n
        z = -h + half * (2 * np.arange(n) + 1)
        centres = np.column_stack([np.zeros(n), np.zeros(n), z])
        return centres, np.full(n, half + r if capsule else math.hypot(half, r))
    if geom_type == t.mjGEOM_BOX:
        half_sizes = np.asarray(size[:3], dtype=float)
        counts = [max(1, math.ceil(float(a) / COVER_SPHERE_M)) for a in half_sizes]
        piece = half_sizes / counts
        axes = [-a + p * (2 * np.arange(n) + 1) for a, p, n in zip(half_sizes, piece, counts)]
        grid = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1).reshape(-1, 3)
        return grid, np.full(len(grid), float(np.linalg.norm(piece)))
    return np.zeros((1, 3)), np.array([rbound])


def distance_bound(
    points: FloatArray, obstacle: Obstacle, x: FloatArray, y: FloatArray
) -> FloatArray:
    """Distance from points to the obstacle centred at each (x, y): (C, P) [m], a lower bound.

    Args:
        points: (P, 3) [m].
        obstacle: Its shape, size, height and z (its x, y replaced by ``x``, ``y``).
        x: Placement centres x, (C,) [m].
        y: Placement centres y, (C,) [m].
    """
    dx = points[None, :, 0] - x[:, None]
    dy = points[None, :, 1] - y[:, None]
    z = points[None, :, 2]
    z0 = obstacle.position[2]
    if isinstance(obstacle, Cylinder):
        radial = np.maximum(np.hypot(dx, dy) - obstacle.radius, 0.0)
        vertical = np.maximum(np.maximum(z0 - z, z - (z0 + obstacle.height)), 0.0)
        out: FloatArray = np.hypot(radial, vertical)
        return out
    if isinstance(obstacle, Sphere):
        out = np.maximum(np.sqrt(dx * dx + dy * dy + (z - z0) ** 2) - obstacle.radius, 0.0)
        return out
    c, s = math.cos(obstacle.yaw), math.sin(obstacle.yaw)
    u = np.maximum(np.abs(c * dx + s * dy) - 0.5 * obstacle.size[0], 0.0)
    v = np.maximum(np.abs(-s * dx + c * dy) - 0.5 * obstacle.size[1], 0.0)
    w = np.maximum(np.maximum(z0 - z, z - (z0 + obstacle.size[2])), 0.0)
    out = np.sqrt(u * u + v * v + w * w)
    return out


@dataclass(frozen=True)
class Prisms:
    """Robot and payload geoms seen from above, per state (n states, G geoms).

    Attributes:
        centre: Centre x, y, (n, G, 2) [m].
        axes: Projected half axes, (n, G, 3, 2) [m].
        normals: Unit normals of the projected half axes (0 for a vertical one), (n, G, 3, 2).
        reach: Reach of the projection along each normal, (n, G, 3) [m].
        z_low: Lowest z of the geom, (n, G) [m].
        z_high: Highest z, (n, G) [m].
        radius: Radius added to the box (capsules, spheres), (G,) [m].
    """

    centre: FloatArray
    axes: FloatArray
    normals: FloatArray
    reach: FloatArray
    z_low: FloatArray
    z_high: FloatArray
    radius: FloatArray

    def bounds(
        self, states: IntArray, geoms: IntArray, cylinder: Cylinder, x: FloatArray, y: FloatArray
    ) -> FloatArray:
        """Lower bounds of the distance from geoms to the cylinder at each (x, y), (C, P) [m].

        Horizontal gap: the largest separation of the cylinder's axis from a
        geom's projection along five directions (the normals of its half axes,
        the direction from its centre and the direction from its corner nearest
        that way), less both radii; vertical gap: between the z extents. The
        separation along any direction bounds the distance from below.

        Args:
            states: State of each (state, geom) pair, (P,).
            geoms: Geom (index among the G) of each pair, (P,).
            cylinder: The obstacle (radius, z, height).
            x: Axis x of each placement, (C,) [m].
            y: Axis y of each placement, (C,) [m].
        """
        centre = self.centre[states, geoms]  # (P, 2)
        dx = x[:, None] - centre[None, :, 0]  # (C, P)
        dy = y[:, None] - centre[None, :, 1]
        normals, axes = self.normals[states, geoms][None], self.axes[states, geoms][None]
        along = np.abs(dx[..., None] * normals[..., 0] + dy[..., None] * normals[..., 1])
        gap = (along - self.reach[states, geoms][None]).max(axis=-1)  # (C, P)
        dist = np.sqrt(dx * dx + dy * dy)
        scale = 1.0 / np.maximum(dist, 1e-300)
        dots = (dx * scale)[..., None] * axes[..., 0] + (dy * scale)[..., None] * axes[..., 1]
        gap = np.maximum(gap, dist - np.abs(dots).sum(axis=-1))
        # The corner of the projection furthest towards the axis, and the direction from it.
        side = np.where(dots >= 0.0, 1.0, -1.0)
        vx = dx - (side * axes[..., 0]).sum(axis=-1)
        vy = dy - (side * axes[..., 1]).sum(axis=-1)
        scale = 1.0 / np.maximum(np.sqrt(vx * vx + vy * vy), 1e-300)
        vx, vy = vx * scale, vy * scale
        reach = np.abs(vx[..., None] * axes[..., 0] + vy[..., None] * axes[..., 1]).sum(axis=-1)
        gap = np.maximum(gap, np.abs(vx * dx + vy * dy) - reach) - cylinder.radius
        z0, z1 = cylinder.position[2], cylinder.position[2] + cylinder.height
        low, high = self.z_low[states, geoms], self.z_high[states, geoms]
        vertical = np.maximum(np.maximum(low - z1, z0 - high), 0.0)
        out: FloatArray = np.hypot(np.maximum(gap, 0.0), vertical[None]) - self.radius[geoms]
        return out


def prisms_of(
    model: mujoco.MjModel, carried: IntArray, xpos: FloatArray, rot: FloatArray
) -> tuple[Prisms, IntArray, FloatArray]:
    """Each carried geom seen from above, for bounds against a vertical cylinder.

    A geom is a box (a capsule: a segment with a radius; a cylinder: its
    bounding box; anything else: its bounding sphere): its projection on the
    table plane is its centre plus three half axes, with a z extent. For
    blocks of :data:`BLOCK_STATES` states: the middle state's box, less how far
    any point of the geom moves within the block.

    Args:
        model: The model.
        carried: The G carried geoms.
        xpos: Their centres in n states, (n, G, 3) [m].
        rot: Their orientations, (n, G, 3, 3).

    Returns:
        The :class:`Prisms`, each block's middle state (B,), and how far any
        point of each geom moves within each block, (B, G) [m].
    """
    m = model
    t = mujoco.mjtGeom
    n, g = xpos.shape[:2]
    half = np.zeros((g, 3))
    radius = np.zeros(g)
    for j, k in enumerate(carried.tolist()):
        kind, size = int(m.geom_type[k]), np.asarray(m.geom_size[k], dtype=float)
        if kind == t.mjGEOM_BOX:
            half[j] = size[:3]
        elif kind == t.mjGEOM_CYLINDER:
            half[j] = (size[0], size[0], size[1])
        elif kind == t.mjGEOM_CAPSULE:
            half[j, 2], radius[j] = size[1], size[0]
        else:  # a sphere, or another shape within its bounding sphere
            radius[j] = size[0] if kind == t.mjGEOM_SPHERE else float(m.geom_rbound[k])
    axes = rot * half[None, :, None, :]  # (n, G, 3, 3): column i is half axis i
    axes_xy = np.swapaxes(axes[:, :, :2, :], 2, 3)  # (n, G, 3 axes, 2)
    reach_z = np.abs(axes[:, :, 2, :]).sum(axis=-1) + radius[None]
    normal = np.stack([-axes_xy[..., 1], axes_xy[..., 0]], axis=-1)
    length = np.linalg.norm(normal, axis=-1, keepdims=True)
    normal = np.divide(normal, length, out=np.zeros_like(normal), where=length > 0)
    # Reach of the projection along each normal: the sum over the axes of |normal . axis|.
    reach = np.abs(np.einsum("ngdc,ngac->ngda", normal, axes_xy)).sum(axis=-1)
    prism = Prisms(
        centre=np.ascontiguousarray(xpos[..., :2]),
        axes=np.ascontiguousarray(axes_xy),
        normals=np.ascontiguousarray(normal),
        reach=reach,
        z_low=xpos[..., 2] - reach_z,
        z_high=xpos[..., 2] + reach_z,
        radius=radius,
    )
    blocks = math.ceil(n / BLOCK_STATES)
    middle = np.minimum(np.arange(blocks) * BLOCK_STATES + BLOCK_STATES // 2, n - 1)
    owner = np.arange(n) // BLOCK_STATES
    ref = middle[owner]
    # A point c + R v of the geom (|v_i| <= half_i) moves at most |dc| + sum_i |dR_i| half_i.
    moved = np.linalg.norm(xpos - xpos[ref], axis=-1)
    turned = np.linalg.norm(rot - rot[ref], axis=-2)  # (n, G, 3): per column of R
    moved = moved + (turned * half[None]).sum(axis=-1)
    block_move = np.zeros((blocks, g))
    np.maximum.at(block_move, owner, moved)
    return prism, middle, block_move
