"""Playing any joint robot's trajectory: physics grid, samples, rollout, report, outputs.

:func:`play_joints` steps a joint trajectory through a robot's position
actuators (:func:`~lynxsim.sim.stepping.rollout.rollout`) and summarises it;
:func:`run_joints` adds the video and the replay data; :func:`record_joints`
keeps the states of a run for the sweeps (:mod:`lynxsim.sim.recorded`). The
robot gives its model, its binding, its tool's forward kinematics and, if it
grips, its gripper's schedule; nothing here names a robot.
"""

from __future__ import annotations

import inspect
import os
from collections.abc import Callable

import mujoco
import numpy as np
import numpy.typing as npt

from lynxsim.scene import Scene
from lynxsim.sim.binding import RobotBinding
from lynxsim.sim.outputs import write_outputs
from lynxsim.sim.recorded import RecordedRun, recorded_run
from lynxsim.sim.recording import ProgressFn, split_progress
from lynxsim.sim.render import RenderSettings
from lynxsim.sim.stepping.commands import physics_grid
from lynxsim.sim.stepping.log import StepHook
from lynxsim.sim.stepping.rollout import rollout
from lynxsim.sim.summary import Playback, summarize
from lynxsim.traj import Trajectory

__all__ = ["Gripper", "ToolPoints", "hold_states", "play_joints", "record_joints", "run_joints"]

FloatArray = npt.NDArray[np.float64]

ToolPoints = Callable[[FloatArray], FloatArray]
"""Forward kinematics of the tool point: joint vectors (T, n) [rad] -> points (T, 3) [m]."""
Gripper = Callable[[float], float]
"""A gripper's opening [m] over time [s] (from the hold before the motion to its end)."""

_PRESETTLE_S: float = inspect.signature(rollout).parameters["presettle_s"].default
"""The hold before the motion of every playback [s] (``rollout``'s own default)."""


def play_joints(
    model: mujoco.MjModel,
    binding: RobotBinding,
    trajectory: Trajectory,
    tool: ToolPoints,
    *,
    task: str,
    data: mujoco.MjData | None = None,
    settle_s: float = 0.5,
    gripper_cmd: Gripper | None = None,
    on_step: StepHook | None = None,
    progress: ProgressFn | None = None,
) -> Playback:
    """Play a joint trajectory through the position actuators, targets updated every step.

    The commanded tool point is ``tool`` of the commanded joints.

    Args:
        model: The robot's scene.
        binding: What the playback drives and watches in it.
        trajectory: The joint trajectory (the binding's joints).
        tool: The tool's forward kinematics.
        task: Task name for the report.
        data: Data to use (a new one if None).
        settle_s: Hold time after the trajectory [s].
        gripper_cmd: Gripper opening [m] over trajectory time [s], or None.
        on_step: Called after every physics step (a monitor; the run then
            steps in a Python loop).
        progress: Called with the fraction of the stepping done, now and then.

    Returns:
        The :class:`~lynxsim.sim.summary.Playback` (report and log).
    """
    data = mujoco.MjData(model) if data is None else data
    t = physics_grid(trajectory.duration, float(model.opt.timestep))
    q_cmd = trajectory.sample(t).q
    log = rollout(
        model,
        data,
        binding,
        q_cmd,
        tool(q_cmd),
        task=task,
        trajectory=trajectory.kind.value,
        settle_s=settle_s,
        gripper_cmd=gripper_cmd,
        on_step=on_step,
        progress=progress,
    )
    return Playback(report=summarize(log), log=log)


def run_joints(
    model: mujoco.MjModel,
    binding: RobotBinding,
    trajectory: Trajectory,
    tool: ToolPoints,
    *,
    task: str,
    targets: npt.ArrayLike,
    render: RenderSettings,
    video: str | os.PathLike[str] | None = None,
    settle_s: float = 0.5,
    gripper_cmd: Gripper | None = None,
    progress: ProgressFn | None = None,
    replay: str | os.PathLike[str] | None = None,
) -> Playback:
    """Play a joint trajectory (:func:`play_joints`), then film it and save its replay.

    Args:
        model: The robot's scene.
        binding: What the playback drives and watches in it.
        trajectory: The joint trajectory.
        tool: The tool's forward kinematics.
        task: Task name for the report.
        targets: The motion's targets to mark in the video and replay, (M, 3) [m].
        render: Frame size, camera, quality and fps.
        video: MP4 path, or None for no video.
        settle_s: Hold time after the trajectory [s].
        gripper_cmd: Gripper opening [m] over trajectory time [s], or None.
        progress: Called with the fraction done.
        replay: Where to save the run's replay data, or None.

    Returns:
        The :class:`~lynxsim.sim.summary.Playback`.
    """
    stepping, rendering = split_progress(progress, video is not None)
    playback = play_joints(
        model,
        binding,
        trajectory,
        tool,
        task=task,
        settle_s=settle_s,
        gripper_cmd=gripper_cmd,
        progress=stepping,
    )
    write_outputs(
        model,
        playback,
        targets,
        video=video,
        render=render,
        replay=replay,
        rendering=rendering,
        progress=progress,
    )
    return playback


def hold_states(
    model: mujoco.MjModel,
    binding: RobotBinding,
    trajectory: Trajectory,
    tool: ToolPoints,
    gripper: Gripper | None,
) -> tuple[FloatArray, int]:
    """The hold before the motion replayed as recorded steps: its states and its length.

    ``rollout`` with no hold, given the hold's commands (the first sample,
    repeated) before the trajectory's, steps the same physics from the same
    reset; its first H states are the hold's, its state H the playback's first.

    Args:
        model: The robot's scene.
        binding: What the playback drives.
        trajectory: The joint trajectory.
        tool: The tool's forward kinematics.
        gripper: The gripper's schedule of the playback (trajectory time), or None.
    """
    dt = float(model.opt.timestep)
    # The whole grid sampled, as the playback samples it (one time alone may round otherwise).
    q_first = trajectory.sample(physics_grid(trajectory.duration, dt)).q[:1]
    hold = round(_PRESETTLE_S / dt)
    q_cmd = np.repeat(q_first, hold + 1, axis=0)
    gripper_at: Gripper | None = None
    if gripper is not None:
        schedule = gripper

        def shifted(t: float) -> float:  # step k of this run is step k - H of the playback
            return schedule((round(t / dt) - hold) * dt)

        gripper_at = shifted
    log = rollout(
        model,
        mujoco.MjData(model),
        binding,
        q_cmd,
        tool(q_cmd),
        task="hold",
        trajectory=trajectory.kind.value,
        settle_s=0.0,
        presettle_s=0.0,
        gripper_cmd=gripper_at,
    )
    return log.qpos, hold


def record_joints(
    playback: Playback,
    model: mujoco.MjModel,
    binding: RobotBinding,
    trajectory: Trajectory,
    tool: ToolPoints,
    *,
    task: str,
    scene: Scene,
    gripper: Gripper | None,
) -> RecordedRun:
    """A playback of a trajectory in ``scene`` and its hold, as one recorded run (sweeps).

    Args:
        playback: The trajectory's playback in ``scene`` (as ``lynxsim play`` plays it).
        model: The scene's model (compiled afresh: the hold steps it from its reset).
        binding: What the playback drives.
        trajectory: The joint trajectory.
        tool: The tool's forward kinematics.
        task: Task name, for the error.
        scene: The scene (without the swept obstacle).
        gripper: The playback's gripper schedule, or None.

    Raises:
        ReplayMismatchError: The replayed hold does not end in the playback's
            first state (the exactness the sweep relies on does not hold).
    """
    hold_qpos, hold = hold_states(model, binding, trajectory, tool, gripper)
    label = f"{task} {trajectory.kind.value}"
    return recorded_run(playback.report, playback.log, hold_qpos, hold, scene, label=label)
