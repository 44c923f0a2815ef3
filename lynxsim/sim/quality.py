"""Rendering presets, apart from the renderer: the command line lists them without MuJoCo."""

from __future__ import annotations

import enum

__all__ = ["Quality"]


class Quality(enum.Enum):
    """Rendering presets (CPU time of a 640x480 arm frame with Mesa's llvmpipe, 2 cores).

    LEAN: for small observation images: FAST without skybox, fog, haze and the
        floor (infinite planes are not drawn: the background is black), and with
        the built-in shapes tessellated coarsely (8 slices, 4 stacks, one quad per
        plane face); ~0.25 ms for an 84x84 frame (FAST: ~4.8 ms; the floor was
        2.7 ms of LEAN's 3.0 ms).
    FAST: no shadows, no multisampling (~21 ms).
    MEDIUM: shadows, no multisampling (~64 ms): the look of DEFAULT with jagged edges.
    DEFAULT: shadows and the model's multisampling (~125 ms).
    """

    LEAN = "lean"
    FAST = "fast"
    MEDIUM = "medium"
    DEFAULT = "default"
