"""Running an arm task end to end: trajectory, physics, report, optional video."""

from __future__ import annotations

import contextlib
import os
from collections.abc import Callable, Iterator

import mujoco
import numpy as np

from lynxsim.sim.arm_playback import play_arm
from lynxsim.sim.playback import Playback, StepHook
from lynxsim.sim.recording import FrameRecorder
from lynxsim.sim.render import RenderSettings, SceneRenderer
from lynxsim.sim.scene import REPORT_OBSTACLE, ObstacleSpec, SceneIds, load_arm_scene
from lynxsim.sim.video import mp4_writer
from lynxsim.traj import Trajectory

__all__ = ["GRIPPER_CLOSED_M", "GRIPPER_OPEN_M", "pick_and_place_gripper", "run_arm_trajectory"]

GRIPPER_OPEN_M = 0.03
"""Gripper opening when open [m] (the Lynxmotion gripper's full opening)."""
GRIPPER_CLOSED_M = 0.0
"""Commanded opening when gripping [m]; the cube (25 mm) stops the fingers."""
_CLOSE_BEFORE_S = 0.25
_OPEN_AFTER_S = 0.1

ProgressFn = Callable[[float], None]
"""Called with the fraction of the run done, 0..1."""


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


def _chain(*hooks: StepHook | None) -> StepHook | None:
    active = [h for h in hooks if h is not None]
    if not active:
        return None

    def hook(step: int, data: mujoco.MjData, touching: frozenset[int]) -> None:
        for h in active:
            h(step, data, touching)

    return hook


@contextlib.contextmanager
def _recorder(
    model: mujoco.MjModel,
    video: str | os.PathLike[str] | None,
    settings: RenderSettings,
    targets: np.ndarray,
) -> Iterator[FrameRecorder | None]:
    if video is None:
        yield None
        return
    with SceneRenderer(model, settings) as renderer, mp4_writer(video, settings.fps) as sink:
        yield FrameRecorder(renderer, sink, SceneIds.from_model(model).tool_site, targets)


def run_arm_trajectory(
    trajectory: Trajectory,
    *,
    task: str,
    obstacle: ObstacleSpec | None = REPORT_OBSTACLE,
    cube: bool = True,
    video: str | os.PathLike[str] | None = None,
    render: RenderSettings | None = None,
    settle_s: float = 0.5,
    progress: ProgressFn | None = None,
) -> Playback:
    """Play a trajectory in the arm scene and optionally record it.

    With the cube (placed at the report's P1), the gripper grips before the
    motion and releases after it.

    Args:
        trajectory: The joint trajectory.
        task: Task name for the report.
        obstacle: The cylinder, or None for a scene without it.
        cube: Whether the scene holds the cube.
        video: MP4 path, or None for no video.
        render: Frame size, camera, quality and fps (defaults if None).
        settle_s: Hold time after the trajectory [s].
        progress: Called with the fraction done.

    Returns:
        The :class:`~lynxsim.sim.playback.Playback`.
    """
    model = load_arm_scene(obstacle=obstacle, cube=cube)
    settings = render or RenderSettings()
    total = trajectory.duration + settle_s
    report_progress: StepHook | None = None
    if progress is not None:
        every = max(1, round(0.05 * total / model.opt.timestep))

        def report_progress(step: int, data: mujoco.MjData, touching: frozenset[int]) -> None:
            if step % every == 0:
                progress(min(1.0, data.time / total))

    targets = np.array([p.position for p in trajectory.waypoints.poses])
    with _recorder(model, video, settings, targets) as recorder:
        playback = play_arm(
            model,
            trajectory,
            task=task,
            settle_s=settle_s,
            gripper_cmd=pick_and_place_gripper(trajectory.duration) if cube else None,
            on_step=_chain(recorder, report_progress),
        )
    if progress is not None:
        progress(1.0)
    return playback
