"""MP4 output: H.264 in yuv420p through imageio-ffmpeg, written atomically."""

from __future__ import annotations

import contextlib
import os
from collections.abc import Iterator
from pathlib import Path
from typing import Protocol

import imageio.v2 as imageio
import numpy as np
import numpy.typing as npt

from lynxsim.errors import InvalidInputError
from lynxsim.fileio import atomic_path

__all__ = ["FrameSink", "mp4_writer"]


class FrameSink(Protocol):
    """Anything that accepts RGB frames of shape (H, W, 3), uint8."""

    def append_data(self, im: npt.NDArray[np.uint8]) -> None:
        """Add one frame."""


@contextlib.contextmanager
def mp4_writer(dest: str | os.PathLike[str], fps: float) -> Iterator[FrameSink]:
    """Open an MP4 writer; the file appears at ``dest`` only when complete.

    Args:
        dest: Output path ending in ``.mp4``.
        fps: Frames per second (video time is real time at this rate).

    Raises:
        InvalidInputError: If ``fps`` is not positive or ``dest`` is not an .mp4.
    """
    dest = Path(dest)
    if dest.suffix.lower() != ".mp4":
        raise InvalidInputError(f"video path must end in .mp4, got {dest}")
    if not fps > 0:
        raise InvalidInputError(f"fps must be positive, got {fps}")
    with atomic_path(dest) as tmp:
        writer = imageio.get_writer(
            tmp,
            format="FFMPEG",
            fps=fps,
            codec="libx264",
            pixelformat="yuv420p",
            quality=7,
            macro_block_size=16,
            ffmpeg_log_level="error",
        )
        try:
            yield writer
        finally:
            writer.close()
