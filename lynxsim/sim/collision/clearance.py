"""Clearances: lower bounds of every (geom, obstacle) distance, then exact distances where needed.

The clearance to an obstacle is the smallest signed distance between it and
any robot or payload geom [m]. :func:`clearances` (one posed state) and
:func:`clearances_of_states` (many) bound every pair from below in one
vectorised pass (:class:`ClearanceGeometry`, :class:`ClearancePlan`) and ask
MuJoCo's exact ``mj_geomDistance`` only for the pairs that may be the nearest,
below :data:`CLEARANCE_CAP_M`.
"""

from __future__ import annotations

from dataclasses import dataclass

import mujoco
import numpy as np
import numpy.typing as npt

from lynxsim.sim.collision.groups import CollisionGroups

__all__ = [
    "CLEARANCE_CAP_M",
    "ClearanceGeometry",
    "ClearancePlan",
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
