"""Running an arm task end to end: trajectory, physics, report, optional video."""

from __future__ import annotations

import os
from collections.abc import Callable

import numpy as np

from lynxsim.arm.motion import tool_poses
from lynxsim.scene import REPORT_SCENE, Scene
from lynxsim.sim.arm.model import load_arm_scene
from lynxsim.sim.arm.playback import play_arm
from lynxsim.sim.recording import ProgressFn, render_log, split_progress
from lynxsim.sim.render import RenderSettings
from lynxsim.sim.replay import save_replay
from lynxsim.sim.summary import Playback
from lynxsim.traj import Trajectory

__all__ = ["GRIPPER_CLOSED_M", "GRIPPER_OPEN_M", "pick_and_place_gripper", "run_arm_trajectory"]

GRIPPER_OPEN_M = 0.03
"""Gripper opening when open [m] (the Lynxmotion gripper's full opening)."""
GRIPPER_CLOSED_M = 0.0
"""Commanded opening when gripping [m]; the cube (25 mm) stops the fingers."""
_CLOSE_BEFORE_S = 0.25
_OPEN_AFTER_S = 0.1


def pick_and_place_gripper(duration_s: float) -> Callable[[float], float]:
    """Gripper schedule of a pick-and-place: grip before moving, release at the end.

    Open until ``_CLOSE_BEFORE_S`` before the motion starts (during the unrecorded
    hold), closed during the motion, open again shortly after it ends.
    """

    def opening(t: float) -> float:
        if t < -_CLOSE_BEFORE_S or t >= duration_s + _OPEN_AFTER_S:
            return GRIPPER_OPEN_M
        return GRIPPER_CLOSED_M

    return opening


def run_arm_trajectory(
    trajectory: Trajectory,
    *,
    task: str,
    scene: Scene = REPORT_SCENE,
    video: str | os.PathLike[str] | None = None,
    render: RenderSettings | None = None,
    settle_s: float = 0.5,
    progress: ProgressFn | None = None,
    replay: str | os.PathLike[str] | None = None,
) -> Playback:
    """Play a trajectory in the arm scene and optionally record it.

    With a cube in the scene, the gripper grips before the motion and releases
    after it.

    Args:
        trajectory: The joint trajectory.
        task: Task name for the report.
        scene: Obstacles, table and cube (default: the report's).
        video: MP4 path, or None for no video.
        render: Frame size, camera, quality and fps (defaults if None).
        settle_s: Hold time after the trajectory [s].
        progress: Called with the fraction done.
        replay: Where to save the run's replay data (``RUN.replay.npz``), or None.

    Returns:
        The :class:`~lynxsim.sim.summary.Playback`.
    """
    model = load_arm_scene(scene)
    stepping, rendering = split_progress(progress, video is not None)
    playback = play_arm(
        model,
        trajectory,
        task=task,
        settle_s=settle_s,
        gripper_cmd=None if scene.cube is None else pick_and_place_gripper(trajectory.duration),
        progress=stepping,
    )
    targets = np.array([p.position for p in tool_poses(trajectory.waypoints)])
    if video is not None:
        render_log(model, playback.log, video, render or RenderSettings(), targets, rendering)
    if replay is not None:
        camera = (render or RenderSettings()).camera
        save_replay(model, playback, replay, targets=targets, camera=camera)
    if progress is not None:
        progress(1.0)
    return playback
