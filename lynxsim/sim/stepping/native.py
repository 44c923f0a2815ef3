"""Native stepping of one run (``mujoco.rollout``), in chunks, its records made meanwhile.

:func:`native_run` steps a run's held and recorded controls with no Python per
step, in chunks (:func:`chunk_bounds`), on a helper thread where a second CPU
is free (:func:`~lynxsim.sim.stepping.overlap.share_stepping`), while the
caller's thread makes the records of the chunks already stepped
(:class:`~lynxsim.sim.stepping.records.SensedRecorder`). :class:`Snapshot`
keeps the state a run starts from, to play it again.
"""

from __future__ import annotations

from collections.abc import Iterator

import mujoco
import numpy as np
import numpy.typing as npt
from mujoco import rollout as native

from lynxsim.sim.collision import CollisionGroups
from lynxsim.sim.stepping.commands import RunCommands, whole_controls
from lynxsim.sim.stepping.log import ProgressFn
from lynxsim.sim.stepping.overlap import cpu_count, share_stepping
from lynxsim.sim.stepping.records import SensedChunk, SensedRecorder, StepRecords
from lynxsim.sim.stepping.sensors import RecordingLayout

__all__ = ["Snapshot", "chunk_bounds", "native_run"]

FloatArray = npt.NDArray[np.float64]

_CHUNK_FIRST = 32
_CHUNK_MOST = 128
_CHUNK_LAST = 16
"""Steps of the first native chunk of a run, the most of any, and of the last
(see :func:`chunk_bounds`)."""


class Snapshot:
    """What a run is played again from: a data's integration state and warning counters.

    Taking it costs a copy of the state vector, not a whole ``MjData``.
    """

    _SPEC = mujoco.mjtState.mjSTATE_INTEGRATION

    def __init__(self, model: mujoco.MjModel) -> None:
        self._state = np.empty(mujoco.mj_stateSize(model, self._SPEC))
        self._number = np.zeros(int(mujoco.mjtWarning.mjNWARNING), dtype=np.int32)
        self._lastinfo = np.zeros_like(self._number)

    def take(self, model: mujoco.MjModel, data: mujoco.MjData) -> None:
        """Remember the state of ``data``."""
        mujoco.mj_getState(model, data, self._state, self._SPEC)
        self._number[:] = data.warning.number
        self._lastinfo[:] = data.warning.lastinfo

    def restore(self, model: mujoco.MjModel, data: mujoco.MjData) -> None:
        """Put ``data`` back in the remembered state (its next step is the same)."""
        mujoco.mj_setState(model, data, self._state, self._SPEC)
        data.warning.number[:] = self._number
        data.warning.lastinfo[:] = self._lastinfo


def _doubling(size: int) -> list[int]:
    """``size``, twice that, and so on while below ``_CHUNK_MOST``."""
    out = []
    while size < _CHUNK_MOST:
        out.append(size)
        size *= 2
    return out


def chunk_bounds(steps: int) -> list[tuple[int, int]]:
    """How a run of ``steps`` steps is stepped natively: consecutive (start, end) pairs.

    At most ``_CHUNK_MOST`` steps each, the middle ones of equal length, and
    short at either end (doubling from ``_CHUNK_FIRST``, halving down to
    ``_CHUNK_LAST``): the records of the first chunk wait for its stepping,
    and those of the last are made after all stepping.
    """
    if steps <= 0:
        return []
    up, down = _doubling(_CHUNK_FIRST), _doubling(_CHUNK_LAST)[::-1]
    middle = steps - sum(up) - sum(down)
    if middle < 0:  # too short to ramp
        sizes = [_CHUNK_FIRST] * (steps // _CHUNK_FIRST) + (
            [steps % _CHUNK_FIRST] if steps % _CHUNK_FIRST else []
        )
    else:
        # the middle in equal chunks: a short one there would starve the
        # stepping, which may run only so many chunks ahead of the records
        count = -(-middle // _CHUNK_MOST)
        size, longer = divmod(middle, count) if count else (0, 0)
        sizes = [*up, *([size + 1] * longer), *([size] * (count - longer)), *down]
    ends = np.cumsum(sizes).tolist()
    return list(zip([0, *ends[:-1]], ends, strict=True))


def native_run(
    model: mujoco.MjModel,
    data: mujoco.MjData,
    start: Snapshot,
    commands: RunCommands,
    layout: RecordingLayout,
    groups: CollisionGroups,
    progress: ProgressFn | None,
) -> StepRecords:
    """Hold and step natively (``mujoco.rollout``), recording through the model's sensors.

    The recorded steps are stepped in chunks (:func:`chunk_bounds`), in a
    helper thread where a second CPU is free, while this thread makes the
    records of the chunks already stepped (:class:`SensedRecorder`); the same
    records either way. ``data`` at rest on entry; on return it holds the last
    state (with the warnings of the whole run) and ``start`` the state the
    record starts from. ``progress`` hears of each chunk recorded.
    """
    full = mujoco.mjtState.mjSTATE_FULLPHYSICS
    state = np.empty(mujoco.mj_stateSize(model, full))
    base = np.array(data.ctrl)

    def play(controls: FloatArray) -> tuple[FloatArray, FloatArray]:
        u = whole_controls(base, commands.ctrl_adr, controls)
        mujoco.mj_getState(model, data, state, full)
        states, sensordata = native.rollout(
            model,
            data,
            state,
            u[None],
            control_spec=mujoco.mjtState.mjSTATE_CTRL,
            initial_warmstart=np.array(data.qacc_warmstart),
        )
        return states[0], sensordata[0]

    def chunks() -> Iterator[SensedChunk]:
        if len(commands.hold):
            play(commands.hold)
        data.time = 0.0  # the record starts here; warnings of the hold still count
        start.take(model, data)
        bounds = chunk_bounds(len(commands.ctrl))
        for i, (a, b) in enumerate(bounds):
            states, stepped = play(commands.ctrl[a:b])
            final = None
            if i == len(bounds) - 1:
                mujoco.mj_forward(model, data)  # the last state's positions and contacts
                final = np.array(data.sensordata)
            yield SensedChunk(states[:, 0], states[:, 1 : 1 + model.nq], stepped, final)

    recorder = SensedRecorder(model, groups, layout, len(commands.ctrl))

    def record(chunk: SensedChunk) -> None:
        recorder.add(chunk)
        if progress is not None:
            progress(recorder.done / len(commands.ctrl))

    # four chunks ahead: the stepping is not held up where the records of a
    # stretch that rubs an obstacle cost more than its physics
    share_stepping([chunks()], record, helpers=min(1, cpu_count() - 1), ahead=4)
    return recorder.finish()
