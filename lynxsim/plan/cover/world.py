"""A robot's sphere cover and its world as plain arrays: what the compiled checks read.

The simulation layer builds a :class:`CoverWorld` from a robot's model
(:func:`lynxsim.sim.cover.cover_world`); everything here is arrays, no MuJoCo.
The robot is a kinematic tree of bodies (hinge and slide joints); each covered
geom hangs on a body with a fixed pose and is enclosed by spheres fixed in its
frame. The obstacles are primitives fixed in the world, the supports (table,
floor) half-spaces that contain them.

The clearance of a joint vector on the cover (:mod:`lynxsim.plan.cover.kernels`)
is ``-inf`` when a moving geom meets a support half-space, two spheres of a
self pair overlap, a sphere meets a fixed geom of the robot or a tabulated
pair may touch; else the smallest ``|c - o| - r`` over every sphere
``(c, r)`` and obstacle ``o``, at most the cap and the exact clearances of what never
moves. Every sphere encloses a part of its geom, so the cover's clearance is
never above the exact one.
"""

from __future__ import annotations

from dataclasses import dataclass, fields

import numpy as np
import numpy.typing as npt

from lynxsim.errors import InvalidInputError

__all__ = [
    "GEOM_BOX",
    "GEOM_CAPSULE",
    "GEOM_CYLINDER",
    "GEOM_SPHERE",
    "JOINT_HINGE",
    "JOINT_SLIDE",
    "CoverWorld",
    "WorldTuple",
]

FloatArray = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.int64]

GEOM_SPHERE = 2
"""Primitive codes (MuJoCo's numbering): sphere."""
GEOM_CAPSULE = 3
"""Capsule: radius, half-length."""
GEOM_CYLINDER = 5
"""Cylinder: radius, half-length."""
GEOM_BOX = 6
"""Box: half sizes."""
JOINT_SLIDE = 2
"""Joint codes (MuJoCo's numbering): slide."""
JOINT_HINGE = 3
"""Hinge."""

WorldTuple = tuple[
    FloatArray, IntArray, FloatArray, IntArray, FloatArray, FloatArray, IntArray, IntArray,
    IntArray, FloatArray, FloatArray, IntArray, IntArray, FloatArray, FloatArray, IntArray,
    FloatArray, FloatArray, IntArray, IntArray, FloatArray, FloatArray, IntArray, FloatArray,
    FloatArray, FloatArray, FloatArray, FloatArray, IntArray, IntArray, IntArray, FloatArray,
    FloatArray, FloatArray, IntArray, IntArray, FloatArray, IntArray, FloatArray, FloatArray,
    IntArray, IntArray,
]  # fmt: skip
"""The fields of a :class:`CoverWorld` in order: the one argument of every compiled check."""


@dataclass(frozen=True, eq=False)
class CoverWorld:
    """A robot's sphere cover in its world, as arrays (B bodies, J joints, G geoms, S spheres).

    Attributes:
        qpos_ref: The reference joint values of every ``qpos`` entry (MuJoCo's
            ``qpos0``: a joint's angle is ``qpos - qpos_ref``), (nq,) [rad or m].
        qpos_adr: Where each of the n planned joints lies in ``qpos``, (n,).
        base_qpos: The state of every other joint (fingers), (nq,).
        body_parent: Parent of each body (body 0, the world, is its own), (B,).
        body_pos: Each body's position in its parent at zero joints, (B, 3) [m].
        body_mat: Its orientation in its parent, (B, 3, 3).
        body_jnt_start: First joint of each body, (B,).
        body_jnt_count: Its number of joints, (B,).
        jnt_type: :data:`JOINT_HINGE` or :data:`JOINT_SLIDE`, (J,).
        jnt_axis: Axis in the body frame, (J, 3).
        jnt_pos: Anchor in the body frame, (J, 3) [m].
        jnt_qadr: ``qpos`` address, (J,).
        geom_body: Body of each covered geom, (G,).
        geom_pos: Its position in the body, (G, 3) [m].
        geom_mat: Its orientation in the body, (G, 3, 3).
        geom_type: Its primitive code, (G,).
        geom_size: Its size as MuJoCo writes it, (G, 3) [m].
        geom_rbound: Radius about the geom's origin enclosing all its spheres, (G,) [m].
        geom_sph_start: Its spheres are ``geom_sph_start[g]:geom_sph_start[g + 1]``, (G + 1,).
        geom_payload: 1 for a geom of the payload (covered only while held), 0 for
            one of the robot's that moves with the planned joints, (G,).
        sph_local: Centre of each sphere in its geom's frame, (S, 3) [m].
        sph_radius: Radius of each sphere, (S,) [m].
        obs_type: Primitive code of each of the m obstacles, (m,).
        obs_pos: Its position in the world, (m, 3) [m].
        obs_mat: Its orientation in the world, (m, 3, 3).
        obs_size: Its size as MuJoCo writes it, (m, 3) [m].
        sup_normal: Outward unit normal of each support half-space, (H, 3).
        sup_offset: The half-space is ``normal . x <= offset``, (H,) [m].
        pair_a: First geom of each self pair that may touch, (Q,).
        pair_b: Second geom, (Q,).
        fix_type: Primitive code of each of the robot's F geoms that never move, (F,).
        fix_pos: Its position in the world, (F, 3) [m].
        fix_mat: Its orientation in the world, (F, 3, 3).
        fix_size: Its size as MuJoCo writes it, (F, 3) [m].
        fpair_geom: Moving geom of each pair (moving, fixed) that may touch, (P,).
        fpair_fixed: Fixed geom of that pair, (P,).
        tab_joint: Planned joint (index into q) of each tabulated pair: a self pair
            whose relative pose hangs on that one joint, (T,).
        tab_lo: Joint value where its table starts, (T,) [rad or m].
        tab_step: Joint step of its table, (T,) [rad or m].
        tab_start: Its intervals are ``tab_flag[tab_start[t]:tab_start[t + 1]]``, (T + 1,).
        tab_flag: 1 where the pair may touch in an interval, 0 where it cannot (certified
            by MuJoCo's distances at the interval's ends and a Lipschitz bound).
        scalars: ``(exact clearance of the fixed geoms without the payload held,
            the same with it held, 1.0 if fixed geoms touch else 0.0, cap)``, (4,) [m].

    Raises:
        InvalidInputError: Shapes or indices disagree.
    """

    qpos_ref: FloatArray
    qpos_adr: IntArray
    base_qpos: FloatArray
    body_parent: IntArray
    body_pos: FloatArray
    body_mat: FloatArray
    body_jnt_start: IntArray
    body_jnt_count: IntArray
    jnt_type: IntArray
    jnt_axis: FloatArray
    jnt_pos: FloatArray
    jnt_qadr: IntArray
    geom_body: IntArray
    geom_pos: FloatArray
    geom_mat: FloatArray
    geom_type: IntArray
    geom_size: FloatArray
    geom_rbound: FloatArray
    geom_sph_start: IntArray
    geom_payload: IntArray
    sph_local: FloatArray
    sph_radius: FloatArray
    obs_type: IntArray
    obs_pos: FloatArray
    obs_mat: FloatArray
    obs_size: FloatArray
    sup_normal: FloatArray
    sup_offset: FloatArray
    pair_a: IntArray
    pair_b: IntArray
    fix_type: IntArray
    fix_pos: FloatArray
    fix_mat: FloatArray
    fix_size: FloatArray
    fpair_geom: IntArray
    fpair_fixed: IntArray
    scalars: FloatArray
    tab_joint: IntArray
    tab_lo: FloatArray
    tab_step: FloatArray
    tab_start: IntArray
    tab_flag: IntArray

    def __post_init__(self) -> None:
        for f in fields(self):
            value = getattr(self, f.name)
            kind = np.int64 if np.asarray(value).dtype.kind in "iub" else np.float64
            arr = np.ascontiguousarray(value, dtype=kind)
            if kind == np.float64 and not np.isfinite(arr).all():
                raise InvalidInputError(f"cover world: {f.name} must be finite")
            arr.setflags(write=False)
            object.__setattr__(self, f.name, arr)
        b, j, g = len(self.body_parent), len(self.jnt_type), len(self.geom_body)
        s, m, nq = len(self.sph_radius), len(self.obs_type), len(self.qpos_ref)
        shapes = {
            "base_qpos": (nq,),
            "body_pos": (b, 3),
            "body_mat": (b, 3, 3),
            "body_jnt_start": (b,),
            "body_jnt_count": (b,),
            "jnt_axis": (j, 3),
            "jnt_pos": (j, 3),
            "jnt_qadr": (j,),
            "geom_pos": (g, 3),
            "geom_mat": (g, 3, 3),
            "geom_type": (g,),
            "geom_size": (g, 3),
            "geom_rbound": (g,),
            "geom_sph_start": (g + 1,),
            "geom_payload": (g,),
            "sph_local": (s, 3),
            "obs_pos": (m, 3),
            "obs_mat": (m, 3, 3),
            "obs_size": (m, 3),
            "sup_normal": (len(self.sup_offset), 3),
            "pair_b": (len(self.pair_a),),
            "fix_pos": (len(self.fix_type), 3),
            "fix_mat": (len(self.fix_type), 3, 3),
            "fix_size": (len(self.fix_type), 3),
            "fpair_fixed": (len(self.fpair_geom),),
            "scalars": (4,),
            "tab_lo": (len(self.tab_joint),),
            "tab_step": (len(self.tab_joint),),
            "tab_start": (len(self.tab_joint) + 1,),
        }
        for name, shape in shapes.items():
            if getattr(self, name).shape != shape:
                raise InvalidInputError(
                    f"cover world: {name} must have shape {shape}, got {getattr(self, name).shape}"
                )
        ok = (
            (self.body_parent >= 0).all()
            and (self.body_parent[1:] < np.arange(1, b)).all()
            and ((self.jnt_qadr >= 0) & (self.jnt_qadr < nq)).all()
            and ((self.qpos_adr >= 0) & (self.qpos_adr < nq)).all()
            and ((self.geom_body >= 0) & (self.geom_body < b)).all()
            and self.geom_sph_start[0] == 0
            and self.geom_sph_start[-1] == s
            and (np.diff(self.geom_sph_start) >= 1).all()
            and (
                (self.pair_a >= 0) & (self.pair_a < g) & (self.pair_b >= 0) & (self.pair_b < g)
            ).all()
            and (self.body_jnt_start + self.body_jnt_count <= j).all()
            and ((self.fpair_geom >= 0) & (self.fpair_geom < g)).all()
            and ((self.tab_joint >= 0) & (self.tab_joint < len(self.qpos_adr))).all()
            and self.tab_start[0] == 0
            and self.tab_start[-1] == len(self.tab_flag)
            and (np.diff(self.tab_start) >= 1).all()
            and (self.tab_step > 0.0).all()
            and ((self.fpair_fixed >= 0) & (self.fpair_fixed < len(self.fix_type))).all()
        )
        if not ok:
            raise InvalidInputError("cover world: an index is out of range or out of order")

    @property
    def n_joints(self) -> int:
        """The number n of planned joints."""
        return len(self.qpos_adr)

    @property
    def n_spheres(self) -> int:
        """The number of spheres of the cover (payload included)."""
        return len(self.sph_radius)

    @property
    def cap_m(self) -> float:
        """Clearances above this read as it [m]."""
        return float(self.scalars[3])

    def as_tuple(self) -> WorldTuple:
        """The arrays in field order: the argument of the compiled checks."""
        out: WorldTuple = tuple(getattr(self, f.name) for f in fields(self))
        return out
