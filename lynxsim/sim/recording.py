"""Recording a playback to MP4: frames at the video rate, overlays drawn per frame."""

from __future__ import annotations

import mujoco
import numpy as np
import numpy.typing as npt

from lynxsim.sim.render import Overlay, SceneRenderer
from lynxsim.sim.video import FrameSink

__all__ = ["FrameRecorder"]


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
