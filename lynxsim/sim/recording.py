"""Step hooks of a playback: MP4 recording at the video rate, progress, chaining."""

from __future__ import annotations

import contextlib
import os
from collections.abc import Callable, Iterator

import mujoco
import numpy as np
import numpy.typing as npt

from lynxsim.sim.playback import StepHook
from lynxsim.sim.render import Overlay, RenderSettings, SceneRenderer
from lynxsim.sim.video import FrameSink, mp4_writer

__all__ = ["FrameRecorder", "ProgressFn", "chain_hooks", "progress_hook", "recorder"]

ProgressFn = Callable[[float], None]
"""Called with the fraction of a run done, 0..1."""


class FrameRecorder:
    """A playback step hook that renders a frame whenever video time is due.

    Video time is simulated time: frame ``i`` shows the state at ``i / fps``
    (the first physics step at or after it). The tool site's path so far is
    traced, targets are marked, and bodies touching the obstacle are drawn red.

    Args:
        renderer: The renderer (its settings give the fps).
        sink: Where frames go (an MP4 writer).
        site_id: Site whose path is traced.
        targets: Points to mark, shape (M, 3) [m].
    """

    def __init__(
        self,
        renderer: SceneRenderer,
        sink: FrameSink,
        site_id: int,
        targets: npt.ArrayLike = (),
    ) -> None:
        self._renderer = renderer
        self._sink = sink
        self._site = site_id
        self._targets = np.asarray(targets, dtype=float).reshape(-1, 3)
        self._period = 1.0 / renderer.settings.fps
        self._path: list[npt.NDArray[np.float64]] = []
        self.frames = 0

    def __call__(self, step: int, data: mujoco.MjData, touching: frozenset[int]) -> None:
        """Record the tool point; render if a frame is due."""
        self._path.append(data.site_xpos[self._site].copy())
        if data.time + 1e-9 < self.frames * self._period:
            return
        overlay = Overlay(
            path=np.asarray(self._path), targets=self._targets, contact_bodies=touching
        )
        self._sink.append_data(self._renderer.render(data, overlay))
        self.frames += 1


@contextlib.contextmanager
def recorder(
    model: mujoco.MjModel,
    video: str | os.PathLike[str] | None,
    settings: RenderSettings,
    site_id: int,
    targets: npt.ArrayLike = (),
) -> Iterator[FrameRecorder | None]:
    """A :class:`FrameRecorder` writing ``video`` (None: no video, yields None).

    The renderer and the MP4 writer are closed on exit; the file appears only
    when complete.
    """
    if video is None:
        yield None
        return
    with SceneRenderer(model, settings) as renderer, mp4_writer(video, settings.fps) as sink:
        yield FrameRecorder(renderer, sink, site_id, targets)


def progress_hook(total_s: float, dt: float, progress: ProgressFn | None) -> StepHook | None:
    """A step hook calling ``progress(fraction)`` about every 5 % of ``total_s`` [s]."""
    if progress is None:
        return None
    every = max(1, round(0.05 * total_s / dt))

    def hook(step: int, data: mujoco.MjData, touching: frozenset[int]) -> None:
        if step % every == 0:
            progress(min(1.0, data.time / total_s))

    return hook


def chain_hooks(*hooks: StepHook | None) -> StepHook | None:
    """One step hook calling each given one in order (None if none is given)."""
    active = [h for h in hooks if h is not None]
    if not active:
        return None

    def hook(step: int, data: mujoco.MjData, touching: frozenset[int]) -> None:
        for h in active:
            h(step, data, touching)

    return hook
