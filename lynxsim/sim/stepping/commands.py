"""A run's commands checked and laid out as the controls of every physics step.

:func:`physics_grid` gives the times a trajectory is sampled at (one target
per physics step); :func:`plan_commands` checks the samples against the
actuators' ranges and lays out the unrecorded hold, the recorded steps and the
settling (:class:`RunCommands`); :func:`rest_at_start` puts a data at rest at
the first command.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import mujoco
import numpy as np
import numpy.typing as npt

from lynxsim.bounds import MAX_SEGMENT_S, MAX_STEPS
from lynxsim.errors import (
    InvalidInputError,
    InvalidTypeError,
    LimitViolationError,
    NonFiniteInputError,
    short,
)
from lynxsim.inputs import number_in_range, positive_number, real_array
from lynxsim.sim.binding import RobotBinding

__all__ = [
    "RANGE_TOL",
    "RunCommands",
    "check_data",
    "physics_grid",
    "plan_commands",
    "rest_at_start",
    "whole_controls",
]

FloatArray = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.intp]

RANGE_TOL = 1e-6
"""Commands may exceed a joint range by this much [rad] (rounding of the samples)."""


def physics_grid(duration_s: float, dt: float) -> np.ndarray:
    """Times at the end of each physics step over a duration: ``k * dt``, k = 1..ceil(T/dt) [s].

    The last time is clipped to the duration, so the final command is the final waypoint.

    Raises:
        InvalidInputError: Duration or step not a positive number, or more than
            :data:`lynxsim.bounds.MAX_STEPS` steps.
    """
    duration_s = positive_number(duration_s, "duration_s", "s")
    dt = positive_number(dt, "dt", "s")
    if duration_s / dt > MAX_STEPS:
        raise InvalidInputError(f"{duration_s:g} s at {dt:g} s a step is over {MAX_STEPS:,} steps")
    n = max(1, int(np.ceil(duration_s / dt - 1e-9)))
    grid: np.ndarray = np.minimum(np.arange(1, n + 1) * dt, duration_s)
    return grid


def _check_ranges(
    model: mujoco.MjModel, binding: RobotBinding, q_cmd: FloatArray, dt: float
) -> None:
    """Refuse commands outside the actuators' control ranges (= joint ranges).

    Sample ``k`` is the target of the step that ends at ``(k + 1) dt``, the time named.
    An actuator without a control range (``ctrllimited`` false) takes any command.
    """
    lo, hi = np.asarray(model.actuator_ctrlrange, dtype=float)[binding.actuator_ids].T
    limited = np.asarray(model.actuator_ctrllimited)[binding.actuator_ids] != 0
    lo, hi = np.where(limited, lo, -np.inf), np.where(limited, hi, np.inf)
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


def whole_controls(base: FloatArray, adr: IntArray, values: FloatArray) -> FloatArray:
    """Whole control vectors, (K, nu): ``base`` (nu,) with columns ``adr`` set from (K, c)."""
    out = np.repeat(base[None], len(values), axis=0)
    out[:, adr] = values
    return out
