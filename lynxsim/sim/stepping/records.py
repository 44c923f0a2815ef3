"""Per-step records of a run, as the stepping leaves them (before the log is made).

:class:`StepRecords` holds, in preallocated arrays, what each recorded state
was: time, state, forces, tool, the carried geoms' poses and MuJoCo's raw
contact list; a Python loop fills it from ``MjData`` step by step.
:class:`SensedRecorder` fills it from natively stepped chunks
(:class:`SensedChunk`: states and the recording sensors,
:mod:`lynxsim.sim.stepping.sensors`), chunk by chunk in step order, and computes the
clearances' minima of each chunk as it comes, so that this Python work can overlap with
the stepping of the next chunk (:mod:`lynxsim.sim.stepping.overlap`).
"""

from __future__ import annotations

from dataclasses import dataclass

import mujoco
import numpy as np
import numpy.typing as npt

from lynxsim.sim.collision import ClearanceGeometry, CollisionGroups, classify_contacts
from lynxsim.sim.collision.minima import ClearanceMinima
from lynxsim.sim.stepping.sensors import RecordingLayout

__all__ = ["SensedChunk", "SensedRecorder", "StepRecords"]

FloatArray = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.intp]


class StepRecords:
    """Preallocated per-step records of a run; contacts kept raw, classified at the end.

    The carried geoms' poses are kept for clearances computed after the run;
    records whose ``clearance`` is already set (a :class:`SensedRecorder`'s)
    keep none.

    Args:
        model: The model.
        steps: Number of steps S to record.
        tool_site: Id of the tracked site.
        groups: The collision groups (the carried geoms' poses are recorded).
    """

    def __init__(
        self, model: mujoco.MjModel, steps: int, tool_site: int, groups: CollisionGroups
    ) -> None:
        carried = np.flatnonzero(groups.carried)
        lo, hi = (int(carried[0]), int(carried[-1]) + 1) if len(carried) else (0, 0)
        self.carried = carried - lo  # their columns in the geom records
        self.time = np.empty(steps)
        self.qpos = np.empty((steps, model.nq))
        self.force = np.empty((steps, model.nu))
        self.tool = np.empty((steps, 3))
        self.geom_xpos = np.empty((steps, hi - lo, 3))
        self.geom_xmat = np.empty((steps, hi - lo, 9))
        self._geom_slice = slice(lo, hi)
        self.contact_start = np.zeros(steps + 1, dtype=np.intp)
        self._geoms = np.empty((max(16, 8 * steps), 2), dtype=np.intp)
        self._dist = np.empty(len(self._geoms))
        self._count = 0
        self._site = tool_site
        self.minima: ClearanceMinima | None = None
        """Each obstacle's smallest clearance, where a :class:`SensedRecorder` found it
        (the clearances of every state are then computed when the log's are read)."""

    def state(self, k: int, data: mujoco.MjData) -> None:
        """What the step reached: time, whole state and actuator forces (of the step itself)."""
        self.time[k] = data.time
        self.qpos[k] = data.qpos
        self.force[k] = data.actuator_force

    def positions(self, k: int, data: mujoco.MjData) -> None:
        """Positions and contacts of step k's state (``data`` must hold them)."""
        self.tool[k] = data.site_xpos[self._site]
        self.geom_xpos[k] = data.geom_xpos[self._geom_slice]
        self.geom_xmat[k] = data.geom_xmat[self._geom_slice]
        self.add_contacts(k, data)

    def add_contacts(self, k: int, data: mujoco.MjData) -> None:
        """Record the contacts in ``data`` as step k's (steps in order).

        Steps skipped in between have no contact once ``contact_start`` is
        carried forward (``np.maximum.accumulate``); steps after k none
        until they are added.
        """
        n, p = data.ncon, self._count
        self.contact_start[k] = p
        if n:
            if p + n > len(self._dist):
                grow = max(n, len(self._dist))
                self._geoms = np.concatenate([self._geoms, np.empty((grow, 2), dtype=np.intp)])
                self._dist = np.concatenate([self._dist, np.empty(grow)])
            contact = data.contact
            self._geoms[p : p + n] = contact.geom
            self._dist[p : p + n] = contact.dist
            self._count = p + n
        self.contact_start[k + 1] = self._count

    def pose(self, k: int, model: mujoco.MjModel, data: mujoco.MjData) -> None:
        """Compute the positions and contacts of the state in ``data`` and record them as step k's.

        ``mj_kinematics`` + ``mj_collision``: the same positions and contacts as
        the forward pass of a ``mj_step`` that starts from this state.
        """
        mujoco.mj_kinematics(model, data)
        mujoco.mj_collision(model, data)
        self.positions(k, data)

    def contacts(
        self, groups: CollisionGroups, steps: int
    ) -> tuple[IntArray, IntArray, FloatArray]:
        """The contacts that count in the first ``steps`` steps: step, geom pair, distance.

        One row per touching geom pair and step, its deepest contact, pairs as
        (smaller, larger geom id), rows in order of step then pair.
        """
        end = int(self.contact_start[steps])
        geoms, dist = self._geoms[:end], self._dist[:end]
        step = np.repeat(np.arange(steps), np.diff(self.contact_start[: steps + 1]))
        c = classify_contacts(groups, geoms, dist)
        keep = c.obstacle | c.self_hit | c.support
        a, b = geoms[keep, 0], geoms[keep, 1]
        low, high, step, dist = np.minimum(a, b), np.maximum(a, b), step[keep], dist[keep]
        order = np.lexsort((dist, high, low, step))
        step, low, high, dist = step[order], low[order], high[order], dist[order]
        first = np.ones(len(step), dtype=bool)
        first[1:] = (step[1:] != step[:-1]) | (low[1:] != low[:-1]) | (high[1:] != high[:-1])
        return step[first], np.column_stack([low[first], high[first]]), dist[first]


@dataclass(frozen=True)
class SensedChunk:
    """Consecutive steps of a run stepped natively (K steps).

    Attributes:
        time: Time after each step, (K,) [s].
        qpos: State after each step, (K, nq).
        sensordata: ``sensordata`` written by each step, (K, nsensordata).
        final: ``sensordata`` of a forward pass at the last state if this is
            the run's last chunk, (nsensordata,); else None.
    """

    time: FloatArray
    qpos: FloatArray
    sensordata: FloatArray
    final: FloatArray | None = None


class SensedRecorder:
    """Builds a run's :class:`StepRecords` from its natively stepped chunks, in order.

    A state's position-stage sensors are read from the next step's row (a
    step's forward pass sees the state it starts from), so a chunk's steps are
    processed as it arrives but for its last, which waits for the next chunk
    (the run's last chunk comes with ``final``). Processing cuts the records
    out of the sensors (:meth:`RecordingLayout.split`), poses the states the
    contact gate flags again (``mj_kinematics`` + ``mj_collision``) for their
    contact lists and finds each obstacle's smallest clearance
    (:class:`~lynxsim.sim.collision.minima.ClearanceMinima`: exact distances
    only where the compiled bounds say the minimum could change; the
    clearances of every state are computed when the log's are read). Each
    state's records are those a Python loop takes from ``MjData``, bit for bit.

    Args:
        model: The model (with the recording sensors).
        groups: The collision groups.
        layout: Where the recording sensors sit.
        steps: Number of steps S the run records.
    """

    def __init__(
        self, model: mujoco.MjModel, groups: CollisionGroups, layout: RecordingLayout, steps: int
    ) -> None:
        r = len(layout.geom_pos)
        record = StepRecords(model, 0, -1, groups)
        record.time, record.qpos = np.empty(steps), np.empty((steps, model.nq))
        record.force, record.tool = np.empty((steps, model.nu)), np.empty((steps, 3))
        # the minima are found chunk by chunk: the geom poses need not be kept
        record.geom_xpos, record.geom_xmat = np.empty((0, r, 3)), np.empty((0, r, 9))
        record.carried = np.arange(r)
        record.contact_start = np.zeros(steps + 1, dtype=np.intp)
        self.record = record
        self._model, self._groups, self._layout = model, groups, layout
        self._data: mujoco.MjData | None = None
        self._geometry: ClearanceGeometry
        self._pending: SensedChunk | None = None
        self._done = 0

    def add(self, chunk: SensedChunk) -> None:
        """Take the next chunk: process its steps but the last (all, if it is the run's last)."""
        if self._pending is not None:
            p = self._pending
            chunk = SensedChunk(
                np.concatenate([p.time, chunk.time]),
                np.concatenate([p.qpos, chunk.qpos]),
                np.concatenate([p.sensordata, chunk.sensordata]),
                chunk.final,
            )
        if chunk.final is not None:
            self._process(chunk, chunk.final)
            self._pending = None
            return
        last = len(chunk.time) - 1
        if last:
            self._process(
                SensedChunk(chunk.time[:last], chunk.qpos[:last], chunk.sensordata[:last]),
                chunk.sensordata[last],
            )
        self._pending = SensedChunk(chunk.time[last:], chunk.qpos[last:], chunk.sensordata[last:])

    @property
    def done(self) -> int:
        """Steps whose records are made."""
        return self._done

    def finish(self) -> StepRecords:
        """The records, once the last chunk (the one with ``final``) was added.

        Raises:
            RuntimeError: Steps are missing.
        """
        record = self.record
        if self._pending is not None or self._done != len(record.time):
            raise RuntimeError(f"{self._done} of {len(record.time)} steps were recorded")
        np.maximum.accumulate(record.contact_start, out=record.contact_start)
        return record

    def _process(self, chunk: SensedChunk, next_row: FloatArray) -> None:
        model, record = self._model, self.record
        if self._data is None:  # made here: in the consumer thread, while the stepping goes on
            self._data = mujoco.MjData(model)
            mujoco.mj_kinematics(model, self._data)  # the obstacles' poses
            geometry = ClearanceGeometry.of(model, self._data, self._groups)
            record.minima = ClearanceMinima(model, self._data, geometry)
        data, minima = self._data, record.minima
        if minima is None:
            raise RuntimeError("the recorder's clearance minima were not made")
        sensors = self._layout.split(chunk.sensordata, next_row)
        start = self._done
        end = start + len(chunk.time)
        rows = slice(start, end)
        record.time[rows], record.qpos[rows] = chunk.time, chunk.qpos
        record.force[rows], record.tool[rows] = sensors.force, sensors.tool
        qpos, kinematics, collision = data.qpos, mujoco.mj_kinematics, mujoco.mj_collision
        posed = -1  # the chunk's state that data holds
        for k in np.flatnonzero(sensors.gate).tolist():
            qpos[:] = chunk.qpos[k]
            kinematics(model, data)
            collision(model, data)
            record.add_contacts(start + k, data)
            posed = k

        def pose(k: int) -> mujoco.MjData:
            nonlocal posed
            if k != posed:
                qpos[:] = chunk.qpos[k]
                kinematics(model, data)
                posed = k
            return data

        minima.add(start, sensors.geom_xpos, sensors.geom_xmat, pose)
        self._done = end
