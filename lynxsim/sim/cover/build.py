"""A robot's sphere cover made from its MuJoCo model, in the world its checker sees.

:func:`cover_world` reads a :class:`~lynxsim.sim.collision.CollisionChecker`'s
model and groups (any robot: nothing here names one) into the arrays of a
:class:`~lynxsim.plan.cover.CoverWorld`:

* the kinematic tree (bodies, hinge and slide joints) from the model, so the
  compiled forward kinematics pose the covered geoms as ``mj_kinematics`` does;
* every colliding geom of the robot that moves with the planned joints, and
  the payload's geoms at the attach site, covered by spheres
  (:func:`~lynxsim.sim.cover.spheres.cover_geom`);
* the obstacles as primitives, the supports (table, floor) as half-spaces that
  contain them;
* the self pairs MuJoCo's collision filter lets through (contype/conaffinity,
  weld bodies, parent and child, excluded body pairs): pairs that move against
  each other are checked on the spheres, a moving geom against a fixed one on
  the spheres against the exact fixed primitive, and a pair whose relative pose
  hangs on one hinge by a table of MuJoCo's distances over the hinge's range;
* what never moves (a pair fixed against each other, the fixed geoms and the
  payload at rest against obstacles and supports) measured once, exactly, by
  ``mj_geomDistance``.
"""

from __future__ import annotations

import hashlib
from dataclasses import dataclass

import mujoco
import numpy as np
import numpy.typing as npt

from lynxsim.errors import InvalidInputError
from lynxsim.plan.cover.world import (
    GEOM_BOX,
    GEOM_CAPSULE,
    GEOM_CYLINDER,
    GEOM_SPHERE,
    JOINT_HINGE,
    JOINT_SLIDE,
    CoverWorld,
)
from lynxsim.sim.collision import CollisionChecker
from lynxsim.sim.cover.spheres import DEFAULT_SLACK_M, cover_geom

__all__ = ["CoverReport", "cover_world"]

FloatArray = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.int64]

_PRIMITIVES = (GEOM_SPHERE, GEOM_CAPSULE, GEOM_CYLINDER, GEOM_BOX)
_PLANE = int(mujoco.mjtGeom.mjGEOM_PLANE)
_TABLE_STEP_M = 2e-4
"""Most a point moves between two entries of a pair's table [m]."""
_RESTING_M = 1e-9
"""A pair whose distance stays within this of 0 along its hinge rests on itself [m]."""
_TABLE_MAX = 20000
"""Most entries of one table [-]."""


@dataclass(frozen=True)
class CoverReport:
    """What a cover is made of.

    Attributes:
        geoms: Covered geoms (payload included).
        spheres: Their spheres.
        slack_m: Largest slack over the covered geoms [m]: no point of the cover
            lies farther than this from its geom.
        self_pairs: Pairs of moving geoms checked on the spheres.
        fixed_pairs: Pairs of a moving and a fixed geom.
        tabulated_pairs: Pairs whose pose hangs on one hinge that may touch
            somewhere (those that never do are left out).
    """

    geoms: int
    spheres: int
    slack_m: float
    self_pairs: int
    fixed_pairs: int
    tabulated_pairs: int


def _mat(quat: FloatArray) -> FloatArray:
    out = np.empty(9)
    mujoco.mju_quat2Mat(out, np.asarray(quat, dtype=float))
    return out.reshape(3, 3)


def _joints_above(model: mujoco.MjModel, body: int) -> set[int]:
    """Joints of ``body`` and of every body above it."""
    found: set[int] = set()
    while body > 0:
        start, count = int(model.body_jntadr[body]), int(model.body_jntnum[body])
        found.update(range(start, start + count))
        body = int(model.body_parentid[body])
    return found


def _may_collide(model: mujoco.MjModel, g1: int, g2: int, excluded: frozenset[int]) -> bool:
    """Whether MuJoCo's collision filter lets geoms ``g1, g2`` through (predefined pairs apart).

    ``excluded`` holds the signatures ``(body1 << 16) + body2`` of excluded body pairs.
    """
    ct, ca = model.geom_contype, model.geom_conaffinity
    if not ((ct[g1] & ca[g2]) or (ct[g2] & ca[g1])):
        return False
    b1, b2 = int(model.geom_bodyid[g1]), int(model.geom_bodyid[g2])
    w1, w2 = int(model.body_weldid[b1]), int(model.body_weldid[b2])
    if w1 == w2:
        return False
    filterparent = not (model.opt.disableflags & int(mujoco.mjtDisableBit.mjDSBL_FILTERPARENT))
    p1 = int(model.body_weldid[model.body_parentid[w1]])
    p2 = int(model.body_weldid[model.body_parentid[w2]])
    if filterparent and w1 != 0 and w2 != 0 and (w1 == p2 or w2 == p1):
        return False
    return ((b1 << 16) + b2) not in excluded and ((b2 << 16) + b1) not in excluded


def _distance(model: mujoco.MjModel, data: mujoco.MjData, g1: int, g2: int, cap: float) -> float:
    return float(mujoco.mj_geomDistance(model, data, g1, g2, cap, np.zeros(6)))


def _primitive(model: mujoco.MjModel, geom: int, what: str) -> int:
    kind = int(model.geom_type[geom])
    if kind not in _PRIMITIVES:
        raise InvalidInputError(
            f"no sphere cover for {what} geom {geom} of type {kind}: "
            "spheres, capsules, cylinders and boxes only"
        )
    return kind


def cover_world(
    checker: CollisionChecker, *, cap_m: float, slack_m: float = DEFAULT_SLACK_M
) -> tuple[CoverWorld, CoverReport]:
    """The cover of the checker's robot in the checker's world.

    Args:
        checker: The robot's collision checker of a scene.
        cap_m: Clearances above this read as it [m] (the planner's cap).
        slack_m: Target slack of each geom's cover [m].

    Returns:
        The :class:`~lynxsim.plan.cover.CoverWorld` and its :class:`CoverReport`.

    Raises:
        InvalidInputError: A covered geom, obstacle or support is not a primitive
            the cover handles, or a joint above a covered geom is neither a hinge
            nor a slide.
    """
    m, g = checker.model, checker.groups
    adr = checker.qpos_adr
    base = checker.base_qpos
    attach = checker.attach
    data = mujoco.MjData(m)
    data.qpos[:] = base
    mujoco.mj_kinematics(m, data)
    planned = {j for j in range(m.njnt) if int(m.jnt_qposadr[j]) in set(adr.tolist())}
    moving_body = [bool(_joints_above(m, b) & planned) for b in range(m.nbody)]
    robot = np.flatnonzero(g.robot).tolist()
    payload = np.flatnonzero(g.payload).tolist()
    moving = [x for x in robot if moving_body[int(m.geom_bodyid[x])]]
    fixed = [x for x in robot if not moving_body[int(m.geom_bodyid[x])]]
    held = payload if attach is not None else []
    chain = _chain(m, moving, attach)
    covered = moving + held
    roles = [0] * len(moving) + [1] * len(held)
    parts = [cover_geom(_primitive(m, x, "robot"), m.geom_size[x], slack_m) for x in covered]
    starts = np.concatenate([[0], np.cumsum([len(p.radii) for p in parts])]).astype(np.int64)
    geom_body, geom_pos, geom_mat, rbound = [], [], [], []
    for x, part in zip(covered, parts):
        geom_body.append(int(m.geom_bodyid[x]) if x in moving else m.nbody)
        geom_pos.append(np.array(m.geom_pos[x]))
        geom_mat.append(_mat(m.geom_quat[x]))
        rbound.append(float((np.linalg.norm(part.centres, axis=1) + part.radii).max()))
    obstacles = g.obstacle_geoms.tolist()
    for o in obstacles:
        _primitive(m, o, "obstacle")
    normals, offsets = [], []
    for s in np.flatnonzero(g.support).tolist():
        kind = int(m.geom_type[s])
        rot = np.asarray(data.geom_xmat[s]).reshape(3, 3)
        n = rot[:, 2]
        if kind == _PLANE:
            offsets.append(float(n @ data.geom_xpos[s]))
        elif kind == GEOM_BOX:  # the half-space below its top face holds the box
            offsets.append(float(n @ data.geom_xpos[s] + m.geom_size[s][2]))
        else:
            raise InvalidInputError(f"support geom {s} must be a plane or a box, got type {kind}")
        normals.append(n)
    excluded = frozenset(int(x) for x in np.asarray(m.exclude_signature).tolist())
    explicit = {frozenset((int(x), int(y))) for x, y in zip(m.pair_geom1, m.pair_geom2)}
    pairs, fpairs, tables, constant_hit = [], [], [], False
    for i, a in enumerate(robot):
        for b in robot[i + 1 :]:
            if not (_may_collide(m, a, b, excluded) or frozenset((a, b)) in explicit):
                continue
            ja = _joints_above(m, int(m.geom_bodyid[a])) & planned
            jb = _joints_above(m, int(m.geom_bodyid[b])) & planned
            if ja == jb:  # fixed against each other: touching now is touching always
                constant_hit |= _distance(m, data, a, b, 0.01) <= 0.0
                continue
            hinge = ja ^ jb
            if len(hinge) == 1 and int(m.jnt_type[next(iter(hinge))]) == JOINT_HINGE:
                table = _tabulate(m, base, a if ja > jb else b, b if ja > jb else a, *hinge)
                if table is not None:
                    index = adr.tolist().index(int(m.jnt_qposadr[next(iter(hinge))]))
                    tables.append((index, *table))
            elif a in moving and b in moving:
                pairs.append((moving.index(a), moving.index(b)))
            elif a in moving:
                fpairs.append((moving.index(a), fixed.index(b)))
            else:
                fpairs.append((moving.index(b), fixed.index(a)))
    for f in fixed:
        for s in np.flatnonzero(g.support).tolist():
            if _may_collide(m, f, s, excluded):
                constant_hit |= _distance(m, data, f, s, 0.01) <= 0.0
    rest = [min([cap_m] + [_distance(m, data, x, o, cap_m) for x in f for o in obstacles])
            for f in (fixed + payload, fixed)]  # fmt: skip
    for f in fixed:
        _primitive(m, f, "robot")

    def poses(ids: list[int]) -> tuple[IntArray, FloatArray, FloatArray, FloatArray]:
        return (
            np.array([int(m.geom_type[x]) for x in ids], dtype=np.int64),
            np.asarray(data.geom_xpos[ids], dtype=float).reshape(-1, 3),
            np.asarray(data.geom_xmat[ids], dtype=float).reshape(-1, 3, 3),
            np.asarray(m.geom_size[ids], dtype=float).reshape(-1, 3),
        )

    o_type, o_pos, o_mat, o_size = poses(obstacles)
    f_type, f_pos, f_mat, f_size = poses(fixed)
    world = CoverWorld(
        qpos_ref=np.array(m.qpos0),
        qpos_adr=adr,
        base_qpos=base,
        body_parent=chain[0],
        body_pos=chain[1],
        body_mat=chain[2],
        body_jnt_start=chain[3],
        body_jnt_count=chain[4],
        jnt_type=chain[5],
        jnt_axis=chain[6],
        jnt_pos=chain[7],
        jnt_qadr=chain[8],
        geom_body=np.array(geom_body, dtype=np.int64),
        geom_pos=np.array(geom_pos).reshape(-1, 3),
        geom_mat=np.array(geom_mat).reshape(-1, 3, 3),
        geom_type=np.array([int(m.geom_type[x]) for x in covered], dtype=np.int64),
        geom_size=np.asarray(m.geom_size[covered], dtype=float).reshape(-1, 3),
        geom_rbound=np.array(rbound),
        geom_sph_start=starts,
        geom_payload=np.array(roles, dtype=np.int64),
        sph_local=np.concatenate([p.centres for p in parts]).reshape(-1, 3),
        sph_radius=np.concatenate([p.radii for p in parts]),
        obs_type=o_type,
        obs_pos=o_pos,
        obs_mat=o_mat,
        obs_size=o_size,
        sup_normal=np.array(normals).reshape(-1, 3),
        sup_offset=np.array(offsets),
        pair_a=np.array([p[0] for p in pairs], dtype=np.int64),
        pair_b=np.array([p[1] for p in pairs], dtype=np.int64),
        fix_type=f_type,
        fix_pos=f_pos,
        fix_mat=f_mat,
        fix_size=f_size,
        fpair_geom=np.array([p[0] for p in fpairs], dtype=np.int64),
        fpair_fixed=np.array([p[1] for p in fpairs], dtype=np.int64),
        scalars=np.array([rest[0], rest[1], 1.0 if constant_hit else 0.0, cap_m]),
        tab_joint=np.array([t[0] for t in tables], dtype=np.int64),
        tab_lo=np.array([t[1] for t in tables]),
        tab_step=np.array([t[2] for t in tables]),
        tab_start=np.concatenate([[0], np.cumsum([len(t[3]) for t in tables])]).astype(np.int64),
        tab_flag=np.concatenate([np.zeros(0, dtype=np.int64)] + [t[3] for t in tables]),
    )
    report = CoverReport(
        geoms=len(covered),
        spheres=world.n_spheres,
        slack_m=max((p.slack_m for p in parts), default=0.0),
        self_pairs=len(pairs),
        fixed_pairs=len(fpairs),
        tabulated_pairs=len(tables),
    )
    return world, report


_TABLES: dict[bytes, tuple[float, float, npt.NDArray[np.int64]] | None] = {}
"""Tables already made, by what they depend on (:func:`_table_key`): a robot's tables
are the same in every scene."""
_MAX_TABLES = 4096


def _table_key(
    model: mujoco.MjModel, base: FloatArray, mover: int, other: int, joint: int
) -> bytes:
    """Everything a pair's table depends on: the tree, the joints, the two geoms, the state."""
    m = model
    digest = hashlib.sha256()
    for arr in (m.body_pos, m.body_quat, m.body_parentid, m.jnt_type, m.jnt_axis, m.jnt_pos,
                m.jnt_range, m.jnt_limited, m.jnt_qposadr, m.qpos0, base, [joint]):  # fmt: skip
        digest.update(np.ascontiguousarray(arr).tobytes())
    for g in (mover, other):
        for arr in (m.geom_bodyid[g], m.geom_type[g], m.geom_pos[g], m.geom_quat[g],
                    m.geom_size[g], m.geom_rbound[g]):  # fmt: skip
            digest.update(np.ascontiguousarray(arr).tobytes())
    return digest.digest()


def _tabulate(
    model: mujoco.MjModel, base: FloatArray, mover: int, other: int, joint: int
) -> tuple[float, float, npt.NDArray[np.int64]] | None:
    """:func:`_table` of the pair, made once per process for what it depends on."""
    key = _table_key(model, base, mover, other, joint)
    if key not in _TABLES:
        if len(_TABLES) >= _MAX_TABLES:
            _TABLES.clear()
        _TABLES[key] = _table(model, base, mover, other, joint)
    return _TABLES[key]


def _table(
    model: mujoco.MjModel, base: FloatArray, mover: int, other: int, joint: int
) -> tuple[float, float, npt.NDArray[np.int64]] | None:
    """Where over a hinge's range geom ``mover`` may touch ``other`` (their pose hangs on it).

    MuJoCo's distance ``d_i`` at joint values ``lo + i h``: no point of the mover
    moves more than ``rho h`` per step ``h`` against the other, ``rho`` bounding
    its distance from the axis, so over an interval the distance is at least
    ``(d_i + d_{i+1} - rho h) / 2``; an interval is flagged where that is ``<= 0``.
    A pair at distance 0 all along (resting on each other, as a turntable on
    its base) is what MuJoCo's collision makes of it in the base state.

    Returns:
        ``(lo, h, flags)``, or None when no interval is flagged (the pair never touches).
    """
    m = model
    data = mujoco.MjData(m)
    data.qpos[:] = base
    mujoco.mj_kinematics(m, data)
    axis = np.asarray(data.xaxis[joint])
    v = np.asarray(data.geom_xpos[mover]) - np.asarray(data.xanchor[joint])
    rho = float(np.linalg.norm(v - (v @ axis) * axis)) + float(m.geom_rbound[mover])
    lo, hi = (
        (float(m.jnt_range[joint][0]), float(m.jnt_range[joint][1]))
        if m.jnt_limited[joint]
        else (-np.pi, np.pi)
    )
    count = int(min(max(np.ceil((hi - lo) * rho / _TABLE_STEP_M), 1), _TABLE_MAX))
    h = (hi - lo) / count
    adr = int(m.jnt_qposadr[joint])
    d = np.empty(count + 1)
    for i in range(count + 1):
        data.qpos[adr] = lo + i * h
        mujoco.mj_kinematics(m, data)
        d[i] = _distance(m, data, mover, other, 1.0)
    if (np.abs(d) <= _RESTING_M).all():
        # A pair resting on each other all along the hinge (a turntable on its
        # base): it counts only if MuJoCo's collision reports it in the base state.
        data.qpos[:] = base
        mujoco.mj_kinematics(m, data)
        mujoco.mj_collision(m, data)
        pairs = {tuple(sorted(c)) for c in np.asarray(data.contact.geom[: data.ncon]).tolist()}
        touching = tuple(sorted((mover, other))) in pairs
        return (lo, hi - lo, np.ones(1, dtype=np.int64)) if touching else None
    flags = ((d[:-1] + d[1:] - rho * h) / 2.0 <= 0.0).astype(np.int64)
    return (lo, h, flags) if flags.any() else None


def _chain(
    model: mujoco.MjModel, moving: list[int], attach: tuple[int, int] | None
) -> tuple[
    IntArray, FloatArray, FloatArray, IntArray, IntArray, IntArray, FloatArray, FloatArray,
    IntArray,
]:  # fmt: skip
    """The kinematic tree's arrays: the model's bodies, then the attach site as a body."""
    m = model
    needed: set[int] = set()
    for x in moving:
        needed |= _joints_above(m, int(m.geom_bodyid[x]))
    if attach is not None:
        needed |= _joints_above(m, int(m.site_bodyid[attach[1]]))
    for j in sorted(needed):
        if int(m.jnt_type[j]) not in (JOINT_HINGE, JOINT_SLIDE):
            raise InvalidInputError(
                f"joint {j} above a covered geom is of type {int(m.jnt_type[j])}: "
                "a cover follows hinge and slide joints only"
            )
    parent = [int(p) for p in m.body_parentid]
    pos = [np.array(p) for p in m.body_pos]
    mats = [_mat(q) for q in m.body_quat]
    jstart = [int(s) if s >= 0 else 0 for s in m.body_jntadr]
    jcount = [int(c) for c in m.body_jntnum]
    for b in range(m.nbody):  # bodies of other joints (a free payload) are never posed
        if not set(range(jstart[b], jstart[b] + jcount[b])) <= needed:
            jstart[b], jcount[b] = 0, 0
    if attach is not None:
        site = attach[1]
        parent.append(int(m.site_bodyid[site]))
        pos.append(np.array(m.site_pos[site]))
        mats.append(_mat(m.site_quat[site]))
    else:
        parent.append(0)
        pos.append(np.zeros(3))
        mats.append(np.eye(3))
    jstart.append(0)
    jcount.append(0)
    return (
        np.array(parent, dtype=np.int64),
        np.array(pos, dtype=float),
        np.array(mats, dtype=float),
        np.array(jstart, dtype=np.int64),
        np.array(jcount, dtype=np.int64),
        np.array([int(t) for t in m.jnt_type], dtype=np.int64),
        np.array(m.jnt_axis, dtype=float).reshape(-1, 3),
        np.array(m.jnt_pos, dtype=float).reshape(-1, 3),
        np.array([int(a) for a in m.jnt_qposadr], dtype=np.int64),
    )
