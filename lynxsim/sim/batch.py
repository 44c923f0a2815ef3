"""Many runs of one model stepped natively on a thread pool, each logged as :func:`rollout` logs it.

:func:`batch_rollout` plays many runs (commands of one model, any lengths) with
:class:`mujoco.batch.Batch`, MuJoCo's own thread pool over simulations (here
one ``MjData`` per run, so that each keeps its warning counters), and returns
for each the :class:`~lynxsim.sim.rollout.PlaybackLog` that
:func:`~lynxsim.sim.rollout.rollout` gives for the same commands, bit for bit;
:func:`~lynxsim.sim.summary.summarize` then gives the same report.

What runs where:

- **Native, in parallel, no Python per step:** the unrecorded hold and every
  recorded step of every run (``mj_step``, controls from one array per run),
  recording the time, the whole state and the recording sensors
  (:mod:`lynxsim.sim.sensors`: tool, forces, carried geoms' poses, contacts)
  after each step.
  ``mujoco.batch`` is used rather than ``mujoco.rollout`` because it keeps
  each run's warning counters (and records any ``MjData`` field, the forces
  of a model without the sensors).
- **Python, after the stepping, one run after the other:** the records cut
  out of the sensors (only states with a self or table contact are posed again
  for their contact lists; in a model without the sensors every state is posed,
  ``mj_kinematics`` + ``mj_collision``), then
  :func:`~lynxsim.sim.rollout.finish_log`, the very code of ``rollout``
  (contacts classified, clearances of all states at once).
- **A run in which MuJoCo warns** (an unstable state that it resets, a full
  contact buffer) is played again by ``rollout`` alone, so that its log, cut
  where it diverged and with its warnings, is ``rollout``'s own.

Runs of different lengths are neither padded nor grouped: all runs step
together, one native call per distinct length, and a run leaves the batch once
its steps are done (no step is simulated that a log does not keep).
"""

from __future__ import annotations

from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass

import mujoco
import numpy as np
import numpy.typing as npt
from mujoco import batch as mjbatch

from lynxsim.arm import tool_pose
from lynxsim.errors import InvalidInputError
from lynxsim.sim.arm.playback import arm_binding, physics_grid
from lynxsim.sim.binding import RobotBinding
from lynxsim.sim.overlap import cpu_count, overlapped, spare_cpu
from lynxsim.sim.records import SensedChunk, SensedRecorder, StepRecords
from lynxsim.sim.rollout import (
    PlaybackLog,
    finish_log,
    mujoco_warnings,
    plan_commands,
    rest_at_start,
    rollout,
)
from lynxsim.sim.sensors import RecordingLayout
from lynxsim.sim.summary import Playback, summarize
from lynxsim.traj import Trajectory

__all__ = ["BatchRun", "batch_rollout", "play_arm_batch"]

FloatArray = npt.NDArray[np.float64]

_TIME = mujoco.mjtState.mjSTATE_TIME
_RECORD = (_TIME, "qpos", "actuator_force")
"""What the native stepping records after each step (models without recording sensors)."""
_SENSED = (_TIME, "qpos", "sensordata")
"""What it records in a model with recording sensors (:mod:`lynxsim.sim.sensors`)."""


@dataclass(frozen=True)
class BatchRun:
    """One run of a batch: what :func:`~lynxsim.sim.rollout.rollout` takes for a run.

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


def _controls(base: FloatArray, adr: npt.NDArray[np.intp], values: FloatArray) -> FloatArray:
    """Whole control vectors, (K, nu): ``base`` (nu,) with columns ``adr`` set from (K, c)."""
    out = np.repeat(base[None], len(values), axis=0)
    out[:, adr] = values
    return out


def batch_rollout(
    model: mujoco.MjModel,
    binding: RobotBinding,
    runs: Sequence[BatchRun],
    *,
    nthread: int | None = None,
    settle_s: float = 0.5,
    presettle_s: float = 0.5,
) -> list[PlaybackLog]:
    """Play many runs of one model natively, in parallel; each log is ``rollout``'s, bit for bit.

    Every run is held at its first command for ``presettle_s`` (not recorded),
    then plays its commands and holds the last for ``settle_s``, exactly as
    :func:`~lynxsim.sim.rollout.rollout` (see the module docstring for what
    runs natively and what in Python). The batch keeps one ``MjData`` per run.

    Args:
        model: The model of every run.
        binding: What to drive and watch.
        runs: The runs.
        nthread: Threads stepping the runs, the caller's included (None: one per CPU).
        settle_s: Hold time after each trajectory [s].
        presettle_s: Hold time before it, unrecorded [s].

    Returns:
        One log per run, in order.

    Raises:
        InvalidInputError: ``nthread`` below 1, or a run's shapes disagree or
            its commands are not finite (before anything is stepped).
        LimitViolationError: A run's command leaves its joint's range (names
            joint and time; before anything is stepped).
    """
    if nthread is not None and nthread < 1:
        raise InvalidInputError(
            f"nthread must be at least 1 (or None for every CPU), got {nthread}"
        )
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
    threads = cpu_count() if nthread is None else nthread
    background = threads > 1 and len(commands) > 1 and spare_cpu()
    stepping = max(1, threads - 1) if background else threads
    data = mujoco.MjData(model)
    sims = mjbatch.Batch(model, len(commands), stepping, persistent=True)
    hold, ctrl = [], []
    for i, c in enumerate(commands):
        rest_at_start(model, data, binding, c.q_cmd[0])
        mujoco.mj_getState(model, data, sims.state[i], mujoco.mjtState.mjSTATE_INTEGRATION)
        base = np.array(data.ctrl)
        hold.append(_controls(base, c.ctrl_adr, c.hold))
        ctrl.append(_controls(base, c.ctrl_adr, c.ctrl))
    layout = RecordingLayout.of(model, binding)
    clock, sensordata = sims.bind("time"), sims.bind("sensordata")
    size = stepping if background else len(commands)
    groups = [np.arange(i, min(i + size, len(commands))) for i in range(0, len(commands), size)]

    def stepped() -> Iterator[list[_Stepped]]:
        probe = mujoco.MjData(model)
        for ids in groups:
            if len(hold[0]):
                sims.rollout(len(hold[0]), np.stack([hold[i] for i in ids]), record=(), ids=ids)
            clock[ids] = 0.0  # the record starts here; warnings of the hold still count
            records = _step_natively(
                sims, [ctrl[i] for i in ids], _RECORD if layout is None else _SENSED, ids
            )
            sims.forward(ids)  # each last state's positions and contacts (sensors)
            final = np.array(sensordata[ids])
            yield [
                _Stepped(
                    int(i), *records[j], final[j], bool(mujoco_warnings(sims.get_data(i, probe)))
                )
                for j, i in enumerate(ids.tolist())
            ]

    logs: list[PlaybackLog | None] = [None] * len(commands)

    def finish(group: list[_Stepped]) -> None:
        for s in group:
            run, c = runs[s.index], commands[s.index]
            if s.warned:
                logs[s.index] = _replay(model, data, binding, run, settle_s, presettle_s)
                continue
            if layout is None:
                record = _posed_records(model, data, binding, s.time, s.qpos, s.recorded)
            else:
                recorder = SensedRecorder(model, binding.groups, layout, len(s.time))
                recorder.add(SensedChunk(s.time, s.qpos, s.recorded, s.final))
                record = recorder.finish()
            logs[s.index] = finish_log(
                model,
                binding,
                c,
                record,
                len(s.time),
                task=run.task,
                trajectory=run.trajectory,
                warnings={},
                diverged_at_s=None,
            )

    overlapped(stepped, finish, background=background)
    return [log for log in logs if log is not None]


@dataclass(frozen=True)
class _Stepped:
    """One run of a batch as the native stepping leaves it (S steps).

    Attributes:
        index: The run's place in the batch.
        time: Time after each step, (S,) [s].
        qpos: State after each step, (S, nq).
        recorded: ``sensordata`` (or, without sensors, actuator forces) after each step.
        final: ``sensordata`` of a forward pass at the last state.
        warned: Whether MuJoCo warned during the run (hold included).
    """

    index: int
    time: FloatArray
    qpos: FloatArray
    recorded: FloatArray
    final: FloatArray
    warned: bool


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


def play_arm_batch(
    model: mujoco.MjModel,
    trajectories: Sequence[Trajectory],
    *,
    task: str,
    settle_s: float = 0.5,
    gripper_cmds: Sequence[Callable[[float], float] | None] | None = None,
    nthread: int | None = None,
) -> list[Playback]:
    """:func:`~lynxsim.sim.arm.playback.play_arm` of many trajectories in one batch.

    Each trajectory is sampled on the physics grid as ``play_arm`` samples it;
    each result equals ``play_arm``'s for the same trajectory and gripper
    schedule, report and log, bit for bit.

    Args:
        model: An arm scene (see :func:`lynxsim.sim.arm.model.load_arm_scene`).
        trajectories: The joint trajectories.
        task: Task name for the reports.
        settle_s: Hold time after each trajectory [s].
        gripper_cmds: Gripper opening [m] over trajectory time [s], one per
            trajectory (None: no gripper command in any run).
        nthread: Threads stepping the runs (None: one per CPU).

    Returns:
        One :class:`~lynxsim.sim.summary.Playback` per trajectory, in order.

    Raises:
        InvalidInputError: ``gripper_cmds`` and ``trajectories`` differ in length.
    """
    grippers = [None] * len(trajectories) if gripper_cmds is None else list(gripper_cmds)
    if len(grippers) != len(trajectories):
        raise InvalidInputError(
            f"{len(grippers)} gripper schedules for {len(trajectories)} trajectories"
        )
    dt = float(model.opt.timestep)
    runs = []
    for trajectory, gripper in zip(trajectories, grippers, strict=True):
        q_cmd = trajectory.sample(physics_grid(trajectory.duration, dt)).q
        runs.append(
            BatchRun(
                q_cmd=q_cmd,
                tool_ref=tool_pose(q_cmd).position,
                task=task,
                trajectory=trajectory.kind.value,
                gripper_cmd=gripper,
            )
        )
    logs = batch_rollout(model, arm_binding(model), runs, nthread=nthread, settle_s=settle_s)
    return [Playback(report=summarize(log), log=log) for log in logs]
