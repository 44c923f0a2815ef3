"""Each obstacle's smallest clearance over a run, with few exact distances: bounds decide.

:class:`ClearanceMinima` takes a run's states chunk by chunk, in step order,
and keeps per obstacle the smallest clearance so far and the first step that
has it: the values :func:`~lynxsim.sim.collision.clearances_of_states` gives
and ``argmin`` picks, bit for bit. The compiled lower bounds
(:class:`~lynxsim.sim.collision.nearest_bounds.NearestBounds`) rule out every
state whose bound is above the smallest clearance found (less a tolerance),
so MuJoCo's exact ``mj_geomDistance`` runs only where the minimum could
change: a few states per chunk and obstacle, not every state and obstacle.
"""

from __future__ import annotations

from collections.abc import Callable

import mujoco
import numpy as np
import numpy.typing as npt

from lynxsim.sim.collision.clearance import CLEARANCE_CAP_M, ClearanceGeometry
from lynxsim.sim.collision.nearest_bounds import NearestBounds

__all__ = ["ClearanceMinima"]

FloatArray = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.intp]

PoseFn = Callable[[int], mujoco.MjData]
"""Poses state k of a chunk (``mj_kinematics``) and returns the data holding it."""


class ClearanceMinima:
    """Per obstacle, the smallest clearance of a run so far and the first step that has it.

    Args:
        model: The model.
        data: Its data, posed in any state (``mj_kinematics``).
        geometry: Its clearance geometry (:meth:`ClearanceGeometry.of`).
        cap: Distances of ``cap`` or more read as ``cap`` [m].
    """

    def __init__(
        self,
        model: mujoco.MjModel,
        data: mujoco.MjData,
        geometry: ClearanceGeometry,
        cap: float = CLEARANCE_CAP_M,
    ) -> None:
        self._model, self._cap = model, cap
        self._bounds = NearestBounds(model, data, geometry, cap)
        self._geoms = geometry.carried.tolist()
        self._targets = geometry.obstacles.tolist()
        m = len(self._targets)
        self.value: FloatArray = np.full(m, cap)
        """Smallest clearance to each obstacle so far, (m,) [m] (``cap`` before any state)."""
        self.step: IntArray = np.zeros(m, dtype=np.intp)
        """The first step that has it, (m,) (0 before any state)."""
        self.exact_calls = 0
        """``mj_geomDistance`` calls made."""

    def add(self, first: int, xpos: FloatArray, xmat: FloatArray, pose: PoseFn) -> None:
        """Take the next K states of the run (steps ``first`` .. ``first + K - 1``).

        Args:
            first: Step of the chunk's first state.
            xpos: Centres of the carried geoms in each state, (K, r, 3) [m].
            xmat: Their orientations, MuJoCo's ``geom_xmat`` rows, (K, r, 9).
            pose: Poses a state of the chunk (its index in the chunk) for the
                exact distances.
        """
        if not self._targets or not self._geoms or len(xpos) == 0:
            return
        xpos = np.ascontiguousarray(xpos, dtype=np.float64)
        xmat = np.ascontiguousarray(xmat, dtype=np.float64)
        # a state needs an exact distance only if its bound is not above the
        # minimum so far (bounds in penetration trusted as ClearancePlan trusts them)
        below = self.value.copy()
        low = self._bounds.nearest(xpos, xmat, below)
        for j in np.flatnonzero((low <= below).any(axis=0)).tolist():
            column = low[:, j]
            candidates = np.flatnonzero(column <= below[j])
            # the smallest bound first: it most often holds the minimum
            order = candidates[np.argsort(column[candidates], kind="stable")]
            best, best_step = float(self.value[j]), int(self.step[j])
            for k in order.tolist():
                b = float(column[k])
                if b > best:
                    break
                if b == best and first + k > best_step:
                    continue  # at best a tie, later than the minimum's step
                value = self._exact(xpos, xmat, k, j, best, pose(k))
                if value < best or (value == best and first + k < best_step):
                    best, best_step = value, first + k
            self.value[j], self.step[j] = best, best_step

    def _exact(
        self, xpos: FloatArray, xmat: FloatArray, k: int, j: int, level: float, data: mujoco.MjData
    ) -> float:
        """State k's clearance to obstacle j where it is at most ``level`` [m]; else more.

        The geoms in the order of their bounds, each whose bound is below both
        ``level`` and the nearest distance found: the same value as
        :class:`~lynxsim.sim.collision.ClearancePlan` gives wherever it is
        below ``level`` (MuJoCo's distance of a pair does not depend on the
        cut-off given, when below it).
        """
        m, cap, distance = self._model, self._cap, mujoco.mj_geomDistance
        bounds = self._bounds.per_geom(xpos, xmat, k, j, level)
        target = self._targets[j]
        best = cap
        for i in np.argsort(bounds, kind="stable").tolist():
            if bounds[i] >= cap or bounds[i] > min(best, level):
                break
            # a cap of at least 0: given a negative one, a capsule and a box may
            # read the cap instead of a deeper depth (MuJoCo 4.0)
            cut = best if best > 0.0 else 0.0
            best = min(best, distance(m, data, self._geoms[i], target, cut, None))
            self.exact_calls += 1
        return best if best < cap else cap
