"""Reading a LeRobot v3.0 dataset back with pyarrow, and checking that it is whole.

:func:`read_lerobot` loads the frames and the episodes' metadata of a dataset
written by :class:`~lynxsim.datasets.lerobot_writer.LeRobotWriter` (or any v3.0
dataset of numeric features); :func:`check_lerobot` is what the writer runs
before the dataset's folder is renamed into place: every file named by the
metadata reads, the counts agree, frames are indexed without a gap, each
episode's rows are where its metadata says, and every video decodes to the
frames of its episodes.
"""

from __future__ import annotations

import json
import os
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt

from lynxsim.datasets.lerobot_meta import EPISODES_PATH, INFO_PATH
from lynxsim.errors import InvalidInputError, LynxsimError, VideoError

__all__ = ["LeRobotData", "check_lerobot", "read_lerobot"]


@dataclass(frozen=True)
class LeRobotData:
    """A dataset as read back.

    Attributes:
        info: ``meta/info.json``.
        frames: Every parquet column of the frames (``image`` columns: PNG bytes
            per frame), over all episodes in order: shape (N, *shape).
        episodes: The columns of ``meta/episodes`` (``stats/...`` left out),
            one entry per episode.
    """

    info: dict[str, Any]
    frames: dict[str, npt.NDArray[Any]]
    episodes: dict[str, list[Any]]


def _files(folder: Path, template: str, pairs: set[tuple[int, int]], **kw: str) -> list[Path]:
    return [folder / template.format(chunk_index=c, file_index=f, **kw) for c, f in sorted(pairs)]


def _column(column: Any) -> npt.NDArray[Any]:
    """A pyarrow column as a NumPy array (N, *shape), or a list of PNG bytes for images."""
    import pyarrow as pa

    kind = column.type
    if pa.types.is_struct(kind):
        return np.array([v["bytes"] for v in column.to_pylist()], dtype=object)
    if pa.types.is_fixed_size_list(kind):
        flat = column.combine_chunks().flatten().to_numpy(zero_copy_only=False)
        return np.asarray(flat).reshape(len(column), kind.list_size)
    return np.asarray(column.to_numpy())


def read_lerobot(folder: str | os.PathLike[str]) -> LeRobotData:
    """The frames and episodes of a LeRobot v3.0 dataset.

    Raises:
        MissingExtraError: pyarrow is not installed.
        InvalidInputError: Not a LeRobot v3.0 dataset (a file missing or unreadable).
    """
    from lynxsim.datasets.lerobot_writer import require_pyarrow

    require_pyarrow()
    import pyarrow as pa
    import pyarrow.parquet as pq

    folder = Path(folder)
    try:
        info = json.loads((folder / INFO_PATH).read_text(encoding="utf-8"))
        meta_files = sorted((folder / EPISODES_PATH).parent.parent.glob("chunk-*/file-*.parquet"))
        if not meta_files:
            raise FileNotFoundError(f"no episodes metadata in {folder / 'meta/episodes'}")
        meta = pa.concat_tables([pq.read_table(p) for p in meta_files])
        keep = [n for n in meta.column_names if not n.startswith("stats/")]
        episodes = {n: meta.column(n).to_pylist() for n in keep}
        groups = set(zip(episodes["data/chunk_index"], episodes["data/file_index"], strict=True))
        tables = [pq.read_table(p) for p in _files(folder, info["data_path"], groups)]
        data = pa.concat_tables(tables)
        frames = {n: _column(data.column(n)) for n in data.column_names}
    except (OSError, ValueError, KeyError, TypeError, pa.ArrowException) as exc:
        raise InvalidInputError(f"{folder} is not a LeRobot v3.0 dataset: {exc}") from None
    return LeRobotData(info, frames, episodes)


def check_lerobot(folder: Path) -> LeRobotData:
    """Read the dataset back and check it is whole and consistent.

    Returns:
        The :class:`LeRobotData`.

    Raises:
        LynxsimError: A file is missing or unreadable, or the counts, indices or
            videos disagree with the metadata.
    """
    from lynxsim.sim.video import decoded_frames

    try:
        data = read_lerobot(folder)
    except InvalidInputError as exc:
        raise LynxsimError(f"the dataset written does not read back: {exc}") from None
    info, frames, episodes = data.info, data.frames, data.episodes
    n = len(frames["index"])
    lengths = np.asarray(episodes["length"], dtype=np.int64)
    starts = np.asarray(episodes["dataset_from_index"], dtype=np.int64)
    problems = []
    if (info["total_frames"], info["total_episodes"]) != (n, len(lengths)) or lengths.sum() != n:
        problems.append(f"{n} frames and {len(lengths)} episodes against info.json's")
    if not np.array_equal(frames["index"], np.arange(n)):
        problems.append("the frames' index is not 0, 1, ...")
    expected_episode = np.repeat(np.arange(len(lengths)), lengths)
    if not np.array_equal(frames["episode_index"], expected_episode) or not np.array_equal(
        starts, np.concatenate([[0], np.cumsum(lengths)[:-1]])
    ):
        problems.append("episode boundaries differ from meta/episodes")
    for key, feature in info["features"].items():
        if feature["dtype"] != "video":
            continue
        by_file: dict[tuple[int, int], int] = {}
        for c, f, length in zip(
            episodes[f"videos/{key}/chunk_index"],
            episodes[f"videos/{key}/file_index"],
            lengths,
            strict=True,
        ):
            by_file[(c, f)] = by_file.get((c, f), 0) + int(length)
        for (c, f), count in sorted(by_file.items()):
            path = folder / info["video_path"].format(video_key=key, chunk_index=c, file_index=f)
            try:
                got = decoded_frames(path)
            except VideoError as exc:
                problems.append(str(exc))
                continue
            if got != count:
                problems.append(f"{path.name} of {key} decodes to {got} frames, not {count}")
    if problems:
        raise LynxsimError(
            f"the dataset written in {folder} is inconsistent: {'; '.join(problems)}"
        )
    return data
