"""What a LeRobot v3.0 dataset of lynxsim episodes holds: its features, rows and metadata files.

The names, paths and defaults are LeRobot's (``lerobot/datasets/utils.py`` and
``dataset_metadata.py`` of lerobot 0.4 to 0.6, ``CODEBASE_VERSION = "v3.0"``);
:mod:`lynxsim.datasets.lerobot_writer` describes the layout. pyarrow is passed
in by the caller (the extra ``lynxsim[datasets]``), never imported here.
"""

from __future__ import annotations

import json
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import gymnasium as gym
import numpy as np
import numpy.typing as npt

from lynxsim.datasets.episode import Episode
from lynxsim.datasets.lerobot_stats import QUANTILES, Stats
from lynxsim.errors import InvalidInputError

__all__ = [
    "CHUNKS_SIZE",
    "CODEBASE_VERSION",
    "DATA_FILES_SIZE_IN_MB",
    "DATA_PATH",
    "EPISODES_PATH",
    "INFO_PATH",
    "LYNXSIM_PATH",
    "MIB",
    "RAW_VIDEO_BYTES",
    "STATS_PATH",
    "STAT_NAMES",
    "TASKS_PATH",
    "VIDEO_FILES_SIZE_IN_MB",
    "VIDEO_PATH",
    "LeRobotLayout",
    "arrow_type",
    "write_meta",
]

CODEBASE_VERSION = "v3.0"
CHUNKS_SIZE = 1000
"""Files per chunk folder."""
DATA_FILES_SIZE_IN_MB = 100
"""A data (or episodes) file is closed before it would pass this (uncompressed, MiB)."""
VIDEO_FILES_SIZE_IN_MB = 200
"""LeRobot's limit of a video file, declared in info.json (lynxsim's files stay far below)."""
MIB = 1024**2
RAW_VIDEO_BYTES = 2_000 * MIB
"""Raw RGB bytes of one camera's frames in a video file (encoded: about 1 % of it at 84 x 84)."""
_FILE = "chunk-{chunk_index:03d}/file-{file_index:03d}"
DATA_PATH = f"data/{_FILE}.parquet"
VIDEO_PATH = "videos/{video_key}/" + f"{_FILE}.mp4"
EPISODES_PATH = f"meta/episodes/{_FILE}.parquet"
INFO_PATH = "meta/info.json"
STATS_PATH = "meta/stats.json"
TASKS_PATH = "meta/tasks.parquet"
LYNXSIM_PATH = "meta/lynxsim.json"
STAT_NAMES = ("min", "max", "mean", "std", "count", *QUANTILES)
"""The statistics of every feature, in LeRobot's order."""
IMAGE_PREFIX = "observation.images."

_PARQUET_OPTIONS: Mapping[str, Any] = {
    "compression": "snappy",
    "use_dictionary": True,
    "write_statistics": True,
    "version": "2.6",
    "data_page_version": "1.0",
}
"""Fixed writer options (pyarrow's defaults spelled out, so that a new default changes nothing)."""

_INDEX_FEATURES: dict[str, dict[str, Any]] = {
    "timestamp": {"dtype": "float32", "shape": [1], "names": None},
    "frame_index": {"dtype": "int64", "shape": [1], "names": None},
    "episode_index": {"dtype": "int64", "shape": [1], "names": None},
    "index": {"dtype": "int64", "shape": [1], "names": None},
    "task_index": {"dtype": "int64", "shape": [1], "names": None},
}
"""LeRobot's columns of every dataset, last in its features."""


def _scalar(dtype: str) -> dict[str, Any]:
    return {"dtype": dtype, "shape": [1], "names": None}


def _vector(size: int, names: list[str] | None) -> dict[str, Any]:
    return {"dtype": "float32", "shape": [size], "names": names}


def _state_names(index: Mapping[str, slice], size: int) -> list[str] | None:
    """``tool_position.0``, ... from the env's ``OBS_INDEX`` (None unless it covers ``size``)."""
    names = []
    for key, s in index.items():
        width = s.stop - s.start
        names += [key] if width == 1 else [f"{key}.{i}" for i in range(width)]
    return names if len(names) == size else None


def _shape(space: gym.Space[Any]) -> tuple[int, ...]:
    if space.shape is None:
        raise InvalidInputError(f"the LeRobot format needs spaces of a shape, got {space}")
    return space.shape


def _size(space: gym.Space[Any]) -> int:
    return _shape(space)[0]


def arrow_type(pa: Any, feature: Mapping[str, Any]) -> Any:
    """The pyarrow type of a feature's column, as ``datasets`` stores LeRobot's features.

    ``shape`` (1,): the scalar; (n,): ``fixed_size_list<item>[n]``; ``image``:
    ``struct<bytes: binary, path: string>``.
    """
    if feature["dtype"] == "image":
        return pa.struct([("bytes", pa.binary()), ("path", pa.string())])
    value = {"float32": pa.float32(), "int64": pa.int64(), "bool": pa.bool_()}[feature["dtype"]]
    size = feature["shape"][0]
    return value if list(feature["shape"]) == [1] else pa.list_(value, size)


def _nested(pa: Any, depth: int, value: Any) -> Any:
    for _ in range(depth):
        value = pa.list_(value)
    return value


@dataclass(frozen=True)
class LeRobotLayout:
    """The features of a dataset of one env's episodes, and how its rows are made.

    Attributes:
        fps: Frames (control steps) per second.
        features: LeRobot's ``features`` of info.json, in column order.
        cameras: ``(camera, feature key)`` of the image features, in channel order.
        videos: Images as MP4 videos, else PNG in the parquet files.
        task: The one task's text (the first line of the env class's docstring).
        chunks_size: Files per chunk folder.
        file_bytes: A data (or episodes) file is closed before an episode would
            take it past this, uncompressed (info.json declares it in MiB).
        raw_video_bytes: Likewise for a video file, in raw frames, per camera.
        parquet_options: The parquet writer's options.
    """

    fps: int
    features: dict[str, dict[str, Any]]
    cameras: tuple[tuple[str, str], ...]
    videos: bool
    task: str
    chunks_size: int = CHUNKS_SIZE
    file_bytes: int = DATA_FILES_SIZE_IN_MB * MIB
    raw_video_bytes: int = RAW_VIDEO_BYTES
    parquet_options: Mapping[str, Any] = field(default_factory=lambda: dict(_PARQUET_OPTIONS))

    @classmethod
    def of_env(cls, env: gym.Env[Any, Any], videos: bool) -> LeRobotLayout:
        """The layout of ``env``'s episodes (a lynxsim goal env, maybe with pixels).

        Raises:
            InvalidInputError: A frame rate that is not a whole number of frames
                per second, or spaces of another kind.
        """
        fps = env.metadata.get("render_fps")
        if not isinstance(fps, int) or fps < 1:
            raise InvalidInputError(
                f"the LeRobot format needs a whole number of frames per second, "
                f"the env steps at {fps} /s"
            )
        spaces = env.observation_space
        action = env.action_space
        if not isinstance(spaces, gym.spaces.Dict) or not isinstance(action, gym.spaces.Box):
            raise InvalidInputError("the LeRobot format needs a dict observation, a Box action")
        unwrapped = env.unwrapped
        n_obs = _size(spaces["observation"])
        n_goal = _size(spaces["achieved_goal"])
        goal_names = [f"{k}.{i}" for k in ("achieved_goal", "desired_goal") for i in range(n_goal)]
        features: dict[str, dict[str, Any]] = {
            "observation.state": _vector(
                n_obs, _state_names(getattr(type(unwrapped), "OBS_INDEX", {}), n_obs)
            ),
            "observation.environment_state": _vector(2 * n_goal, goal_names),
        }
        cameras: tuple[str, ...] = getattr(unwrapped, "pixel_cameras", ())
        if cameras:
            height, width = _shape(spaces["pixels"])[:2]
        for camera in cameras:
            info = {
                "video.height": height,
                "video.width": width,
                "video.codec": "h264",
                "video.pix_fmt": "yuv444p",
                "video.is_depth_map": False,
                "video.fps": fps,
                "video.channels": 3,
                "has_audio": False,
            }
            features[IMAGE_PREFIX + camera] = {
                "dtype": "video" if videos else "image",
                "shape": [height, width, 3],
                "names": ["height", "width", "channels"],
                **({"info": info} if videos else {}),
            }
        n_act = _size(action)
        features |= {
            "action": _vector(n_act, None),
            "expert_action": _vector(n_act, None),
            "next.reward": _scalar("float32"),
            "next.done": _scalar("bool"),
            "next.terminated": _scalar("bool"),
            "next.success": _scalar("bool"),
            "next.collision": _scalar("bool"),
            **{k: dict(v) for k, v in _INDEX_FEATURES.items()},
        }
        doc = (type(unwrapped).__doc__ or type(unwrapped).__name__).strip().splitlines()[0]
        return cls(
            fps=fps,
            features=features,
            cameras=tuple((c, IMAGE_PREFIX + c) for c in cameras),
            videos=videos,
            task=doc,
        )

    def frame_columns(
        self, episode: Episode, episode_index: int, first_index: int
    ) -> tuple[dict[str, npt.NDArray[Any]], dict[str, npt.NDArray[np.uint8]]]:
        """One episode's frames: the numeric columns (T, *shape), and the images (T, H, W, 3).

        Raises:
            InvalidInputError: Arrays that do not fit the features.
        """
        t = episode.steps
        obs = episode.observations
        infos = episode.infos
        done = episode.terminations | episode.truncations
        columns: dict[str, npt.NDArray[Any]] = {
            "observation.state": obs["observation"][:t],
            "observation.environment_state": np.concatenate(
                [obs["achieved_goal"][:t], obs["desired_goal"][:t]], axis=1
            ),
            "action": episode.actions,
            "expert_action": infos["expert_action"][1:],
            "next.reward": episode.rewards,
            "next.done": done,
            "next.terminated": episode.terminations,
            "next.success": infos["is_success"][1:],
            "next.collision": infos["collision"][1:],
            "timestamp": np.arange(t) / self.fps,
            "frame_index": np.arange(t),
            "episode_index": np.full(t, episode_index),
            "index": np.arange(first_index, first_index + t),
            "task_index": np.zeros(t),
        }
        out: dict[str, npt.NDArray[Any]] = {}
        for key, values in columns.items():
            feature = self.features[key]
            dtype = np.dtype(feature["dtype"])
            shape = tuple(feature["shape"])
            out[key] = np.asarray(values).astype(dtype).reshape(t, *shape)
        images: dict[str, npt.NDArray[np.uint8]] = {}
        for k, (_, key) in enumerate(self.cameras):
            images[key] = np.ascontiguousarray(obs["pixels"][:t, :, :, 3 * k : 3 * k + 3])
        return out, images

    def column(self, pa: Any, key: str, values: Any) -> Any:
        """The pyarrow array of a column: ``values`` (T, *shape), or PNG bytes for images."""
        feature = self.features[key]
        kind = arrow_type(pa, feature)
        if feature["dtype"] == "image":
            return pa.array([{"bytes": v, "path": None} for v in values], type=kind)
        if list(feature["shape"]) == [1]:
            return pa.array(values.reshape(-1), type=kind)
        flat = pa.array(values.reshape(-1), type=kind.value_type)
        return pa.FixedSizeListArray.from_arrays(flat, feature["shape"][0])

    def episode_row(
        self,
        pa: Any,
        *,
        index: int,
        length: int,
        data_file: tuple[int, int],
        first_frame: int,
        video_times: Mapping[str, tuple[float, float]],
        stats: Mapping[str, Stats],
        meta_file: tuple[int, int],
    ) -> Any:
        """One row of ``meta/episodes``: a pyarrow table, columns in LeRobot's order."""
        i64, f64 = pa.int64(), pa.float64()
        cols: dict[str, tuple[Any, Any]] = {
            "episode_index": (index, i64),
            "tasks": ([self.task], pa.list_(pa.string())),
            "length": (length, i64),
            "data/chunk_index": (data_file[0], i64),
            "data/file_index": (data_file[1], i64),
            "dataset_from_index": (first_frame, i64),
            "dataset_to_index": (first_frame + length, i64),
        }
        for key, (start, stop) in video_times.items():
            cols |= {
                f"videos/{key}/chunk_index": (data_file[0], i64),
                f"videos/{key}/file_index": (data_file[1], i64),
                f"videos/{key}/from_timestamp": (start, f64),
                f"videos/{key}/to_timestamp": (stop, f64),
            }
        for key in self.features:
            for name in STAT_NAMES:
                value = stats[key][name]
                if name == "count":
                    cols[f"stats/{key}/{name}"] = ([int(value[0])], pa.list_(i64))
                else:
                    cols[f"stats/{key}/{name}"] = (value.tolist(), _nested(pa, value.ndim, f64))
        cols |= {
            "meta/episodes/chunk_index": (meta_file[0], i64),
            "meta/episodes/file_index": (meta_file[1], i64),
        }
        return pa.table({k: pa.array([v], type=t) for k, (v, t) in cols.items()})

    def info(self, episodes: int, frames: int) -> dict[str, Any]:
        """``meta/info.json``."""
        return {
            "codebase_version": CODEBASE_VERSION,
            "robot_type": None,
            "total_episodes": episodes,
            "total_frames": frames,
            "total_tasks": 1,
            "chunks_size": self.chunks_size,
            "data_files_size_in_mb": -(-self.file_bytes // MIB),
            "video_files_size_in_mb": VIDEO_FILES_SIZE_IN_MB,
            "fps": self.fps,
            "splits": {"train": f"0:{episodes}"},
            "data_path": DATA_PATH,
            "video_path": VIDEO_PATH if self.videos and self.cameras else None,
            "features": self.features,
        }


def _tasks_table(pa: Any, task: str) -> Any:
    """``meta/tasks.parquet``: column ``task_index``, and ``task`` as the pandas index."""
    pandas_meta = {
        "index_columns": ["task"],
        "column_indexes": [],
        "columns": [
            {
                "name": "task_index",
                "field_name": "task_index",
                "pandas_type": "int64",
                "numpy_type": "int64",
                "metadata": None,
            },
            {
                "name": "task",
                "field_name": "task",
                "pandas_type": "unicode",
                "numpy_type": "object",
                "metadata": None,
            },
        ],
        "creator": {"library": "pyarrow", "version": pa.__version__},
    }
    schema = pa.schema(
        [("task_index", pa.int64()), ("task", pa.string())],
        metadata={b"pandas": json.dumps(pandas_meta).encode()},
    )
    return pa.table({"task_index": [0], "task": [task]}, schema=schema)


def _json(data: Any) -> str:
    return json.dumps(data, indent=4) + "\n"


def write_meta(
    pa: Any,
    folder: Path,
    layout: LeRobotLayout,
    episodes: int,
    frames: int,
    stats: Mapping[str, Stats],
    metadata: Mapping[str, Any],
) -> None:
    """Write info.json, stats.json, tasks.parquet and lynxsim.json into ``folder/meta``."""
    import pyarrow.parquet as pq

    meta = folder / "meta"
    meta.mkdir(parents=True, exist_ok=True)
    (folder / INFO_PATH).write_text(_json(layout.info(episodes, frames)), encoding="utf-8")
    serial = {
        key: {n: (s[n].astype(np.int64) if n == "count" else s[n]).tolist() for n in STAT_NAMES}
        for key, s in stats.items()
    }
    (folder / STATS_PATH).write_text(_json(serial), encoding="utf-8")
    pq.write_table(_tasks_table(pa, layout.task), folder / TASKS_PATH, **layout.parquet_options)
    (folder / LYNXSIM_PATH).write_text(_json(dict(metadata)), encoding="utf-8")
