"""The arm's runs recorded for a sweep (:mod:`lynxsim.sim.recorded` says why that is exact).

:func:`record_run` plays the run as ``lynxsim play`` does
(:func:`~lynxsim.sim.arm.task.run_arm_trajectory`, whose report is kept) and
replays the hold before the motion on its own
(:func:`lynxsim.sim.joint_playback.record_joints`, the arm's gripper schedule
included); :func:`arm_scene_model` gives the sweep judge
(:class:`lynxsim.sim.sweep_judge.PlacementJudge`) the arm's scenes.
"""

from __future__ import annotations

import mujoco

from lynxsim.scene import Scene
from lynxsim.sim.arm.model import SceneIds, load_arm_scene
from lynxsim.sim.arm.playback import arm_binding, arm_tool_points
from lynxsim.sim.arm.task import pick_and_place_gripper, run_arm_trajectory
from lynxsim.sim.collision import CollisionGroups
from lynxsim.sim.joint_playback import record_joints
from lynxsim.sim.recorded import RecordedRun
from lynxsim.traj import Trajectory

__all__ = ["arm_scene_model", "record_run"]


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
    model = load_arm_scene(scene)
    return record_joints(
        playback,
        model,
        arm_binding(model),
        trajectory,
        arm_tool_points,
        task=task,
        scene=scene,
        gripper=None if scene.cube is None else pick_and_place_gripper(trajectory.duration),
    )


def arm_scene_model(scene: Scene) -> tuple[mujoco.MjModel, CollisionGroups]:
    """The arm scene of ``scene`` compiled, and its collision groups (for the sweep judge)."""
    model = load_arm_scene(scene)
    return model, SceneIds.from_model(model).collision_groups(model)
