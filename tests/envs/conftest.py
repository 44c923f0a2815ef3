"""Fixtures of the env tests.

``MUJOCO_GL`` defaults to ``egl`` before any test module imports ``mujoco`` (MuJoCo
reads it once, at import), so that ``rgb_array`` rendering works headless.
"""

from __future__ import annotations

import os

os.environ.setdefault("MUJOCO_GL", "egl")

from collections.abc import Iterator

import gymnasium as gym
import pytest

import lynxsim.envs  # noqa: F401  (registers the envs)
from lynxsim.envs import LATEST_ENV_IDS

ENV_MODES = [(env_id, control) for env_id in LATEST_ENV_IDS for control in ("tool", "joint")]
"""Every registered env in every action mode."""
ENV_MODE_IDS = [f"{env_id.removeprefix('Lynx').removesuffix('-v1')}-{c}" for env_id, c in ENV_MODES]


@pytest.fixture
def pick_and_place() -> Iterator[gym.Env]:
    """``LynxPickAndPlace-v1`` as ``gym.make`` gives it (default arguments)."""
    env = gym.make("LynxPickAndPlace-v1")
    yield env
    env.close()
