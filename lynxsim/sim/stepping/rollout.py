"""Stepping: joint commands in, a :class:`~lynxsim.sim.stepping.log.PlaybackLog` out.

The caller samples its trajectory on the physics time grid (one target per
step, :func:`~lynxsim.sim.stepping.commands.physics_grid`) and gives the
commanded tool point of each sample; :func:`rollout` steps MuJoCo and records,
per step, the whole state, the commanded and actual joints, the tool site,
actuator forces, the contacts that count (:mod:`lynxsim.sim.collision`, one row
per touching pair and step) and the clearance to each obstacle, into
preallocated arrays (:mod:`lynxsim.sim.stepping.records`). In a scene compiled
with the recording sensors (:mod:`lynxsim.sim.stepping.sensors`) a run without
a step hook is stepped natively (``mujoco.rollout``, no Python per step) in
chunks, on a helper thread where a second CPU is free, while the caller's
thread makes the records of the chunks already stepped from ``sensordata``
(contacts of the states the gate flags, clearances of all;
:mod:`lynxsim.sim.stepping.native`); otherwise a Python loop records each step
from ``MjData`` and the clearances are computed once the run is over. Every way
gives the same log, bit for bit. The verdicts and figures come from
:func:`lynxsim.sim.summary.summarize`; videos from
:func:`lynxsim.sim.recording.render_log`.
"""

from __future__ import annotations

from collections.abc import Callable

import mujoco
import numpy as np
import numpy.typing as npt

from lynxsim.inputs import instance
from lynxsim.sim.binding import RobotBinding
from lynxsim.sim.stepping.commands import check_data, plan_commands, rest_at_start
from lynxsim.sim.stepping.log import (
    PlaybackLog,
    ProgressFn,
    StepHook,
    finish_log,
    mujoco_warnings,
)
from lynxsim.sim.stepping.native import Snapshot, native_run
from lynxsim.sim.stepping.records import StepRecords
from lynxsim.sim.stepping.sensors import RecordingLayout

__all__ = ["rollout"]

FloatArray = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.intp]

_PROGRESS_EVERY = 0.05
"""A Python-loop run reports its progress about every this fraction of its steps."""


def _fresh_run(
    model: mujoco.MjModel,
    data: mujoco.MjData,
    ctrl_adr: IntArray,
    ctrl: FloatArray,
    record: StepRecords,
    on_step: StepHook | None,
    progress: ProgressFn | None,
    clock: FloatArray,
) -> int:
    """Step with the positions and contacts brought to each new state (for a hook that reads them).

    A step whose state is not finite, or whose time is not ``clock``'s (MuJoCo
    found a bad state and reset the data, its time included), ends the record.

    Returns:
        How many steps were recorded (fewer than ``len(ctrl)`` if the state diverged).
    """
    qpos, qvel = data.qpos, data.qvel
    every = _report_every(len(ctrl), progress)
    for k in range(len(ctrl)):
        data.ctrl[ctrl_adr] = ctrl[k]
        mujoco.mj_step(model, data)
        if data.time != clock[k] or not (np.isfinite(qpos).all() and np.isfinite(qvel).all()):
            return k
        record.state(k, data)
        record.pose(k, model, data)
        if on_step is not None:
            on_step(k, data)
        if progress is not None and k % every == 0:
            progress(k / len(ctrl))
    if progress is not None:
        progress(1.0)
    return len(ctrl)


def _report_every(steps: int, progress: ProgressFn | None) -> int:
    """Steps between progress reports of a Python-loop run (never, without a callback)."""
    return max(1, round(_PROGRESS_EVERY * steps)) if progress is not None else steps + 1


def _lagged_run(
    model: mujoco.MjModel,
    data: mujoco.MjData,
    ctrl_adr: IntArray,
    ctrl: FloatArray,
    record: StepRecords,
    progress: ProgressFn | None,
) -> None:
    """Step, taking each state's positions and contacts from the next step's own forward pass.

    ``mj_step`` computes positions and contacts of the state it starts from, so
    after step ``k + 1`` they describe the state reached by step ``k``: the
    records of step ``k`` are completed then, and those of the last step by one
    ``mj_kinematics`` + ``mj_collision`` after the loop. No position is computed
    twice. A state that is not finite is not looked for here: the next
    ``mj_step`` finds it (and resets, with a warning), which the caller checks.
    """
    step, state, positions = mujoco.mj_step, record.state, record.positions
    every = _report_every(len(ctrl), progress)
    for k in range(len(ctrl)):
        data.ctrl[ctrl_adr] = ctrl[k]
        step(model, data)
        if k:
            positions(k - 1, data)
        state(k, data)
        if progress is not None and k % every == 0:
            progress(k / len(ctrl))
    record.pose(len(ctrl) - 1, model, data)
    if progress is not None:
        progress(1.0)


def rollout(
    model: mujoco.MjModel,
    data: mujoco.MjData,
    binding: RobotBinding,
    q_cmd: FloatArray,
    tool_ref: FloatArray,
    *,
    task: str,
    trajectory: str,
    settle_s: float = 0.5,
    presettle_s: float = 0.5,
    gripper_cmd: Callable[[float], float] | None = None,
    on_step: StepHook | None = None,
    progress: ProgressFn | None = None,
) -> PlaybackLog:
    """Play commanded joints sampled at every physics step and record what happened.

    The robot is put at rest at ``q_cmd[0]`` and held there for ``presettle_s``
    (not recorded: it lets gravity load the servos), then sample ``k`` is the
    target during step ``k``; after the last sample the final command is held
    for ``settle_s``. Every record describes the instant ``data.time`` it is
    stamped with: ``mj_step`` leaves the positions and contacts of the state it
    started from, so those of step ``k`` are read after step ``k + 1`` (no
    position computed twice; with ``on_step``, or if MuJoCo resets a bad state,
    they are computed after each step instead, the same records). A run whose
    state diverges (not finite, or so bad that MuJoCo resets the data inside
    ``mj_step``) is logged up to the step before, with ``diverged_at_s`` set:
    nothing after a reset describes the run. The clearances are computed after
    the run for all states at once
    (:func:`~lynxsim.sim.collision.clearances_of_states`).

    Args:
        model: The model.
        data: Its data (reset here).
        binding: What to drive and watch.
        q_cmd: Commands, (T, n) [rad], one per physics step (``T * dt`` = duration).
        tool_ref: Commanded tool point per sample, (T, 3) [m]; the last is the target.
        task: Task name for the log.
        trajectory: Trajectory type name for the log.
        settle_s: Hold time after the trajectory [s].
        presettle_s: Hold time before it, unrecorded [s].
        gripper_cmd: Gripper opening [m] as a function of time [s], from
            ``-presettle_s`` to the end of the settling.
        on_step: Called after every recorded step (robot monitors), with the
            positions and contacts of the new state in ``data`` (the run then
            steps in a Python loop).
        progress: Called with the fraction of the recorded steps done, now
            and then (each native chunk, or about every 5 % of the steps).

    Returns:
        The :class:`PlaybackLog`.

    Raises:
        InvalidInputError: Shapes disagree, commands (hold times, gripper
            openings) are not finite, or ``data`` is not the model's.
        LimitViolationError: A command leaves its joint's range (names joint and time).
    """
    check_data(model, data)
    instance(task, str, "task")
    instance(trajectory, str, "trajectory")
    commands = plan_commands(
        model,
        binding,
        q_cmd,
        tool_ref,
        settle_s=settle_s,
        presettle_s=presettle_s,
        gripper_cmd=gripper_cmd,
    )
    ctrl_adr, ctrl = commands.ctrl_adr, commands.ctrl
    steps = len(ctrl)
    clock = np.cumsum(np.full(steps, float(model.opt.timestep)))  # data.time: dt added per step
    rest_at_start(model, data, binding, commands.q_cmd[0])
    layout = None if on_step is not None else RecordingLayout.of(model, binding)
    start = Snapshot(model) if on_step is None else None
    record: StepRecords | None = None
    if layout is not None and start is not None:
        record = native_run(model, data, start, commands, layout, binding.groups, progress)
    else:
        for hold in commands.hold:
            data.ctrl[ctrl_adr] = hold
            mujoco.mj_step(model, data)
        data.time = 0.0  # the record starts here; warnings of the hold still count
        if start is not None:
            start.take(model, data)
            record = StepRecords(model, steps, binding.tool_site_id, binding.groups)
            _lagged_run(model, data, ctrl_adr, ctrl, record, progress)
    recorded = steps
    finite = bool(np.isfinite(data.qpos).all() and np.isfinite(data.qvel).all())
    if record is None or not finite or not np.array_equal(record.time, clock):
        # A bad state: MuJoCo resets it (time included) inside mj_step, so the
        # positions a lagged record takes would be the reset's. Play again
        # (deterministic), each state posed on its own, cut where it diverged.
        if start is not None:
            start.restore(model, data)
        record = StepRecords(model, steps, binding.tool_site_id, binding.groups)
        recorded = _fresh_run(model, data, ctrl_adr, ctrl, record, on_step, progress, clock)
    return finish_log(
        model,
        binding,
        commands,
        record,
        recorded,
        task=task,
        trajectory=trajectory,
        warnings=mujoco_warnings(data),
        diverged_at_s=None if recorded == steps else float(clock[recorded]),
    )
