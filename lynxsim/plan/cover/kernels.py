"""Compiled checks on a sphere cover: forward kinematics, distances, clearance, certified edges.

Every function here is compiled by numba (``nopython``; cached on disk, so a
process compiles once per machine) and takes the world as the tuple
:meth:`~lynxsim.plan.cover.world.CoverWorld.as_tuple`, plus a scratch
:func:`scratch` of the world, so that a check allocates nothing. The rules are
those of :mod:`lynxsim.plan.cover.world` (the clearance) and
:mod:`lynxsim.plan.edges` (certified edges).
"""

from __future__ import annotations

import math

import numpy as np
import numpy.typing as npt
from numba import njit

from lynxsim.plan.cover.world import (
    GEOM_BOX,
    GEOM_CAPSULE,
    GEOM_CYLINDER,
    GEOM_SPHERE,
    JOINT_HINGE,
    FloatArray,
    WorldTuple,
)

__all__ = ["MAX_SPLIT", "batch_clearance", "clearance", "edge_clear", "path_clear", "scratch"]

MAX_SPLIT = 64
"""Most new points one round puts into one interval [-] (as :mod:`lynxsim.plan.edges`)."""

Scratch = tuple[
    FloatArray, FloatArray, FloatArray, FloatArray, FloatArray, FloatArray, FloatArray,
    npt.NDArray[np.bool_], npt.NDArray[np.bool_], FloatArray, FloatArray,
]  # fmt: skip
"""Work arrays of one world: full state, body and geom frames, sphere centres, stack, flags,
and an edge's point and new points."""


def scratch(world: WorldTuple) -> Scratch:
    """Fresh work arrays for :func:`clearance` on ``world`` (not shared between threads)."""
    nq, n, b = len(world[0]), len(world[1]), len(world[3])
    g, s = len(world[12]), len(world[21])
    return (
        np.zeros(nq),
        np.zeros((b, 3)),
        np.zeros((b, 3, 3)),
        np.zeros((g, 3)),
        np.zeros((g, 3, 3)),
        np.zeros((s, 3)),
        np.zeros((4 * MAX_SPLIT + 64, 4)),
        np.zeros(g, dtype=np.bool_),
        np.zeros(g, dtype=np.bool_),
        np.zeros(n),
        np.zeros((MAX_SPLIT, 2)),
    )


@njit(cache=True, inline="always", error_model="numpy")
def _forward(w, q, grasped, work):  # type: ignore[no-untyped-def]  # numba
    """Body and geom frames of joint vector ``q`` (n,) into the scratch."""
    qref, qadr, base, parent, bpos, bmat, jstart, jcount = (
        w[0],
        w[1],
        w[2],
        w[3],
        w[4],
        w[5],
        w[6],
        w[7],
    )
    jtype, jaxis, jpos, jqadr = w[8], w[9], w[10], w[11]
    gbody, gpos_l, groles = w[12], w[13], w[19]
    qfull, xpos, xmat, gpos = work[0], work[1], work[2], work[3]
    qfull[:] = base
    for i in range(qadr.shape[0]):
        qfull[qadr[i]] = q[i]
    for r in range(3):
        xpos[0, r] = 0.0
        for c in range(3):
            xmat[0, r, c] = 1.0 if r == c else 0.0
    for b in range(1, parent.shape[0]):
        p = parent[b]
        for r in range(3):
            xpos[b, r] = (
                xpos[p, r]
                + xmat[p, r, 0] * bpos[b, 0]
                + xmat[p, r, 1] * bpos[b, 1]
                + xmat[p, r, 2] * bpos[b, 2]
            )
            for c in range(3):
                xmat[b, r, c] = (
                    xmat[p, r, 0] * bmat[b, 0, c]
                    + xmat[p, r, 1] * bmat[b, 1, c]
                    + xmat[p, r, 2] * bmat[b, 2, c]
                )
        for j in range(jstart[b], jstart[b] + jcount[b]):
            value = qfull[jqadr[j]] - qref[jqadr[j]]
            ax, ay, az = jaxis[j, 0], jaxis[j, 1], jaxis[j, 2]
            if jtype[j] == JOINT_HINGE:
                # Rotation A about the anchor: x = anchor + R_b A (x_local - pos).
                ca, sa = math.cos(value), math.sin(value)
                t = 1.0 - ca
                r00, r01, r02 = ca + ax * ax * t, ax * ay * t - az * sa, ax * az * t + ay * sa
                r10, r11, r12 = ay * ax * t + az * sa, ca + ay * ay * t, ay * az * t - ax * sa
                r20, r21, r22 = az * ax * t - ay * sa, az * ay * t + ax * sa, ca + az * az * t
                px, py, pz = jpos[j, 0], jpos[j, 1], jpos[j, 2]
                for r in range(3):
                    m0, m1, m2 = xmat[b, r, 0], xmat[b, r, 1], xmat[b, r, 2]
                    anchor = xpos[b, r] + m0 * px + m1 * py + m2 * pz
                    n0 = m0 * r00 + m1 * r10 + m2 * r20
                    n1 = m0 * r01 + m1 * r11 + m2 * r21
                    n2 = m0 * r02 + m1 * r12 + m2 * r22
                    xmat[b, r, 0], xmat[b, r, 1], xmat[b, r, 2] = n0, n1, n2
                    xpos[b, r] = anchor - (n0 * px + n1 * py + n2 * pz)
            else:
                for r in range(3):
                    xpos[b, r] += value * (
                        xmat[b, r, 0] * ax + xmat[b, r, 1] * ay + xmat[b, r, 2] * az
                    )
    for g in range(gbody.shape[0]):
        if groles[g] == 1 and not grasped:
            continue
        b = gbody[g]
        for r in range(3):
            gpos[g, r] = (
                xpos[b, r]
                + xmat[b, r, 0] * gpos_l[g, 0]
                + xmat[b, r, 1] * gpos_l[g, 1]
                + xmat[b, r, 2] * gpos_l[g, 2]
            )


@njit(cache=True, inline="always", error_model="numpy")
def _point_distance(x, y, z, kind, pos, mat, size, k):  # type: ignore[no-untyped-def]  # numba
    """Signed distance [m] of point (x, y, z) to a primitive of type ``kind`` at ``pos, mat``."""
    dx, dy, dz = x - pos[k, 0], y - pos[k, 1], z - pos[k, 2]
    lx = mat[k, 0, 0] * dx + mat[k, 1, 0] * dy + mat[k, 2, 0] * dz
    ly = mat[k, 0, 1] * dx + mat[k, 1, 1] * dy + mat[k, 2, 1] * dz
    lz = mat[k, 0, 2] * dx + mat[k, 1, 2] * dy + mat[k, 2, 2] * dz
    if kind == GEOM_SPHERE:
        return math.sqrt(lx * lx + ly * ly + lz * lz) - size[k, 0]
    if kind == GEOM_BOX:
        qx, qy, qz = abs(lx) - size[k, 0], abs(ly) - size[k, 1], abs(lz) - size[k, 2]
        ox, oy, oz = max(qx, 0.0), max(qy, 0.0), max(qz, 0.0)
        return math.sqrt(ox * ox + oy * oy + oz * oz) + min(max(qx, max(qy, qz)), 0.0)
    if kind == GEOM_CYLINDER:
        qr = math.sqrt(lx * lx + ly * ly) - size[k, 0]
        qa = abs(lz) - size[k, 1]
        orr, oa = max(qr, 0.0), max(qa, 0.0)
        return math.sqrt(orr * orr + oa * oa) + min(max(qr, qa), 0.0)
    # capsule
    cz = min(max(lz, -size[k, 1]), size[k, 1])
    return math.sqrt(lx * lx + ly * ly + (lz - cz) * (lz - cz)) - size[k, 0]


@njit(cache=True, inline="always", error_model="numpy")
def _support_extent(kind, mat, size, k, nx, ny, nz):  # type: ignore[no-untyped-def]  # numba
    """How far a primitive reaches from its origin along the unit direction n [m]."""
    a0 = abs(mat[k, 0, 0] * nx + mat[k, 1, 0] * ny + mat[k, 2, 0] * nz)
    a1 = abs(mat[k, 0, 1] * nx + mat[k, 1, 1] * ny + mat[k, 2, 1] * nz)
    a2 = abs(mat[k, 0, 2] * nx + mat[k, 1, 2] * ny + mat[k, 2, 2] * nz)
    if kind == GEOM_BOX:
        return size[k, 0] * a0 + size[k, 1] * a1 + size[k, 2] * a2
    if kind == GEOM_SPHERE:
        return size[k, 0]
    if kind == GEOM_CYLINDER:
        return size[k, 1] * a2 + size[k, 0] * math.sqrt(max(0.0, 1.0 - a2 * a2))
    if kind == GEOM_CAPSULE:
        return size[k, 1] * a2 + size[k, 0]
    return math.inf


@njit(cache=True, inline="always", error_model="numpy")
def _frame(w, g, work, framed):  # type: ignore[no-untyped-def]  # numba
    """World orientation of geom ``g`` into the scratch (once per check)."""
    if framed[g]:
        return
    gbody, gmat_l, xmat, gmat = w[12], w[14], work[2], work[4]
    b = gbody[g]
    for r in range(3):
        for c in range(3):
            gmat[g, r, c] = (
                xmat[b, r, 0] * gmat_l[g, 0, c]
                + xmat[b, r, 1] * gmat_l[g, 1, c]
                + xmat[b, r, 2] * gmat_l[g, 2, c]
            )
    framed[g] = True


@njit(cache=True, inline="always", error_model="numpy")
def _centres(w, g, work, done):  # type: ignore[no-untyped-def]  # numba
    """World centres of geom ``g``'s spheres into the scratch (once per check)."""
    if done[g]:
        return
    _frame(w, g, work, work[8])
    start, local, gpos, gmat, cen = w[18], w[20], work[3], work[4], work[5]
    for s in range(start[g], start[g + 1]):
        for r in range(3):
            cen[s, r] = (
                gpos[g, r]
                + gmat[g, r, 0] * local[s, 0]
                + gmat[g, r, 1] * local[s, 1]
                + gmat[g, r, 2] * local[s, 2]
            )
    done[g] = True


@njit(cache=True, error_model="numpy")
def _clearance(w, q, grasped, work):  # type: ignore[no-untyped-def]  # numba
    """The cover's clearance of ``q`` (n,) [m]; see :mod:`lynxsim.plan.cover.world`."""
    gtype, gsize, grb, start, roles, radius = w[15], w[16], w[17], w[18], w[19], w[21]
    otype, opos, omat, osize, snorm, soff = w[22], w[23], w[24], w[25], w[26], w[27]
    pa, pb, ftype, fpos, fmat, fsize, fpg, fpf, sc = (
        w[28],
        w[29],
        w[30],
        w[31],
        w[32],
        w[33],
        w[34],
        w[35],
        w[36],
    )
    if sc[2] > 0.0:
        return -math.inf
    tj, tlo, tstep, tstart, tflag = w[37], w[38], w[39], w[40], w[41]
    for t in range(tj.shape[0]):
        x = (q[tj[t]] - tlo[t]) / tstep[t]
        count = tstart[t + 1] - tstart[t]
        if not (0.0 <= x <= count):
            return -math.inf
        k = min(int(x), count - 1)
        if tflag[tstart[t] + k] != 0 or (x == k and k > 0 and tflag[tstart[t] + k - 1] != 0):
            return -math.inf
    _forward(w, q, grasped, work)
    gpos, gmat, cen = work[3], work[4], work[5]
    ng = gtype.shape[0]
    done, framed = work[7], work[8]
    done[:] = False
    framed[:] = False
    for g in range(ng):
        if roles[g] != 0:
            continue
        for h in range(soff.shape[0]):
            nx, ny, nz = snorm[h, 0], snorm[h, 1], snorm[h, 2]
            height = nx * gpos[g, 0] + ny * gpos[g, 1] + nz * gpos[g, 2] - soff[h]
            if height - grb[g] > 0.0:
                continue
            _frame(w, g, work, framed)
            if height - _support_extent(gtype[g], gmat, gsize, g, nx, ny, nz) <= 0.0:
                return -math.inf
    for k in range(pa.shape[0]):
        a, b = pa[k], pb[k]
        dx, dy, dz = gpos[a, 0] - gpos[b, 0], gpos[a, 1] - gpos[b, 1], gpos[a, 2] - gpos[b, 2]
        if math.sqrt(dx * dx + dy * dy + dz * dz) - grb[a] - grb[b] > 0.0:
            continue
        _centres(w, a, work, done)
        _centres(w, b, work, done)
        for i in range(start[a], start[a + 1]):
            for j in range(start[b], start[b + 1]):
                dx, dy, dz = cen[i, 0] - cen[j, 0], cen[i, 1] - cen[j, 1], cen[i, 2] - cen[j, 2]
                if math.sqrt(dx * dx + dy * dy + dz * dz) - radius[i] - radius[j] <= 0.0:
                    return -math.inf
    for k in range(fpg.shape[0]):
        g, f = fpg[k], fpf[k]
        if (
            _point_distance(gpos[g, 0], gpos[g, 1], gpos[g, 2], ftype[f], fpos, fmat, fsize, f)
            - grb[g]
            > 0.0
        ):
            continue
        _centres(w, g, work, done)
        for i in range(start[g], start[g + 1]):
            if (
                _point_distance(cen[i, 0], cen[i, 1], cen[i, 2], ftype[f], fpos, fmat, fsize, f)
                - radius[i]
                <= 0.0
            ):
                return -math.inf
    best = min(sc[3], sc[1] if grasped else sc[0])
    for g in range(ng):
        if roles[g] == 1 and not grasped:
            continue
        for o in range(otype.shape[0]):
            if (
                _point_distance(gpos[g, 0], gpos[g, 1], gpos[g, 2], otype[o], opos, omat, osize, o)
                - grb[g]
                >= best
            ):
                continue
            _centres(w, g, work, done)
            for i in range(start[g], start[g + 1]):
                d = (
                    _point_distance(cen[i, 0], cen[i, 1], cen[i, 2], otype[o], opos, omat, osize, o)
                    - radius[i]
                )
                if d <= 0.0:
                    return -math.inf  # touching an obstacle reads as a hit, as exactly
                if d < best:
                    best = d
    return best


@njit(cache=True, error_model="numpy")
def _edge_clear(w, qa, qb, ca, cb, lipschitz, margin, grasped, work, counter):  # type: ignore[no-untyped-def]  # numba
    """Whether edge ``qa -> qb`` is certified clear; counts the checks it makes.

    ``ca``, ``cb`` are the ends' clearances [m]; ``cb`` is NaN when not known yet
    (it is checked then).

    Returns the end's clearance when clear, ``-inf`` when not (the rule of
    :mod:`lynxsim.plan.edges`; intervals on a stack, same verdict as its rounds).
    """
    n = qa.shape[0]
    length = 0.0
    for i in range(n):
        length += (qb[i] - qa[i]) ** 2
    length = math.sqrt(length)
    if math.isnan(cb):
        cb = _clearance(w, qb, grasped, work)
        counter[0] += 1
    if not (ca >= margin and cb >= margin):
        return -math.inf
    stack = work[6]
    top = 0
    stack[0, 0], stack[0, 1], stack[0, 2], stack[0, 3] = 0.0, length, ca, cb
    q, points = work[9], work[10]
    while top >= 0:
        s_a, s_b, c_a, c_b = stack[top, 0], stack[top, 1], stack[top, 2], stack[top, 3]
        top -= 1
        h = s_b - s_a
        if lipschitz * h <= c_a + c_b - margin:
            continue
        spacing = max(min(c_a, c_b), margin) / lipschitz
        k = int(min(max(math.ceil(h / spacing) - 1.0, 1.0), MAX_SPLIT))
        for j in range(1, k + 1):
            s = s_a + h * j / (k + 1)
            for i in range(n):
                q[i] = qa[i] + s / length * (qb[i] - qa[i])
            c = _clearance(w, q, grasped, work)
            counter[0] += 1
            if not c >= margin:
                return -math.inf
            points[j - 1, 0], points[j - 1, 1] = s, c
        if top + k + 1 >= stack.shape[0]:
            return -math.inf  # never: the stack holds MAX_SPLIT + 1 per level of a few levels
        prev_s, prev_c = s_a, c_a
        for j in range(k):
            top += 1
            stack[top, 0], stack[top, 1], stack[top, 2], stack[top, 3] = (
                prev_s,
                points[j, 0],
                prev_c,
                points[j, 1],
            )
            prev_s, prev_c = points[j, 0], points[j, 1]
        top += 1
        stack[top, 0], stack[top, 1], stack[top, 2], stack[top, 3] = prev_s, s_b, prev_c, c_b
    return cb


@njit(cache=True, error_model="numpy")
def _batch(w, q, grasped, work):  # type: ignore[no-untyped-def]  # numba
    out = np.empty(q.shape[0])
    for k in range(q.shape[0]):
        out[k] = _clearance(w, q[k], grasped, work)
    return out


@njit(cache=True, error_model="numpy")
def _path(w, path, lipschitz, margin, grasped, work):  # type: ignore[no-untyped-def]  # numba
    counter = np.zeros(1, dtype=np.int64)
    c = _clearance(w, path[0], grasped, work)
    counter[0] += 1
    ok = c >= margin
    for k in range(path.shape[0] - 1):
        if not ok:
            break
        c = _edge_clear(
            w, path[k], path[k + 1], c, math.nan, lipschitz, margin, grasped, work, counter
        )
        ok = c >= margin
    return ok, counter[0]


def clearance(world: WorldTuple, q: FloatArray, grasped: bool, work: Scratch) -> float:
    """The cover's clearance of one joint vector ``q`` (n,) [m] (``-inf`` on a hit)."""
    return float(_clearance(world, q, grasped, work))


def batch_clearance(world: WorldTuple, q: FloatArray, grasped: bool, work: Scratch) -> FloatArray:
    """The cover's clearances of joint vectors ``q`` (N, n), (N,) [m], in one compiled call."""
    out: FloatArray = _batch(world, np.ascontiguousarray(q, dtype=float), grasped, work)
    return out


def edge_clear(
    world: WorldTuple,
    qa: FloatArray,
    qb: FloatArray,
    *,
    lipschitz: float,
    margin_m: float,
    grasped: bool,
    work: Scratch,
) -> tuple[bool, int]:
    """Whether the edge ``qa -> qb`` (n,) is certified clear on the cover; the checks asked."""
    ok, checks = _path(world, np.stack([qa, qb]), lipschitz, margin_m, grasped, work)
    return bool(ok), int(checks)


def path_clear(
    world: WorldTuple,
    path: FloatArray,
    *,
    lipschitz: float,
    margin_m: float,
    grasped: bool,
    work: Scratch,
) -> tuple[bool, int]:
    """Whether every edge of ``path`` (M, n) is certified clear on the cover; the checks asked."""
    ok, checks = _path(
        world, np.ascontiguousarray(path, dtype=float), lipschitz, margin_m, grasped, work
    )
    return bool(ok), int(checks)
