"""Judging obstacle placements on the states of a recorded run, exactly and fast.

For each placement of the swept obstacle (its centre x, y), on the states of a
:class:`~lynxsim.sweep.recorded.RecordedRun` (see there why this is exact):

* **verdict and first contact**: MuJoCo's own collision detection
  (``mj_kinematics``, ``mj_collision``) on the state, classified by the one
  collision definition (:func:`lynxsim.sim.collision.classify_contacts`), in
  time order; a contact during the hold before the motion is a
  ``start_overlap`` (the run with the obstacle there differs before its record
  begins), one during the record a ``collision`` at that step's time;
* **clearance** of a placement never touched: the smallest, over the recorded
  states, of the clearance :func:`lynxsim.sim.collision.clearances` computes
  (``mj_geomDistance``), with the time of its first occurrence.

Both ask MuJoCo only about states that could matter. Lower bounds on the
distance from each robot or payload geom to the obstacle come from spheres that
cover the geom (a few per geom, in its own frame), and bound whole blocks of
consecutive states at once; a state is checked for contact only where a bound
reaches zero, and a (state, geom) pair's exact distance is asked only while its
bound is below the best distance found. Bounds only skip work: the verdicts,
times and distances are MuJoCo's, on the same states, as a run of its own
computes them.

The obstacle moves by its geom's position in a private copy of the model
(``geom_pos``, exactly the numbers the scene builder writes), with MuJoCo's
midphase (its per-body bounding-volume trees, compiled for the obstacle's
original place) turned off in that copy: the contacts are those of the model
compiled with the obstacle there.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, replace

import mujoco
import numpy as np
import numpy.typing as npt

from lynxsim.errors import InvalidInputError
from lynxsim.scene import Box, Cylinder, Obstacle, Scene, Sphere
from lynxsim.sim.arm.model import SceneIds, load_arm_scene
from lynxsim.sim.collision import CLEARANCE_CAP_M, classify_contacts, clearances
from lynxsim.sweep.recorded import RecordedRun

__all__ = [
    "BLOCK_STATES",
    "CONTACT_SLACK_M",
    "COVER_SPHERE_M",
    "PlacementJudge",
    "PlacementResults",
    "Verdict",
]

FloatArray = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.intp]


class Verdict:
    """Codes of a placement's verdict."""

    CLEAR = 0
    """Never touched: its clearance is exact."""
    COLLIDED = 1
    """Touched during the recorded run: the first contact time is exact."""
    START_OVERLAP = 2
    """Touched during the hold before the motion (the obstacle overlaps the start)."""
    INVALID = 3
    """No scene: the obstacle would enclose the robot's base or the cube's start."""

    NAMES = ("clear", "collided", "start_overlap", "invalid")


BLOCK_STATES = 16
"""Consecutive states bounded together."""
COVER_SPHERE_M = 0.012
"""Target half size of the pieces a geom is cut into for its covering spheres [m]."""
_VERDICT_BLOCKS = 8
"""Blocks bounded at a time while looking for the first contact."""
CONTACT_SLACK_M = 1e-6
"""States whose distance bound is below this are checked for contact [m] (bounds are
rounded floating-point numbers; a contact has distance <= 0)."""


@dataclass(frozen=True)
class PlacementResults:
    """Verdicts of N placements on one recorded run (the swept obstacle only).

    Attributes:
        verdict: :class:`Verdict` code of each, (N,).
        first_contact_s: Time of the first contact during the record [s], NaN if none, (N,).
        min_clearance_m: Smallest clearance over the record [m] where never
            touched (capped at :data:`~lynxsim.sim.collision.CLEARANCE_CAP_M`), else NaN, (N,).
        min_clearance_time_s: Its first time [s], NaN where not clear, (N,).
        state_checks: Contact checks done (for the benchmarks).
        distance_queries: ``mj_geomDistance`` calls done.
    """

    verdict: npt.NDArray[np.int8]
    first_contact_s: FloatArray
    min_clearance_m: FloatArray
    min_clearance_time_s: FloatArray
    state_checks: int
    distance_queries: int


def _cover(geom_type: int, size: FloatArray, rbound: float) -> tuple[FloatArray, FloatArray]:
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


def _distance_bound(
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
class _Prisms:
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


class PlacementJudge:
    """Verdicts and clearances of placements of one obstacle on one recorded run.

    Args:
        run: The run, recorded without the obstacle.
        obstacle: The obstacle (shape, size, z; its x, y are what varies).

    Raises:
        InvalidInputError: The obstacle's shape is not a cylinder, box or sphere.
    """

    def __init__(self, run: RecordedRun, obstacle: Obstacle) -> None:
        if not isinstance(obstacle, Cylinder | Box | Sphere):
            raise InvalidInputError(f"cannot sweep {obstacle!r}")
        self.run = run
        self.obstacle = obstacle
        # The model: the run's table and cube, the obstacle alone, first put off the table.
        away = replace(obstacle, position=(5.0, 5.0, obstacle.position[2]))
        model = load_arm_scene(Scene((away,), run.scene.table, run.scene.cube))
        model.opt.disableflags |= int(mujoco.mjtDisableBit.mjDSBL_MIDPHASE)
        self._model = model
        self._data = mujoco.MjData(model)
        ids = SceneIds.from_model(model)
        self._groups = ids.collision_groups(model)
        self._geom = int(self._groups.obstacle_geoms[0])
        self._geom_z = float(model.geom_pos[self._geom, 2])
        self._carried = np.flatnonzero(self._groups.carried)
        self._fromto = np.zeros(6)
        self._prepare_states()

    def _prepare_states(self) -> None:
        """Geom poses of every state, and the covering spheres' centres."""
        m, d, carried = self._model, self._data, self._carried
        states = self.run.qpos
        n, g = len(states), len(carried)
        xpos = np.empty((n, g, 3))
        xmat = np.empty((n, g, 9))
        for i in range(n):
            d.qpos[:] = states[i]
            mujoco.mj_kinematics(m, d)
            xpos[i] = d.geom_xpos[carried]
            xmat[i] = d.geom_xmat[carried]
        self._xpos, self._xmat = xpos, xmat
        # A geom that never moves (the arm's base) is judged at the first state and at the
        # record's first state only: its distance is the same at every other.
        self._static = np.all(
            (xpos == xpos[:1]).all(axis=2) & (xmat == xmat[:1]).all(axis=2), axis=0
        )
        self._static_states = np.array([0, self.run.hold_steps])
        blocks = math.ceil(n / BLOCK_STATES)
        elsewhere = np.ones((blocks, g), dtype=bool)
        elsewhere[self._static_states // BLOCK_STATES] = False
        self._static_elsewhere = elsewhere & self._static[None]
        if isinstance(self.obstacle, Cylinder):
            self._prepare_prisms(xpos, xmat.reshape(n, g, 3, 3))
        covers = [
            _cover(int(m.geom_type[k]), np.asarray(m.geom_size[k]), float(m.geom_rbound[k]))
            for k in carried.tolist()
        ]
        local = np.concatenate([c for c, _ in covers])  # (G', 3)
        self._sub_radius = np.concatenate([r for _, r in covers])
        self._sub_owner = np.repeat(np.arange(g), [len(r) for _, r in covers])
        self._sub_start = np.concatenate([[0], np.cumsum([len(r) for _, r in covers])[:-1]])
        rot = xmat.reshape(n, g, 3, 3)[:, self._sub_owner]  # (n, G', 3, 3)
        centres = xpos[:, self._sub_owner] + np.einsum("nkij,kj->nki", rot, local)
        self._sub_centre = np.ascontiguousarray(centres)
        # Blocks of consecutive states: per covering sphere, a sphere around its places.
        blocks = math.ceil(n / BLOCK_STATES)
        pad = blocks * BLOCK_STATES - n
        padded = np.concatenate([self._sub_centre, np.repeat(self._sub_centre[-1:], pad, axis=0)])
        by_block = padded.reshape(blocks, BLOCK_STATES, len(local), 3)
        centre = 0.5 * (by_block.min(axis=1) + by_block.max(axis=1))  # (B, G', 3)
        spread = np.linalg.norm(by_block - centre[:, None], axis=-1).max(axis=1)  # (B, G')
        self._block_centre = np.ascontiguousarray(centre.reshape(-1, 3))
        self._block_radius = (spread + self._sub_radius[None]).reshape(-1)
        self._blocks = blocks

    def _prepare_prisms(self, xpos: FloatArray, rot: FloatArray) -> None:
        """Each geom seen from above, for bounds against a vertical cylinder.

        A geom is a box (a capsule: a segment with a radius; a cylinder: its
        bounding box; anything else: its bounding sphere): its projection on the
        table plane is its centre plus three half axes, with a z extent. For
        blocks of states: the middle state's box, less how far any point of the
        geom moves within the block.
        """
        m, carried = self._model, self._carried
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
        self._prism = _Prisms(
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
        self._block_ref = middle
        self._block_move = np.zeros((blocks, g))
        np.maximum.at(self._block_move, owner, moved)

    def _block_bounds(self, x: FloatArray, y: FloatArray) -> FloatArray:
        """Lower bound of each geom's distance over each block of states, (C, B, G) [m]."""
        g = len(self._carried)
        if isinstance(self.obstacle, Cylinder):
            states = np.repeat(self._block_ref, g)
            geoms = np.tile(np.arange(g), self._blocks)
            bound = self._prism.bounds(states, geoms, self.obstacle, x, y)
            bound = bound.reshape(len(x), self._blocks, g) - self._block_move[None]
        else:
            bound = _distance_bound(self._block_centre, self.obstacle, x, y) - self._block_radius
            bound = np.minimum.reduceat(
                bound.reshape(len(x), self._blocks, -1), self._sub_start, axis=2
            )
        bound[:, self._static_elsewhere] = np.inf
        out: FloatArray = bound
        return out

    def _pair_bounds(
        self, blocks: IntArray, geoms: IntArray, x: float, y: float
    ) -> tuple[IntArray, IntArray, FloatArray]:
        """Lower bounds for each state of some (block, geom) pairs: states, geoms, bounds (P,)."""
        n = len(self.run.qpos)
        states = (blocks[:, None] * BLOCK_STATES + np.arange(BLOCK_STATES)[None]).reshape(-1)
        geoms = np.repeat(geoms, BLOCK_STATES)
        keep = (states < n) & (~self._static[geoms] | np.isin(states, self._static_states))
        states, geoms = states[keep], geoms[keep]
        if len(states) == 0:
            return states, geoms, np.zeros(0)
        px, py = np.array([x]), np.array([y])
        if isinstance(self.obstacle, Cylinder):
            out = self._prism.bounds(states, geoms, self.obstacle, px, py)[0]
        else:
            first = self._sub_start[geoms]
            count = np.diff(np.append(self._sub_start, len(self._sub_radius)))[geoms]
            owner = np.repeat(np.arange(len(states)), count)
            sub = np.concatenate([np.arange(f, f + c) for f, c in zip(first, count)])
            centres = self._sub_centre[states[owner], sub]
            one = _distance_bound(centres, self.obstacle, px, py)[0] - self._sub_radius[sub]
            out = np.full(len(states), np.inf)
            np.minimum.at(out, owner, one)
        return states, geoms, out

    def _touches(self, state: int) -> bool:
        """Whether MuJoCo reports a contact of the robot or payload with the obstacle."""
        m, d = self._model, self._data
        d.qpos[:] = self.run.qpos[state]
        mujoco.mj_kinematics(m, d)
        mujoco.mj_collision(m, d)
        ncon = int(d.ncon)
        if not ncon:
            return False
        geoms = np.array(d.contact.geom[:ncon], dtype=np.intp)
        dist = np.array(d.contact.dist[:ncon])
        return bool(classify_contacts(self._groups, geoms, dist).obstacle.any())

    def judge(
        self,
        x_m: npt.ArrayLike,
        y_m: npt.ArrayLike,
        progress: Callable[[int], None] | None = None,
    ) -> PlacementResults:
        """Judge placements of the obstacle's centre.

        Args:
            x_m: Centre x of each placement, (N,) [m].
            y_m: Centre y of each placement, (N,) [m].
            progress: Called with the number of placements done so far, now and then.

        Returns:
            The :class:`PlacementResults`.
        """
        x = np.asarray(x_m, dtype=float).reshape(-1)
        y = np.asarray(y_m, dtype=float).reshape(-1)
        count = len(x)
        verdict = np.zeros(count, dtype=np.int8)
        first = np.full(count, np.nan)
        clearance = np.full(count, np.nan)
        clearance_time = np.full(count, np.nan)
        self._checks = 0
        self._queries = 0
        chunk = 32
        for start in range(0, count, chunk):
            stop = min(start + chunk, count)
            bounds = self._block_bounds(x[start:stop], y[start:stop])
            for j in range(start, stop):
                code, t, c, tc = self._one(float(x[j]), float(y[j]), bounds[j - start])
                verdict[j], first[j], clearance[j], clearance_time[j] = code, t, c, tc
            if progress is not None:
                progress(stop)
        return PlacementResults(
            verdict, first, clearance, clearance_time, self._checks, self._queries
        )

    def _valid(self, x: float, y: float) -> bool:
        moved = replace(self.obstacle, position=(x, y, self.obstacle.position[2]))
        others = tuple(o for o in self.run.scene.obstacles)
        try:
            Scene((*others, moved), self.run.scene.table, self.run.scene.cube)
        except InvalidInputError:
            return False
        return True

    def _one(self, x: float, y: float, block_bounds: FloatArray) -> tuple[int, float, float, float]:
        """Verdict, first contact [s], clearance [m] and its time [s] of one placement.

        ``block_bounds``: each geom's bound over each block, (B, G) [m].
        """
        if not self._valid(x, y):
            return Verdict.INVALID, math.nan, math.nan, math.nan
        m, d = self._model, self._data
        m.geom_pos[self._geom] = (x, y, self._geom_z)
        hold = self.run.hold_steps
        # Verdict: the first state, in time order, where MuJoCo reports a contact.
        near_blocks, near_geoms = np.nonzero(block_bounds <= CONTACT_SLACK_M)  # time order
        cuts = np.searchsorted(near_blocks, np.unique(near_blocks)[::_VERDICT_BLOCKS])
        for chunk in np.split(np.arange(len(near_blocks)), cuts[1:]):  # whole blocks at a time
            states, _, bounds = self._pair_bounds(near_blocks[chunk], near_geoms[chunk], x, y)
            for state in np.unique(states[bounds <= CONTACT_SLACK_M]).tolist():
                self._checks += 1
                if self._touches(state):
                    if state < hold:
                        return Verdict.START_OVERLAP, math.nan, math.nan, math.nan
                    return (
                        Verdict.COLLIDED,
                        float(self.run.time_s[state - hold]),
                        math.nan,
                        math.nan,
                    )
        # Clearance: exact distances where a bound is at most the best found so far,
        # first for the (block, geom) of the lowest bound, then for all still in question.
        mujoco.mj_kinematics(m, d)  # the obstacle's pose, from the moved geom_pos
        best, best_state = CLEARANCE_CAP_M, -1
        flat = block_bounds.reshape(-1)
        lowest = int(np.argmin(flat))
        for pairs in (np.array([lowest]), None):
            if pairs is None:
                pairs = np.flatnonzero(flat <= best)
                pairs = pairs[pairs != lowest]
            blocks, geoms = np.divmod(pairs, block_bounds.shape[1])
            states, geoms, bounds = self._pair_bounds(blocks, geoms, x, y)
            bounds[states < hold] = np.inf
            best, best_state = self._closest(states, geoms, bounds, best, best_state)
        if best_state < 0:  # nothing within the cap: the cap at the first step, as a run gives
            return Verdict.CLEAR, math.nan, CLEARANCE_CAP_M, float(self.run.time_s[0])
        d.qpos[:] = self.run.qpos[best_state]  # the value a run computes at that state
        mujoco.mj_kinematics(m, d)
        value = float(clearances(m, d, self._groups)[0])
        return Verdict.CLEAR, math.nan, value, float(self.run.time_s[best_state - hold])

    def _closest(
        self,
        states: IntArray,
        geoms: IntArray,
        bounds: FloatArray,
        best: float,
        best_state: int,
    ) -> tuple[float, int]:
        """Exact distances of the (state, geom) pairs whose bound is at most ``best``.

        Returns the smallest distance and its earliest state.
        """
        m, d = self._model, self._data
        candidates = np.flatnonzero(bounds <= best)
        order = candidates[np.argsort(bounds[candidates], kind="stable")]
        carried = self._carried.tolist()
        fromto = self._fromto
        for state, g, bound in zip(
            states[order].tolist(), geoms[order].tolist(), bounds[order].tolist()
        ):
            if bound > best:
                break
            if bound == best and state > best_state >= 0:
                continue
            d.geom_xpos[carried[g]] = self._xpos[state, g]
            d.geom_xmat[carried[g]] = self._xmat[state, g]
            self._queries += 1
            dist = mujoco.mj_geomDistance(m, d, carried[g], self._geom, CLEARANCE_CAP_M, fromto)
            if dist < best or (dist == best and state < best_state):
                best, best_state = dist, state
        return best, best_state
