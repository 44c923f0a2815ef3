"""LeRobotDataset v3.0's documented layout, checked with pyarrow and ffmpeg alone (no lynxsim code).

Written from LeRobot's ``lerobot/datasets`` (``CODEBASE_VERSION = "v3.0"``, the
default paths and features of ``utils.py``, the info.json of
``create_empty_dataset_info``, the per-episode metadata that
``LeRobotDatasetMetadata.save_episode`` writes, the statistics of
``compute_stats.py`` and how ``aggregate_stats`` merges them, ``datasets``'s
arrow types of each feature), so that a writer that got a detail wrong fails
here. :func:`validate` returns what it read, for further checks.
"""

from __future__ import annotations

import itertools
import json
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import imageio.v3 as iio
import imageio_ffmpeg
import numpy as np
import pyarrow as pa
import pyarrow.parquet as pq

INFO_KEYS = {
    "codebase_version": str,
    "robot_type": (str, type(None)),
    "total_episodes": int,
    "total_frames": int,
    "total_tasks": int,
    "chunks_size": int,
    "data_files_size_in_mb": int,
    "video_files_size_in_mb": int,
    "fps": int,
    "splits": dict,
    "data_path": str,
    "video_path": (str, type(None)),
    "features": dict,
}
DATA_PATH = "data/chunk-{chunk_index:03d}/file-{file_index:03d}.parquet"
VIDEO_PATH = "videos/{video_key}/chunk-{chunk_index:03d}/file-{file_index:03d}.mp4"
DEFAULT_FEATURES = {
    "timestamp": {"dtype": "float32", "shape": [1], "names": None},
    "frame_index": {"dtype": "int64", "shape": [1], "names": None},
    "episode_index": {"dtype": "int64", "shape": [1], "names": None},
    "index": {"dtype": "int64", "shape": [1], "names": None},
    "task_index": {"dtype": "int64", "shape": [1], "names": None},
}
VIDEO_INFO_KEYS = {
    "video.height",
    "video.width",
    "video.codec",
    "video.pix_fmt",
    "video.fps",
    "video.channels",
    "has_audio",
}
STATS = ["min", "max", "mean", "std", "count", "q01", "q10", "q50", "q90", "q99"]
QUANTILE_LEVELS = {"q01": 0.01, "q10": 0.10, "q50": 0.50, "q90": 0.90, "q99": 0.99}
ARROW = {"float32": pa.float32(), "float64": pa.float64(), "int64": pa.int64(), "bool": pa.bool_()}
IMAGE = pa.struct([("bytes", pa.binary()), ("path", pa.string())])
STATS_RTOL = 1e-9
"""Relative tolerance of statistics recomputed in another order of summation (float64)."""
VIDEO_STATS_ATOL = 0.01
"""Tolerance of an episode's per-channel mean and std in [0, 1] against its decoded video's
(H.264 at CRF 15 in yuv444p moves a pixel by 2 to 3 levels of 255 on average)."""


@dataclass
class Dataset:
    """What :func:`validate` read: info.json, the frames' table and the episodes' table."""

    info: dict[str, Any]
    frames: pa.Table
    episodes: pa.Table
    stats: dict[str, dict[str, Any]]


def _file(template: str, chunk: int, file: int, **kw: str) -> str:
    return template.format(chunk_index=chunk, file_index=file, **kw)


def _numpy(column: pa.ChunkedArray) -> np.ndarray:
    """A numeric column as (N, *shape) float64."""
    values = column.to_pylist()
    return np.asarray(values, dtype=np.float64).reshape(len(values), -1)


def _check_info(info: dict[str, Any]) -> None:
    assert set(info) >= set(INFO_KEYS), sorted(set(INFO_KEYS) - set(info))
    for key, kind in INFO_KEYS.items():
        assert isinstance(info[key], kind), (key, info[key])
    assert info["codebase_version"] == "v3.0"
    assert info["fps"] > 0
    assert info["chunks_size"] > 0
    assert info["data_path"] == DATA_PATH
    assert info["splits"] == {"train": f"0:{info['total_episodes']}"}
    features = info["features"]
    for key, spec in DEFAULT_FEATURES.items():
        assert features[key] == spec, key
    has_video = False
    for key, ft in features.items():
        assert "/" not in key, key  # LeRobot refuses it: "/" separates the stats/ columns
        assert set(ft) <= {"dtype", "shape", "names", "info"}, key
        assert ft["dtype"] in {"float32", "float64", "int64", "bool", "video", "image"}, key
        assert all(isinstance(s, int) and s > 0 for s in ft["shape"]), key
        if ft["dtype"] in ("video", "image"):
            assert key.startswith("observation.images."), key
            assert len(ft["shape"]) == 3, key
            assert ft["shape"][2] == 3, key
            assert ft["names"] == ["height", "width", "channels"], key
        elif ft["names"] is not None:
            assert len(ft["names"]) == ft["shape"][0], key
            assert len(set(ft["names"])) == len(ft["names"]), key
        if ft["dtype"] == "video":
            has_video = True
            video = ft["info"]
            assert set(video) >= VIDEO_INFO_KEYS, key
            assert [video["video.height"], video["video.width"], video["video.channels"]] == ft[
                "shape"
            ]
            assert video["video.fps"] == info["fps"]
            assert video["has_audio"] is False
    assert info["video_path"] == (VIDEO_PATH if has_video else None)


def _check_frames(info: dict[str, Any], table: pa.Table) -> None:
    features = info["features"]
    columns = [k for k, ft in features.items() if ft["dtype"] != "video"]
    assert table.column_names == columns
    for key in columns:
        ft = features[key]
        kind = table.schema.field(key).type
        if ft["dtype"] == "image":
            assert kind == IMAGE, (key, kind)
        elif ft["shape"] == [1]:
            assert kind == ARROW[ft["dtype"]], (key, kind)
        else:
            assert len(ft["shape"]) == 1, key
            assert pa.types.is_fixed_size_list(kind), (key, kind)
            assert kind.list_size == ft["shape"][0], key
            assert kind.value_type == ARROW[ft["dtype"]], (key, kind)
    n = info["total_frames"]
    assert table.num_rows == n
    index = table.column("index").to_numpy()
    np.testing.assert_array_equal(index, np.arange(n))


def _check_episodes(info: dict[str, Any], episodes: pa.Table, frames: pa.Table) -> None:
    features = info["features"]
    n_ep, fps = info["total_episodes"], info["fps"]
    assert episodes.num_rows == n_ep
    e = {k: episodes.column(k).to_pylist() for k in episodes.column_names}
    assert e["episode_index"] == list(range(n_ep))
    assert episodes.schema.field("tasks").type == pa.list_(pa.string())
    lengths = np.array(e["length"])
    assert (lengths > 0).all()
    assert lengths.sum() == info["total_frames"]
    starts = np.concatenate([[0], np.cumsum(lengths)[:-1]])
    np.testing.assert_array_equal(e["dataset_from_index"], starts)
    np.testing.assert_array_equal(e["dataset_to_index"], starts + lengths)
    episode_index = frames.column("episode_index").to_numpy()
    frame_index = frames.column("frame_index").to_numpy()
    timestamp = frames.column("timestamp").to_numpy()
    task_index = frames.column("task_index").to_numpy()
    np.testing.assert_array_equal(episode_index, np.repeat(np.arange(n_ep), lengths))
    np.testing.assert_array_equal(frame_index, np.concatenate([np.arange(n) for n in lengths]))
    np.testing.assert_array_equal(timestamp, (frame_index / fps).astype(np.float32))
    assert ((task_index >= 0) & (task_index < info["total_tasks"])).all()
    for key, ft in features.items():
        for stat in STATS:
            assert f"stats/{key}/{stat}" in e, (key, stat)
        if ft["dtype"] != "video":
            continue
        pairs = list(
            zip(e[f"videos/{key}/chunk_index"], e[f"videos/{key}/file_index"], strict=True)
        )
        start = e[f"videos/{key}/from_timestamp"]
        stop = e[f"videos/{key}/to_timestamp"]
        for i in range(n_ep):
            assert np.isclose(stop[i] - start[i], lengths[i] / fps, rtol=1e-12), (key, i)
            first_in_file = i == 0 or pairs[i] != pairs[i - 1]
            assert start[i] == (0.0 if first_in_file else stop[i - 1]), (key, i)
    for i, (chunk, file) in enumerate(
        zip(e["meta/episodes/chunk_index"], e["meta/episodes/file_index"], strict=True)
    ):
        assert 0 <= file < info["chunks_size"], i
        assert chunk >= 0, i


def _decode(path: Path) -> tuple[dict[str, Any], np.ndarray]:
    """The metadata ffmpeg reads from a video, and its frames, (N, H, W, 3) uint8."""
    reader = imageio_ffmpeg.read_frames(str(path))
    meta = next(reader)
    width, height = meta["size"]
    frames = [np.frombuffer(f, np.uint8).reshape(height, width, 3) for f in reader]
    return meta, np.stack(frames)


def _check_videos(root: Path, info: dict[str, Any], episodes: pa.Table) -> None:
    """Every video decodes (ffmpeg) to its episodes' frames, at the feature's size and rate.

    Each episode's image statistics are its decoded frames' (within the codec's loss).
    """
    e = {k: episodes.column(k).to_pylist() for k in episodes.column_names}
    for key, ft in info["features"].items():
        if ft["dtype"] != "video":
            continue
        files: dict[tuple[int, int], list[int]] = {}
        for i, pair in enumerate(
            zip(e[f"videos/{key}/chunk_index"], e[f"videos/{key}/file_index"], strict=True)
        ):
            files.setdefault(pair, []).append(i)
        for (c, f), members in files.items():
            path = root / _file(info["video_path"], c, f, video_key=key)
            meta, frames = _decode(path)
            assert len(frames) == sum(e["length"][i] for i in members), path
            assert meta["fps"] == info["fps"], (path, meta["fps"])
            assert list(frames.shape[1:]) == ft["shape"], (path, frames.shape)
            start = 0
            for i in members:
                clip = frames[start : start + e["length"][i]]
                start += e["length"][i]
                decoded = clip.reshape(-1, 3).astype(np.float64) / 255
                for s in ("mean", "std"):
                    got = np.asarray(e[f"stats/{key}/{s}"][i]).reshape(3)
                    expected = getattr(decoded, s)(axis=0)
                    np.testing.assert_allclose(got, expected, atol=VIDEO_STATS_ATOL, err_msg=s)


def recompute_stats(values: np.ndarray) -> dict[str, np.ndarray]:
    """LeRobot's statistics of (N, d) values, as numpy computes them."""
    out = {
        "min": values.min(axis=0),
        "max": values.max(axis=0),
        "mean": values.mean(axis=0),
        "std": values.std(axis=0),
        "count": np.array([len(values)]),
    }
    for name, q in QUANTILE_LEVELS.items():
        out[name] = np.quantile(values, q, axis=0)
    return out


def _check_stats(info: dict[str, Any], episodes: pa.Table, frames: pa.Table, stats: dict) -> None:
    """Per-episode statistics are the episode's frames'; stats.json merges them as LeRobot does."""
    features = info["features"]
    lengths = episodes.column("length").to_pylist()
    bounds = np.concatenate([[0], np.cumsum(lengths)])
    assert set(stats) == set(features)
    for key, ft in features.items():
        assert set(stats[key]) == set(STATS), key
        per_episode = {s: episodes.column(f"stats/{key}/{s}").to_pylist() for s in STATS}
        if ft["dtype"] in ("video", "image"):
            for s in STATS:
                shape = (1,) if s == "count" else (3, 1, 1)
                assert np.asarray(stats[key][s]).shape == shape, (key, s)
                assert np.asarray(per_episode[s][0]).shape == shape, (key, s)
            if ft["dtype"] == "video":
                continue  # checked against the decoded videos
            pngs = [v["bytes"] for v in frames.column(key).to_pylist()]
            pixels = np.stack([iio.imread(b, extension=".png") for b in pngs])
            assert list(pixels.shape[1:]) == ft["shape"], key
            values = pixels.reshape(len(pixels), -1, 3)
            for i, (a, b) in enumerate(itertools.pairwise(bounds)):
                expected = recompute_stats(values[a:b].reshape(-1, 3) / 255.0)
                for s in STATS:
                    got = np.asarray(per_episode[s][i], dtype=np.float64).reshape(-1)
                    want = np.array([b - a]) if s == "count" else expected[s]
                    np.testing.assert_allclose(got, want, rtol=STATS_RTOL, err_msg=f"{key} {s}")
            continue
        values = _numpy(frames.column(key))
        for i, (a, b) in enumerate(itertools.pairwise(bounds)):
            expected = recompute_stats(values[a:b])
            for s in STATS:
                got = np.asarray(per_episode[s][i], dtype=np.float64)
                assert got.shape == expected[s].shape, (key, s, got.shape)
                np.testing.assert_allclose(got, expected[s], rtol=STATS_RTOL, err_msg=f"{key} {s}")
        merged = {s: np.asarray(stats[key][s], dtype=np.float64) for s in STATS}
        everything = recompute_stats(values)
        for s in ("min", "max", "mean", "std", "count"):
            np.testing.assert_allclose(merged[s], everything[s], rtol=STATS_RTOL, err_msg=key)
        for s, q in QUANTILE_LEVELS.items():
            episodes_q = np.asarray(per_episode[s], dtype=np.float64)
            bound = episodes_q.min(axis=0) if q <= 0.5 else episodes_q.max(axis=0)
            np.testing.assert_array_equal(merged[s], bound, err_msg=f"{key} {s}")


def _check_tasks(root: Path, info: dict[str, Any]) -> None:
    table = pq.read_table(root / "meta/tasks.parquet")
    assert table.num_rows == info["total_tasks"]
    assert table.schema.field("task_index").type == pa.int64()
    assert table.schema.field("task").type == pa.string()
    assert table.column("task_index").to_pylist() == list(range(info["total_tasks"]))
    pandas = json.loads(table.schema.metadata[b"pandas"])
    assert pandas["index_columns"] == ["task"]  # pandas reads the task's text as the index


def validate(root: Path) -> Dataset:
    """Check the dataset in ``root`` against LeRobot v3.0's layout; AssertionError if it differs."""
    info = json.loads((root / "meta/info.json").read_text())
    _check_info(info)
    episode_files = sorted((root / "meta/episodes").glob("chunk-*/file-*.parquet"))
    assert episode_files
    episodes = pa.concat_tables([pq.read_table(p) for p in episode_files])
    pairs = sorted(
        set(
            zip(
                episodes.column("data/chunk_index").to_pylist(),
                episodes.column("data/file_index").to_pylist(),
                strict=True,
            )
        )
    )
    data_files = [root / _file(DATA_PATH, c, f) for c, f in pairs]
    assert sorted(data_files) == sorted((root / "data").glob("chunk-*/file-*.parquet"))
    frames = pa.concat_tables([pq.read_table(p) for p in data_files])
    _check_frames(info, frames)
    _check_episodes(info, episodes, frames)
    stats = json.loads((root / "meta/stats.json").read_text())
    _check_stats(info, episodes, frames, stats)
    _check_tasks(root, info)
    _check_videos(root, info, episodes)
    return Dataset(info, frames, episodes, stats)
