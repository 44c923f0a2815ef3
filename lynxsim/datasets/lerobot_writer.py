"""LeRobot's dataset format, v3.0, written with pyarrow (extra ``lynxsim[datasets]``), not lerobot.

The layout of ``LeRobotDataset`` (``CODEBASE_VERSION = "v3.0"``), in the dataset's folder::

    meta/info.json                                   codebase_version, fps, counts, paths, features
    meta/stats.json                                  per feature: min, max, mean, std, count, q01..
    meta/tasks.parquet                               the task's text (pandas index) and task_index
    meta/episodes/chunk-000/file-000.parquet         one row per episode: length, file indices,
                                                     frame range, video times, stats/...
    data/chunk-000/file-000.parquet                  one row per frame (one row group per episode)
    videos/observation.images.CAM/chunk-000/file-000.mp4   the frames of CAM, episode after episode
    meta/lynxsim.json                                lynxsim's metadata (env spec, noise, seeds)

A frame is a step: observation ``t``, the action taken there, and what the step
returned. Per frame (``T`` per episode: the final observation is not a frame)::

    observation.state              float32 (n_obs,)  the env's observation, named by its slices
    observation.environment_state  float32 (6,)      achieved_goal then desired_goal [m]
    observation.images.CAM         video (or image) (H, W, 3)  camera CAM, with --images
    action                         float32 (n_act,)  as stepped (noise included)
    expert_action                  float32 (n_act,)  the expert's action before the noise
    next.reward                    float32           the step's reward
    next.done                      bool              terminated or truncated
    next.terminated                bool
    next.success                   bool              info["is_success"] after the step
    next.collision                 bool              info["collision"] after the step
    timestamp                      float32 [s]       frame_index / fps
    frame_index, episode_index, index, task_index    int64

Files hold whole episodes; a new data file (and video files) starts when the
next episode would take the data file past ``data_files_size_in_mb``
(uncompressed) or the raw frames of a video past
:data:`~lynxsim.datasets.lerobot_meta.RAW_VIDEO_BYTES` (the layout's limits).
Videos are H.264 at CRF 15 by lynxsim's encoder, at the images' own size and
full colour resolution (yuv444p: at 32 x 32 px, yuv420p's half-resolution
colour moved a pixel's red and blue by 5 to 9 levels on average); without
videos the images are PNG inside the parquet files (LeRobot's ``image`` dtype,
lossless). Parquet is written with fixed options
and no timestamps, videos by a deterministic encoder: the same episodes give the
same bytes. :meth:`LeRobotWriter.finish` reads everything back
(:func:`~lynxsim.datasets.lerobot_check.check_lerobot`).
"""

from __future__ import annotations

import contextlib
from pathlib import Path
from types import ModuleType, TracebackType
from typing import Any

import numpy as np
import numpy.typing as npt

from lynxsim.datasets.episode import Episode
from lynxsim.datasets.lerobot_meta import (
    DATA_PATH,
    EPISODES_PATH,
    VIDEO_PATH,
    LeRobotLayout,
    write_meta,
)
from lynxsim.datasets.lerobot_stats import RunningStats, Stats, feature_stats, image_stats
from lynxsim.datasets.minari_writer import MissingExtraError
from lynxsim.sim.video import FrameSink, mp4_writer

__all__ = ["LeRobotWriter", "require_pyarrow"]


def require_pyarrow() -> ModuleType:
    """The ``pyarrow`` module.

    Raises:
        MissingExtraError: pyarrow is not installed.
    """
    try:
        import pyarrow
        import pyarrow.parquet
    except ImportError as exc:
        raise MissingExtraError(
            f"the LeRobot format needs the 'datasets' extra: pip install 'lynxsim[datasets]' "
            f"(or use --format npz) [{exc}]"
        ) from None
    module: ModuleType = pyarrow
    return module


def _png(frame: npt.NDArray[np.uint8]) -> bytes:
    import imageio.v3 as iio

    data: bytes = iio.imwrite("<bytes>", frame, extension=".png")
    return data


class LeRobotWriter:
    """Writes episodes into ``folder`` as a LeRobot v3.0 dataset, one by one.

    Use as a context manager; :meth:`finish` completes and checks the dataset.
    Memory holds one episode, and the current episodes-metadata file's rows.

    Args:
        folder: An existing, empty folder (the temporary one of
            :func:`~lynxsim.fileio.atomic_folder`).
        layout: The features and limits (:meth:`LeRobotLayout.of_env` of the
            env the episodes come from).

    Raises:
        MissingExtraError: pyarrow is not installed.
    """

    def __init__(self, folder: Path, layout: LeRobotLayout) -> None:
        self._pa = require_pyarrow()
        self._folder = folder
        self.layout = layout
        self._stats = {key: RunningStats() for key in self.layout.features}
        self._group: tuple[int, int] = (0, 0)  # (chunk, file) of the current data/video files
        self._group_bytes = 0
        self._group_frames = 0
        self._group_raw = 0
        self._data: Any = None  # the current data file's pyarrow.parquet.ParquetWriter
        self._videos: dict[str, FrameSink] = {}
        self._video_stack = contextlib.ExitStack()
        self._meta_rows: list[Any] = []  # pyarrow tables of one row, the current episodes file
        self._meta_bytes = 0
        self._meta_group = (0, 0)
        self.episodes = 0
        self.frames = 0

    def __enter__(self) -> LeRobotWriter:
        return self

    def __exit__(
        self,
        kind: type[BaseException] | None,
        exc: BaseException | None,
        tb: TracebackType | None,
    ) -> None:
        """Close the files; on an error, stop the encoders at once (the folder is then removed)."""
        try:
            if self._data is not None:
                with contextlib.suppress(OSError) if kind is not None else contextlib.nullcontext():
                    self._data.close()  # a full disk after another error: the first one stands
                self._data = None
        finally:
            self._video_stack.__exit__(kind, exc, tb)  # the encoders see the error and abort

    def _next(self, group: tuple[int, int]) -> tuple[int, int]:
        chunk, file = group
        return (chunk + 1, 0) if file == self.layout.chunks_size - 1 else (chunk, file + 1)

    def _path(self, template: str, group: tuple[int, int], **kw: str) -> Path:
        path = self._folder / template.format(chunk_index=group[0], file_index=group[1], **kw)
        path.parent.mkdir(parents=True, exist_ok=True)
        return path

    def _close_group(self) -> None:
        self._video_stack.close()  # waits for the encoders; each file is checked by decoding
        self._videos = {}
        if self._data is not None:
            self._data.close()
            self._data = None

    def add(self, episode: Episode) -> None:
        """Append an episode.

        Raises:
            InvalidInputError: An episode whose arrays do not fit the env's spaces.
            VideoError: The video encoder failed (a full disk).
        """
        layout, steps = self.layout, episode.steps
        columns, images = layout.frame_columns(episode, self.episodes, self.frames)
        stats = {key: feature_stats(values) for key, values in columns.items()}
        stats |= {key: image_stats(frames) for key, frames in images.items()}
        arrays = {key: layout.column(self._pa, key, values) for key, values in columns.items()}
        if not layout.videos:
            for key, frames in images.items():
                arrays[key] = layout.column(self._pa, key, [_png(f) for f in frames])
        table = self._pa.table({key: arrays[key] for key in layout.features if key in arrays})
        raw = sum(f.nbytes for f in images.values()) if layout.videos else 0
        if self._group_frames and (
            self._group_bytes + table.nbytes > layout.file_bytes
            or self._group_raw + raw > layout.raw_video_bytes * len(images)
        ):
            self._close_group()
            self._group = self._next(self._group)
            self._group_bytes = self._group_frames = self._group_raw = 0
        if self._data is None:
            import pyarrow.parquet as pq

            path = self._path(DATA_PATH, self._group)
            self._data = pq.ParquetWriter(path, table.schema, **layout.parquet_options)
        self._data.write_table(table, row_group_size=steps)  # one row group per episode
        times: dict[str, tuple[float, float]] = {}
        if layout.videos:
            for key, frames in images.items():
                if key not in self._videos:
                    path = self._path(VIDEO_PATH, self._group, video_key=key)
                    self._videos[key] = self._video_stack.enter_context(
                        mp4_writer(path, layout.fps, exact=True)
                    )
                for frame in frames:
                    self._videos[key].append_data(frame)
                start = self._group_frames / layout.fps
                times[key] = (start, start + steps / layout.fps)
        for key, s in stats.items():
            self._stats[key].add(s)
        self._add_meta_row(episode.steps, stats, times)
        self._group_bytes += table.nbytes
        self._group_raw += raw
        self._group_frames += steps
        self.episodes += 1
        self.frames += steps

    def _add_meta_row(
        self, length: int, stats: dict[str, Stats], times: dict[str, tuple[float, float]]
    ) -> None:
        def row() -> Any:
            return self.layout.episode_row(
                self._pa,
                index=self.episodes,
                length=length,
                data_file=self._group,
                first_frame=self.frames,
                video_times=times,
                stats=stats,
                meta_file=self._meta_group,
            )

        table = row()
        if self._meta_rows and self._meta_bytes + table.nbytes > self.layout.file_bytes:
            self._write_meta_file()
            self._meta_group = self._next(self._meta_group)
            table = row()  # it names its own file
        self._meta_rows.append(table)
        self._meta_bytes += table.nbytes

    def _write_meta_file(self) -> None:
        import pyarrow.parquet as pq

        table = self._pa.concat_tables(self._meta_rows)
        path = self._path(EPISODES_PATH, self._meta_group)
        pq.write_table(table, path, **self.layout.parquet_options)
        self._meta_rows = []
        self._meta_bytes = 0

    def finish(self, metadata: dict[str, Any]) -> None:
        """Close the files, write the metadata, and check the dataset reads back whole.

        Args:
            metadata: lynxsim's metadata, written to ``meta/lynxsim.json``.

        Raises:
            LynxsimError: A file does not read back as written.
        """
        from lynxsim.datasets.lerobot_check import check_lerobot

        self._close_group()
        if self._meta_rows:
            self._write_meta_file()
        stats = {k: s.stats for k, s in self._stats.items() if s.stats is not None}
        write_meta(self._pa, self._folder, self.layout, self.episodes, self.frames, stats, metadata)
        check_lerobot(self._folder)
