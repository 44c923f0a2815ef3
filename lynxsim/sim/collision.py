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
  (``mj_geomDistance``) only for the pairs that a lower bound says could be the
  nearest, below the cap (in penetration: the depth of the pairs the bound
  leaves, which for shallow contacts is the deepest).

Playback's per-step verdict (:class:`ContactTracker`), the environments'
``info["collision"]`` and the batch :class:`CollisionChecker` all use
:func:`classify_contacts` and :func:`clearances` (or its batch form
:func:`clearances_of_states`); nothing else decides.
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
from lynxsim.sim.report import CollisionVerdict, ContactPair

__all__ = [
    "CLEARANCE_CAP_M",
    "ClearanceGeometry",
    "ClearancePlan",
    "CollisionCheck",
    "CollisionChecker",
    "CollisionGroups",
    "ContactClasses",
    "ContactTracker",
    "classify_contacts",
    "clearances",
    "clearances_of_states",
    "obstacle_boxes",
]

FloatArray = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.intp]
BoolArray = npt.NDArray[np.bool_]

_BOX, _CAPSULE, _CYLINDER, _SPHERE = (
    int(t)
    for t in (
        mujoco.mjtGeom.mjGEOM_BOX,
        mujoco.mjtGeom.mjGEOM_CAPSULE,
        mujoco.mjtGeom.mjGEOM_CYLINDER,
        mujoco.mjtGeom.mjGEOM_SPHERE,
    )
)
"""Geom types as plain ints (comparing arrays with MuJoCo's enum is slow)."""

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
    a, b = g[:, 0], g[:, 1]  # the two columns apart: a reduction over an axis of 2 is slow
    touching = np.asarray(dist, dtype=float).reshape(-1) <= 0.0
    robot, carried, support = groups.robot, groups.carried, groups.support
    index = groups.obstacle_index
    carried_a, carried_b, index_a, index_b = carried[a], carried[b], index[a], index[b]
    obstacle = touching & (carried_a | carried_b) & ((index_a >= 0) | (index_b >= 0))
    robot_a, robot_b = robot[a], robot[b]
    self_hit = touching & robot_a & robot_b
    on_support = (robot_a | robot_b) & (support[a] | support[b])
    return ContactClasses(
        obstacle=obstacle,
        obstacle_index=np.where(obstacle, np.maximum(index_a, index_b), -1),
        self_hit=self_hit,
        support=touching & on_support & ~obstacle,
        carried_first=carried_a,
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


def _obstacle_sdf(
    kind: int, size: FloatArray, rbound: float, local: tuple[FloatArray, FloatArray, FloatArray]
) -> tuple[FloatArray, tuple[FloatArray, FloatArray, FloatArray]]:
    """Signed distance of points to an obstacle, and the way out, in its frame.

    Boxes, cylinders and spheres exactly; any other type by its bounding sphere
    (a convex set around it, so the bounds built on it stay lower bounds).
    Points come as their three coordinates, each an array of one shape (one
    contiguous array per coordinate keeps the arithmetic vectorised).

    Args:
        kind: The geom type.
        size: Its MuJoCo size, (3,) [m].
        rbound: Its bounding-sphere radius [m].
        local: The points' x, y and z in the obstacle's frame, each (...) [m].

    Returns:
        Signed distance (...) [m] and, where it is positive, the vector from
        the nearest obstacle point to the point, as x, y, z, each (...) [m]
        (zero inside).
    """
    x, y, z = local
    if kind == _BOX:
        over = (np.abs(x) - size[0], np.abs(y) - size[1], np.abs(z) - size[2])
        inside = np.maximum(np.maximum(over[0], over[1]), over[2])
        out = (
            np.copysign(np.maximum(over[0], 0.0), x),
            np.copysign(np.maximum(over[1], 0.0), y),
            np.copysign(np.maximum(over[2], 0.0), z),
        )
    elif kind == _CYLINDER:
        rho = np.hypot(x, y)
        radial, axial = rho - size[0], np.abs(z) - size[1]
        scale = np.maximum(radial, 0.0) / np.where(rho > 0.0, rho, 1.0)
        out = (x * scale, y * scale, np.copysign(np.maximum(axial, 0.0), z))
        inside = np.maximum(radial, axial)
    else:
        radius = size[0] if kind == _SPHERE else rbound
        norm = np.sqrt(x * x + y * y + z * z)
        inside = norm - radius
        scale = np.maximum(inside, 0.0) / np.where(norm > 0.0, norm, 1.0)
        out = (x * scale, y * scale, z * scale)
    dist = np.sqrt(out[0] * out[0] + out[1] * out[1] + out[2] * out[2])
    return np.where(dist > 0.0, dist, inside), out


def _extents(model: mujoco.MjModel, geoms: IntArray) -> tuple[FloatArray, FloatArray]:
    """How far each geom reaches from its centre along a unit direction n, linearly in |n . axis|.

    The extent is at most ``|n . axes| @ e + c`` [m], capped by the bounding
    radius: a box's half sizes; a capsule's radius plus its half length along
    its axis; a cylinder's radius times ``|n_x| + |n_y|`` (at least its
    ``sqrt(1 - n_z^2)``) plus its half height; a sphere's radius; any other
    shape its bounding radius.

    Returns:
        ``e``, shape (k, 3) [m], and per geom ``(c, rbound)``, shape (k, 2) [m].
    """
    kind = np.asarray(model.geom_type)[geoms]
    size = np.asarray(model.geom_size)[geoms]
    rbound = np.asarray(model.geom_rbound)[geoms]
    linear = np.zeros((len(geoms), 3))
    const = rbound.copy()
    box = kind == _BOX
    linear[box], const[box] = size[box], 0.0
    capsule = kind == _CAPSULE
    linear[capsule, 2], const[capsule] = size[capsule, 1], size[capsule, 0]
    cylinder = kind == _CYLINDER
    linear[cylinder] = size[cylinder][:, [0, 0, 1]]
    const[cylinder] = 0.0
    sphere = kind == _SPHERE
    const[sphere] = size[sphere, 0]
    return linear, np.column_stack([const, rbound])


@dataclass(frozen=True)
class ClearanceGeometry:
    """What the clearance bounds need of a scene, fixed for all its states.

    Attributes:
        carried: The carried geoms (robot and payload), (r,).
        extent: Their extents along their axes, (r, 3) [m] (see :func:`_extents`).
        reach: Per carried geom, the constant part of its extent and its
            bounding radius, (r, 2) [m].
        obstacles: The obstacle geoms, (m,).
        kind: Their geom types, (m,).
        size: Their MuJoCo sizes, (m, 3) [m].
        rbound: Their bounding radii, (m,) [m].
        pos: Their centres, (m, 3) [m].
        rot: Their orientations, (m, 3, 3).
    """

    carried: IntArray
    extent: FloatArray
    reach: FloatArray
    obstacles: IntArray
    kind: IntArray
    size: FloatArray
    rbound: FloatArray
    pos: FloatArray
    rot: FloatArray

    @classmethod
    def of(
        cls, model: mujoco.MjModel, data: mujoco.MjData, groups: CollisionGroups
    ) -> ClearanceGeometry:
        """The geometry of a scene; ``data`` posed in any state (``mj_kinematics``).

        Obstacles are fixed to the world: their poses hold for every state.
        """
        carried = np.flatnonzero(groups.carried)
        obstacles = np.asarray(groups.obstacle_geoms, dtype=np.intp)
        extent, reach = _extents(model, carried)
        return cls(
            carried=carried,
            extent=extent,
            reach=reach,
            obstacles=obstacles,
            kind=np.asarray(model.geom_type)[obstacles].astype(np.intp),
            size=np.asarray(model.geom_size)[obstacles].copy(),
            rbound=np.asarray(model.geom_rbound)[obstacles].copy(),
            pos=np.asarray(data.geom_xpos)[obstacles].copy(),
            rot=np.asarray(data.geom_xmat)[obstacles].reshape(-1, 3, 3).copy(),
        )


def _bounds(geometry: ClearanceGeometry, xpos: FloatArray, xmat: FloatArray) -> FloatArray:
    """Lower bounds of the distance of every carried geom to every obstacle [m], (N, r, m).

    A carried geom whose centre c lies outside an obstacle O is at least
    ``d(c, O) - h`` from it, with h the geom's extent towards O (its support
    along the direction out of O: the distance to a convex set is convex, with
    that direction as gradient); a centre inside gives ``d(c, O) - rbound``.
    Positive bounds are rigorous; in penetration they hold for the depth of the
    points of the geom (as MuJoCo's depth does for shallow contacts).

    Args:
        geometry: The scene's clearance geometry.
        xpos: Centres of the r carried geoms in N states, (N, r, 3) [m].
        xmat: Their orientations (rows of MuJoCo's ``geom_xmat``), (N, r, 9).
    """
    extent, reach = geometry.extent, geometry.reach
    # Coordinates first, (3, N, r), and geom_xmat as (row i, column a, N, r):
    # whole-array passes, the 3x3 products as tensordot over the first axis.
    centre = np.moveaxis(np.asarray(xpos), -1, 0)
    mat = np.ascontiguousarray(np.moveaxis(np.asarray(xmat), -1, 0)).reshape(3, 3, *xpos.shape[:2])
    scale = extent.T[:, None, :]  # (3, 1, r): the extent along each geom axis
    out = np.empty((*xpos.shape[:2], len(geometry.obstacles)))
    for j in range(len(geometry.obstacles)):
        rot = geometry.rot[j]
        local = np.tensordot(rot, centre - geometry.pos[j][:, None, None], axes=([0], [0]))
        sdf, away = _obstacle_sdf(
            int(geometry.kind[j]), geometry.size[j], float(geometry.rbound[j]), tuple(local)
        )
        outside = sdf > 0.0
        # the unit direction out of the obstacle, world frame, (3, N, r)
        n = np.tensordot(rot, np.stack(away), axes=([1], [0])) / np.where(outside, sdf, 1.0)
        proj = np.abs((n[:, None] * mat).sum(axis=0))  # |n . axis a|, (3, N, r)
        towards = (proj * scale).sum(axis=0) + reach[:, 0]
        np.minimum(towards, reach[:, 1], out=towards)
        out[..., j] = sdf - np.where(outside, towards, reach[:, 1])
    return out


def clearances(
    model: mujoco.MjModel,
    data: mujoco.MjData,
    groups: CollisionGroups,
    cap: float = CLEARANCE_CAP_M,
) -> FloatArray:
    """Smallest signed distance from the robot and payload to each obstacle [m], (m,).

    The :class:`ClearancePlan` of this one state: each geom's distance from the
    obstacle's own shape at its centre, less its extent towards the obstacle,
    bounds every pair from below; exact distances (``mj_geomDistance``) are
    computed from the smallest bound on until the next bound reaches the best
    distance found, so geoms far from an obstacle cost nothing. Distances of
    ``cap`` or more read as ``cap``. Needs the geom poses of ``data``
    (``mj_kinematics``).
    """
    carried = np.flatnonzero(groups.carried)
    xpos = np.asarray(data.geom_xpos)[carried][None]
    xmat = np.asarray(data.geom_xmat)[carried][None]
    plan = ClearancePlan(model, ClearanceGeometry.of(model, data, groups), xpos, xmat, cap)
    if not plan.near[0]:
        return np.full(len(groups.obstacle_geoms), cap)
    return np.array(plan.row(0, data), dtype=float)


class ClearancePlan:
    """How to get the exact clearances of many states: bounds first, then a few exact distances.

    The bounds of every state come from the carried geoms' poses given, in one
    vectorised pass (:func:`_bounds`); :meth:`row` then computes one posed
    state's row exactly, starting with the pair of smallest bound (most often
    the nearest: one ``mj_geomDistance`` per obstacle). States whose every
    bound is at least ``cap`` read ``cap`` and need not be posed (``near``).

    Args:
        model: The model.
        geometry: Its clearance geometry (:meth:`ClearanceGeometry.of`).
        xpos: Centres of the carried geoms (robot and payload, in geom order)
            in N states, (N, r, 3) [m].
        xmat: Their orientations, MuJoCo's ``geom_xmat`` rows, (N, r, 9).
        cap: Distances of ``cap`` or more read as ``cap`` [m].
    """

    def __init__(
        self,
        model: mujoco.MjModel,
        geometry: ClearanceGeometry,
        xpos: FloatArray,
        xmat: FloatArray,
        cap: float = CLEARANCE_CAP_M,
    ) -> None:
        carried = geometry.carried
        self._model, self._cap = model, cap
        self._geoms, self._targets = carried.tolist(), geometry.obstacles.tolist()
        n = len(xpos)
        if not self._targets or not self._geoms or n == 0:
            self.near: BoolArray = np.zeros(n, dtype=bool)
            return
        bounds = _bounds(geometry, xpos, xmat)  # (N, r, m)
        self._bounds = bounds
        first = bounds.argmin(axis=1)  # (N, m)
        first_low = np.take_along_axis(bounds, first[:, None, :], axis=1)[:, 0, :]
        self.near = first_low.min(axis=1) < cap
        if len(carried) > 1:
            rest = bounds.copy()
            np.put_along_axis(rest, first[:, None, :], np.inf, axis=1)
            second_low = rest.min(axis=1)
        else:
            second_low = np.full_like(first_low, cap)
        # per state, per obstacle: (geom of smallest bound, that bound, the next bound, obstacle)
        self._rows = [
            list(zip(g, b0, b1, self._targets, strict=True))
            for g, b0, b1 in zip(
                carried[first].tolist(), first_low.tolist(), second_low.tolist(), strict=True
            )
        ]

    def row(self, k: int, data: mujoco.MjData) -> list[float]:
        """State k's clearance to each obstacle, (m,) [m].

        ``data`` must be posed in state k (``mj_kinematics``); a state that is
        not ``near`` needs no call (its row is ``cap``).
        """
        m, cap, distance = self._model, self._cap, mujoco.mj_geomDistance
        out = []
        for j, (g, b0, b1, target) in enumerate(self._rows[k]):
            if b0 >= cap:
                out.append(cap)
                continue
            best = distance(m, data, g, target, cap, None)
            if best > b1:  # another geom may be nearer: the others, in the order of their bounds
                bound = self._bounds[k, :, j]
                for i in np.argsort(bound).tolist():
                    if bound[i] >= best:
                        break
                    if self._geoms[i] != g:
                        # a cap of at least 0: given a negative one, a capsule and a box
                        # may read the cap instead of a deeper depth (MuJoCo 4.0)
                        cut = best if best > 0.0 else 0.0
                        best = min(best, distance(m, data, self._geoms[i], target, cut, None))
            out.append(best if best < cap else cap)
        return out


def clearances_of_states(
    model: mujoco.MjModel,
    data: mujoco.MjData,
    groups: CollisionGroups,
    qpos: npt.ArrayLike,
    xpos: npt.ArrayLike,
    xmat: npt.ArrayLike,
    cap: float = CLEARANCE_CAP_M,
) -> FloatArray:
    """:func:`clearances` of many states at once [m], (N, m).

    A :class:`ClearancePlan` bounds every state at once; only a state with a
    pair whose bound is below ``cap`` is posed again (``qpos`` into ``data``,
    ``mj_kinematics``) for its exact distances. Each row equals what
    :func:`clearances` gives in that state.

    Args:
        model: The model.
        data: A data of the model to pose (its state is overwritten).
        groups: The collision groups.
        qpos: The states, (N, nq); each must pose the geoms as ``xpos`` and
            ``xmat`` say (the payload included).
        xpos: Centres of the carried geoms (robot and payload, in geom order) in
            each state, (N, r, 3) [m].
        xmat: Their orientations, MuJoCo's ``geom_xmat`` rows, (N, r, 9).
        cap: Distances of ``cap`` or more read as ``cap`` [m].

    Returns:
        Shape (N, m).
    """
    states = np.asarray(qpos, dtype=float).reshape(-1, model.nq)
    r = int(np.count_nonzero(groups.carried))
    out = np.full((len(states), len(groups.obstacle_geoms)), cap)
    if len(states):
        data.qpos[:] = states[0]
        mujoco.mj_kinematics(model, data)  # the obstacles' poses
    centres = np.asarray(xpos, dtype=float).reshape(len(states), r, 3)
    axes = np.asarray(xmat, dtype=float).reshape(len(states), r, 9)
    plan = ClearancePlan(model, ClearanceGeometry.of(model, data, groups), centres, axes, cap)
    near = np.flatnonzero(plan.near)
    rows = []
    for k in near.tolist():
        data.qpos[:] = states[k]
        mujoco.mj_kinematics(model, data)
        rows.append(plan.row(k, data))
    if rows:
        out[near] = rows
    return out


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

    def update_many(
        self, time_s: npt.ArrayLike, step: npt.ArrayLike, geoms: IntArray, dist: FloatArray
    ) -> None:
        """Record the contacts of many instants at once, in time order.

        The same records as :meth:`update` called instant by instant (first
        times, worst penetrations, the first hit, steps in contact), classified
        in one vectorised pass.

        Args:
            time_s: Simulated time of each contact, (K,) [s], non-decreasing.
            step: The instant (step) each contact belongs to, (K,).
            geoms: Geom pairs of the contacts, (K, 2).
            dist: Their signed distances, (K,) [m].
        """
        g = np.asarray(geoms, dtype=np.intp).reshape(-1, 2)
        if len(g) == 0:
            return
        times = np.asarray(time_s, dtype=float).reshape(-1)
        steps = np.asarray(step).reshape(-1)
        pen = -np.asarray(dist, dtype=float).reshape(-1)
        c = classify_contacts(self._groups, g, -pen)
        pairs = np.where(c.carried_first[:, None], g, g[:, ::-1])
        ordered = np.sort(g, axis=1)
        pairs = np.where(c.self_hit[:, None], ordered, pairs)
        for mask, table in (
            (c.obstacle, self._obstacle),
            (c.self_hit, self._self),
            (c.support & ~c.self_hit, self._support),
        ):
            rows = np.flatnonzero(mask)
            if len(rows) == 0:
                continue
            ngeom = len(self._groups.robot)  # a pair as one integer: unique over 1-D is fast
            codes, first, inverse = np.unique(
                pairs[rows, 0] * ngeom + pairs[rows, 1], return_index=True, return_inverse=True
            )
            keys = np.column_stack(np.divmod(codes, ngeom))
            worst = np.full(len(keys), -np.inf)
            np.maximum.at(worst, inverse.reshape(-1), pen[rows])
            for i in np.argsort(first, kind="stable").tolist():
                key = (int(keys[i, 0]), int(keys[i, 1]))
                stats = table.get(key)
                if stats is None:
                    table[key] = _PairStats(float(times[rows[first[i]]]), float(worst[i]))
                else:
                    stats.max_penetration_m = max(stats.max_penetration_m, float(worst[i]))
        hits = np.flatnonzero(c.obstacle)
        if len(hits) == 0:
            return
        self.obstacle_steps += len(np.unique(steps[hits]))
        index = c.obstacle_index[hits]
        for j, k in zip(*np.unique(index, return_index=True), strict=True):
            self._first_by_obstacle.setdefault(int(j), float(times[hits[k]]))
        if self._first is None:
            k = int(hits[0])
            self._first = (float(times[k]), (int(pairs[k, 0]), int(pairs[k, 1])), int(index[0]))

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
