"""Recorded datasets: byte-identical when regenerated, faithful to the env, whole or absent."""

from __future__ import annotations

import json
from pathlib import Path

import gymnasium as gym
import numpy as np
import pytest

from lynxsim.datasets import (
    INFO_KEYS,
    action_noise_std,
    default_dataset_id,
    noise_generator,
    read_npz,
    write_dataset,
)
from lynxsim.datasets.npz import METADATA_FILE, NPZ_FILE
from lynxsim.envs import PICK_AND_PLACE_ID, REACH_ID
from tests.datasets.conftest import EPISODES, FORMATS, NOISE, SEED, record

NOISE_STD_REL_TOL = 0.1
"""Relative tolerance of the noise's sample standard deviation (~2,000 unclipped draws)."""


def _files(root: Path) -> dict[str, bytes]:
    return {
        str(p.relative_to(root)): p.read_bytes() for p in sorted(root.rglob("*")) if p.is_file()
    }


@pytest.mark.parametrize("fmt", FORMATS)
def test_regenerating_gives_byte_identical_files(tmp_path, fmt):
    first = record(tmp_path / "a", fmt)
    again = record(tmp_path / "b", fmt)
    other = record(tmp_path / "c", fmt, seed=SEED + 1)
    files = _files(first.path)
    assert files
    assert files == _files(again.path)
    assert files != _files(other.path)


def test_the_default_id_names_the_env_and_is_the_folder(npz_dataset):
    assert default_dataset_id(PICK_AND_PLACE_ID) == "lynxsim/pick-and-place-v1/expert-v0"
    assert default_dataset_id(REACH_ID) == "lynxsim/reach-v1/expert-v0"
    assert npz_dataset.dataset_id == "lynxsim/pick-and-place-v1/expert-v0"
    assert npz_dataset.path.parts[-3:] == ("lynxsim", "pick-and-place-v1", "expert-v0")
    assert sorted(p.name for p in npz_dataset.path.iterdir()) == [NPZ_FILE, METADATA_FILE]
    assert sorted(p.name for p in npz_dataset.path.parent.iterdir()) == ["expert-v0"]


def test_npz_episodes_hold_what_the_env_returned(npz_dataset):
    episodes = read_npz(npz_dataset.path)
    assert [e.seed for e in episodes] == [SEED + i for i in range(EPISODES)]
    assert npz_dataset.episodes == EPISODES
    assert npz_dataset.steps == sum(e.steps for e in episodes)
    assert npz_dataset.successes == sum(e.success for e in episodes)
    for e in episodes:
        t = e.steps
        assert t == 200  # the registered time limit
        assert {k: v.shape for k, v in e.observations.items()} == {
            "observation": (t + 1, 45),
            "achieved_goal": (t + 1, 3),
            "desired_goal": (t + 1, 3),
        }
        assert e.actions.shape == (t, 5)
        assert e.actions.dtype == np.float32
        assert np.all(np.abs(e.actions) <= 1.0)
        assert e.rewards.shape == e.terminations.shape == e.truncations.shape == (t,)
        assert e.truncations[-1]
        assert not e.truncations[:-1].any()
        assert not e.terminations.any()
        assert set(e.infos) == {*INFO_KEYS, "expert_action"}
        for key, dtype in INFO_KEYS.items():
            assert e.infos[key].shape == (t + 1,)
            assert e.infos[key].dtype == dtype
        assert np.isnan(e.infos["expert_action"][0]).all()
        assert np.isfinite(e.infos["expert_action"][1:]).all()
        np.testing.assert_array_equal(e.rewards, e.infos["reward_goal"][1:])


def test_replaying_the_actions_reproduces_every_observation(npz_dataset):
    episode = read_npz(npz_dataset.path)[-1]
    env = gym.make(PICK_AND_PLACE_ID)
    try:
        obs, _ = env.reset(seed=episode.seed)
        seen = [obs]
        for action in episode.actions:
            seen.append(env.step(action)[0])
    finally:
        env.close()
    for key, recorded in episode.observations.items():
        np.testing.assert_array_equal(np.stack([o[key] for o in seen]), recorded)


def test_noise_is_the_asked_fraction_of_the_action_range(npz_dataset):
    std = action_noise_std(gym.spaces.Box(-1.0, 1.0, (5,), np.float32), NOISE)
    np.testing.assert_array_equal(std, np.full(5, 2 * NOISE))
    episodes = read_npz(npz_dataset.path)
    noise = np.concatenate([e.actions - e.infos["expert_action"][1:] for e in episodes])
    unclipped = np.abs(np.concatenate([e.actions for e in episodes])) < 1.0
    assert np.std(noise[unclipped]) == pytest.approx(2 * NOISE, rel=NOISE_STD_REL_TOL)
    metadata = json.loads((npz_dataset.path / METADATA_FILE).read_text())
    assert metadata["action_noise"] == NOISE
    assert metadata["action_noise_std"] == [2 * NOISE] * 5


def test_without_noise_the_actions_are_the_experts(tmp_path):
    (episode,) = read_npz(record(tmp_path, "npz", episodes=1, noise=0.0).path)
    np.testing.assert_array_equal(episode.actions, episode.infos["expert_action"][1:])


def test_the_noise_stream_is_not_the_envs():
    env_stream = np.random.default_rng(SEED).normal(size=8)  # as Gymnasium seeds np_random
    assert not np.array_equal(noise_generator(SEED).normal(size=8), env_stream)
    np.testing.assert_array_equal(
        noise_generator(SEED).normal(size=8), noise_generator(SEED).normal(size=8)
    )


def test_npz_metadata_describes_the_dataset(npz_dataset):
    metadata = json.loads((npz_dataset.path / METADATA_FILE).read_text())
    assert metadata["format"] == "npz"
    assert metadata["env_id"] == PICK_AND_PLACE_ID
    assert gym.make(gym.envs.registration.EnvSpec.from_json(json.dumps(metadata["env_spec"])))
    assert metadata["first_seed"] == SEED
    assert metadata["total_episodes"] == EPISODES
    assert metadata["total_steps"] == npz_dataset.steps
    assert metadata["observation_index"]["tool_position"] == [0, 3]
    assert metadata["info_keys"] == [*INFO_KEYS, "expert_action"]
    assert set(metadata["versions"]) == {"lynxsim", "mujoco", "numpy", "gymnasium"}


def test_a_reach_dataset_has_four_actions(tmp_path):
    summary = write_dataset(tmp_path, 1, env_id=REACH_ID, seed=3)
    (episode,) = read_npz(summary.path)
    assert summary.dataset_id == "lynxsim/reach-v1/expert-v0"
    assert episode.steps == 100
    assert episode.actions.shape == (100, 4)
    assert episode.observations["observation"].shape[0] == 101


def test_minari_loads_the_dataset_by_id_and_recovers_the_env(
    minari_dataset, npz_dataset, monkeypatch
):
    minari = pytest.importorskip("minari")
    monkeypatch.setenv("MINARI_DATASETS_PATH", str(minari_dataset.path.parents[2]))
    assert list(minari.list_local_datasets()) == [minari_dataset.dataset_id]
    dataset = minari.load_dataset(minari_dataset.dataset_id)
    assert dataset.total_episodes == EPISODES
    assert dataset.total_steps == npz_dataset.steps
    assert dataset.storage.metadata["lynxsim"]["first_seed"] == SEED
    seeds = [m["seed"] for m in dataset.storage.get_episode_metadata(range(EPISODES))]
    assert seeds == [SEED + i for i in range(EPISODES)]
    ours_all = read_npz(npz_dataset.path)
    for ours, theirs in zip(ours_all, dataset.iterate_episodes(), strict=True):
        for key, obs in ours.observations.items():
            np.testing.assert_array_equal(theirs.observations[key], obs)
        np.testing.assert_array_equal(theirs.actions, ours.actions)
        np.testing.assert_array_equal(theirs.rewards, ours.rewards)
        np.testing.assert_array_equal(theirs.terminations, ours.terminations)
        np.testing.assert_array_equal(theirs.truncations, ours.truncations)
        for key, info in ours.infos.items():
            np.testing.assert_array_equal(theirs.infos[key], info)
    env = dataset.recover_environment()
    try:
        assert env.spec.id == PICK_AND_PLACE_ID
        obs, _ = env.reset(seed=SEED)
        first = ours_all[0].observations
        for key, value in obs.items():
            np.testing.assert_array_equal(value, first[key][0])
    finally:
        env.close()
