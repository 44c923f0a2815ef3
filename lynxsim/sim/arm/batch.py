"""Many arm trajectories played in one native batch (:func:`play_arm_batch`)."""

from __future__ import annotations

from collections.abc import Callable, Sequence

import mujoco

from lynxsim.arm import tool_pose
from lynxsim.errors import InvalidInputError
from lynxsim.sim.arm.playback import arm_binding
from lynxsim.sim.stepping.batch import BatchRun, batch_rollout
from lynxsim.sim.stepping.commands import physics_grid
from lynxsim.sim.stepping.log import ProgressFn
from lynxsim.sim.summary import Playback, summarize
from lynxsim.traj import Trajectory

__all__ = ["play_arm_batch"]


def play_arm_batch(
    model: mujoco.MjModel,
    trajectories: Sequence[Trajectory],
    *,
    task: str,
    settle_s: float = 0.5,
    gripper_cmds: Sequence[Callable[[float], float] | None] | None = None,
    nthread: int | None = None,
    progress: ProgressFn | None = None,
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
        nthread: Threads to use, the caller's included (None: one per CPU).
        progress: Called with the fraction of the stepping done, now and then
            (see :func:`~lynxsim.sim.stepping.batch.batch_rollout`).

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
    logs = batch_rollout(
        model, arm_binding(model), runs, nthread=nthread, settle_s=settle_s, progress=progress
    )
    return [Playback(report=summarize(log), log=log) for log in logs]
