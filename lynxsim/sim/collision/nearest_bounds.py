"""Compiled lower bounds of each obstacle's clearance, per state: the rule of :mod:`.clearance`.

:class:`NearestBounds` gives, for every state and obstacle, the smallest of
the lower bounds that :func:`lynxsim.sim.collision.clearance._bounds` puts on
the distance of each carried geom to the obstacle (a geom's distance from the
obstacle's own shape at its centre, less its extent towards the obstacle),
compiled by numba with no Python per state. A playback uses it to decide
which states may hold an obstacle's smallest clearance
(:class:`~lynxsim.sim.stepping.records.SensedRecorder`); the exact distances
stay MuJoCo's. The arithmetic is the same as the NumPy bounds but not
bit-identical to them (the caller keeps a tolerance of
:data:`BOUND_TOLERANCE_M`).
"""

from __future__ import annotations

import math

import mujoco
import numpy as np
import numpy.typing as npt
from numba import njit

from lynxsim.errors import InvalidInputError
from lynxsim.sim.collision.clearance import ClearanceGeometry
from lynxsim.sim.cover.spheres import cover_geom

__all__ = ["BOUND_TOLERANCE_M", "NearestBounds"]

FloatArray = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.intp]

BOUND_TOLERANCE_M = 1e-6
"""Taken off every computed bound [m]: more than the rounding of the bounds, and than
any amount by which MuJoCo's distance may fall short of the true one."""

_BOX, _CYLINDER, _SPHERE = 6, 5, 2
"""MuJoCo's geom types box, cylinder and sphere (``mjtGeom``), as plain ints."""


@njit(cache=True, inline="always", error_model="numpy")
def _sdf(kind, size, rbound, x, y, z):  # type: ignore[no-untyped-def]  # numba
    """Signed distance of a point to an obstacle in its frame, and the way out (zero inside)."""
    if kind == _BOX:
        ox, oy, oz = abs(x) - size[0], abs(y) - size[1], abs(z) - size[2]
        inside = max(max(ox, oy), oz)
        ax = math.copysign(max(ox, 0.0), x)
        ay = math.copysign(max(oy, 0.0), y)
        az = math.copysign(max(oz, 0.0), z)
    elif kind == _CYLINDER:
        rho = math.hypot(x, y)
        radial, axial = rho - size[0], abs(z) - size[1]
        scale = max(radial, 0.0) / (rho if rho > 0.0 else 1.0)
        ax, ay, az = x * scale, y * scale, math.copysign(max(axial, 0.0), z)
        inside = max(radial, axial)
    else:
        radius = size[0] if kind == _SPHERE else rbound
        norm = math.sqrt(x * x + y * y + z * z)
        inside = norm - radius
        scale = max(inside, 0.0) / (norm if norm > 0.0 else 1.0)
        ax, ay, az = x * scale, y * scale, z * scale
    dist = math.sqrt(ax * ax + ay * ay + az * az)
    return (dist if dist > 0.0 else inside), ax, ay, az


@njit(cache=True, inline="always", error_model="numpy")
def _extent_bound(xpos, xmat, s, g, extent, reach, kind, size, rbound, pos, r, j):  # type: ignore[no-untyped-def]  # numba
    """The geom's distance from the obstacle at its centre, less its extent towards it [m]."""
    dx = xpos[s, g, 0] - pos[j, 0]
    dy = xpos[s, g, 1] - pos[j, 1]
    dz = xpos[s, g, 2] - pos[j, 2]
    lx = r[0, 0] * dx + r[1, 0] * dy + r[2, 0] * dz
    ly = r[0, 1] * dx + r[1, 1] * dy + r[2, 1] * dz
    lz = r[0, 2] * dx + r[1, 2] * dy + r[2, 2] * dz
    sdf, ax, ay, az = _sdf(kind[j], size[j], rbound[j], lx, ly, lz)
    if sdf <= 0.0:
        return sdf - reach[g, 1]
    nx = (r[0, 0] * ax + r[0, 1] * ay + r[0, 2] * az) / sdf
    ny = (r[1, 0] * ax + r[1, 1] * ay + r[1, 2] * az) / sdf
    nz = (r[2, 0] * ax + r[2, 1] * ay + r[2, 2] * az) / sdf
    towards = reach[g, 0]
    for a in range(3):
        proj = nx * xmat[s, g, a] + ny * xmat[s, g, 3 + a] + nz * xmat[s, g, 6 + a]
        towards += abs(proj) * extent[g, a]
    return sdf - min(towards, reach[g, 1])


@njit(cache=True, inline="always", error_model="numpy")
def _sphere_bound(  # type: ignore[no-untyped-def]  # numba
    xpos, xmat, s, g, first, centres, radii, kind, size, rbound, pos, r, j, floor, level
):
    """The smallest distance of the geom's cover spheres to the obstacle [m].

    ``floor`` (another lower bound) as soon as one sphere is within ``level``
    (the bound is then below the level either way).
    """
    low = np.inf
    for k in range(first[g], first[g + 1]):
        u, v, w = centres[k, 0], centres[k, 1], centres[k, 2]
        dx = xpos[s, g, 0] + xmat[s, g, 0] * u + xmat[s, g, 1] * v + xmat[s, g, 2] * w - pos[j, 0]
        dy = xpos[s, g, 1] + xmat[s, g, 3] * u + xmat[s, g, 4] * v + xmat[s, g, 5] * w - pos[j, 1]
        dz = xpos[s, g, 2] + xmat[s, g, 6] * u + xmat[s, g, 7] * v + xmat[s, g, 8] * w - pos[j, 2]
        lx = r[0, 0] * dx + r[1, 0] * dy + r[2, 0] * dz
        ly = r[0, 1] * dx + r[1, 1] * dy + r[2, 1] * dz
        lz = r[0, 2] * dx + r[1, 2] * dy + r[2, 2] * dz
        sdf, _, _, _ = _sdf(kind[j], size[j], rbound[j], lx, ly, lz)
        low = min(low, sdf - radii[k])
        if low - BOUND_TOLERANCE_M < level:
            return floor
    return low


@njit(cache=True, inline="always", error_model="numpy")
def _bound(  # type: ignore[no-untyped-def]  # numba
    xpos, xmat, s, g, level, geo, first, centres, radii, fixed, kind, size, rbound, pos, r, j
):
    """A lower bound of geom g's distance to obstacle j [m], tightened while below ``level``.

    A geom fixed to the world has its exact distance (MuJoCo's); another gets
    the extent bound, and where that is below ``level`` the larger of it and
    its cover spheres' (both lower bounds), less :data:`BOUND_TOLERANCE_M`.
    """
    if not math.isnan(fixed[g, j]):
        return fixed[g, j]
    extent, reach = geo
    # the bounding spheres first: a bound below both of theirs is no lower
    dx = xpos[s, g, 0] - pos[j, 0]
    dy = xpos[s, g, 1] - pos[j, 1]
    dz = xpos[s, g, 2] - pos[j, 2]
    weak = math.sqrt(dx * dx + dy * dy + dz * dz) - rbound[j] - reach[g, 1] - BOUND_TOLERANCE_M
    if weak >= level:
        return weak
    b = _extent_bound(xpos, xmat, s, g, extent, reach, kind, size, rbound, pos, r, j)
    if b - BOUND_TOLERANCE_M >= level:
        return b - BOUND_TOLERANCE_M
    tight = _sphere_bound(
        xpos, xmat, s, g, first, centres, radii, kind, size, rbound, pos, r, j, b, level
    )
    return max(b, tight) - BOUND_TOLERANCE_M


@njit(cache=True, error_model="numpy")
def _nearest(  # type: ignore[no-untyped-def]  # numba
    xpos, xmat, geo, first, centres, radii, fixed, kind, size, rbound, pos, rot, below, out
):
    for j in range(kind.shape[0]):
        r = rot[j]
        for s in range(xpos.shape[0]):
            low = np.inf
            for g in range(xpos.shape[1]):  # the geoms fixed to the world first: exact
                if not math.isnan(fixed[g, j]):
                    low = min(low, fixed[g, j])
            for g in range(xpos.shape[1]):
                if math.isnan(fixed[g, j]):
                    level = min(low, below[j])
                    b = _bound(
                        xpos,
                        xmat,
                        s,
                        g,
                        level,
                        geo,
                        first,
                        centres,
                        radii,
                        fixed,
                        kind,
                        size,
                        rbound,
                        pos,
                        r,
                        j,
                    )
                    low = min(low, b)
            out[s, j] = low


@njit(cache=True, error_model="numpy")
def _per_geom(  # type: ignore[no-untyped-def]  # numba
    xpos, xmat, s, level, geo, first, centres, radii, fixed, kind, size, rbound, pos, rot, j, out
):
    for g in range(xpos.shape[1]):
        out[g] = _bound(
            xpos,
            xmat,
            s,
            g,
            level,
            geo,
            first,
            centres,
            radii,
            fixed,
            kind,
            size,
            rbound,
            pos,
            rot[j],
            j,
        )


class NearestBounds:
    """The compiled bounds of one scene's clearance geometry.

    Args:
        model: The model.
        data: Its data, posed (``mj_kinematics``): the distances of the geoms
            fixed to the world are computed once, here.
        geometry: Its :class:`~lynxsim.sim.collision.ClearanceGeometry`.
        cap: Distances of ``cap`` or more read as ``cap`` [m].
    """

    def __init__(
        self, model: mujoco.MjModel, data: mujoco.MjData, geometry: ClearanceGeometry, cap: float
    ) -> None:
        f64 = np.float64
        carried, obstacles = geometry.carried.tolist(), geometry.obstacles.tolist()
        centres, radii = [], []
        fixed = np.full((len(carried), len(obstacles)), np.nan)
        for i, g in enumerate(carried):
            try:
                cover = cover_geom(int(model.geom_type[g]), model.geom_size[g], 0.025)
                centres.append(np.asarray(cover.centres))
                radii.append(np.asarray(cover.radii))
            except InvalidInputError:  # no primitive: its bounding sphere
                centres.append(np.zeros((1, 3)))
                radii.append(np.array([model.geom_rbound[g]]))
            if model.body_weldid[model.geom_bodyid[g]] == 0:  # welded to the world
                for j, target in enumerate(obstacles):
                    fixed[i, j] = mujoco.mj_geomDistance(model, data, g, target, cap, None)
        self._geo = (
            np.ascontiguousarray(geometry.extent, dtype=f64),
            np.ascontiguousarray(geometry.reach, dtype=f64),
        )
        self._spheres = (
            np.cumsum([0, *(len(r) for r in radii)]).astype(np.int64),
            np.ascontiguousarray(np.concatenate([np.zeros((0, 3)), *centres]), dtype=f64),
            np.ascontiguousarray(np.concatenate([np.zeros(0), *radii]), dtype=f64),
            fixed,
        )
        self._obstacles = (
            np.ascontiguousarray(geometry.kind, dtype=np.int64),
            np.ascontiguousarray(geometry.size, dtype=f64),
            np.ascontiguousarray(geometry.rbound, dtype=f64),
            np.ascontiguousarray(geometry.pos, dtype=f64),
            np.ascontiguousarray(geometry.rot, dtype=f64),
        )
        self.obstacles = len(obstacles)
        self._geoms = len(carried)

    def nearest(self, xpos: FloatArray, xmat: FloatArray, below: FloatArray) -> FloatArray:
        """Per state and obstacle, a lower bound of its clearance [m], (N, m).

        Each geom's bound is made tighter (its cover spheres) only while it is
        below ``below`` and the state's smallest so far.

        Args:
            xpos: Centres of the carried geoms in N states, (N, r, 3) [m],
                C-contiguous.
            xmat: Their orientations (rows of MuJoCo's ``geom_xmat``), (N, r, 9).
            below: Per obstacle, the level under which bounds are tightened, (m,) [m].
        """
        out = np.empty((len(xpos), self.obstacles))
        _nearest(xpos, xmat, self._geo, *self._spheres, *self._obstacles, below, out)
        return out

    def per_geom(
        self, xpos: FloatArray, xmat: FloatArray, s: int, j: int, level: float
    ) -> FloatArray:
        """Bound of each carried geom of state ``s`` to obstacle ``j`` [m], (r,).

        Tightened while below ``level`` [m].
        """
        out = np.empty(self._geoms)
        _per_geom(xpos, xmat, s, level, self._geo, *self._spheres, *self._obstacles, j, out)
        return out
