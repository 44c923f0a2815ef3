"""A log's clearances: each obstacle's minimum known at once, every step's computed when read.

A run's report needs, per obstacle, the smallest clearance and the first step
that has it; a natively stepped run finds those as it goes with few exact
distances (:class:`~lynxsim.sim.collision.ClearanceMinima`). The clearance of
every step to every obstacle, (S, m), costs an exact ``mj_geomDistance`` per
step and obstacle: :class:`LoggedClearance` computes it the first time it is
read (:func:`~lynxsim.sim.collision.clearances_of_states`, the same values as
a run that computes them all while it steps, bit for bit), from the log's
states.
"""

from __future__ import annotations

import mujoco
import numpy as np
import numpy.typing as npt

from lynxsim.sim.collision import CollisionGroups, clearances_of_states

__all__ = ["LoggedClearance"]

_GEOMETRY = (
    "geom_pos",
    "geom_quat",
    "geom_size",
    "geom_rbound",
    "geom_aabb",
    "body_pos",
    "body_quat",
)
"""The model's fields that place and size geoms: kept with a deferred log, since a
model may be changed in place after its run (obstacle slots, randomization)."""

FloatArray = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.intp]


class LoggedClearance:
    """Clearance of each of S steps to each of m obstacles, and each obstacle's minimum.

    Make one with :meth:`known` (values at hand) or :meth:`deferred` (values
    computed when first read).

    Attributes:
        minimum: Smallest clearance to each obstacle over the steps, (m,) [m]
            (the cap where no step is nearer; undefined for S = 0).
        first_step: The first step that has it, (m,).
    """

    def __init__(
        self,
        minimum: FloatArray,
        first_step: IntArray,
        values: FloatArray | None,
        source: tuple[mujoco.MjModel, CollisionGroups, FloatArray, tuple[FloatArray, ...]] | None,
    ) -> None:
        self.minimum = minimum
        self.first_step = first_step
        self._values = values
        self._source = source

    @classmethod
    def known(cls, values: FloatArray) -> LoggedClearance:
        """Clearances computed already, (S, m) [m]."""
        if len(values):
            first = np.argmin(values, axis=0)
            minimum = values[first, np.arange(values.shape[1])]
        else:
            first = np.zeros(values.shape[1], dtype=np.intp)
            minimum = np.zeros(values.shape[1])
        return cls(minimum, first, values, None)

    @classmethod
    def deferred(
        cls,
        model: mujoco.MjModel,
        groups: CollisionGroups,
        qpos: FloatArray,
        minimum: FloatArray,
        first_step: IntArray,
    ) -> LoggedClearance:
        """Clearances of the states ``qpos`` (S, nq), computed when first read.

        ``minimum`` and ``first_step`` must be those of the values (as
        :class:`~lynxsim.sim.collision.ClearanceMinima` finds them).
        """
        kept = tuple(np.array(getattr(model, name)) for name in _GEOMETRY)
        return cls(minimum, first_step, None, (model, groups, qpos, kept))

    def __eq__(self, other: object) -> bool:
        """Equal minima, first steps and values, bit for bit (the values computed if need be)."""
        if not isinstance(other, LoggedClearance):
            return NotImplemented
        return all(
            a.dtype == b.dtype and a.shape == b.shape and np.array_equal(a, b)
            for a, b in (
                (self.minimum, other.minimum),
                (self.first_step, other.first_step),
                (self.values, other.values),
            )
        )

    __hash__ = None  # type: ignore[assignment]  # mutable: computed when read

    @property
    def values(self) -> FloatArray:
        """Clearance of each step to each obstacle, (S, m) [m]; exact below the cap."""
        if self._values is None:
            if self._source is None:
                raise RuntimeError("a logged clearance has neither values nor states")
            model, groups, qpos, kept = self._source
            now = tuple(np.array(getattr(model, name)) for name in _GEOMETRY)
            for name, value in zip(_GEOMETRY, kept, strict=True):
                getattr(model, name)[:] = value  # the geometry of the run
            try:
                self._values = _clearances(model, groups, qpos)
            finally:
                for name, value in zip(_GEOMETRY, now, strict=True):
                    getattr(model, name)[:] = value
            self._source = None
        return self._values


def _clearances(model: mujoco.MjModel, groups: CollisionGroups, qpos: FloatArray) -> FloatArray:
    """Clearances of states, each posed (``mj_kinematics``) for its carried geoms' poses."""
    data = mujoco.MjData(model)
    carried = np.flatnonzero(groups.carried)
    xpos = np.empty((len(qpos), len(carried), 3))
    xmat = np.empty((len(qpos), len(carried), 9))
    for k in range(len(qpos) if len(groups.obstacle_geoms) else 0):
        data.qpos[:] = qpos[k]
        mujoco.mj_kinematics(model, data)
        xpos[k] = data.geom_xpos[carried]
        xmat[k] = data.geom_xmat[carried]
    return clearances_of_states(model, data, groups, qpos, xpos, xmat)
