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

from lynxsim.errors import InvalidInputError, LimitViolationError
from lynxsim.sim.binding import RobotBinding
from lynxsim.sim.contacts import ContactTracker
from lynxsim.sim.report import RunReport

__all__ = ["Playback", "PlaybackLog", "StepHook", "play"]

FloatArray = npt.NDArray[np.float64]

StepHook = Callable[[int, mujoco.MjData, frozenset[int]], None]
"""Called after each physics step with (step index, data, bodies touching the obstacle)."""

_CLEARANCE_MAX_M = 1.0
RANGE_TOL = 1e-6
"""Commands may exceed a joint range by this much [rad] (rounding of the samples)."""


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


def _clearance(
    model: mujoco.MjModel,
    data: mujoco.MjData,
    robot_ids: npt.NDArray[np.intp],
    obstacle_ids: npt.NDArray[np.intp],
    rbound: FloatArray,
    fromto: FloatArray,
) -> float:
    """Smallest robot–obstacle distance [m] (negative: penetration).

    Robot bounding spheres against the obstacles' boxes give a lower bound for
    every pair; exact distances
    (``mj_geomDistance``) are computed in order of that bound until the next
    bound exceeds the best distance found, so far-away geoms cost nothing.
    """
    xpos = np.asarray(data.geom_xpos)
    # World-aligned boxes around the obstacle geoms (from their local AABBs).
    aabb = np.asarray(model.geom_aabb)[obstacle_ids]  # (m, 6): centre, half sizes
    rot = np.asarray(data.geom_xmat)[obstacle_ids].reshape(-1, 3, 3)
    centre = xpos[obstacle_ids] + np.einsum("mij,mj->mi", rot, aabb[:, :3])
    half = np.einsum("mij,mj->mi", np.abs(rot), aabb[:, 3:])
    outside = np.abs(xpos[robot_ids, None, :] - centre[None]) - half[None]  # (r, m, 3)
    gaps = np.linalg.norm(np.maximum(outside, 0.0), axis=-1)
    bounds = gaps - rbound[robot_ids, None]
    best = _CLEARANCE_MAX_M
    for flat in np.argsort(bounds, axis=None):
        i, j = divmod(int(flat), len(obstacle_ids))
        if bounds[i, j] >= best:
            break
        d = mujoco.mj_geomDistance(
            model, data, int(robot_ids[i]), int(obstacle_ids[j]), best, fromto
        )
        best = min(best, d)
    return best


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
        LimitViolationError: A command leaves its joint's range (names joint and time).
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
    _check_ranges(model, binding, q_cmd, dt)
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
    data.time = 0.0  # the record starts here; warnings of the hold still count

    tracker = ContactTracker(model, binding)
    robot_ids = np.flatnonzero(binding.carried_geoms)
    obstacle_ids = np.flatnonzero(binding.obstacle_geoms)
    pairs = len(robot_ids) > 0 and len(obstacle_ids) > 0
    rbound = np.asarray(model.geom_rbound)
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
        # mj_step leaves positions and contacts of the state it started from:
        # bring sites, geoms and contacts to the new qpos, so that they match
        # data.time and the command.
        mujoco.mj_kinematics(model, data)
        mujoco.mj_collision(model, data)
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
            clearance[k] = _clearance(model, data, robot_ids, obstacle_ids, rbound, fromto)
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
