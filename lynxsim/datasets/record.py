"""Recording a dataset: seeded expert episodes with action noise, written whole or not at all."""

from __future__ import annotations

import importlib.metadata
import json
import os
from collections.abc import Callable, Sequence
from contextlib import AbstractContextManager
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Literal, Protocol

import gymnasium as gym
import numpy as np
import numpy.typing as npt
from gymnasium.envs.registration import EnvSpec

import lynxsim
from lynxsim.bounds import MAX_EPISODES, check_count
from lynxsim.datasets.episode import INFO_KEYS, Episode, record_episode
from lynxsim.datasets.layout import (
    NEW_FOLDER_HINT,
    DatasetFormat,
    dataset_folder,
    default_dataset_id,
)
from lynxsim.datasets.lerobot_meta import LeRobotLayout
from lynxsim.datasets.lerobot_writer import LeRobotWriter, require_pyarrow
from lynxsim.datasets.minari_writer import MinariWriter, require_minari, write_namespaces
from lynxsim.datasets.npz import NpzWriter
from lynxsim.envs.evaluation import make_policy
from lynxsim.envs.noise import action_noise_std, check_noise, noise_generator
from lynxsim.envs.registration import ENV_IDS, PICK_AND_PLACE_ID, make_env
from lynxsim.errors import InvalidInputError, InvalidTypeError, short
from lynxsim.fileio import atomic_folder, check_new_folder

__all__ = ["MAX_SEED", "DatasetSummary", "write_dataset"]

MAX_SEED = int(np.iinfo(np.int64).max)
"""Largest episode seed: seeds are stored as int64."""

_FORMAT_VERSION = 1
"""Version of the layout described in :mod:`lynxsim.datasets` (raised when it changes)."""


@dataclass(frozen=True)
class DatasetSummary:
    """What was written.

    Attributes:
        path: The dataset's folder (``out / dataset_id``).
        dataset_id: Its id.
        format: Its format.
        episodes: Number of episodes.
        steps: Number of steps, over all episodes.
        successes: Episodes whose last step was a success.
        collision_episodes: Episodes with an arm–obstacle contact (checked on the
            last physics step of each control step, as the env does by default).
    """

    path: Path
    dataset_id: str
    format: DatasetFormat
    episodes: int
    steps: int
    successes: int
    collision_episodes: int


class _Writer(AbstractContextManager[Any], Protocol):
    def add(self, episode: Episode) -> None: ...

    def finish(self, metadata: dict[str, Any]) -> None: ...


def _versions() -> dict[str, str]:
    names = ("mujoco", "numpy", "gymnasium")
    return {"lynxsim": lynxsim.__version__} | {n: importlib.metadata.version(n) for n in names}


def write_dataset(
    out: str | os.PathLike[str],
    episodes: int,
    *,
    env_id: str = PICK_AND_PLACE_ID,
    noise: float = 0.1,
    seed: int = 0,
    format: DatasetFormat | Literal["npz", "minari", "lerobot"] = DatasetFormat.NPZ,
    dataset_id: str | None = None,
    images: Sequence[str] = (),
    image_size: int = 84,
    videos: bool = True,
    on_episode: Callable[[Episode], None] | None = None,
) -> DatasetSummary:
    """Record ``episodes`` episodes of the env's scripted expert into ``out / dataset_id``.

    Episode ``i`` is reset with seed ``seed + i``; every action gets Gaussian
    noise of standard deviation ``noise`` times the action range (see
    :func:`~lynxsim.datasets.action_noise_std`) from
    :func:`~lynxsim.datasets.noise_generator` of that seed, and is clipped to
    the action space. The same arguments give the same bytes. The dataset is
    written into a hidden temporary folder and renamed when complete and read
    back: an interrupted call leaves no folder under the dataset's name.

    Args:
        out: The datasets' root folder (for Minari: what ``MINARI_DATASETS_PATH``
            points to).
        episodes: How many, 1 to :data:`~lynxsim.bounds.MAX_EPISODES`.
        env_id: ``"LynxPickAndPlace-v1"`` or ``"LynxReach-v1"`` (their default
            arguments, as ``gym.make(env_id)`` makes them).
        noise: Noise as a fraction of the action range, 0 to
            :data:`~lynxsim.datasets.MAX_NOISE`.
        seed: Seed of the first episode; the last, ``seed + episodes - 1``, at
            most :data:`MAX_SEED`.
        format: ``"npz"``, ``"minari"`` or ``"lerobot"`` (LeRobot v3.0, see
            :mod:`lynxsim.datasets.lerobot_writer`).
        dataset_id: Minari-style id, also the dataset's path under ``out``
            (default :func:`default_dataset_id`).
        images: Cameras whose images the observations carry (the env's
            ``pixels`` option: an ``observations/pixels`` entry, uint8
            (T + 1, size, size, 3 x cameras)); empty: none.
        image_size: Side of the images [px], 16 to 512.
        videos: LeRobot only: the images as MP4 videos (H.264, lossy), else as
            PNG inside the parquet files (lossless, larger).
        on_episode: Called with each episode once recorded.

    Returns:
        The :class:`DatasetSummary`.

    Raises:
        InvalidInputError: A bad argument (the message names it and the valid values).
        OutputPathError: The dataset's folder exists, or its path crosses a file.
        MissingExtraError: ``format="minari"`` or ``"lerobot"`` without the
            ``datasets`` extra.
    """
    if not isinstance(out, str | os.PathLike):
        raise InvalidTypeError(f"out must be a path, got {short(out)}")
    if not isinstance(env_id, str) or env_id not in ENV_IDS:
        raise InvalidInputError(f"env_id must be one of {list(ENV_IDS)}, got {short(env_id)}")
    episodes = check_count(episodes, "episodes", 1, MAX_EPISODES)
    seed = check_count(seed, "seed", 0, MAX_SEED)
    if seed > MAX_SEED - (episodes - 1):
        raise InvalidInputError(
            f"the last episode's seed, seed + episodes - 1 = {seed + episodes - 1:,}, exceeds "
            f"{MAX_SEED:,} (seeds are stored as int64)"
        )
    try:
        fmt = DatasetFormat(format.value if isinstance(format, DatasetFormat) else format)
    except (ValueError, TypeError):
        choices = [f.value for f in DatasetFormat]
        raise InvalidInputError(f"format must be one of {choices}, got {short(format)}") from None
    noise = check_noise(noise)
    dataset_id = default_dataset_id(env_id) if dataset_id is None else dataset_id
    dest = check_new_folder(dataset_folder(out, dataset_id), NEW_FOLDER_HINT)
    if fmt is DatasetFormat.MINARI:
        require_minari()  # before any work
    elif fmt is DatasetFormat.LEROBOT:
        require_pyarrow()
    if not isinstance(videos, bool):
        raise InvalidTypeError(f"videos must be True or False, got {short(videos)}")
    if isinstance(images, str):
        images = (images,)
    if not isinstance(images, Sequence) or not all(isinstance(c, str) for c in images):
        raise InvalidTypeError(
            f"images must be camera names (a string or a sequence of strings), got {short(images)}"
        )
    image_size = check_count(image_size, "image_size", 16, 512)
    pixels: dict[str, Any] = {}
    if images:
        pixels = {"pixels": tuple(images), "pixel_width": image_size, "pixel_height": image_size}
    env = make_env(env_id, **pixels)
    spec = env.spec if env.spec is not None else gym.spec(env_id)
    try:
        # LeRobot's features, made before any write (it refuses what it cannot store)
        layout = LeRobotLayout.of_env(env, videos) if fmt is DatasetFormat.LEROBOT else None
        std = action_noise_std(env.action_space, noise)
        policy = make_policy("expert", env)
        description = (
            f"{episodes} episodes of {env_id} by lynxsim's scripted expert "
            f"({type(policy).__name__}) with Gaussian action noise of {noise:g} x the action "
            f"range on every step; episode i reset with seed {seed} + i."
        )
        steps = successes = collisions = 0
        with (
            atomic_folder(dest, NEW_FOLDER_HINT) as tmp,
            _writer(fmt, tmp, env, dataset_id, description, layout) as w,
        ):
            for i in range(episodes):
                episode = record_episode(env, policy, seed + i, std, noise_generator(seed + i))
                w.add(episode)
                steps += episode.steps
                successes += episode.success
                collisions += bool(episode.infos["collision"].any())
                if on_episode is not None:
                    on_episode(episode)
            w.finish(
                _metadata(
                    env, spec, fmt, dataset_id, description, noise, std, seed, episodes, steps
                )
            )
    finally:
        env.close()
    if fmt is DatasetFormat.MINARI:
        write_namespaces(Path(out), dataset_id)
    return DatasetSummary(dest, dataset_id, fmt, episodes, steps, successes, collisions)


def _writer(
    fmt: DatasetFormat,
    folder: Path,
    env: gym.Env[Any, Any],
    dataset_id: str,
    description: str,
    layout: LeRobotLayout | None,
) -> _Writer:
    if fmt is DatasetFormat.NPZ:
        return NpzWriter(folder)
    if layout is not None:
        return LeRobotWriter(folder, layout)
    return MinariWriter(folder, env, dataset_id, description)


def _metadata(
    env: gym.Env[Any, Any],
    spec: EnvSpec,
    fmt: DatasetFormat,
    dataset_id: str,
    description: str,
    noise: float,
    std: npt.NDArray[np.float64],
    seed: int,
    episodes: int,
    steps: int,
) -> dict[str, Any]:
    """What lynxsim keeps: NPZ's metadata.json, Minari's key "lynxsim", meta/lynxsim.json."""
    index = getattr(type(env.unwrapped), "OBS_INDEX", {})
    return {
        "format": fmt.value,
        "format_version": _FORMAT_VERSION,
        "dataset_id": dataset_id,
        "description": description,
        "env_id": spec.id,
        "env_spec": json.loads(spec.to_json()),
        "action_noise": noise,
        "action_noise_std": std.tolist(),
        "first_seed": seed,
        "total_episodes": episodes,
        "total_steps": steps,
        "observation_index": {k: [s.start, s.stop] for k, s in index.items()},
        "info_keys": [*INFO_KEYS, "expert_action"],
        "versions": _versions(),
    }
