"""Datasets with image observations: the env's pixels, stored losslessly, bit for bit."""

from __future__ import annotations

import hashlib
import os
from pathlib import Path

import gymnasium as gym
import numpy as np
import pytest

from lynxsim.datasets import read_npz
from lynxsim.errors import InvalidInputError
from tests.datasets.conftest import FORMATS, MINARI, SEED, record


def _digest(folder: Path) -> dict[str, str]:
    return {
        str(p.relative_to(folder)): hashlib.sha256(p.read_bytes()).hexdigest()
        for p in sorted(folder.rglob("*"))
        if p.is_file()
    }


@pytest.mark.parametrize("fmt", FORMATS)
def test_images_regenerate_byte_identically(tmp_path, fmt):
    a = record(tmp_path / "a", fmt, episodes=2, images=("front",), image_size=32)
    b = record(tmp_path / "b", fmt, episodes=2, images=("front",), image_size=32)
    assert _digest(a.path) == _digest(b.path)


def test_npz_images_are_the_envs_pixels(tmp_path):
    summary = record(tmp_path, "npz", episodes=1, images=("front", "top"), image_size=32)
    episode = read_npz(summary.path)[0]
    pixels = episode.observations["pixels"]
    assert pixels.dtype == np.uint8
    assert pixels.shape == (episode.steps + 1, 32, 32, 6)
    env = gym.make("LynxPickAndPlace-v1", pixels=("front", "top"), pixel_width=32, pixel_height=32)
    obs, _ = env.reset(seed=episode.seed)
    np.testing.assert_array_equal(pixels[0], obs["pixels"])
    for action, expected in zip(episode.actions[:5], pixels[1:6], strict=True):
        obs, *_ = env.step(action)
        np.testing.assert_array_equal(expected, obs["pixels"])
    env.close()


@pytest.mark.parametrize("fmt", [MINARI])
def test_minari_recovers_an_env_with_the_same_images(tmp_path, fmt, monkeypatch):
    import minari

    summary = record(tmp_path, fmt, episodes=1, images=("front",), image_size=32)
    monkeypatch.setenv("MINARI_DATASETS_PATH", os.fspath(tmp_path))
    dataset = minari.load_dataset(summary.dataset_id)
    env = dataset.recover_environment()
    assert env.observation_space["pixels"].shape == (32, 32, 3)
    episode = next(iter(dataset.iterate_episodes()))
    obs, _ = env.reset(seed=SEED)  # the first episode's
    np.testing.assert_array_equal(episode.observations["pixels"][0], obs["pixels"])


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"images": ("side",)}, "camera"),
        ({"images": ("front",), "image_size": 8}, "image_size"),
    ],
)
def test_bad_image_arguments_are_refused_before_any_write(tmp_path, kwargs, match):
    with pytest.raises(InvalidInputError, match=match):
        record(tmp_path, "npz", episodes=1, **kwargs)
    assert not any(tmp_path.iterdir())
