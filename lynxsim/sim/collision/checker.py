"""Batch collision verdicts and clearances of joint vectors, without stepping physics.

:class:`CollisionChecker` poses the robot (kinematics only) and applies the
one collision definition (:func:`~lynxsim.sim.collision.groups.classify_contacts`,
:func:`~lynxsim.sim.collision.clearance.clearances`): the verdict a playback
step gives in the same configuration. The planners and the environments ask it.
"""

from __future__ import annotations

import threading
from dataclasses import dataclass
from typing import Any

import mujoco
import numpy as np
import numpy.typing as npt

from lynxsim.errors import InvalidInputError, NonFiniteInputError
from lynxsim.inputs import finite_array, positive_number, real_array
from lynxsim.sim.collision.clearance import CLEARANCE_CAP_M, clearances_of_states, obstacle_boxes
from lynxsim.sim.collision.groups import CollisionGroups

__all__ = ["CollisionCheck", "CollisionChecker"]

FloatArray = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.intp]
BoolArray = npt.NDArray[np.bool_]


@dataclass(frozen=True)
class CollisionCheck:
    """Verdicts of N configurations.

    Attributes:
        obstacle: Robot or payload touches an obstacle, (N,).
        self_hit: Two robot geoms touch, (N,).
        support: A robot geom touches the table or floor, (N,).
        clearance_m: Signed distance to each obstacle, (N, m) [m]; exact below
            :data:`CLEARANCE_CAP_M`, the cap above it.
        obstacle_names: The m obstacles' names.
    """

    obstacle: BoolArray
    self_hit: BoolArray
    support: BoolArray
    clearance_m: FloatArray
    obstacle_names: tuple[str, ...]

    @property
    def in_collision(self) -> BoolArray:
        """An obstacle or a self hit, (N,) (table contacts are reported, not counted)."""
        out: BoolArray = self.obstacle | self.self_hit
        return out

    @property
    def min_clearance_m(self) -> FloatArray:
        """Smallest clearance over the obstacles, (N,) [m] (the cap without obstacles)."""
        out: FloatArray = self.clearance_m.min(axis=1, initial=CLEARANCE_CAP_M)
        return out


class CollisionChecker:
    """Batch collision verdicts and clearances of joint vectors, without stepping physics.

    Poses the robot (kinematics only) on a private :class:`mujoco.MjData` and
    runs MuJoCo's collision detection, then applies :func:`classify_contacts`
    and :func:`clearances`: the verdict a playback step would give in the same
    configuration. One checker may serve several threads: its calls take turns
    on the private data.

    Args:
        model: The scene.
        groups: Its collision groups.
        qpos_adr: ``qpos`` addresses of the n joints of the vectors to check, (n,).
        base_qpos: The rest of the state (fingers, payload), (nq,); default the
            model's ``qpos0``.
        attach: ``(payload qpos address, site id)``: with ``grasped=True`` the
            payload's free joint is put at that site (the cube held by the gripper).
        cap: Clearance cap [m].

    Raises:
        InvalidInputError: ``base_qpos`` is not finite or has the wrong shape,
            ``attach`` names no free joint, or ``cap`` is not a positive number.
    """

    def __init__(
        self,
        model: mujoco.MjModel,
        groups: CollisionGroups,
        qpos_adr: npt.ArrayLike,
        *,
        base_qpos: npt.ArrayLike | None = None,
        attach: tuple[int, int] | None = None,
        cap: float = CLEARANCE_CAP_M,
    ) -> None:
        self.model = model
        self.groups = groups
        self._data = mujoco.MjData(model)
        self._lock = threading.Lock()
        self._adr = np.asarray(qpos_adr, dtype=np.intp).reshape(-1)
        base = finite_array(model.qpos0 if base_qpos is None else base_qpos, "base_qpos").copy()
        if base.shape != (model.nq,):
            raise InvalidInputError(f"base_qpos must have shape ({model.nq},), got {base.shape}")
        self._base = base
        self._attach = attach
        self._payload = self._payload_frames(attach)
        self._cap = positive_number(cap, "cap", "m")
        self._fromto = np.zeros(6)
        robot = np.flatnonzero(groups.robot).tolist()
        support = np.flatnonzero(groups.support).tolist()
        self._obstacle_pairs = groups.obstacle_pairs()
        self._self_pairs = frozenset((a, b) for a in robot for b in robot)
        self._support_pairs = frozenset(
            pair for r in robot for s in support for pair in ((r, s), (s, r))
        )

    def _payload_frames(
        self, attach: tuple[int, int] | None
    ) -> tuple[int, IntArray, FloatArray, FloatArray]:
        """The payload body, and the poses in its frame of its inertial frame and its geoms.

        Returns:
            The body id (-1 without a payload), its geoms' ids (k,), and the
            positions (1 + k, 3) [m] and orientations (1 + k, 3, 3) of its
            inertial frame (first) and geoms.
        """
        m = self.model
        if attach is None:
            return -1, np.zeros(0, dtype=np.intp), np.zeros((0, 3)), np.zeros((0, 3, 3))
        joint = np.flatnonzero(
            (np.asarray(m.jnt_qposadr) == attach[0])
            & (np.asarray(m.jnt_type) == int(mujoco.mjtJoint.mjJNT_FREE))
        )
        if len(joint) != 1:
            raise InvalidInputError(f"qpos address {attach[0]} is not that of a free joint")
        body = int(m.jnt_bodyid[joint[0]])
        geoms = np.flatnonzero(np.asarray(m.geom_bodyid) == body)
        quats = np.concatenate([m.body_iquat[body][None], m.geom_quat[geoms]])
        local = np.empty((len(quats), 9))
        for i, quat in enumerate(quats):
            mujoco.mju_quat2Mat(local[i], quat)
        offsets = np.concatenate([m.body_ipos[body][None], m.geom_pos[geoms]])
        return body, geoms, offsets, local.reshape(-1, 3, 3)

    def __getstate__(self) -> dict[str, Any]:
        """State for pickling (an environment holding a checker is copied): without the lock."""
        state = self.__dict__.copy()
        del state["_lock"]
        return state

    def __setstate__(self, state: dict[str, Any]) -> None:
        """Restore a pickled checker, with a lock of its own."""
        self.__dict__.update(state)
        self._lock = threading.Lock()

    @property
    def n_joints(self) -> int:
        """Number of joints of a checked vector."""
        return len(self._adr)

    @property
    def qpos_adr(self) -> IntArray:
        """``qpos`` addresses of the checked joints, (n,) (a copy)."""
        return self._adr.copy()

    @property
    def base_qpos(self) -> FloatArray:
        """The state of everything else, (nq,) (a copy)."""
        return self._base.copy()

    @property
    def attach(self) -> tuple[int, int] | None:
        """``(payload qpos address, site id)`` of the held payload, or None."""
        return self._attach

    @property
    def cap_m(self) -> float:
        """The checker's clearance cap [m]."""
        return self._cap

    def check(self, q: npt.ArrayLike, *, grasped: bool = False) -> CollisionCheck:
        """Check joint vectors.

        Args:
            q: Joint vectors, (N, n) or (n,) [rad].
            grasped: Whether the payload is held at the attach site.

        Returns:
            The :class:`CollisionCheck` of each vector.

        Raises:
            InvalidInputError: Wrong shape, or ``grasped`` without an attach point.
            NonFiniteInputError: A value is NaN or infinite.
        """
        states = self._states(q, grasped)
        with self._lock:
            return self._check(states, grasped)

    def min_clearance(
        self, q: npt.ArrayLike, *, grasped: bool = False, cap: float | None = None
    ) -> FloatArray:
        """Smallest clearance to any obstacle of each joint vector; ``-inf`` on a hit.

        What a planner asks: one number per vector, the minimum of
        :meth:`check`'s clearances, exactly, for less work: the bounds of
        :func:`clearances` for all vectors at once, then exact distances
        (``mj_geomDistance``) over every (geom, obstacle) pair in the order of its
        bound until the next bound exceeds the best distance found. An obstacle,
        self or table contact reads as ``-inf``.

        Args:
            q: Joint vectors, (N, n) or (n,) [rad].
            grasped: Whether the payload is held at the attach site.
            cap: Clearances of ``cap`` or more read as ``cap`` [m] (default: the checker's).

        Returns:
            Shape (N,) [m].

        Raises:
            InvalidInputError: Wrong shape, ``grasped`` without an attach point, or
                a cap that is not positive.
            NonFiniteInputError: A value is NaN or infinite.
        """
        states = self._states(q, grasped)
        limit = self._cap if cap is None else positive_number(cap, "cap", "m")
        with self._lock:
            return self._min_clearance(states, grasped, limit)

    def _min_clearance(self, states: FloatArray, grasped: bool, limit: float) -> FloatArray:
        m, d, g = self.model, self._data, self.groups
        hits = self._obstacle_pairs | self._self_pairs | self._support_pairs
        carried = np.flatnonzero(g.carried)
        obstacles = g.obstacle_geoms
        count = len(states)
        out = np.full(count, limit)
        posed = np.empty_like(states)
        xpos = np.empty((count, len(carried), 3))
        for k in range(count):  # pass 1: contacts, and where every geom is
            if any(pair in hits for pair in self._touching(states[k], grasped)):
                out[k] = -np.inf
            posed[k] = d.qpos  # the payload held, if it is
            xpos[k] = d.geom_xpos[carried]
        if len(obstacles) == 0 or len(carried) == 0 or count == 0:
            return out
        # Bounding spheres against the obstacles' boxes: a few array operations
        # for the whole batch (the planner asks small batches, many times).
        centre, half = obstacle_boxes(m, d, g)
        outside = np.abs(xpos[:, :, None, :] - centre) - half
        bounds = np.sqrt(np.square(np.maximum(outside, 0.0)).sum(axis=-1))  # (N, r, m)
        bounds -= np.asarray(m.geom_rbound)[carried][None, :, None]
        flat = bounds.reshape(count, -1)  # (N, r * m)
        order = np.argsort(flat, axis=1)
        low = np.take_along_axis(flat, order, axis=1)
        pairs = len(obstacles)
        geoms, targets = carried.tolist(), obstacles.tolist()
        for k in np.flatnonzero((out > -np.inf) & (low[:, 0] < limit)).tolist():
            d.qpos[:] = posed[k]  # pass 2: exact distances of the pairs that may be near
            mujoco.mj_kinematics(m, d)
            best = limit
            for index, bound in zip(order[k].tolist(), low[k].tolist(), strict=True):
                if bound >= best:
                    break
                i, j = divmod(index, pairs)
                dist = mujoco.mj_geomDistance(m, d, geoms[i], targets[j], best, self._fromto)
                best = min(best, dist)
            out[k] = best
        return out

    def _states(self, q: npt.ArrayLike, grasped: bool) -> FloatArray:
        """Whole states of joint vectors, (N, nq), the rest from the base state."""
        q = real_array(q, "q")
        n = self.n_joints
        if q.ndim not in (1, 2) or q.shape[-1] != n:
            raise InvalidInputError(f"q must have shape (N, {n}) or ({n},), got {q.shape}")
        if not np.isfinite(q).all():
            raise NonFiniteInputError("joint vectors must be finite")
        if grasped and self._attach is None:
            raise InvalidInputError("grasped=True needs a payload attached to a site")
        states = np.repeat(self._base[None], len(q.reshape(-1, n)), axis=0)
        states[:, self._adr] = q.reshape(-1, n)
        return states

    def check_states(self, qpos: npt.ArrayLike) -> CollisionCheck:
        """Check whole states (e.g. a playback log's ``qpos``), (N, nq)."""
        states = real_array(qpos, "qpos")
        if states.ndim != 2 or states.shape[1] != self.model.nq:
            raise InvalidInputError(
                f"qpos must have shape (N, {self.model.nq}), got {states.shape}"
            )
        if not np.isfinite(states).all():
            raise NonFiniteInputError("states must be finite")
        with self._lock:
            return self._check(states, False)

    def _check(self, states: FloatArray, grasped: bool) -> CollisionCheck:
        m, d, g = self.model, self._data, self.groups
        count = len(states)
        carried = np.flatnonzero(g.carried)
        obstacle = np.zeros(count, dtype=bool)
        self_hit = np.zeros(count, dtype=bool)
        support = np.zeros(count, dtype=bool)
        posed = np.empty_like(states)
        xpos = np.empty((count, len(carried), 3))
        xmat = np.empty((count, len(carried), 9))
        for k in range(count):
            touching = self._touching(states[k], grasped)
            if touching:
                obstacle[k] = any(pair in self._obstacle_pairs for pair in touching)
                self_hit[k] = any(pair in self._self_pairs for pair in touching)
                support[k] = any(pair in self._support_pairs for pair in touching)
            posed[k] = d.qpos  # the payload held, if it is
            xpos[k] = d.geom_xpos[carried]
            xmat[k] = d.geom_xmat[carried]
        clearance = clearances_of_states(m, d, g, posed, xpos, xmat, self._cap)
        return CollisionCheck(obstacle, self_hit, support, clearance, g.obstacle_names)

    def _touching(self, state: FloatArray, grasped: bool) -> list[tuple[int, int]]:
        """Pose ``state`` (the payload held if ``grasped``) and list the touching geom pairs."""
        m, d = self.model, self._data
        d.qpos[:] = state
        mujoco.mj_kinematics(m, d)
        if grasped and self._attach is not None:
            self._hold_payload(*self._attach)
        mujoco.mj_collision(m, d)
        ncon = int(d.ncon)
        if not ncon:
            return []
        return [
            (g1, g2)
            for (g1, g2), dist in zip(
                d.contact.geom[:ncon].tolist(), d.contact.dist[:ncon].tolist()
            )
            if dist <= 0.0
        ]

    def _hold_payload(self, qpos_adr: int, site: int) -> None:
        """Put the payload's free joint at the site, its body and geoms with it.

        No second kinematics: ``data`` must hold the kinematics of the rest of
        the state. The payload body's frames (MuJoCo's broadphase bounds a
        body in its inertial frame) and its geoms get the site's pose composed
        with their own offsets, as ``mj_kinematics`` would place them (to rounding).
        """
        d = self._data
        d.qpos[qpos_adr : qpos_adr + 3] = d.site_xpos[site]
        quat = np.empty(4)
        mujoco.mju_mat2Quat(quat, d.site_xmat[site])
        d.qpos[qpos_adr + 3 : qpos_adr + 7] = quat
        origin, rot = d.site_xpos[site], d.site_xmat[site].reshape(3, 3)
        body, geoms, offset, local = self._payload
        pos, mat = origin + offset @ rot.T, (rot @ local).reshape(-1, 9)
        d.xpos[body], d.xmat[body] = origin, rot.reshape(9)
        d.xipos[body], d.ximat[body] = pos[0], mat[0]
        d.geom_xpos[geoms], d.geom_xmat[geoms] = pos[1:], mat[1:]
