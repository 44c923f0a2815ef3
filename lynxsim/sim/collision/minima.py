"""Each obstacle's smallest clearance over a run, with few exact distances: bounds decide.

:class:`ClearanceMinima` takes a run's states chunk by chunk, in step order,
and keeps per obstacle the smallest clearance so far and the first step that
has it: the values :func:`~lynxsim.sim.collision.clearances_of_states` gives
and ``argmin`` picks, bit for bit. The compiled lower bounds
(:class:`~lynxsim.sim.collision.nearest_bounds.NearestBounds`) rule out every
state whose bound is above the smallest clearance found (less a tolerance),
so MuJoCo's exact ``mj_geomDistance`` runs only where the minimum could
change: a few states per chunk and obstacle, not every state and obstacle.
The search among those states is compiled too (:func:`_lower`), calling
MuJoCo's own ``mj_geomDistance`` (:mod:`.native_distance`) on the carried
geoms' recorded poses, with no Python per state.
"""

from __future__ import annotations

import mujoco
import numpy as np
import numpy.typing as npt
from numba import njit

from lynxsim.sim.collision.clearance import CLEARANCE_CAP_M, ClearanceGeometry
from lynxsim.sim.collision.native_distance import geom_distance, geom_distance_address
from lynxsim.sim.collision.nearest_bounds import NearestBounds, geom_bound

__all__ = ["ClearanceMinima"]

FloatArray = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.intp]


@njit(cache=True, error_model="numpy")
def _lower(  # type: ignore[no-untyped-def]  # numba
    first,
    xpos,
    xmat,
    low,
    below,
    value,
    step,
    geoms,
    targets,
    cap,
    function,
    model,
    data,
    geom_xpos,
    geom_xmat,
    extent,
    reach,
    start,
    centres,
    radii,
    fixed,
    kind,
    size,
    rbound,
    pos,
    rot,
):
    """Lower ``value`` and ``step`` (in place) by the chunk's states; returns the exact calls made.

    Per obstacle j, the states whose bound ``low[k, j]`` is not above
    ``below[j]`` (the minimum before the chunk), the smallest bound first (it
    most often holds the minimum), until a bound is above the minimum found;
    a state whose bound only ties it and comes later is skipped. A state's
    clearance: its geoms in the order of their bounds (stable), each whose
    bound is below both the minimum and the nearest distance found, MuJoCo's
    distance with a cut-off of that nearest distance (at least 0: given a
    negative one, a capsule and a box may read the cut-off instead of a
    deeper depth, MuJoCo 4.0), the geom posed first in ``data`` as recorded.
    The same value as :class:`~lynxsim.sim.collision.ClearancePlan` gives
    wherever it is below the minimum (MuJoCo's distance of a pair does not
    depend on the cut-off given, when below it).
    """
    calls = 0
    bounds = np.empty(xpos.shape[1])
    for j in range(targets.shape[0]):
        column = low[:, j]
        candidates = np.flatnonzero(column <= below[j])
        order = candidates[np.argsort(column[candidates], kind="mergesort")]
        best, best_step = value[j], step[j]
        for k in order:
            b = column[k]
            if b > best:
                break
            if b == best and first + k > best_step:
                continue  # at best a tie, later than the minimum's step
            level = best
            for g in range(xpos.shape[1]):
                bounds[g] = geom_bound(
                    xpos,
                    xmat,
                    k,
                    g,
                    level,
                    extent,
                    reach,
                    start,
                    centres,
                    radii,
                    fixed,
                    kind,
                    size,
                    rbound,
                    pos,
                    rot,
                    j,
                )
            near = cap
            for i in np.argsort(bounds, kind="mergesort"):
                if bounds[i] >= cap or bounds[i] > min(near, level):
                    break
                geom = geoms[i]
                geom_xpos[geom, :] = xpos[k, i, :]
                geom_xmat[geom, :] = xmat[k, i, :]
                cut = near if near > 0.0 else 0.0
                # the intrinsic takes no typing context when called (mypy sees its definition)
                near = min(near, geom_distance(function, model, data, geom, targets[j], cut))  # type: ignore[call-arg]
                calls += 1
            exact = near if near < cap else cap
            if exact < best or (exact == best and first + k < best_step):
                best, best_step = exact, first + k
        value[j], step[j] = best, best_step
    return calls


class ClearanceMinima:
    """Per obstacle, the smallest clearance of a run so far and the first step that has it.

    Args:
        model: The model.
        data: Its data, posed in any state (``mj_kinematics``): the obstacles'
            poses are read from it; the carried geoms' are written into it.
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
        self._model, self._data, self._cap = model, data, cap
        self._bounds = NearestBounds(model, data, geometry, cap)
        self._geoms = np.ascontiguousarray(geometry.carried, dtype=np.int64)
        self._targets = np.ascontiguousarray(geometry.obstacles, dtype=np.int64)
        m = len(self._targets)
        self.value: FloatArray = np.full(m, cap)
        """Smallest clearance to each obstacle so far, (m,) [m] (``cap`` before any state)."""
        self.step: IntArray = np.zeros(m, dtype=np.intp)
        """The first step that has it, (m,) (0 before any state)."""
        self.exact_calls = 0
        """``mj_geomDistance`` calls made."""

    def add(self, first: int, xpos: FloatArray, xmat: FloatArray) -> None:
        """Take the next K states of the run (steps ``first`` .. ``first + K - 1``).

        Args:
            first: Step of the chunk's first state.
            xpos: Centres of the carried geoms in each state, (K, r, 3) [m].
            xmat: Their orientations, MuJoCo's ``geom_xmat`` rows, (K, r, 9).
        """
        if not len(self._targets) or not len(self._geoms) or len(xpos) == 0:
            return
        xpos = np.ascontiguousarray(xpos, dtype=np.float64)
        xmat = np.ascontiguousarray(xmat, dtype=np.float64)
        # a state needs an exact distance only if its bound is not above the
        # minimum so far (bounds in penetration trusted as ClearancePlan trusts them)
        below = self.value.copy()
        low = self._bounds.nearest(xpos, xmat, below)
        data = self._data
        self.exact_calls += _lower(
            first,
            xpos,
            xmat,
            low,
            below,
            self.value,
            self.step,
            self._geoms,
            self._targets,
            self._cap,
            geom_distance_address(),
            self._model._address,
            data._address,
            data.geom_xpos,
            data.geom_xmat,
            *self._bounds.arrays,
        )
