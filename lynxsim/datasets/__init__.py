"""Demonstration datasets: seeded episodes of the scripted experts, with action noise.

:func:`write_dataset` steps a registered env (``gym.make(env_id)``, default
arguments) with its scripted expert (:class:`~lynxsim.envs.PickAndPlaceExpert` or
:class:`~lynxsim.envs.ReachExpert`); every action gets Gaussian noise of standard
deviation ``noise`` times the action range, from a generator seeded per episode
(:func:`noise_generator`), and is clipped to the action space. Episode ``i`` is
reset with seed ``seed + i``. The same arguments give the same bytes, in every
format::

    from lynxsim.datasets import read_npz, write_dataset

    summary = write_dataset("datasets", episodes=100, noise=0.1, seed=0)
    episodes = read_npz(summary.path)  # datasets/lynxsim/pick-and-place-v1/expert-v0

A dataset lives in ``OUT/DATASET_ID`` (default id
``lynxsim/pick-and-place-v1/expert-v0``), in one of three formats:

- ``npz`` (NumPy only): ``episodes.npz`` with the arrays of every episode
  (layout in :mod:`lynxsim.datasets.npz`) and ``metadata.json`` (env id and
  spec, noise, seeds, counts, the observation's named slices, versions);
- ``minari`` (extra ``lynxsim[datasets]``): Minari's standard format with HDF5
  storage; ``MINARI_DATASETS_PATH=OUT`` then ``minari.load_dataset(DATASET_ID)``
  loads it and ``recover_environment()`` makes the env (the same metadata under
  the key ``"lynxsim"``);
- ``lerobot`` (extra ``lynxsim[datasets]``, pyarrow; lerobot itself is not
  needed): LeRobot's ``LeRobotDataset`` v3.0, one row per step (layout in
  :mod:`lynxsim.datasets.lerobot_writer`; the same metadata in
  ``meta/lynxsim.json``); :func:`read_lerobot` reads it back.

Per episode of ``T`` steps, in the first two: observations (the dict's entries, ``T + 1``
rows: the reset's first, the final one last), actions as stepped (``T``, float32,
noise included), rewards, terminations and truncations (``T``), infos (``T + 1``
rows, the reset's first: ``is_success``, ``collision``, ``distance`` [m],
``reward_goal``, ``reward_collision``, ``target_status``, ``target_held``, and
``expert_action``, the expert's action before the noise, NaN in the reset's
row), and the episode's seed. The writer runs in a hidden temporary folder
renamed when complete and read back, so an interrupted run leaves no dataset.

The import is light (no MuJoCo, no Minari); the recording functions load the
envs, and MuJoCo, on first use.
"""

from __future__ import annotations

import importlib
from typing import Any

__all__ = [
    "INFO_KEYS",
    "MAX_NOISE",
    "MAX_SEED",
    "DatasetFormat",
    "DatasetSummary",
    "Episode",
    "MissingExtraError",
    "action_noise_std",
    "check_dataset_id",
    "check_noise",
    "default_dataset_id",
    "noise_generator",
    "read_lerobot",
    "read_npz",
    "record_episode",
    "write_dataset",
]

_LAZY = {
    "INFO_KEYS": "lynxsim.datasets.episode",
    "MAX_NOISE": "lynxsim.envs.noise",
    "Episode": "lynxsim.datasets.episode",
    "action_noise_std": "lynxsim.envs.noise",
    "check_noise": "lynxsim.envs.noise",
    "noise_generator": "lynxsim.envs.noise",
    "record_episode": "lynxsim.datasets.episode",
    "DatasetFormat": "lynxsim.datasets.layout",
    "check_dataset_id": "lynxsim.datasets.layout",
    "default_dataset_id": "lynxsim.datasets.layout",
    "MissingExtraError": "lynxsim.datasets.minari_writer",
    "read_npz": "lynxsim.datasets.npz",
    "read_lerobot": "lynxsim.datasets.lerobot_check",
    "MAX_SEED": "lynxsim.datasets.record",
    "DatasetSummary": "lynxsim.datasets.record",
    "write_dataset": "lynxsim.datasets.record",
}


def __getattr__(name: str) -> Any:
    if name in _LAZY:
        return getattr(importlib.import_module(_LAZY[name]), name)
    raise AttributeError(f"module 'lynxsim.datasets' has no attribute {name!r}")
