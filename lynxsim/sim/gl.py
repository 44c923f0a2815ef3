"""Choosing MuJoCo's OpenGL backend before ``mujoco`` is imported.

MuJoCo reads ``MUJOCO_GL`` once, when the ``mujoco`` module is first imported.
lynxsim defaults it to ``egl`` (off-screen; GPU where one exists, Mesa on the
CPU otherwise) when no display is present, and never overrides a user's choice.
"""

from __future__ import annotations

import os

__all__ = ["default_gl_backend"]


def default_gl_backend() -> str:
    """Set ``MUJOCO_GL=egl`` if it is unset and no display exists; return the value."""
    if "MUJOCO_GL" not in os.environ and not (
        os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY")
    ):
        os.environ["MUJOCO_GL"] = "egl"
    return os.environ.get("MUJOCO_GL", "")
