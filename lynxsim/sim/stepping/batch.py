"""Many runs of one model stepped natively, on every CPU, each logged as :func:`rollout` logs it.

:func:`batch_rollout` plays many runs (commands of one model, any lengths) and
returns for each the :class:`~lynxsim.sim.stepping.log.PlaybackLog` that
:func:`~lynxsim.sim.stepping.rollout.rollout` gives for the same commands, bit for bit;
:func:`~lynxsim.sim.summary.summarize` then gives the same report.

What runs where:

- **Native, no Python per step:** the unrecorded hold and every recorded step
  of every run, with :class:`mujoco.batch.Batch` (one ``MjData`` per run, so
  that each keeps its warning counters), recording the time, the whole state
  and the recording sensors (:mod:`lynxsim.sim.stepping.sensors`: tool, forces, carried
  geoms' poses, the contact gate) after each step. The runs are split into one
  group per thread, each a batch of its own stepped in time chunks
  (:func:`~lynxsim.sim.stepping.native.chunk_bounds`); the groups' chunks are stepped
  by helper threads and by the caller's thread whenever it has nothing to
  record (:func:`~lynxsim.sim.stepping.overlap.share_stepping`), the GIL released.
- **Python, in the caller's thread, chunk by chunk as they are stepped:** each
  run's records (:class:`~lynxsim.sim.stepping.records.SensedRecorder`: only states the
  gate flags are posed again for their contact lists; the clearances of every
  state; in a model without the sensors every state is posed), then, once a
  run is stepped, :func:`~lynxsim.sim.stepping.log.finish_log`, the very code of
  ``rollout``.
- **A run in which MuJoCo warns** (an unstable state that it resets, a full
  contact buffer) is played again by ``rollout`` alone, so that its log, cut
  where it diverged and with its warnings, is ``rollout``'s own.

Runs of different lengths are neither padded nor grouped by length: a run
leaves its group's batch once its steps are done (no step is simulated that a
log does not keep).
"""

from __future__ import annotations

from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass

import mujoco
import numpy as np
import numpy.typing as npt
from mujoco import batch as mjbatch

from lynxsim.inputs import count
from lynxsim.sim.binding import RobotBinding
from lynxsim.sim.stepping.commands import RunCommands, plan_commands, rest_at_start, whole_controls
from lynxsim.sim.stepping.log import PlaybackLog, ProgressFn, finish_log, mujoco_warnings
from lynxsim.sim.stepping.native import chunk_bounds
from lynxsim.sim.stepping.overlap import cpu_count, share_stepping
from lynxsim.sim.stepping.records import SensedChunk, SensedRecorder, StepRecords
from lynxsim.sim.stepping.rollout import rollout
from lynxsim.sim.stepping.sensors import RecordingLayout

__all__ = ["MAX_THREADS", "BatchRun", "batch_rollout"]

FloatArray = npt.NDArray[np.float64]

MAX_THREADS = 1024
"""Most threads a batch may be asked for (it uses no more than one per run)."""

_TIME = mujoco.mjtState.mjSTATE_TIME
_RECORD = (_TIME, "qpos", "actuator_force")
"""What the native stepping records after each step (models without recording sensors)."""
_SENSED = (_TIME, "qpos", "sensordata")
"""What it records in a model with recording sensors (:mod:`lynxsim.sim.stepping.sensors`)."""


@dataclass(frozen=True)
class BatchRun:
    """One run of a batch: what :func:`~lynxsim.sim.stepping.rollout.rollout` takes for a run.

    Attributes:
        q_cmd: Commands, (T, n) [rad], one per physics step.
        tool_ref: Commanded tool point per sample, (T, 3) [m].
        task: Task name for the log.
        trajectory: Trajectory type name for the log.
        gripper_cmd: Gripper opening [m] as a function of time [s], or None.
    """

    q_cmd: FloatArray
    tool_ref: FloatArray
    task: str
    trajectory: str
    gripper_cmd: Callable[[float], float] | None = None


def batch_rollout(
    model: mujoco.MjModel,
    binding: RobotBinding,
    runs: Sequence[BatchRun],
    *,
    nthread: int | None = None,
    settle_s: float = 0.5,
    presettle_s: float = 0.5,
    progress: ProgressFn | None = None,
) -> list[PlaybackLog]:
    """Play many runs of one model natively, in parallel; each log is ``rollout``'s, bit for bit.

    Every run is held at its first command for ``presettle_s`` (not recorded),
    then plays its commands and holds the last for ``settle_s``, exactly as
    :func:`~lynxsim.sim.stepping.rollout.rollout` (see the module docstring for what
    runs natively and what in Python). The batch keeps one ``MjData`` per run.

    Args:
        model: The model of every run.
        binding: What to drive and watch.
        runs: The runs.
        nthread: Threads to use, the caller's included (None: one per CPU; never
            more than one per run); the caller's thread records, and steps
            when it has nothing to record.
        settle_s: Hold time after each trajectory [s].
        presettle_s: Hold time before it, unrecorded [s].
        progress: Called with the fraction of all runs' recorded steps done,
            after each stepped chunk is recorded.

    Returns:
        One log per run, in order.

    Raises:
        InvalidInputError: ``nthread`` is not an integer from 1 to
            :data:`MAX_THREADS`, or a run's shapes disagree or
            its commands are not finite (before anything is stepped).
        LimitViolationError: A run's command leaves its joint's range (names
            joint and time; before anything is stepped).
    """
    threads = cpu_count() if nthread is None else count(nthread, "nthread", 1, MAX_THREADS)
    runs = list(runs)
    commands = [
        plan_commands(
            model,
            binding,
            run.q_cmd,
            run.tool_ref,
            settle_s=settle_s,
            presettle_s=presettle_s,
            gripper_cmd=run.gripper_cmd,
        )
        for run in runs
    ]
    if not commands:
        return []
    layout = RecordingLayout.of(model, binding)
    data = mujoco.MjData(model)
    lengths = [len(c.ctrl) for c in commands]
    logs: list[PlaybackLog | None] = [None] * len(commands)
    recorders = [
        None if layout is None else SensedRecorder(model, binding.groups, layout, n)
        for n in lengths
    ]
    pieces: list[list[SensedChunk]] = [[] for _ in commands]
    total, done = sum(lengths), 0

    def record(chunks: list[tuple[int, SensedChunk, bool]]) -> None:
        nonlocal done
        for i, chunk, warned in chunks:
            recorder = recorders[i]
            if recorder is not None:
                recorder.add(chunk)
            else:
                pieces[i].append(chunk)
            if chunk.final is not None:
                logs[i] = _log(i, warned, recorder)
            done += len(chunk.time)
        if progress is not None:
            progress(done / total)

    def _log(i: int, warned: bool, recorder: SensedRecorder | None) -> PlaybackLog:
        run, c = runs[i], commands[i]
        if warned:
            return _replay(model, data, binding, run, settle_s, presettle_s)
        if recorder is not None:
            steps = recorder.finish()
        else:
            time, qpos, force = (
                np.concatenate(x)
                for x in zip(*((p.time, p.qpos, p.sensordata) for p in pieces[i]), strict=True)
            )
            steps = _posed_records(model, data, binding, time, qpos, force)
        return finish_log(
            model,
            binding,
            c,
            steps,
            lengths[i],
            task=run.task,
            trajectory=run.trajectory,
            warnings={},
            diverged_at_s=None,
        )

    groups = min(len(commands), threads)  # one per thread (measured better than 2 or 3)
    sources = [
        _stepped(model, binding, commands, list(range(g, len(commands), groups)), layout is None)
        for g in range(groups)
    ]
    share_stepping(sources, record, helpers=groups - 1)
    return [log for log in logs if log is not None]


def _stepped(
    model: mujoco.MjModel,
    binding: RobotBinding,
    commands: list[RunCommands],
    share: list[int],
    bare: bool,
) -> Iterator[list[tuple[int, SensedChunk, bool]]]:
    """Step runs ``share`` of a batch natively, in time chunks, in a batch of their own.

    Yields, per chunk (:func:`~lynxsim.sim.stepping.native.chunk_bounds`), each run
    still stepping: (run, chunk, whether MuJoCo warned in the run, known at its
    last chunk). ``bare``: the model has no recording sensors (the chunk's
    ``sensordata`` then holds actuator forces).
    """
    data = mujoco.MjData(model)
    sims = mjbatch.Batch(model, len(share), 1, persistent=True)
    hold, ctrl = [], []
    for j, i in enumerate(share):
        c = commands[i]
        rest_at_start(model, data, binding, c.q_cmd[0])
        mujoco.mj_getState(model, data, sims.state[j], mujoco.mjtState.mjSTATE_INTEGRATION)
        base = np.array(data.ctrl)
        hold.append(whole_controls(base, c.ctrl_adr, c.hold))
        ctrl.append(whole_controls(base, c.ctrl_adr, c.ctrl))
    clock, sensordata = sims.bind("time"), sims.bind("sensordata")
    if len(hold[0]):
        sims.rollout(len(hold[0]), np.stack(hold), record=())
    clock[:] = 0.0  # the record starts here; warnings of the hold still count
    lengths = [len(u) for u in ctrl]
    what = _RECORD if bare else _SENSED
    for a, b in chunk_bounds(max(lengths)):
        ids = [j for j, n in enumerate(lengths) if n > a]
        records = _step_natively(sims, [ctrl[j][a:b] for j in ids], what, np.array(ids))
        ending = [j for j in ids if lengths[j] <= b]
        if ending:
            sims.forward(ending)  # each last state's positions and contacts (sensors)
        out = []
        for j, (time, qpos, third) in zip(ids, records, strict=True):
            last = lengths[j] <= b
            final = np.array(sensordata[j]) if last else None
            warned = last and bool(mujoco_warnings(sims.get_data(j, data)))
            out.append((share[j], SensedChunk(time, qpos, third, final), warned))
        yield out


def _step_natively(
    sims: mjbatch.Batch,
    ctrl: list[FloatArray],
    record: tuple[mujoco.mjtState, str, str],
    runs: npt.NDArray[np.intp],
) -> list[tuple[FloatArray, FloatArray, FloatArray]]:
    """Step the batch's simulations ``runs`` through their controls, (S_i, nu) each.

    One native call per distinct length.

    Returns:
        Per run: time (S_i,) [s], state (S_i, nq) and the third record item
        (actuator forces or sensordata) after each step.
    """
    model = sims.model
    width = model.nu if record[2] == "actuator_force" else model.nsensordata
    lengths = np.array([len(u) for u in ctrl])
    out = [(np.empty(s), np.empty((s, model.nq)), np.empty((s, width))) for s in lengths]
    done = 0
    for end in np.unique(lengths).tolist():
        ids = np.flatnonzero(lengths >= end)
        control = np.stack([ctrl[i][done:end] for i in ids])
        rec = sims.rollout(end - done, control, record=record, ids=runs[ids])
        for j, i in enumerate(ids.tolist()):
            time, qpos, third = out[i]
            time[done:end] = rec[_TIME][j, :, 0]
            qpos[done:end] = rec["qpos"][j]
            third[done:end] = rec[record[2]][j]
        done = end
    return out


def _posed_records(
    model: mujoco.MjModel,
    data: mujoco.MjData,
    binding: RobotBinding,
    time: FloatArray,
    qpos: FloatArray,
    force: FloatArray,
) -> StepRecords:
    """Records of a run stepped natively in a model without sensors: each state posed."""
    record = StepRecords(model, len(time), binding.tool_site_id, binding.groups)
    record.time[:] = time
    record.qpos[:] = qpos
    record.force[:] = force
    for k, q in enumerate(qpos):
        data.qpos[:] = q
        record.pose(k, model, data)
    return record


def _replay(
    model: mujoco.MjModel,
    data: mujoco.MjData,
    binding: RobotBinding,
    run: BatchRun,
    settle_s: float,
    presettle_s: float,
) -> PlaybackLog:
    """A run in which MuJoCo warned, played again by ``rollout`` alone."""
    return rollout(
        model,
        data,
        binding,
        run.q_cmd,
        run.tool_ref,
        task=run.task,
        trajectory=run.trajectory,
        settle_s=settle_s,
        presettle_s=presettle_s,
        gripper_cmd=run.gripper_cmd,
    )
