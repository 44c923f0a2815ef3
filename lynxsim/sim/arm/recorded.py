"""The arm's runs recorded for a sweep (:mod:`lynxsim.sim.recorded` says why that is exact).

:func:`record_run` plays the run as ``lynxsim play`` does
(:func:`~lynxsim.sim.arm.task.run_arm_trajectory`, whose report is kept) and
replays the hold before the motion on its own; :func:`arm_scene_model` gives
the sweep judge (:class:`lynxsim.sim.sweep_judge.PlacementJudge`) the arm's
scenes.
"""

from __future__ import annotations

import inspect

import mujoco
import numpy as np
import numpy.typing as npt

from lynxsim.arm import tool_pose
from lynxsim.scene import Scene
from lynxsim.sim.arm.model import SceneIds, load_arm_scene
from lynxsim.sim.arm.playback import arm_binding
from lynxsim.sim.arm.task import pick_and_place_gripper, run_arm_trajectory
from lynxsim.sim.collision import CollisionGroups
from lynxsim.sim.recorded import RecordedRun, recorded_run
from lynxsim.sim.stepping.commands import physics_grid
from lynxsim.sim.stepping.rollout import rollout
from lynxsim.traj import Trajectory

__all__ = ["arm_scene_model", "record_run"]

FloatArray = npt.NDArray[np.float64]

_PRESETTLE_S: float = inspect.signature(rollout).parameters["presettle_s"].default
"""The hold before the motion of every playback [s] (``rollout``'s own default)."""


def _hold_states(
    model: mujoco.MjModel, trajectory: Trajectory, gripper: bool
) -> tuple[FloatArray, int]:
    """The hold before the motion replayed as recorded steps: its states and its length.

    ``rollout`` with no hold, given the hold's commands (the first sample,
    repeated) before the trajectory's, steps the same physics from the same
    reset; its first H states are the hold's, its state H the playback's first.
    """
    dt = float(model.opt.timestep)
    # The whole grid sampled, as the playback samples it (one time alone may round otherwise).
    q_first = trajectory.sample(physics_grid(trajectory.duration, dt)).q[:1]
    hold = round(_PRESETTLE_S / dt)
    q_cmd = np.repeat(q_first, hold + 1, axis=0)
    schedule = pick_and_place_gripper(trajectory.duration)

    def gripper_at(t: float) -> float:  # step k of this run is step k - H of the playback
        return schedule((round(t / dt) - hold) * dt)

    log = rollout(
        model,
        mujoco.MjData(model),
        arm_binding(model),
        q_cmd,
        tool_pose(q_cmd).position,
        task="hold",
        trajectory=trajectory.kind.value,
        settle_s=0.0,
        presettle_s=0.0,
        gripper_cmd=gripper_at if gripper else None,
    )
    return log.qpos, hold


def record_run(trajectory: Trajectory, *, task: str, scene: Scene) -> RecordedRun:
    """Play a trajectory in a scene as ``lynxsim play`` does, keeping every state.

    Args:
        trajectory: The joint trajectory.
        task: Task name for the report.
        scene: The scene without the swept obstacle.

    Returns:
        The :class:`RecordedRun`.

    Raises:
        ReplayMismatchError: The replayed hold does not end in the playback's
            first state (the exactness the sweep relies on does not hold).
        LynxsimError: The trajectory cannot be played (see ``rollout``).
    """
    playback = run_arm_trajectory(trajectory, task=task, scene=scene)
    hold_qpos, hold = _hold_states(load_arm_scene(scene), trajectory, scene.cube is not None)
    label = f"{task} {trajectory.kind.value}"
    return recorded_run(playback.report, playback.log, hold_qpos, hold, scene, label=label)


def arm_scene_model(scene: Scene) -> tuple[mujoco.MjModel, CollisionGroups]:
    """The arm scene of ``scene`` compiled, and its collision groups (for the sweep judge)."""
    model = load_arm_scene(scene)
    return model, SceneIds.from_model(model).collision_groups(model)
