"""Registration: ``import lynxsim`` registers the envs without importing MuJoCo."""

from __future__ import annotations

import subprocess
import sys

import gymnasium as gym
import numpy as np

import lynxsim.envs
from lynxsim.envs import ENV_IDS, PickAndPlaceEnv, ReachEnv


def test_import_lynxsim_registers_envs_and_stays_light():
    code = (
        "import sys, gymnasium, lynxsim; "
        "ids = {'LynxPickAndPlace-v0', 'LynxReach-v0'}; "
        "sys.exit(0 if ids <= set(gymnasium.registry) and 'mujoco' not in sys.modules else 1)"
    )
    assert subprocess.run([sys.executable, "-c", code], check=False).returncode == 0


def test_acceptance_make_and_reset():
    env = gym.make("LynxPickAndPlace-v0")
    obs, info = env.reset(seed=0)
    assert set(obs) == {"observation", "achieved_goal", "desired_goal"}
    assert info["is_success"] is False
    env.close()


def test_specs_use_string_entry_points_and_time_limits():
    steps = {"LynxPickAndPlace-v0": 200, "LynxReach-v0": 100}
    for env_id in ENV_IDS:
        spec = gym.spec(env_id)
        assert isinstance(spec.entry_point, str)
        assert spec.max_episode_steps == steps[env_id]
    assert isinstance(gym.make("LynxReach-v0").unwrapped, ReachEnv)
    assert isinstance(gym.make("LynxPickAndPlace-v0").unwrapped, PickAndPlaceEnv)


def test_registering_twice_is_harmless():
    lynxsim.envs.register_envs()
    assert gym.spec("LynxReach-v0").max_episode_steps == 100


def test_manual_documents_every_observation():
    for cls in (PickAndPlaceEnv, ReachEnv):
        size = max(s.stop for s in cls.OBS_INDEX.values())
        assert size == cls._OBS_SIZE
        assert f"shape ({size},)" in " ".join(cls.__doc__.split())
        env = cls()
        obs, _ = env.reset(seed=0)
        assert obs["observation"].shape == (size,)
        assert np.isfinite(obs["observation"]).all()
        env.close()
