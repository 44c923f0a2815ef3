"""The cover as the planner's world: a :class:`~lynxsim.plan.oracle.ClearanceOracle`.

OMPL's planners (and every Python-side check) ask it in batches; each batch is
one compiled call (:func:`~lynxsim.plan.cover.kernels.batch_clearance`). The
compiled planner (:mod:`lynxsim.plan.cover.search`) reads its world directly.
"""

from __future__ import annotations

import threading

import numpy as np

from lynxsim.errors import InvalidInputError
from lynxsim.inputs import instance
from lynxsim.plan.cover.kernels import batch_clearance, scratch
from lynxsim.plan.cover.search import CoverSearch, search_cover
from lynxsim.plan.cover.world import CoverWorld, FloatArray

__all__ = ["CoverOracle"]


class CoverOracle:
    """Clearances of joint vectors on a robot's sphere cover (never above the exact ones).

    Args:
        world: The cover in its world.

    Attributes:
        world: The cover.
        n_joints: Length of a joint vector.

    """

    def __init__(self, world: CoverWorld) -> None:
        self.world = instance(world, CoverWorld, "world")
        self.n_joints = world.n_joints
        self._tuple = world.as_tuple()
        self._work = scratch(self._tuple)
        self._lock = threading.Lock()

    def clearance(self, q: FloatArray, *, grasped: bool) -> FloatArray:
        """The cover's clearance of each joint vector, (N, n) -> (N,) [m]; ``-inf`` on a hit."""
        arr = np.asarray(q, dtype=float)
        if arr.ndim != 2 or arr.shape[1] != self.n_joints or not np.isfinite(arr).all():
            raise InvalidInputError(
                f"q must be finite joint vectors of shape (N, {self.n_joints}), got {arr.shape}"
            )
        with self._lock:
            return batch_clearance(self._tuple, arr, bool(grasped), self._work)

    def search(
        self,
        start: FloatArray,
        goals: FloatArray,
        lower: FloatArray,
        upper: FloatArray,
        *,
        lipschitz: float,
        margin_m: float,
        grasped: bool,
        seed: int,
        shortcuts: int,
    ) -> CoverSearch:
        """RRT-Connect and shortcutting on the cover in one compiled call (:func:`search_cover`)."""
        with self._lock:
            return search_cover(
                self._tuple,
                start,
                goals,
                lower,
                upper,
                lipschitz=lipschitz,
                margin_m=margin_m,
                grasped=grasped,
                seed=seed,
                shortcuts=shortcuts,
                work=self._work,
            )
