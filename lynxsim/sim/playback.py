"""Playing joint commands through position actuators, watching every physics step.

The caller samples its trajectory on the physics time grid (targets change
every step) and gives the commanded tool point for each sample; :func:`play`
steps MuJoCo, records commanded and actual joints, the tool site, actuator
forces, contacts and clearance, and summarises them in a
:class:`~lynxsim.sim.report.RunReport`.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import NamedTuple

import mujoco
import numpy as np
import numpy.typing as npt

from lynxsim.errors import InvalidInputError
from lynxsim.sim.binding import RobotBinding
from lynxsim.sim.contacts import ContactTracker
from lynxsim.sim.report import RunReport

__all__ = ["Playback", "PlaybackLog", "StepHook", "play"]

FloatArray = npt.NDArray[np.float64]

StepHook = Callable[[int, mujoco.MjData, frozenset[int]], None]
"""Called after each physics step with (step index, data, bodies touching the obstacle)."""

_CLEARANCE_MAX_M = 1.0


@dataclass(frozen=True)
class PlaybackLog:
    """Per-step record of a playback (S steps, n commanded joints).

    Attributes:
        time_s: Simulated time after each step, (S,) [s].
        q_cmd: Commanded joints, (S, n) [rad].
        q: Simulated joints, (S, n) [rad].
        tool_ref: Commanded tool point, (S, 3) [m].
        tool: Simulated tool site, (S, 3) [m].
        force: Actuator forces, (S, n) [N·m].
        clearance_m: Smallest robot–obstacle distance, (S,) [m] (NaN without obstacle).
        trajectory_steps: How many of the S steps belong to the trajectory (the rest settle).
    """

    time_s: FloatArray
    q_cmd: FloatArray
    q: FloatArray
    tool_ref: FloatArray
    tool: FloatArray
    force: FloatArray
    clearance_m: FloatArray
    trajectory_steps: int


class Playback(NamedTuple):
    """A report and the log it was computed from."""

    report: RunReport
    log: PlaybackLog


def _warnings(data: mujoco.MjData) -> dict[str, int]:
    out = {}
    for name, w in mujoco.mjtWarning.__members__.items():
        if int(w) >= int(mujoco.mjtWarning.mjNWARNING):
            continue
        count = int(data.warning[int(w)].number)
        if count:
            out[name.removeprefix("mjWARN_").lower()] = count
    return out


def play(
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
    extra_metrics: Callable[[mujoco.MjData], dict[str, float]] | None = None,
) -> Playback:
    """Play commanded joints sampled at every physics step.

    The robot is put at rest at ``q_cmd[0]`` and held there for ``presettle_s``
    (not recorded: it lets gravity load the servos), then sample ``k`` is the
    target during step ``k``; after the last sample the final command is held
    for ``settle_s``. Contacts are checked after every step.

    Args:
        model: The model.
        data: Its data (reset here).
        binding: What to drive and watch.
        q_cmd: Commands, (T, n) [rad], one per physics step (``T * dt`` = duration).
        tool_ref: Commanded tool point per sample, (T, 3) [m]; the last is the target.
        task: Task name for the report.
        trajectory: Trajectory type name for the report.
        settle_s: Hold time after the trajectory [s].
        presettle_s: Hold time before it, unrecorded [s].
        gripper_cmd: Gripper opening [m] as a function of time [s], from
            ``-presettle_s`` to the end of the settling.
        on_step: Called after every recorded step (rendering, progress).
        extra_metrics: Robot-specific figures per step; the report keeps each one's maximum.

    Returns:
        The :class:`Playback` (report and per-step log).

    Raises:
        InvalidInputError: Shapes disagree, or commands are not finite.
    """
    q_cmd = np.asarray(q_cmd, dtype=float)
    tool_ref = np.asarray(tool_ref, dtype=float)
    n = len(binding.actuator_ids)
    if q_cmd.ndim != 2 or q_cmd.shape[1] != n or len(q_cmd) == 0:
        raise InvalidInputError(f"q_cmd must have shape (T, {n}), got {q_cmd.shape}")
    if tool_ref.shape != (len(q_cmd), 3):
        raise InvalidInputError(f"tool_ref must have shape ({len(q_cmd)}, 3), got {tool_ref.shape}")
    if not (np.isfinite(q_cmd).all() and np.isfinite(tool_ref).all()):
        raise InvalidInputError("commands must be finite")
    dt = float(model.opt.timestep)
    settle_steps = round(settle_s / dt)
    steps = len(q_cmd) + settle_steps

    mujoco.mj_resetData(model, data)
    data.qpos[binding.qpos_adr] = q_cmd[0]
    data.ctrl[binding.actuator_ids] = q_cmd[0]
    gripper = binding.gripper_actuator_id if gripper_cmd is not None else None
    mujoco.mj_forward(model, data)
    presettle_steps = round(presettle_s / dt)
    for k in range(presettle_steps):
        if gripper is not None and gripper_cmd is not None:
            data.ctrl[gripper] = gripper_cmd((k - presettle_steps) * dt)
        mujoco.mj_step(model, data)
    data.time = 0.0
    data.warning.number[:] = 0  # the record starts here

    tracker = ContactTracker(model, binding)
    robot_ids = np.flatnonzero(binding.robot_geoms)
    obstacle_ids = np.flatnonzero(binding.obstacle_geoms)
    pairs = [(int(r), int(o)) for r in robot_ids for o in obstacle_ids]
    fromto = np.zeros(6)

    log_q = np.empty((steps, n))
    log_tool = np.empty((steps, 3))
    log_force = np.empty((steps, n))
    log_t = np.empty(steps)
    clearance = np.full(steps, np.nan)
    extra: dict[str, float] = {}
    diverged_at: float | None = None
    recorded = steps
    force_limit = np.abs(np.asarray(model.actuator_forcerange)[binding.actuator_ids]).max(axis=1)

    for k in range(steps):
        target = q_cmd[min(k, len(q_cmd) - 1)]
        data.ctrl[binding.actuator_ids] = target
        if gripper is not None and gripper_cmd is not None:
            data.ctrl[gripper] = gripper_cmd(k * dt)
        mujoco.mj_step(model, data)
        if not (np.isfinite(data.qpos).all() and np.isfinite(data.qvel).all()):
            diverged_at = float(data.time)
            recorded = k
            break
        log_t[k] = data.time
        log_q[k] = data.qpos[binding.qpos_adr]
        log_tool[k] = data.site_xpos[binding.tool_site_id]
        log_force[k] = data.actuator_force[binding.actuator_ids]
        touching = tracker.update(data)
        if pairs:
            clearance[k] = min(
                mujoco.mj_geomDistance(model, data, r, o, _CLEARANCE_MAX_M, fromto)
                for r, o in pairs
            )
        if extra_metrics is not None:
            for key, value in extra_metrics(data).items():
                extra[key] = max(extra.get(key, -np.inf), value)
        if on_step is not None:
            on_step(k, data, touching)

    traj_steps = min(len(q_cmd), recorded)
    cmd = np.concatenate([q_cmd, np.repeat(q_cmd[-1:], settle_steps, axis=0)])[:recorded]
    ref = np.concatenate([tool_ref, np.repeat(tool_ref[-1:], settle_steps, axis=0)])[:recorded]
    log = PlaybackLog(
        time_s=log_t[:recorded],
        q_cmd=cmd,
        q=log_q[:recorded],
        tool_ref=ref,
        tool=log_tool[:recorded],
        force=log_force[:recorded],
        clearance_m=clearance[:recorded],
        trajectory_steps=traj_steps,
    )
    joint_err = np.abs(log.q[:traj_steps] - log.q_cmd[:traj_steps])
    tool_err = np.linalg.norm(log.tool[:traj_steps] - log.tool_ref[:traj_steps], axis=1)
    final_err = float(np.linalg.norm(log.tool[-1] - tool_ref[-1])) if recorded else np.inf
    warnings = _warnings(data)
    has_obstacle = bool(pairs)
    i_min = int(np.nanargmin(clearance[:recorded])) if has_obstacle and recorded else None
    report = RunReport(
        task=task,
        trajectory=trajectory,
        duration_s=len(q_cmd) * dt,
        settle_s=settle_steps * dt,
        physics_dt_s=dt,
        joint_max_error_rad=tuple(float(v) for v in joint_err.max(axis=0, initial=0.0)),
        joint_rms_error_rad=tuple(
            float(v) for v in np.sqrt(np.mean(joint_err**2, axis=0)) if traj_steps
        ),
        tool_max_error_m=float(tool_err.max(initial=0.0)),
        tool_rms_error_m=float(np.sqrt(np.mean(tool_err**2))) if traj_steps else 0.0,
        tool_final_error_m=final_err,
        max_torque_ratio=tuple(
            float(v) for v in (np.abs(log.force).max(axis=0, initial=0.0) / force_limit)
        ),
        obstacle=tracker.verdict() if has_obstacle else None,
        min_clearance_m=float(clearance[i_min]) if i_min is not None else None,
        min_clearance_time_s=float(log.time_s[i_min]) if i_min is not None else None,
        self_collisions=tracker.self_collisions(),
        floor_contacts=tracker.support_contacts(),
        healthy=diverged_at is None and not warnings,
        warnings=warnings,
        diverged_at_s=diverged_at,
        extra=extra,
    )
    return Playback(report=report, log=log)
