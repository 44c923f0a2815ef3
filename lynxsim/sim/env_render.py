"""Frames, windows and image observations for the envs, made lazily where they are needed.

The envs (:mod:`lynxsim.envs`) reach MuJoCo's rendering through this module.

``rgb_array`` frames and image observations (:class:`PixelRenderer`, on GL
contexts of their own) come from :class:`~lynxsim.sim.render.SceneRenderer`
(EGL off-screen on a headless machine), ``human`` from a passive
:mod:`mujoco.viewer` window. Nothing is made before the first frame, so vector
envs render in their workers. A process forked after an env of this module made a
GL context refuses to make one (Mesa's EGL deadlocks there) and says what to do.
"""

from __future__ import annotations

import os
from typing import Any

import mujoco
import numpy as np
import numpy.typing as npt

from lynxsim.errors import InvalidInputError, LynxsimError
from lynxsim.sim.render import Overlay, RenderSettings, SceneRenderer, camera_names

__all__ = ["RENDER_MODES", "EnvRenderer", "PixelRenderer", "check_frame", "has_display"]

RENDER_MODES = ("human", "rgb_array")

_gl_pid: int | None = None
"""Process in which a renderer of this module made a GL context (a fork inherits it)."""


def has_display() -> bool:
    """Whether a display server is named in the environment (X11 or Wayland)."""
    return bool(os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY"))


def check_frame(model: mujoco.MjModel, settings: RenderSettings) -> None:
    """Refuse a frame larger than the model's off-screen buffer or an unknown camera.

    An env checks its frames at construction, so that a bad argument fails
    where it is given and not at the first ``render()``.

    Raises:
        InvalidInputError: The frame exceeds the buffer, or the camera is not the model's.
    """
    buf_w, buf_h = int(model.vis.global_.offwidth), int(model.vis.global_.offheight)
    if settings.width > buf_w or settings.height > buf_h:
        raise InvalidInputError(
            f"frame {settings.width}x{settings.height} exceeds the model's off-screen buffer "
            f"{buf_w}x{buf_h} px"
        )
    if mujoco.mj_name2id(model, int(mujoco.mjtObj.mjOBJ_CAMERA), settings.camera) < 0:
        names = ", ".join(camera_names(model))
        raise InvalidInputError(f"no camera named {settings.camera!r}; cameras: {names}")


def _scene_renderer(model: mujoco.MjModel, settings: RenderSettings) -> SceneRenderer:
    """A new renderer (and GL context) in this process, unless it was forked after one was made.

    Raises:
        LynxsimError: This process was forked after its parent made a GL context.
    """
    global _gl_pid
    if _gl_pid is not None and _gl_pid != os.getpid():
        raise LynxsimError(
            "cannot render in a process forked after its parent created a GL context; "
            "make async vector envs with vector_kwargs={'context': 'forkserver'} (or "
            "'spawn'), or render in the parent only after forking"
        )
    scene = SceneRenderer(model, settings)
    _gl_pid = os.getpid()
    return scene


class EnvRenderer:
    """The rendering of one env.

    Args:
        model: The env's model.
        render_mode: None, ``"rgb_array"`` or ``"human"``.
        settings: Frame size, camera and quality of ``rgb_array`` frames.

    Raises:
        InvalidInputError: An unknown mode, or ``"human"`` without a display.
    """

    def __init__(
        self, model: mujoco.MjModel, render_mode: str | None, settings: RenderSettings
    ) -> None:
        if render_mode is not None and render_mode not in RENDER_MODES:
            raise InvalidInputError(
                f"render_mode must be None or one of {list(RENDER_MODES)}, got {render_mode!r}"
            )
        if render_mode == "human" and not has_display():
            raise InvalidInputError(
                "render_mode='human' needs a display (DISPLAY or WAYLAND_DISPLAY); "
                "use render_mode='rgb_array' off-screen"
            )
        self._model = model
        self.mode = render_mode
        self.settings = settings
        self._scene: SceneRenderer | None = None
        self._viewer: Any = None

    def __getstate__(self) -> dict[str, Any]:
        """State for pickling: without the GL context or window (made again on the next frame).

        A GL context belongs to the process (and thread) that made it and cannot
        be pickled; copies of an env (``copy.deepcopy``, ``pickle``, a vector env's
        workers) render with their own, made lazily like the first one.
        """
        state = self.__dict__.copy()
        state["_scene"] = None
        state["_viewer"] = None
        return state

    @property
    def started(self) -> bool:
        """Whether a GL context or window exists."""
        return self._scene is not None or self._viewer is not None

    def render(self, data: mujoco.MjData, goal: npt.NDArray[np.float64]) -> Any:
        """A frame (``rgb_array``: (height, width, 3) uint8, goal marked), or None."""
        if self.mode == "rgb_array":
            if self._scene is None:
                self._scene = _scene_renderer(self._model, self.settings)
            return self._scene.render(data, Overlay(targets=goal.reshape(1, 3)))
        if self.mode == "human":
            if self._viewer is None:
                import mujoco.viewer

                self._viewer = mujoco.viewer.launch_passive(self._model, data)
            self._viewer.sync()
        return None

    def close(self) -> None:
        """Free the GL context and close the window, if any (idempotent)."""
        if self._scene is not None:
            self._scene.close()
            self._scene = None
        if self._viewer is not None:
            self._viewer.close()
            self._viewer = None


class PixelRenderer:
    """Image observations: the frames of some cameras, side by side along the channels.

    One :class:`~lynxsim.sim.render.SceneRenderer` (GL context) per camera, apart
    from :class:`EnvRenderer`'s, made at the first frame in the process that asks
    for it. Sites are not drawn (the goal mark would contradict a relabelled goal)
    and nothing is overlaid: a frame shows the arm, the table, the cube and the
    obstacles only.

    Args:
        model: The env's model.
        settings: One per camera, in order: size, camera and quality of its frames.
    """

    def __init__(self, model: mujoco.MjModel, settings: tuple[RenderSettings, ...]) -> None:
        self._model = model
        self.settings = settings
        self._scenes: list[SceneRenderer] = []

    def __getstate__(self) -> dict[str, Any]:
        """State for pickling: without the GL contexts (made again on the next frame)."""
        state = self.__dict__.copy()
        state["_scenes"] = []
        return state

    @property
    def started(self) -> bool:
        """Whether the GL contexts exist."""
        return bool(self._scenes)

    def render(self, data: mujoco.MjData) -> npt.NDArray[np.uint8]:
        """The frames of ``data``, shape (height, width, 3 * cameras), uint8, a new array.

        Channels ``3k:3k+3`` are the RGB frame of camera ``k``.
        """
        if not self._scenes:
            self._scenes = [_scene_renderer(self._model, s) for s in self.settings]
        if len(self._scenes) == 1:
            return self._scenes[0].render(data)
        return np.concatenate([scene.render(data) for scene in self._scenes], axis=2)

    def close(self) -> None:
        """Free the GL contexts, if any (idempotent)."""
        for scene in self._scenes:
            scene.close()
        self._scenes = []
