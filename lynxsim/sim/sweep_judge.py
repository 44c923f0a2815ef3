"""Judging obstacle placements on the states of a recorded run, exactly and fast.

For each placement of the swept obstacle (its centre x, y), on the states of a
:class:`~lynxsim.sim.recorded.RecordedRun` (see there why this is exact):

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
compiled with the obstacle there. The judge names no robot: the caller gives
the robot's model of a scene (:data:`SceneModel`); the bounds are in
:mod:`lynxsim.sim.placement_bounds`, the verdicts :class:`lynxsim.verdicts.Verdict`.
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
from lynxsim.sim.collision import CLEARANCE_CAP_M, CollisionGroups, classify_contacts, clearances
from lynxsim.sim.placement_bounds import BLOCK_STATES, cover, distance_bound, prisms_of
from lynxsim.sim.recorded import RecordedRun
from lynxsim.verdicts import Verdict

__all__ = ["CONTACT_SLACK_M", "PlacementJudge", "PlacementResults", "SceneModel"]

FloatArray = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.intp]

SceneModel = Callable[[Scene], tuple[mujoco.MjModel, CollisionGroups]]
"""A robot's model of a scene, compiled, and its collision groups (the arm's:
:func:`lynxsim.sim.arm.recorded.arm_scene_model`)."""


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


class PlacementJudge:
    """Verdicts and clearances of placements of one obstacle on one recorded run.

    Args:
        run: The run, recorded without the obstacle.
        obstacle: The obstacle (shape, size, z; its x, y are what varies).
        scene_model: The robot's model of a scene (the run's robot).

    Raises:
        InvalidInputError: The obstacle's shape is not a cylinder, box or sphere.
    """

    def __init__(self, run: RecordedRun, obstacle: Obstacle, scene_model: SceneModel) -> None:
        if not isinstance(obstacle, Cylinder | Box | Sphere):
            raise InvalidInputError(f"cannot sweep {obstacle!r}")
        self.run = run
        self.obstacle = obstacle
        # The model: the run's table and cube, the obstacle alone, first put off the table.
        away = replace(obstacle, position=(5.0, 5.0, obstacle.position[2]))
        model, groups = scene_model(Scene((away,), run.scene.table, run.scene.cube))
        model.opt.disableflags |= int(mujoco.mjtDisableBit.mjDSBL_MIDPHASE)
        self._model = model
        self._data = mujoco.MjData(model)
        self._groups = groups
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
            self._prism, self._block_ref, self._block_move = prisms_of(
                m, carried, xpos, xmat.reshape(n, g, 3, 3)
            )
        covers = [
            cover(int(m.geom_type[k]), np.asarray(m.geom_size[k]), float(m.geom_rbound[k]))
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

    def _block_bounds(self, x: FloatArray, y: FloatArray) -> FloatArray:
        """Lower bound of each geom's distance over each block of states, (C, B, G) [m]."""
        g = len(self._carried)
        if isinstance(self.obstacle, Cylinder):
            states = np.repeat(self._block_ref, g)
            geoms = np.tile(np.arange(g), self._blocks)
            bound = self._prism.bounds(states, geoms, self.obstacle, x, y)
            bound = bound.reshape(len(x), self._blocks, g) - self._block_move[None]
        else:
            bound = distance_bound(self._block_centre, self.obstacle, x, y) - self._block_radius
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
            one = distance_bound(centres, self.obstacle, px, py)[0] - self._sub_radius[sub]
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
