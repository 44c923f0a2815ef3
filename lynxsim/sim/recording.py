"""Videos of runs, rendered from their logs; progress hooks of the stepping.

:func:`render_log` draws any :class:`~lynxsim.sim.stepping.log.PlaybackLog` (a run
just stepped, or one of a batch) into an MP4: video time is simulated time,
frame ``i`` shows the first recorded step at or after ``i / fps``, the tracked
site's path so far (the log's ``tool``) is traced, targets are marked, and bodies of the robot
touching an obstacle are drawn red. Frames are drawn into one reused buffer and
encoded while the next is drawn (:func:`~lynxsim.sim.video.mp4_writer`).
"""

from __future__ import annotations

import os

import mujoco
import numpy as np
import numpy.typing as npt

from lynxsim.sim.collision import classify_contacts
from lynxsim.sim.render import Overlay, PathTrace, RenderSettings, SceneRenderer
from lynxsim.sim.stepping.log import PlaybackLog, ProgressFn, StepHook
from lynxsim.sim.video import mp4_writer

__all__ = ["ProgressFn", "frame_steps", "progress_hook", "render_log", "split_progress"]

"""Called with the fraction of a run done, 0..1."""


def frame_steps(time_s: npt.ArrayLike, fps: float) -> npt.NDArray[np.intp]:
    """Which recorded step each video frame shows: the first at or after ``i / fps``.

    Args:
        time_s: Times of the recorded steps, (S,) [s], increasing.
        fps: Frame rate [1/s].

    Returns:
        Step index of each frame, (F,).
    """
    t = np.asarray(time_s, dtype=float)
    if len(t) == 0:
        return np.zeros(0, dtype=np.intp)
    count = int(np.floor((t[-1] + 1e-9) * fps)) + 1
    due = np.arange(count) / fps
    steps: npt.NDArray[np.intp] = np.searchsorted(t + 1e-9, due, side="left").astype(np.intp)
    return steps[steps < len(t)]


def render_log(
    model: mujoco.MjModel,
    log: PlaybackLog,
    video: str | os.PathLike[str],
    settings: RenderSettings,
    targets: npt.ArrayLike = (),
    progress: ProgressFn | None = None,
) -> int:
    """Render a run's log into an MP4 (which appears only when complete).

    Args:
        model: The model the log was recorded with.
        log: The run's log.
        video: MP4 path.
        settings: Frame size, camera, quality and fps.
        targets: Points to mark, shape (M, 3) [m].
        progress: Called with the fraction of frames done.

    Returns:
        The number of frames written.
    """
    data = mujoco.MjData(model)
    marks = np.asarray(targets, dtype=float).reshape(-1, 3)
    c = classify_contacts(log.meta.groups, log.contact_geoms, log.contact_dist)
    hit_step = log.contact_step[c.obstacle]
    hit_body = np.asarray(model.geom_bodyid)[
        np.where(
            c.carried_first[c.obstacle],
            log.contact_geoms[c.obstacle, 0],
            log.contact_geoms[c.obstacle, 1],
        )
    ]
    trace = PathTrace.of(log.tool)
    frames = frame_steps(log.time_s, settings.fps)
    image = np.empty((settings.height, settings.width, 3), dtype=np.uint8)
    with SceneRenderer(model, settings) as renderer, mp4_writer(video, settings.fps) as sink:
        for i, k in enumerate(frames.tolist()):
            data.qpos[:] = log.qpos[k]
            mujoco.mj_kinematics(model, data)
            mujoco.mj_camlight(model, data)
            overlay = Overlay(
                path=trace.until(k),
                targets=marks,
                contact_bodies=frozenset(hit_body[hit_step == k].tolist()),
            )
            sink.append_data(renderer.render(data, overlay, out=image))
            if progress is not None:
                progress((i + 1) / len(frames))
    return len(frames)


def progress_hook(total_s: float, dt: float, progress: ProgressFn | None) -> StepHook | None:
    """A step hook calling ``progress(fraction)`` about every 5 % of ``total_s`` [s]."""
    if progress is None:
        return None
    every = max(1, round(0.05 * total_s / dt))

    def hook(step: int, data: mujoco.MjData) -> None:
        if step % every == 0:
            progress(min(1.0, data.time / total_s))

    return hook


def split_progress(
    progress: ProgressFn | None, video: bool
) -> tuple[ProgressFn | None, ProgressFn | None]:
    """Progress callbacks of the stepping and the rendering of one run.

    With a video, stepping reports 0..0.5 and rendering 0.5..1; without, stepping 0..1.
    """
    if progress is None:
        return None, None
    if not video:
        return progress, None
    report = progress

    def stepping(f: float) -> None:
        report(0.5 * f)

    def rendering(f: float) -> None:
        report(0.5 + 0.5 * f)

    return stepping, rendering
