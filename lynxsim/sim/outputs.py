"""What every robot's playback writes after stepping: its video, its replay data.

A robot's adapter plays a motion into a :class:`~lynxsim.sim.summary.Playback`,
then :func:`write_outputs` films it (:func:`~lynxsim.sim.recording.render_log`)
and saves its replay data (:func:`~lynxsim.sim.replay.save_replay`), marking the
motion's targets, the same way for any robot.
"""

from __future__ import annotations

import os

import mujoco
import numpy.typing as npt

from lynxsim.sim.recording import ProgressFn, render_log
from lynxsim.sim.render import RenderSettings
from lynxsim.sim.replay import save_replay
from lynxsim.sim.summary import Playback

__all__ = ["write_outputs"]


def write_outputs(
    model: mujoco.MjModel,
    playback: Playback,
    targets: npt.ArrayLike,
    *,
    video: str | os.PathLike[str] | None,
    render: RenderSettings,
    replay: str | os.PathLike[str] | None,
    rendering: ProgressFn | None = None,
    progress: ProgressFn | None = None,
) -> None:
    """Film a run (unless ``video`` is None), save its replay (unless ``replay`` is None).

    Args:
        model: The model the run was recorded with.
        playback: The run.
        targets: Points to mark, (M, 3) [m].
        video: MP4 path, or None.
        render: Frame size, camera, quality and fps (the replay starts from its camera).
        replay: The replay data file, or None.
        rendering: Called with the fraction of the frames done.
        progress: Called with 1.0 when all is written.
    """
    if video is not None:
        render_log(model, playback.log, video, render, targets, rendering)
    if replay is not None:
        save_replay(model, playback, replay, targets=targets, camera=render.camera)
    if progress is not None:
        progress(1.0)
