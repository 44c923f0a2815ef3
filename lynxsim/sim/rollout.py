"""Stepping: joint commands in, a :class:`PlaybackLog` out (no verdicts, no video).

The caller samples its trajectory on the physics time grid (one target per
step) and gives the commanded tool point of each sample; :func:`rollout`
steps MuJoCo and records, per step, the whole state, the commanded and actual
joints, the tool site, actuator forces, the contacts that count
(:mod:`lynxsim.sim.collision`, one row per touching pair and step) and the
clearance to each obstacle, into preallocated arrays
(:mod:`lynxsim.sim.records`). In a scene compiled with the recording sensors
(:mod:`lynxsim.sim.sensors`) a run without a step hook is stepped natively
(``mujoco.rollout``, no Python per step) in chunks, on a helper thread where a
second CPU is free, while the caller's thread makes the records of the chunks
already stepped from ``sensordata`` (contacts of the states the gate flags,
clearances of all); otherwise a Python loop records each step from ``MjData``
and the clearances are computed once the run is over. Every way gives the same
log, bit for bit. The verdicts and figures come from
:func:`lynxsim.sim.summary.summarize`; videos from
:func:`lynxsim.sim.recording.render_log`.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from dataclasses import dataclass, field

import mujoco
import numpy as np
import numpy.typing as npt
from mujoco import rollout as native

from lynxsim.bounds import MAX_SEGMENT_S
from lynxsim.errors import (
    InvalidInputError,
    InvalidTypeError,
    LimitViolationError,
    NonFiniteInputError,
    short,
)
from lynxsim.inputs import instance, number_in_range, real_array
from lynxsim.sim.binding import RobotBinding
from lynxsim.sim.collision import CollisionGroups, classify_contacts, clearances_of_states
from lynxsim.sim.overlap import cpu_count, share_stepping
from lynxsim.sim.records import SensedChunk, SensedRecorder, StepRecords
from lynxsim.sim.sensors import RecordingLayout

__all__ = [
    "RANGE_TOL",
    "LogMeta",
    "PlaybackLog",
    "ProgressFn",
    "RunCommands",
    "StepHook",
    "check_data",
    "chunk_bounds",
    "finish_log",
    "mujoco_warnings",
    "plan_commands",
    "rest_at_start",
    "rollout",
    "whole_controls",
]

FloatArray = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.intp]

StepHook = Callable[[int, mujoco.MjData], None]
"""Called after each recorded physics step with (step index, data)."""

ProgressFn = Callable[[float], None]
"""Called with the fraction of some work done, 0..1."""

_PROGRESS_EVERY = 0.05
"""A Python-loop run reports its progress about every this fraction of its steps."""

_CHUNK_FIRST = 32
_CHUNK_MOST = 128
_CHUNK_LAST = 16
"""Steps of the first native chunk of a run, the most of any, and of the last
(see :func:`chunk_bounds`)."""

RANGE_TOL = 1e-6
"""Commands may exceed a joint range by this much [rad] (rounding of the samples)."""


@dataclass(frozen=True)
class LogMeta:
    """What a summary needs to know about the model of a log.

    Attributes:
        task: Task name.
        trajectory: Trajectory type name.
        physics_dt_s: Physics time step [s].
        geom_names: Name of every geom, (ngeom,).
        groups: The collision groups.
        force_limit: Largest |force| of each commanded actuator, (n,) [N·m].
    """

    task: str
    trajectory: str
    physics_dt_s: float
    geom_names: tuple[str, ...]
    groups: CollisionGroups
    force_limit: FloatArray


@dataclass(frozen=True)
class PlaybackLog:
    """Per-step record of a playback (S recorded steps, n commanded joints, m obstacles).

    Attributes:
        meta: Names and limits of the model.
        time_s: Simulated time after each step, (S,) [s].
        qpos: The whole state after each step, (S, nq).
        q_cmd: Commanded joints, (S, n) [rad].
        q: Simulated joints, (S, n) [rad].
        tool_ref: Commanded tool point, (S, 3) [m].
        tool: Simulated tool site, (S, 3) [m].
        force: Actuator forces, (S, n) [N·m].
        clearance_m: Signed distance to each obstacle, (S, m) [m].
        contact_step: Step of each recorded contact, (K,).
        contact_geoms: Its geom pair, (K, 2).
        contact_dist: Its signed distance, (K,) [m] (only contacts that count
            as an obstacle, self or table hit are recorded).
        trajectory_steps: How many of the S steps belong to the trajectory (the rest settle).
        duration_s: Trajectory duration [s].
        settle_s: Hold time after it [s].
        tool_target: The final commanded tool point, (3,) [m].
        warnings: MuJoCo warning counts by name (only those that fired).
        diverged_at_s: End of the step in which the state diverged (not finite, or
            so bad that MuJoCo reset it) [s]; the log ends before it. None if it did not.
        channels: Robot-specific per-step records, each (S,) (see the robot's adapter).
    """

    meta: LogMeta
    time_s: FloatArray
    qpos: FloatArray
    q_cmd: FloatArray
    q: FloatArray
    tool_ref: FloatArray
    tool: FloatArray
    force: FloatArray
    clearance_m: FloatArray
    contact_step: IntArray
    contact_geoms: IntArray
    contact_dist: FloatArray
    trajectory_steps: int
    duration_s: float
    settle_s: float
    tool_target: FloatArray
    warnings: dict[str, int] = field(default_factory=dict)
    diverged_at_s: float | None = None
    channels: dict[str, FloatArray] = field(default_factory=dict)

    @property
    def steps(self) -> int:
        """Number of recorded steps S."""
        return len(self.time_s)

    def obstacle_hits(self) -> npt.NDArray[np.bool_]:
        """Per step, whether the robot or payload touched an obstacle, (S,)."""
        c = classify_contacts(self.meta.groups, self.contact_geoms, self.contact_dist)
        out = np.zeros(self.steps, dtype=bool)
        out[self.contact_step[c.obstacle]] = True
        return out


def mujoco_warnings(data: mujoco.MjData) -> dict[str, int]:
    """MuJoCo's warning counters that fired, by short name."""
    out = {}
    for name, w in mujoco.mjtWarning.__members__.items():
        if int(w) >= int(mujoco.mjtWarning.mjNWARNING):
            continue
        count = int(data.warning[int(w)].number)
        if count:
            out[name.removeprefix("mjWARN_").lower()] = count
    return out


class _Snapshot:
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


def _check_ranges(
    model: mujoco.MjModel, binding: RobotBinding, q_cmd: FloatArray, dt: float
) -> None:
    """Refuse commands outside the actuators' control ranges (= joint ranges).

    Sample ``k`` is the target of the step that ends at ``(k + 1) dt``, the time named.
    """
    lo, hi = np.asarray(model.actuator_ctrlrange)[binding.actuator_ids].T
    excess = np.maximum(lo - q_cmd, q_cmd - hi)  # (T, n), > 0 outside
    k, j = np.unravel_index(int(np.argmax(excess)), excess.shape)
    worst = float(excess[k, j])
    if worst > RANGE_TOL:
        name = model.actuator(int(binding.actuator_ids[j])).name
        raise LimitViolationError(
            f"command leaves the range of joint {j + 1} ({name}) by {np.degrees(worst):.3f} deg "
            f"at t = {(k + 1) * dt:.3f} s; refused before playback",
            joint=int(j) + 1,
            quantity="position",
            time=(k + 1) * dt,
            segment=-1,
            value=float(q_cmd[k, j]),
            limit=float(lo[j] if q_cmd[k, j] < lo[j] else hi[j]),
        )


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


def whole_controls(base: FloatArray, adr: IntArray, values: FloatArray) -> FloatArray:
    """Whole control vectors, (K, nu): ``base`` (nu,) with columns ``adr`` set from (K, c)."""
    out = np.repeat(base[None], len(values), axis=0)
    out[:, adr] = values
    return out


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


def _native_run(
    model: mujoco.MjModel,
    data: mujoco.MjData,
    start: _Snapshot,
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


@dataclass(frozen=True)
class RunCommands:
    """A run's checked commands as the controls of each physics step (H held, S recorded).

    Attributes:
        q_cmd: Commanded joints of the trajectory, (T, n) [rad].
        tool_ref: Commanded tool point per sample, (T, 3) [m].
        ctrl_adr: Actuators the controls set, (c,): the commanded joints', then
            the gripper's if it is commanded.
        hold: Controls of the unrecorded hold, (H, c) (``q_cmd[0]``, gripper
            opening at ``-presettle_s + k dt``).
        ctrl: Controls of the recorded steps, (S, c): ``q_cmd``, then its last
            sample held for the settling.
        settle_steps: How many of the S recorded steps settle.
    """

    q_cmd: FloatArray
    tool_ref: FloatArray
    ctrl_adr: IntArray
    hold: FloatArray
    ctrl: FloatArray
    settle_steps: int


def plan_commands(
    model: mujoco.MjModel,
    binding: RobotBinding,
    q_cmd: FloatArray,
    tool_ref: FloatArray,
    *,
    settle_s: float,
    presettle_s: float,
    gripper_cmd: Callable[[float], float] | None,
) -> RunCommands:
    """Check a run's commands and lay out the controls of every step (see :func:`rollout`).

    Raises:
        InvalidInputError: Shapes disagree; commands, hold times or gripper
            openings are not finite real numbers, or a hold time is negative.
        LimitViolationError: A command or gripper opening leaves its range
            (names joint and time).
    """
    settle_s = number_in_range(settle_s, "settle_s", 0.0, MAX_SEGMENT_S, "s")
    presettle_s = number_in_range(presettle_s, "presettle_s", 0.0, MAX_SEGMENT_S, "s")
    if gripper_cmd is not None and not callable(gripper_cmd):
        raise InvalidTypeError(
            f"gripper_cmd must be a function of time [s] or None, got {short(gripper_cmd)}"
        )
    q_cmd = real_array(q_cmd, "q_cmd")
    tool_ref = real_array(tool_ref, "tool_ref")
    n = len(binding.actuator_ids)
    if q_cmd.ndim != 2 or q_cmd.shape[1] != n or len(q_cmd) == 0:
        raise InvalidInputError(f"q_cmd must have shape (T, {n}), got {q_cmd.shape}")
    if tool_ref.shape != (len(q_cmd), 3):
        raise InvalidInputError(f"tool_ref must have shape ({len(q_cmd)}, 3), got {tool_ref.shape}")
    if not (np.isfinite(q_cmd).all() and np.isfinite(tool_ref).all()):
        raise InvalidInputError("commands must be finite")
    dt = float(model.opt.timestep)
    _check_ranges(model, binding, q_cmd, dt)
    settle_steps = round(settle_s / dt)
    steps = len(q_cmd) + settle_steps
    presettle_steps = round(presettle_s / dt)
    ctrl_adr = binding.actuator_ids
    hold = np.repeat(q_cmd[:1], presettle_steps, axis=0)
    ctrl = np.concatenate([q_cmd, np.repeat(q_cmd[-1:], settle_steps, axis=0)])
    gripper = binding.gripper_actuator_id
    if gripper is not None and gripper_cmd is not None:
        ctrl_adr = np.append(ctrl_adr, gripper)
        times = np.arange(-presettle_steps, steps, dtype=float) * dt
        opening = _gripper_openings(model, gripper, gripper_cmd, times, joint=n + 1)
        hold = np.column_stack([hold, opening[:presettle_steps]])
        ctrl = np.column_stack([ctrl, opening[presettle_steps:]])
    return RunCommands(
        q_cmd=q_cmd,
        tool_ref=tool_ref,
        ctrl_adr=ctrl_adr,
        hold=hold,
        ctrl=ctrl,
        settle_steps=settle_steps,
    )


def _gripper_openings(
    model: mujoco.MjModel,
    actuator: int,
    gripper_cmd: Callable[[float], float],
    times: FloatArray,
    *,
    joint: int,
) -> FloatArray:
    """The gripper's commanded openings at ``times`` [s], (T,) [m], checked before any step.

    Raises:
        InvalidInputError: An opening is not one real number.
        NonFiniteInputError: An opening is NaN or infinite.
        LimitViolationError: An opening leaves the actuator's control range.
    """
    values = real_array([gripper_cmd(t) for t in times.tolist()], "gripper_cmd's openings")
    if values.shape != times.shape:
        raise InvalidInputError(
            f"gripper_cmd must return one number per time, got shape {values.shape[1:]}"
        )
    bad = np.flatnonzero(~np.isfinite(values))
    if len(bad):
        k = int(bad[0])
        raise NonFiniteInputError(
            f"gripper_cmd must be finite, got {values[k]!r} at t = {times[k]:.3f} s"
        )
    lo, hi = (float(v) for v in model.actuator_ctrlrange[actuator])
    excess = np.maximum(lo - values, values - hi)
    k = int(np.argmax(excess))
    if excess[k] > RANGE_TOL:
        raise LimitViolationError(
            f"gripper opening {values[k]:g} m at t = {times[k]:.3f} s leaves its range "
            f"[{lo:g}, {hi:g}] m; refused before playback",
            joint=joint,
            quantity="position",
            time=float(times[k]),
            segment=-1,
            value=float(values[k]),
            limit=lo if values[k] < lo else hi,
        )
    return values


def check_data(model: mujoco.MjModel, data: object) -> None:
    """Refuse a ``data`` that is not an ``MjData`` of ``model`` (MuJoCo would overrun its arrays).

    Raises:
        InvalidInputError: ``data`` is no ``MjData``, or its sizes are another model's.
    """
    if not isinstance(data, mujoco.MjData):
        raise InvalidTypeError(f"data must be a mujoco.MjData, got {short(data)}")
    sizes = {
        "qpos": (data.qpos.size, model.nq),
        "qvel": (data.qvel.size, model.nv),
        "act": (data.act.size, model.na),
        "ctrl": (data.ctrl.size, model.nu),
        "sensordata": (data.sensordata.size, model.nsensordata),
        "xpos": (len(data.xpos), model.nbody),
        "geom_xpos": (len(data.geom_xpos), model.ngeom),
        "site_xpos": (len(data.site_xpos), model.nsite),
    }
    for name, (has, wants) in sizes.items():
        if has != wants:
            raise InvalidInputError(
                f"data was made for another model: its {name} has {has} values, the model's {wants}"
            )


def rest_at_start(
    model: mujoco.MjModel, data: mujoco.MjData, binding: RobotBinding, q0: FloatArray
) -> None:
    """Reset ``data``: the commanded joints at rest at ``q0``, (n,) [rad], targets there."""
    mujoco.mj_resetData(model, data)
    data.qpos[binding.qpos_adr] = q0
    data.ctrl[binding.actuator_ids] = q0
    mujoco.mj_forward(model, data)


def finish_log(
    model: mujoco.MjModel,
    binding: RobotBinding,
    commands: RunCommands,
    record: StepRecords,
    recorded: int,
    *,
    task: str,
    trajectory: str,
    warnings: dict[str, int],
    diverged_at_s: float | None,
) -> PlaybackLog:
    """A run's log from its records: contacts classified, clearances computed, all steps at once.

    Args:
        model: The model.
        binding: What was driven and watched.
        commands: The run's commands.
        record: Its records, complete for the first ``recorded`` steps.
        recorded: Steps recorded (fewer than planned if the state diverged).
        task: Task name for the log.
        trajectory: Trajectory type name for the log.
        warnings: MuJoCo warning counts by name, of the whole run (hold included).
        diverged_at_s: End of the step in which the state diverged [s], or None.

    Returns:
        The :class:`PlaybackLog`.
    """
    dt = float(model.opt.timestep)
    groups = binding.groups
    ctrl = commands.ctrl
    c_step, c_geoms, c_dist = record.contacts(groups, recorded)
    qpos = record.qpos[:recorded].copy()
    if record.clearance is not None:
        clearance = record.clearance[:recorded].copy()
    else:
        clearance = clearances_of_states(
            model,
            mujoco.MjData(model),
            groups,
            qpos,
            record.geom_xpos[:recorded, record.carried],
            record.geom_xmat[:recorded, record.carried],
        )
    tool_ref, settle_steps = commands.tool_ref, commands.settle_steps
    ref = np.concatenate([tool_ref, np.repeat(tool_ref[-1:], settle_steps, axis=0)])[:recorded]
    meta = LogMeta(
        task=task,
        trajectory=trajectory,
        physics_dt_s=dt,
        geom_names=tuple(model.geom(g).name for g in range(model.ngeom)),
        groups=groups,
        force_limit=np.abs(np.asarray(model.actuator_forcerange)[binding.actuator_ids]).max(axis=1),
    )
    n = len(binding.actuator_ids)
    return PlaybackLog(
        meta=meta,
        time_s=record.time[:recorded].copy(),
        qpos=qpos,
        q_cmd=ctrl[:recorded, :n].copy(),
        q=qpos[:, binding.qpos_adr],
        tool_ref=ref,
        tool=record.tool[:recorded].copy(),
        force=record.force[:recorded, binding.actuator_ids],
        clearance_m=clearance,
        contact_step=c_step,
        contact_geoms=c_geoms,
        contact_dist=c_dist,
        trajectory_steps=min(len(commands.q_cmd), recorded),
        duration_s=len(commands.q_cmd) * dt,
        settle_s=settle_steps * dt,
        tool_target=tool_ref[-1].copy(),
        warnings=warnings,
        diverged_at_s=diverged_at_s,
    )


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
    start = _Snapshot(model) if on_step is None else None
    record: StepRecords | None = None
    if layout is not None and start is not None:
        record = _native_run(model, data, start, commands, layout, binding.groups, progress)
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
