"""What a run leaves: its :class:`PlaybackLog`, made from the stepping's records.

:func:`finish_log` turns the records of a stepped run
(:mod:`lynxsim.sim.stepping.records`) into its log: contacts classified,
clearances computed (:mod:`lynxsim.sim.collision`), all steps at once, or,
for a natively stepped run, each obstacle's minimum found while it stepped and
every step's clearance computed when the log's are first read
(:class:`~lynxsim.sim.stepping.clearance_log.LoggedClearance`). Every
way of stepping (:mod:`lynxsim.sim.stepping.rollout`,
:mod:`lynxsim.sim.stepping.batch`) ends here, so that their logs are the same.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

import mujoco
import numpy as np
import numpy.typing as npt

from lynxsim.sim.binding import RobotBinding
from lynxsim.sim.collision import CollisionGroups, classify_contacts, clearances_of_states
from lynxsim.sim.stepping.clearance_log import LoggedClearance
from lynxsim.sim.stepping.commands import RunCommands
from lynxsim.sim.stepping.records import StepRecords

__all__ = [
    "LogMeta",
    "LoggedClearance",
    "PlaybackLog",
    "ProgressFn",
    "StepHook",
    "finish_log",
    "mujoco_warnings",
]

FloatArray = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.intp]

StepHook = Callable[[int, mujoco.MjData], None]
"""Called after each recorded physics step with (step index, data)."""

ProgressFn = Callable[[float], None]
"""Called with the fraction of some work done, 0..1."""


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
        clearance: Signed distance to each obstacle, (S, m) [m], and each
            obstacle's minimum (:class:`LoggedClearance`; ``clearance_m`` reads
            the values).
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
    clearance: LoggedClearance
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
    def clearance_m(self) -> FloatArray:
        """Signed distance to each obstacle after each step, (S, m) [m] (computed when read)."""
        return self.clearance.values

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
    if record.minima is not None and recorded == len(record.time):
        minima = record.minima
        clearance = LoggedClearance.deferred(
            model, groups, qpos, minima.value.copy(), minima.step.copy()
        )
    else:
        clearance = LoggedClearance.known(
            clearances_of_states(
                model,
                mujoco.MjData(model),
                groups,
                qpos,
                record.geom_xpos[:recorded, record.carried],
                record.geom_xmat[:recorded, record.carried],
            )
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
        clearance=clearance,
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
