"""The one collision definition: what is the robot, what counts as a hit, how far from one.

* the **robot** is every colliding geom of the robot's bodies (arm, fingers;
  for the 3-RRR its links); the **payload** (the cube) counts as part of the
  robot against obstacles, since whatever the robot carries must not touch them
  either, but its contacts with the robot (a grip) and the table (resting) are not hits;
* an **obstacle hit** is a contact at zero or negative distance between a robot
  or payload geom and an obstacle geom;
* a **self hit** is such a contact between two robot geoms (MuJoCo has already
  filtered parent–child pairs and excluded bodies);
* a **table hit** is such a contact between a robot geom and the table or floor;
* the **clearance** to an obstacle is the smallest signed distance between it and
  any robot or payload geom [m] (negative: penetration), computed exactly
  (``mj_geomDistance``) only where a bounding-volume bound says it could be
  below the cap.

Playback's per-step verdict (:class:`ContactTracker`), the environments'
``info["collision"]`` and the batch :class:`CollisionChecker` all use
:func:`classify_contacts` and :func:`clearances`; nothing else decides.
"""

from __future__ import annotations

from dataclasses import dataclass

import mujoco
import numpy as np
import numpy.typing as npt

from lynxsim.errors import InvalidInputError, NonFiniteInputError
from lynxsim.sim.report import CollisionVerdict, ContactPair

__all__ = [
    "CLEARANCE_CAP_M",
    "CollisionCheck",
    "CollisionChecker",
    "CollisionGroups",
    "ContactClasses",
    "ContactTracker",
    "classify_contacts",
    "clearances",
    "obstacle_boxes",
]

FloatArray = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.intp]
BoolArray = npt.NDArray[np.bool_]

CLEARANCE_CAP_M = 1.0
"""Clearances are exact below this distance [m]; larger ones read as the cap."""


@dataclass(frozen=True)
class CollisionGroups:
    """Which geoms of a model are the robot, its payload, the obstacles and the support.

    Attributes:
        robot: Mask over geoms: the robot's colliding geoms, (ngeom,).
        payload: Mask over geoms: what the robot carries (the cube), (ngeom,).
        support: Mask over geoms: the table and floor, (ngeom,).
        obstacle_geoms: Geom id of each obstacle, in the scene's order, (m,).
        obstacle_names: Name of each obstacle, (m,).
    """

    robot: BoolArray
    payload: BoolArray
    support: BoolArray
    obstacle_geoms: IntArray
    obstacle_names: tuple[str, ...]

    def __post_init__(self) -> None:
        if len(self.obstacle_geoms) != len(self.obstacle_names):
            raise InvalidInputError("one name per obstacle geom is needed")

    @property
    def carried(self) -> BoolArray:
        """Robot and payload geoms: what must not touch an obstacle, (ngeom,)."""
        out: BoolArray = self.robot | self.payload
        return out

    def obstacle_pairs(self) -> frozenset[tuple[int, int]]:
        """Every ordered geom pair whose contact is an obstacle hit (for fast per-step lookups)."""
        carried = np.flatnonzero(self.carried).tolist()
        return frozenset(
            pair for c in carried for o in self.obstacle_geoms.tolist() for pair in ((c, o), (o, c))
        )

    @property
    def obstacle_index(self) -> IntArray:
        """Per geom, the index of the obstacle it is, or -1, (ngeom,)."""
        index = np.full(len(self.robot), -1, dtype=np.intp)
        index[self.obstacle_geoms] = np.arange(len(self.obstacle_geoms))
        return index


@dataclass(frozen=True)
class ContactClasses:
    """What each of n contacts is (all False for a contact apart, dist > 0).

    Attributes:
        obstacle: Robot or payload against an obstacle, (n,).
        obstacle_index: Which obstacle (-1 where ``obstacle`` is False), (n,).
        self_hit: Robot against robot, (n,).
        support: Robot against table or floor, (n,).
        carried_first: Whether the first geom of the pair is the robot's (or the
            payload's), (n,): pairs are reported robot geom first.
    """

    obstacle: BoolArray
    obstacle_index: IntArray
    self_hit: BoolArray
    support: BoolArray
    carried_first: BoolArray


def classify_contacts(
    groups: CollisionGroups, geoms: npt.ArrayLike, dist: npt.ArrayLike
) -> ContactClasses:
    """Classify contacts by the collision definition of this module.

    Args:
        groups: The geom groups of the model.
        geoms: Geom pairs of the contacts, (n, 2).
        dist: Their signed distances, (n,) [m]; only ``dist <= 0`` touches.

    Returns:
        The :class:`ContactClasses`.
    """
    g = np.asarray(geoms, dtype=np.intp).reshape(-1, 2)
    touching = np.asarray(dist, dtype=float).reshape(-1) <= 0.0
    robot = groups.robot[g]
    carried = groups.carried[g]
    index = groups.obstacle_index[g]
    is_obstacle = index >= 0
    obstacle = touching & carried.any(axis=1) & is_obstacle.any(axis=1)
    self_hit = touching & robot.all(axis=1)
    support = touching & robot.any(axis=1) & groups.support[g].any(axis=1) & ~obstacle
    return ContactClasses(
        obstacle=obstacle,
        obstacle_index=np.where(obstacle, index.max(axis=1), -1),
        self_hit=self_hit,
        support=support,
        carried_first=carried[:, 0],
    )


def obstacle_boxes(
    model: mujoco.MjModel, data: mujoco.MjData, groups: CollisionGroups
) -> tuple[FloatArray, FloatArray]:
    """World-aligned boxes around the obstacle geoms: centres and half sizes, each (m, 3) [m].

    Obstacles are fixed to the world, so the boxes hold for every configuration;
    ``data`` needs its geom poses (``mj_kinematics``).
    """
    obstacles = groups.obstacle_geoms
    aabb = np.asarray(model.geom_aabb)[obstacles]  # (m, 6): centre, half sizes (local)
    rot = np.asarray(data.geom_xmat)[obstacles].reshape(-1, 3, 3)
    centre = np.asarray(data.geom_xpos)[obstacles] + np.einsum("mij,mj->mi", rot, aabb[:, :3])
    half = np.einsum("mij,mj->mi", np.abs(rot), aabb[:, 3:])
    return centre, half


def clearances(
    model: mujoco.MjModel,
    data: mujoco.MjData,
    groups: CollisionGroups,
    cap: float = CLEARANCE_CAP_M,
    fromto: FloatArray | None = None,
    boxes: tuple[FloatArray, FloatArray] | None = None,
) -> FloatArray:
    """Smallest signed distance from the robot and payload to each obstacle [m], (m,).

    World-aligned boxes around the obstacles (:func:`obstacle_boxes`, given or
    computed here) and bounding spheres around the robot's geoms give a lower
    bound for every pair; exact distances (``mj_geomDistance``) are computed in
    the order of that bound until the next bound exceeds the best distance found,
    so geoms far from an obstacle cost nothing. Distances of ``cap`` or more read
    as ``cap``. Needs the geom poses of ``data`` (``mj_kinematics``).
    """
    obstacles = groups.obstacle_geoms
    result = np.full(len(obstacles), cap)
    carried = np.flatnonzero(groups.carried)
    if len(obstacles) == 0 or len(carried) == 0:
        return result
    fromto = np.zeros(6) if fromto is None else fromto
    centre, half = obstacle_boxes(model, data, groups) if boxes is None else boxes
    xpos = np.asarray(data.geom_xpos)[carried]
    outside = np.abs(xpos[:, None, :] - centre[None]) - half[None]  # (r, m, 3)
    bounds = np.sqrt(np.square(np.maximum(outside, 0.0)).sum(axis=-1))
    bounds -= np.asarray(model.geom_rbound)[carried, None]
    order = np.argsort(bounds, axis=0).T.tolist()
    for j, obstacle in enumerate(obstacles.tolist()):
        best = cap
        column = bounds[:, j].tolist()
        for i in order[j]:
            if column[i] >= best:
                break
            d = mujoco.mj_geomDistance(model, data, int(carried[i]), obstacle, best, fromto)
            best = min(best, d)
        result[j] = best
    return result


@dataclass
class _PairStats:
    first_time_s: float
    max_penetration_m: float


class ContactTracker:
    """Accumulates the classified contacts of a run: every pair, its first time, its worst.

    Args:
        geom_names: Name of every geom of the model, (ngeom,).
        groups: The collision groups.
    """

    def __init__(self, geom_names: tuple[str, ...], groups: CollisionGroups) -> None:
        self._names = geom_names
        self._groups = groups
        self._obstacle: dict[tuple[int, int], _PairStats] = {}
        self._self: dict[tuple[int, int], _PairStats] = {}
        self._support: dict[tuple[int, int], _PairStats] = {}
        self._first: tuple[float, tuple[int, int], int] | None = None
        self._first_by_obstacle: dict[int, float] = {}
        self.obstacle_steps = 0

    def update(self, time_s: float, geoms: IntArray, dist: FloatArray) -> frozenset[int]:
        """Record one instant's contacts; returns the robot geoms touching an obstacle.

        Args:
            time_s: Simulated time [s].
            geoms: Geom pairs of the contacts, (n, 2).
            dist: Their signed distances, (n,) [m].
        """
        if len(geoms) == 0:
            return frozenset()
        c = classify_contacts(self._groups, geoms, dist)
        hit: set[int] = set()
        for k in np.flatnonzero(c.obstacle | c.self_hit | c.support).tolist():
            g1, g2 = int(geoms[k, 0]), int(geoms[k, 1])
            if not c.carried_first[k]:
                g1, g2 = g2, g1
            pen = float(-dist[k])
            if c.obstacle[k]:
                table = self._obstacle
                hit.add(g1)
                index = int(c.obstacle_index[k])
                self._first_by_obstacle.setdefault(index, time_s)
                if self._first is None:
                    self._first = (time_s, (g1, g2), index)
            elif c.self_hit[k]:
                table = self._self
                g1, g2 = min(g1, g2), max(g1, g2)
            else:
                table = self._support
            stats = table.get((g1, g2))
            if stats is None:
                table[(g1, g2)] = _PairStats(time_s, pen)
            else:
                stats.max_penetration_m = max(stats.max_penetration_m, pen)
        if hit:
            self.obstacle_steps += 1
        return frozenset(hit)

    def _pairs(self, table: dict[tuple[int, int], _PairStats]) -> tuple[ContactPair, ...]:
        name = self._names
        return tuple(
            ContactPair(name[g1], name[g2], s.first_time_s, s.max_penetration_m)
            for (g1, g2), s in sorted(table.items(), key=lambda kv: kv[1].first_time_s)
        )

    def first_contact_s(self, obstacle: int) -> float | None:
        """Time of the first contact with obstacle ``obstacle`` (its index) [s], or None."""
        return self._first_by_obstacle.get(obstacle)

    def verdict(self) -> CollisionVerdict:
        """The obstacle-collision verdict so far."""
        pairs = self._pairs(self._obstacle)
        first = self._first
        return CollisionVerdict(
            collided=first is not None,
            first_time_s=None if first is None else first[0],
            first_pair=None
            if first is None
            else (self._names[first[1][0]], self._names[first[1][1]]),
            first_obstacle=None if first is None else self._groups.obstacle_names[first[2]],
            max_penetration_m=max((p.max_penetration_m for p in pairs), default=0.0),
            steps_in_contact=self.obstacle_steps,
            pairs=pairs,
        )

    def self_collisions(self) -> tuple[ContactPair, ...]:
        """Robot–robot pairs that touched."""
        return self._pairs(self._self)

    def support_contacts(self) -> tuple[ContactPair, ...]:
        """Robot geoms that touched the table or floor."""
        return self._pairs(self._support)


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
    configuration.

    Args:
        model: The scene.
        groups: Its collision groups.
        qpos_adr: ``qpos`` addresses of the n joints of the vectors to check, (n,).
        base_qpos: The rest of the state (fingers, payload), (nq,); default the
            model's ``qpos0``.
        attach: ``(payload qpos address, site id)``: with ``grasped=True`` the
            payload's free joint is put at that site (the cube held by the gripper).
        cap: Clearance cap [m].
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
        self._adr = np.asarray(qpos_adr, dtype=np.intp).reshape(-1)
        base = np.array(model.qpos0 if base_qpos is None else base_qpos, dtype=float)
        if base.shape != (model.nq,) or not np.isfinite(base).all():
            raise InvalidInputError(f"base_qpos must be finite with shape ({model.nq},)")
        self._base = base
        self._attach = attach
        self._cap = float(cap)
        self._fromto = np.zeros(6)
        self._boxes: tuple[FloatArray, FloatArray] | None = None
        robot = np.flatnonzero(groups.robot).tolist()
        support = np.flatnonzero(groups.support).tolist()
        self._obstacle_pairs = groups.obstacle_pairs()
        self._self_pairs = frozenset((a, b) for a in robot for b in robot)
        self._support_pairs = frozenset(
            pair for r in robot for s in support for pair in ((r, s), (s, r))
        )

    @property
    def n_joints(self) -> int:
        """Number of joints of a checked vector."""
        return len(self._adr)

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
        return self._check(self._states(q, grasped), grasped)

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
        limit = self._cap if cap is None else float(cap)
        if not limit > 0.0:
            raise InvalidInputError(f"cap must be positive, got {cap!r}")
        m, d, g = self.model, self._data, self.groups
        hits = self._obstacle_pairs | self._self_pairs | self._support_pairs
        carried = np.flatnonzero(g.carried)
        obstacles = g.obstacle_geoms
        count = len(states)
        out = np.full(count, limit)
        xpos = np.empty((count, len(carried), 3))
        for k in range(count):  # pass 1: contacts, and where every geom is
            if any(pair in hits for pair in self._touching(states[k], grasped)):
                out[k] = -np.inf
            xpos[k] = d.geom_xpos[carried]
        if len(obstacles) == 0 or len(carried) == 0:
            return out
        if self._boxes is None:
            self._boxes = obstacle_boxes(m, d, g)
        centre, half = self._boxes
        outside = np.abs(xpos[:, :, None, :] - centre[None, None]) - half[None, None]
        bounds = np.sqrt(np.square(np.maximum(outside, 0.0)).sum(axis=-1))  # (N, r, m)
        bounds -= np.asarray(m.geom_rbound)[carried][None, :, None]
        flat = bounds.reshape(count, -1)
        order = np.argsort(flat, axis=1)
        pairs = len(obstacles)
        geoms, targets = carried.tolist(), obstacles.tolist()
        for k in np.flatnonzero((out > -np.inf) & (flat.min(axis=1) < limit)).tolist():
            d.qpos[:] = states[k]  # pass 2: exact distances of the pairs that may be near
            if grasped and self._attach is not None:
                self._hold_payload(*self._attach)
            mujoco.mj_kinematics(m, d)
            best, row = limit, flat[k].tolist()
            for index in order[k].tolist():
                if row[index] >= best:
                    break
                i, j = divmod(index, pairs)
                dist = mujoco.mj_geomDistance(m, d, geoms[i], targets[j], best, self._fromto)
                best = min(best, dist)
            out[k] = best
        return out

    def _states(self, q: npt.ArrayLike, grasped: bool) -> FloatArray:
        """Whole states of joint vectors, (N, nq), the rest from the base state."""
        q = np.asarray(q, dtype=float)
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
        states = np.asarray(qpos, dtype=float)
        if states.ndim != 2 or states.shape[1] != self.model.nq:
            raise InvalidInputError(
                f"qpos must have shape (N, {self.model.nq}), got {states.shape}"
            )
        if not np.isfinite(states).all():
            raise NonFiniteInputError("states must be finite")
        return self._check(states, False)

    def _check(self, states: FloatArray, grasped: bool) -> CollisionCheck:
        m, d, g = self.model, self._data, self.groups
        count = len(states)
        obstacle = np.zeros(count, dtype=bool)
        self_hit = np.zeros(count, dtype=bool)
        support = np.zeros(count, dtype=bool)
        clearance = np.empty((count, len(g.obstacle_geoms)))
        for k in range(count):
            touching = self._touching(states[k], grasped)
            if touching:
                obstacle[k] = any(pair in self._obstacle_pairs for pair in touching)
                self_hit[k] = any(pair in self._self_pairs for pair in touching)
                support[k] = any(pair in self._support_pairs for pair in touching)
            if self._boxes is None:
                self._boxes = obstacle_boxes(m, d, g)
            clearance[k] = clearances(m, d, g, self._cap, self._fromto, self._boxes)
        return CollisionCheck(obstacle, self_hit, support, clearance, g.obstacle_names)

    def _touching(self, state: FloatArray, grasped: bool) -> list[tuple[int, int]]:
        """Pose ``state`` (the payload held if ``grasped``) and list the touching geom pairs."""
        m, d = self.model, self._data
        d.qpos[:] = state
        if grasped and self._attach is not None:
            self._hold_payload(*self._attach)
        mujoco.mj_kinematics(m, d)
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
        """Put the payload's free joint at the site (position and orientation)."""
        m, d = self.model, self._data
        mujoco.mj_kinematics(m, d)
        d.qpos[qpos_adr : qpos_adr + 3] = d.site_xpos[site]
        quat = np.empty(4)
        mujoco.mju_mat2Quat(quat, d.site_xmat[site])
        d.qpos[qpos_adr + 3 : qpos_adr + 7] = quat
