"""MP4 output: H.264 in yuv420p by an ffmpeg process, written atomically and proven.

Frames are copied into a few reused buffers and handed to a writer thread that
pipes them to ffmpeg (libx264 in its own process), so the caller renders the
next frame while the last one is written and encoded. The file is encoded under
a temporary name, then decoded again by ffmpeg and its frames counted; only when
the encoder exited cleanly and the count matches the frames given is it renamed
into place. Anything else (a full disk, a killed encoder, an interrupt) stops the
encoder, removes the temporary file and leaves the destination as it was.
"""

from __future__ import annotations

import contextlib
import os
import queue
import re
import signal
import subprocess
import tempfile
import threading
from collections.abc import Iterator
from fractions import Fraction
from pathlib import Path
from typing import IO, Protocol, cast

import imageio_ffmpeg
import numpy as np
import numpy.typing as npt

from lynxsim.bounds import MAX_FPS, MIN_FPS, check_range
from lynxsim.errors import InvalidInputError, VideoError
from lynxsim.fileio import atomic_path, check_destination

__all__ = ["FrameSink", "decoded_frames", "mp4_writer"]

Frame = npt.NDArray[np.uint8]

_PRESET = "veryfast"
"""x264 speed preset: 3.2 ms of CPU a 640x480 frame against 6.0 ms for ffmpeg's
"medium", files no larger at the same CRF (measured on the arm's videos)."""
_CRF = 15
"""x264 constant rate factor (0 lossless .. 51): visually lossless."""
_BUFFERS = 4
"""Frame buffers in flight between the caller and the writer thread."""
_MACRO_BLOCK_PX = 16
"""Frames are scaled up to a multiple of this (H.264 players expect whole macroblocks)."""


class FrameSink(Protocol):
    """Anything that accepts RGB frames of shape (H, W, 3), uint8."""

    def append_data(self, im: Frame) -> None:
        """Add one frame (copied: the caller may reuse ``im`` at once)."""


_FFMPEG_TAG = re.compile(r"^(\[[^\]]*\]\s*)+")
"""ffmpeg's ``[out#0/mp4 @ 0x55d0...]`` prefixes: its internals, not the user's concern."""


def _last_line(stream: IO[bytes]) -> str:
    stream.seek(0)
    lines = stream.read().decode(errors="replace").strip().splitlines()
    return _FFMPEG_TAG.sub("", lines[-1]).strip() if lines else ""


def _exit_reason(code: int, message: str) -> str:
    """Why ffmpeg ended with ``code``, in words: its last message, or the signal that ended it."""
    if code < 0:
        if -code == getattr(signal, "SIGXFSZ", None):
            return "File too large (the file size limit was reached)"
        try:
            name = signal.Signals(-code).name
        except ValueError:
            name = f"signal {-code}"
        return message or f"the encoder was killed by {name}"
    return message or f"the encoder failed (exit status {code})"


class _Encoder:
    """An ffmpeg process fed by a writer thread; started by the first frame (which sets the size).

    Args:
        path: The MP4 to write.
        fps: Frame rate [1/s].
        log: File receiving ffmpeg's messages (read back when it fails).
        exact: Keep the frames' size and full colour resolution (yuv444p), else
            scale them up to whole macroblocks and halve the colour planes (yuv420p).
        dest: The file the user asked for, named in errors (``path`` is its
            temporary name); default ``path``.
    """

    def __init__(
        self, path: Path, fps: float, log: IO[bytes], exact: bool = False, dest: Path | None = None
    ) -> None:
        self._path = path
        self._dest = path if dest is None else dest
        self._fps = fps
        self._log = log
        self._exact = exact
        self._proc: subprocess.Popen[bytes] | None = None
        self._thread: threading.Thread | None = None
        self._todo: queue.SimpleQueue[Frame | None] = queue.SimpleQueue()
        self._free: queue.SimpleQueue[Frame] = queue.SimpleQueue()
        self._failure: OSError | None = None
        self._shape: tuple[int, ...] | None = None
        self.frames = 0

    def append_data(self, im: Frame) -> None:
        frame = np.asarray(im)
        if frame.dtype != np.uint8 or frame.ndim != 3 or frame.shape[2] != 3 or 0 in frame.shape:
            raise InvalidInputError(
                f"a video frame must be (height, width, 3) uint8, got {frame.shape} {frame.dtype}"
            )
        if self._shape is None:
            self._start(frame.shape)
        elif frame.shape != self._shape:
            raise InvalidInputError(
                f"every frame of a video must have one size: {self._shape}, then {frame.shape}"
            )
        self._check()
        buffer = self._free.get()
        np.copyto(buffer, frame)
        self._todo.put(buffer)
        self.frames += 1

    def _start(self, shape: tuple[int, ...]) -> None:
        height, width = shape[0], shape[1]
        cmd = [imageio_ffmpeg.get_ffmpeg_exe(), "-y", "-nostdin", "-loglevel", "error"]
        cmd += ["-f", "rawvideo", "-pix_fmt", "rgb24", "-s", f"{width}x{height}"]
        cmd += ["-r", str(Fraction(self._fps).limit_denominator()), "-i", "pipe:0", "-an"]
        pix_fmt = "yuv444p" if self._exact else "yuv420p"
        cmd += ["-c:v", "libx264", "-preset", _PRESET, "-crf", str(_CRF), "-pix_fmt", pix_fmt]
        padded = [-(-side // _MACRO_BLOCK_PX) * _MACRO_BLOCK_PX for side in (width, height)]
        if not self._exact and padded != [width, height]:
            cmd += ["-vf", f"scale={padded[0]}:{padded[1]}"]
        cmd += ["-f", "mp4", str(self._path)]
        # A session of its own: Ctrl-C reaches lynxsim, which stops the encoder itself.
        self._proc = subprocess.Popen(
            cmd,
            stdin=subprocess.PIPE,
            stdout=subprocess.DEVNULL,
            stderr=self._log,
            start_new_session=True,
        )
        self._shape = shape
        for _ in range(_BUFFERS):
            self._free.put(np.empty(shape, dtype=np.uint8))
        pipe = cast("IO[bytes]", self._proc.stdin)  # stdin=PIPE: never None
        self._thread = threading.Thread(
            target=self._write_all, args=(pipe,), name="mp4-writer", daemon=True
        )
        self._thread.start()

    def _write_all(self, pipe: IO[bytes]) -> None:
        """The writer thread: pipe queued frames to ffmpeg until None arrives."""
        while (buffer := self._todo.get()) is not None:
            if self._failure is None:
                try:
                    pipe.write(buffer.data)
                except OSError as exc:  # the encoder died: disk full, killed
                    self._failure = exc
            self._free.put(buffer)

    def _check(self) -> None:
        if self._failure is not None:
            raise VideoError(f"cannot write {self._dest}: {self._failure_message()}")

    def _failure_message(self) -> str:
        if self._proc is not None and (code := self._proc.poll()) is not None:
            return _exit_reason(code, _last_line(self._log))
        failure = self._failure
        if isinstance(failure, OSError) and failure.errno:
            return os.strerror(failure.errno)
        return f"the encoder stopped ({failure})"

    def _stop_thread(self) -> None:
        if self._thread is not None:
            self._todo.put(None)
            self._thread.join()
            self._thread = None

    def finish(self) -> None:
        """Write the queued frames and wait for ffmpeg to complete the file.

        Raises:
            VideoError: A write failed or ffmpeg exited with an error.
        """
        if self._proc is None or self._proc.stdin is None:
            return
        self._stop_thread()
        try:
            self._proc.stdin.close()
        except OSError as exc:
            self._failure = self._failure or exc
        code = self._proc.wait()
        if code != 0:
            raise VideoError(
                f"cannot write {self._dest}: {_exit_reason(code, _last_line(self._log))}"
            )
        self._check()

    def abort(self) -> None:
        """Stop ffmpeg at once; the file it was writing is abandoned."""
        if self._proc is None:
            return
        self._proc.kill()
        self._stop_thread()  # the writer sees a broken pipe and drains the queue
        with contextlib.suppress(OSError):
            if self._proc.stdin is not None:
                self._proc.stdin.close()
        self._proc.wait()


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
def mp4_writer(
    dest: str | os.PathLike[str], fps: float, *, exact: bool = False
) -> Iterator[FrameSink]:
    """Open an MP4 writer; the file appears at ``dest`` only when complete and decodable.

    Frames are encoded while the caller goes on (a writer thread feeds ffmpeg);
    leaving the ``with`` block waits for the last of them.

    Args:
        dest: Output path ending in ``.mp4``.
        fps: Frames per second (video time is real time at this rate), in
            [:data:`~lynxsim.bounds.MIN_FPS`, :data:`~lynxsim.bounds.MAX_FPS`].
        exact: For videos whose frames are data (datasets): keep each frame's
            size (any) and full colour resolution (H.264 High 4:4:4, yuv444p;
            decoders such as FFmpeg's read it, some players do not). Else (the
            default, for watching) frames are scaled up to a multiple of 16 px
            (whole macroblocks) and stored in yuv420p, as players expect.

    Raises:
        InvalidInputError: ``fps`` out of range, ``dest`` not an .mp4, or a frame
            that is not (H, W, 3) uint8 or not the size of the first.
        OutputPathError: ``dest`` exists and is not a regular file.
        VideoError: The encoder failed (e.g. the disk is full) or the written
            file does not decode to the frames given; ``dest`` is left as it was.
    """
    dest = Path(dest)
    if dest.suffix.lower() != ".mp4":
        raise InvalidInputError(f"video path must end in .mp4, got {dest}")
    fps = check_range(fps, "fps", MIN_FPS, MAX_FPS, "frames/s")
    check_destination(dest)
    with atomic_path(dest) as tmp, tempfile.TemporaryFile() as log:
        encoder = _Encoder(tmp, fps, log, exact, dest=dest)
        try:
            yield encoder
            if encoder.frames == 0:
                raise VideoError(f"{dest}: no frames were written")
            encoder.finish()
        except BaseException:
            encoder.abort()
            raise
        got = decoded_frames(tmp)
        if got != encoder.frames:
            raise VideoError(
                f"{dest}: the encoded file decodes to {got} frames, {encoder.frames} were written"
            )
