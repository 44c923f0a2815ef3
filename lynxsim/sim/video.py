"""MP4 output: H.264 in yuv420p through imageio-ffmpeg, written atomically and proven.

The file is encoded under a temporary name, then decoded again by ffmpeg and its
frames counted; only when the encoder reported success and the count matches the
frames given is it renamed into place. Anything else (a full disk, a killed
encoder, an interrupt) removes the temporary file and leaves the destination as
it was.
"""

from __future__ import annotations

import contextlib
import os
from collections.abc import Iterator
from pathlib import Path
from typing import Any, Protocol

import imageio.v2 as imageio
import imageio_ffmpeg
import numpy as np
import numpy.typing as npt

from lynxsim.bounds import MAX_FPS, MIN_FPS, check_range
from lynxsim.errors import InvalidInputError, VideoError
from lynxsim.fileio import atomic_path, check_destination

__all__ = ["FrameSink", "decoded_frames", "mp4_writer"]


class FrameSink(Protocol):
    """Anything that accepts RGB frames of shape (H, W, 3), uint8."""

    def append_data(self, im: npt.NDArray[np.uint8]) -> None:
        """Add one frame."""


class _CountingWriter:
    """An imageio writer that counts the frames it was given."""

    def __init__(self, writer: Any) -> None:
        self._writer = writer
        self.frames = 0

    def append_data(self, im: npt.NDArray[np.uint8]) -> None:
        try:
            self._writer.append_data(im)
        except (OSError, RuntimeError) as exc:  # the encoder died: disk full, killed
            raise VideoError(f"the video encoder stopped: {exc}") from None
        self.frames += 1


def decoded_frames(path: str | os.PathLike[str]) -> int:
    """Number of video frames ffmpeg decodes from ``path``.

    Raises:
        VideoError: ffmpeg cannot read the file (truncated, not a video).
    """
    try:
        frames, _ = imageio_ffmpeg.count_frames_and_secs(str(path))
    except (RuntimeError, ValueError, TypeError) as exc:
        last = str(exc).strip().splitlines()[-1:] or [""]
        raise VideoError(f"{path} does not decode: {last[0]}") from None
    return int(frames)


@contextlib.contextmanager
def mp4_writer(dest: str | os.PathLike[str], fps: float) -> Iterator[FrameSink]:
    """Open an MP4 writer; the file appears at ``dest`` only when complete and decodable.

    Args:
        dest: Output path ending in ``.mp4``.
        fps: Frames per second (video time is real time at this rate), in
            [:data:`~lynxsim.bounds.MIN_FPS`, :data:`~lynxsim.bounds.MAX_FPS`].

    Raises:
        InvalidInputError: ``fps`` out of range or ``dest`` not an .mp4.
        OutputPathError: ``dest`` exists and is not a regular file.
        VideoError: The encoder failed (e.g. the disk is full) or the written
            file does not decode to the frames given; ``dest`` is left as it was.
    """
    dest = Path(dest)
    if dest.suffix.lower() != ".mp4":
        raise InvalidInputError(f"video path must end in .mp4, got {dest}")
    fps = check_range(fps, "fps", MIN_FPS, MAX_FPS, "frames/s")
    check_destination(dest)
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
        counting = _CountingWriter(writer)
        try:
            yield counting
        except BaseException:
            _close_quietly(writer)
            raise
        try:
            writer.close()
        except (OSError, RuntimeError, ValueError) as exc:
            raise VideoError(f"the video encoder failed writing {dest}: {exc}") from None
        if counting.frames == 0:
            raise VideoError(f"{dest}: no frames were written")
        got = decoded_frames(tmp)
        if got != counting.frames:
            raise VideoError(
                f"{dest}: the encoded file decodes to {got} frames, {counting.frames} were written"
            )


def _close_quietly(writer: Any) -> None:
    """Close a writer whose file is being abandoned; its own errors are beside the point."""
    with contextlib.suppress(Exception):
        writer.close()
