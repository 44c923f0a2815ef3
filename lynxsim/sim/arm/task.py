"""Running an arm task end to end: trajectory, physics, report, optional video."""

from __future__ import annotations

import os
from collections.abc import Callable

import numpy as np
import numpy.typing as npt

from lynxsim.arm.motion import tool_poses
from lynxsim.scene import REPORT_SCENE, Scene
from lynxsim.sim.arm.model import load_arm_scene
from lynxsim.sim.arm.playback import arm_binding, arm_tool_points
from lynxsim.sim.joint_playback import run_joints
from lynxsim.sim.recording import ProgressFn
from lynxsim.sim.render import RenderSettings
from lynxsim.sim.summary import Playback
from lynxsim.traj import Trajectory

__all__ = [
    "GRIPPER_CLOSED_M",
    "GRIPPER_OPEN_M",
    "arm_targets",
    "pick_and_place_gripper",
    "run_arm_trajectory",
]

FloatArray = npt.NDArray[np.float64]

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


def arm_targets(trajectory: Trajectory) -> FloatArray:
    """The tool points of a trajectory's waypoints, (N, 3) [m]: what its video and replay mark."""
    return np.array([p.position for p in tool_poses(trajectory.waypoints)])


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
    after it (:func:`lynxsim.sim.joint_playback.run_joints` with the arm's parts).

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
    return run_joints(
        model,
        arm_binding(model),
        trajectory,
        arm_tool_points,
        task=task,
        targets=arm_targets(trajectory),
        render=render or RenderSettings(),
        video=video,
        settle_s=settle_s,
        gripper_cmd=None if scene.cube is None else pick_and_place_gripper(trajectory.duration),
        progress=progress,
        replay=replay,
    )
