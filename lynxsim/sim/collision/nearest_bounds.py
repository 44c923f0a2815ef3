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
def _sdf(kind, s0, s1, s2, rbound, x, y, z):  # type: ignore[no-untyped-def]  # numba
    """Signed distance of a point to an obstacle in its frame, and the way out (zero inside)."""
    if kind == _BOX:
        ox, oy, oz = abs(x) - s0, abs(y) - s1, abs(z) - s2
        inside = max(max(ox, oy), oz)
        ax = math.copysign(max(ox, 0.0), x)
        ay = math.copysign(max(oy, 0.0), y)
        az = math.copysign(max(oz, 0.0), z)
    elif kind == _CYLINDER:
        rho = math.hypot(x, y)
        radial, axial = rho - s0, abs(z) - s1
        scale = max(radial, 0.0) / (rho if rho > 0.0 else 1.0)
        ax, ay, az = x * scale, y * scale, math.copysign(max(axial, 0.0), z)
        inside = max(radial, axial)
    else:
        radius = s0 if kind == _SPHERE else rbound
        norm = math.sqrt(x * x + y * y + z * z)
        inside = norm - radius
        scale = max(inside, 0.0) / (norm if norm > 0.0 else 1.0)
        ax, ay, az = x * scale, y * scale, z * scale
    dist = math.sqrt(ax * ax + ay * ay + az * az)
    return (dist if dist > 0.0 else inside), ax, ay, az


@njit(cache=True, error_model="numpy")
def _bound(  # type: ignore[no-untyped-def]  # numba
    xpos,
    xmat,
    s,
    g,
    level,
    extent,
    reach,
    first,
    centres,
    radii,
    fixed,
    kind,
    size,
    rbound,
    pos,
    rot,
    j,
):
    """A lower bound of geom g's distance to obstacle j in state s [m], tightened below ``level``.

    A geom fixed to the world has its exact distance (MuJoCo's); another its
    bounding sphere's, then, where that is below ``level``, its extent bound
    (its distance from the obstacle at its centre less its extent towards
    it), then, where still below, the larger of that and its cover spheres'
    (all lower bounds), less :data:`BOUND_TOLERANCE_M`. Written out in one
    function: array arguments passed on per geom cost reference counts.
    """
    if not math.isnan(fixed[g, j]):
        return fixed[g, j]
    tol = BOUND_TOLERANCE_M
    px, py, pz = pos[j, 0], pos[j, 1], pos[j, 2]
    cx, cy, cz = xpos[s, g, 0], xpos[s, g, 1], xpos[s, g, 2]
    dx, dy, dz = cx - px, cy - py, cz - pz
    weak = math.sqrt(dx * dx + dy * dy + dz * dz) - rbound[j] - reach[g, 1] - tol
    if weak >= level:
        return weak
    k, s0, s1, s2, rb = kind[j], size[j, 0], size[j, 1], size[j, 2], rbound[j]
    r00, r01, r02 = rot[j, 0, 0], rot[j, 0, 1], rot[j, 0, 2]
    r10, r11, r12 = rot[j, 1, 0], rot[j, 1, 1], rot[j, 1, 2]
    r20, r21, r22 = rot[j, 2, 0], rot[j, 2, 1], rot[j, 2, 2]
    lx = r00 * dx + r10 * dy + r20 * dz
    ly = r01 * dx + r11 * dy + r21 * dz
    lz = r02 * dx + r12 * dy + r22 * dz
    sdf, ax, ay, az = _sdf(k, s0, s1, s2, rb, lx, ly, lz)
    if sdf <= 0.0:
        b = sdf - reach[g, 1]
    else:
        nx = (r00 * ax + r01 * ay + r02 * az) / sdf
        ny = (r10 * ax + r11 * ay + r12 * az) / sdf
        nz = (r20 * ax + r21 * ay + r22 * az) / sdf
        towards = reach[g, 0]
        for a in range(3):
            proj = nx * xmat[s, g, a] + ny * xmat[s, g, 3 + a] + nz * xmat[s, g, 6 + a]
            towards += abs(proj) * extent[g, a]
        b = sdf - min(towards, reach[g, 1])
    if b - tol >= level:
        return b - tol
    m0, m1, m2 = xmat[s, g, 0], xmat[s, g, 1], xmat[s, g, 2]
    m3, m4, m5 = xmat[s, g, 3], xmat[s, g, 4], xmat[s, g, 5]
    m6, m7, m8 = xmat[s, g, 6], xmat[s, g, 7], xmat[s, g, 8]
    tight = np.inf
    for i in range(first[g], first[g + 1]):
        u, v, w = centres[i, 0], centres[i, 1], centres[i, 2]
        ex = dx + m0 * u + m1 * v + m2 * w
        ey = dy + m3 * u + m4 * v + m5 * w
        ez = dz + m6 * u + m7 * v + m8 * w
        qx = r00 * ex + r10 * ey + r20 * ez
        qy = r01 * ex + r11 * ey + r21 * ez
        qz = r02 * ex + r12 * ey + r22 * ez
        d, _, _, _ = _sdf(k, s0, s1, s2, rb, qx, qy, qz)
        tight = min(tight, d - radii[i])
        if tight - tol < level:  # below the level either way: the extent bound will do
            return b - tol
    return max(b, tight) - tol


@njit(cache=True, error_model="numpy")
def _nearest(  # type: ignore[no-untyped-def]  # numba
    xpos,
    xmat,
    extent,
    reach,
    first,
    centres,
    radii,
    fixed,
    kind,
    size,
    rbound,
    pos,
    rot,
    below,
    out,
):
    for j in range(kind.shape[0]):
        for s in range(xpos.shape[0]):
            low = np.inf
            for g in range(xpos.shape[1]):  # the geoms fixed to the world first: exact
                if not math.isnan(fixed[g, j]):
                    low = min(low, fixed[g, j])
            for g in range(xpos.shape[1]):
                if math.isnan(fixed[g, j]):
                    level = min(low, below[j])
                    # the bounding spheres here too: most geoms end at them, with no call
                    dx = xpos[s, g, 0] - pos[j, 0]
                    dy = xpos[s, g, 1] - pos[j, 1]
                    dz = xpos[s, g, 2] - pos[j, 2]
                    weak = math.sqrt(dx * dx + dy * dy + dz * dz) - rbound[j] - reach[g, 1]
                    if weak - BOUND_TOLERANCE_M >= level:
                        low = min(low, weak - BOUND_TOLERANCE_M)
                        continue
                    b = _bound(
                        xpos,
                        xmat,
                        s,
                        g,
                        level,
                        extent,
                        reach,
                        first,
                        centres,
                        radii,
                        fixed,
                        kind,
                        size,
                        rbound,
                        pos,
                        rot,
                        j,
                    )
                    low = min(low, b)
            out[s, j] = low


@njit(cache=True, error_model="numpy")
def _per_geom(  # type: ignore[no-untyped-def]  # numba
    xpos,
    xmat,
    s,
    level,
    extent,
    reach,
    first,
    centres,
    radii,
    fixed,
    kind,
    size,
    rbound,
    pos,
    rot,
    j,
    out,
):
    for g in range(xpos.shape[1]):
        out[g] = _bound(
            xpos,
            xmat,
            s,
            g,
            level,
            extent,
            reach,
            first,
            centres,
            radii,
            fixed,
            kind,
            size,
            rbound,
            pos,
            rot,
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
        _nearest(xpos, xmat, *self._geo, *self._spheres, *self._obstacles, below, out)
        return out

    def per_geom(
        self, xpos: FloatArray, xmat: FloatArray, s: int, j: int, level: float
    ) -> FloatArray:
        """Bound of each carried geom of state ``s`` to obstacle ``j`` [m], (r,).

        Tightened while below ``level`` [m].
        """
        out = np.empty(self._geoms)
        _per_geom(xpos, xmat, s, level, *self._geo, *self._spheres, *self._obstacles, j, out)
        return out
