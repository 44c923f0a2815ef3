"""Running a 3-RRR task end to end: task-space path, physics, report, optional video."""

from __future__ import annotations

import os

import mujoco
import numpy as np

from lynxsim.rrr.modes import HOME_MODE
from lynxsim.rrr.path import PlatformPath
from lynxsim.sim.outputs import write_outputs
from lynxsim.sim.recording import ProgressFn, progress_hook, split_progress
from lynxsim.sim.render import RenderSettings
from lynxsim.sim.rrr.model import RRRIds
from lynxsim.sim.rrr.playback import play_rrr, start_model
from lynxsim.sim.summary import Playback

__all__ = ["DEFAULT_RRR_RENDER", "run_rrr_path"]

DEFAULT_RRR_RENDER = RenderSettings(camera="top")
"""Video defaults for the 3-RRR: 640x480 at 30 frames/s from the orthographic top camera."""


def run_rrr_path(
    path: PlatformPath,
    *,
    task: str,
    mode: int = HOME_MODE,
    video: str | os.PathLike[str] | None = None,
    render: RenderSettings = DEFAULT_RRR_RENDER,
    settle_s: float = 0.5,
    progress: ProgressFn | None = None,
    replay: str | os.PathLike[str] | None = None,
) -> Playback:
    """Play a platform path in the 3-RRR scene and optionally record it.

    The video traces the needle tip above the platform centre and marks the
    path's poses.

    Args:
        path: The timed platform path.
        task: Task name for the report.
        mode: Working mode 0..7 of the inverse kinematics.
        video: MP4 path, or None for no video.
        render: Frame size, camera (``top`` or ``front``), quality and fps.
        settle_s: Hold time after the path [s].
        progress: Called with the fraction done.
        replay: Where to save the run's replay data (``RUN.replay.npz``), or None.

    Returns:
        The :class:`~lynxsim.sim.summary.Playback` (report ``metrics``:
        :class:`lynxsim.sim.rrr.playback.RRRMetrics`).
    """
    model, _ = start_model(path, mode)
    ids = RRRIds.from_model(model)
    data = mujoco.MjData(model)
    data.qpos[:] = model.qpos0
    mujoco.mj_kinematics(model, data)
    height = float(data.site_xpos[ids.centre_site][2])
    stepping, rendering = split_progress(progress, video is not None)
    playback = play_rrr(
        path,
        mode,
        task=task,
        model=model,
        data=data,
        settle_s=settle_s,
        on_step=progress_hook(path.duration + settle_s, float(model.opt.timestep), stepping),
    )
    targets = np.column_stack([path.waypoints[:, :2], np.full(len(path.waypoints), height)])
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
