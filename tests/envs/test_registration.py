"""Registration: ``import lynxsim.envs`` registers the envs; ``import lynxsim`` stays light."""

from __future__ import annotations

import subprocess
import sys
import textwrap

import gymnasium as gym
import numpy as np
import pytest

import lynxsim.envs
from lynxsim.envs import ENV_IDS, PickAndPlaceEnv, ReachEnv

LIGHT_MODULES = [
    "lynxsim",
    "lynxsim.arm",
    "lynxsim.rrr",
    "lynxsim.traj",
    "lynxsim.scene",
    "lynxsim.tasks",
]
"""Modules whose import loads neither MuJoCo nor Gymnasium."""


def _run_python(code: str) -> subprocess.CompletedProcess[str]:
    """Run ``code`` in a fresh interpreter (an empty ``sys.modules`` and gym registry)."""
    return subprocess.run(
        [sys.executable, "-c", textwrap.dedent(code)],
        capture_output=True,
        text=True,
        timeout=120,
        check=False,
    )


@pytest.mark.parametrize("module", LIGHT_MODULES)
def test_math_and_task_modules_import_neither_mujoco_nor_gymnasium(module):
    run = _run_python(
        f"""
        import sys, {module}
        print(sorted(m for m in ("mujoco", "gymnasium") if m in sys.modules))
        """
    )
    assert run.returncode == 0, run.stderr[-2000:]
    assert run.stdout.strip() == "[]"


def test_import_lynxsim_registers_nothing():
    run = _run_python(
        """
        import gymnasium as gym, lynxsim
        print(sorted(i for i in gym.registry if i.startswith("Lynx")))
        """
    )
    assert run.returncode == 0, run.stderr[-2000:]
    assert run.stdout.strip() == "[]"


def test_import_lynxsim_envs_registers_them_without_mujoco():
    run = _run_python(
        """
        import sys
        import gymnasium as gym
        import lynxsim.envs

        gym.register_envs(lynxsim.envs)
        assert {"LynxPickAndPlace-v1", "LynxReach-v1"} <= set(gym.registry)
        assert "mujoco" not in sys.modules
        env = gym.make("LynxPickAndPlace-v1")
        env.reset(seed=0)
        print(type(env.unwrapped).__name__)
        """
    )
    assert run.returncode == 0, run.stderr[-2000:]
    assert run.stdout.strip() == "PickAndPlaceEnv"


def test_module_colon_id_makes_without_an_import():
    run = _run_python(
        """
        import gymnasium as gym

        env = gym.make("lynxsim.envs:LynxPickAndPlace-v1")
        env.reset(seed=0)
        print(type(env.unwrapped).__name__, env.spec.max_episode_steps)
        """
    )
    assert run.returncode == 0, run.stderr[-2000:]
    assert run.stdout.strip() == "PickAndPlaceEnv 200"


def test_acceptance_make_and_reset():
    env = gym.make("LynxPickAndPlace-v1")
    obs, info = env.reset(seed=0)
    assert set(obs) == {"observation", "achieved_goal", "desired_goal"}
    assert info["is_success"] is False
    env.close()


def test_specs_use_string_entry_points_and_time_limits():
    steps = {"LynxPickAndPlace": 200, "LynxReach": 100}
    for env_id in ENV_IDS:
        spec = gym.spec(env_id)
        assert isinstance(spec.entry_point, str)
        assert spec.max_episode_steps == steps[env_id.split("-")[0]]
    fallback = {"v0": "hold", "v1": "nearest", "v2": "nearest"}
    for env_id in ENV_IDS:
        version = env_id.split("-")[1]
        assert gym.make(env_id).unwrapped.controller.fallback.value == fallback[version]
    assert isinstance(gym.make("LynxReach-v1").unwrapped, ReachEnv)
    assert isinstance(gym.make("LynxPickAndPlace-v1").unwrapped, PickAndPlaceEnv)


def test_registering_twice_is_harmless():
    lynxsim.envs.register_envs()
    assert gym.spec("LynxReach-v1").max_episode_steps == 100


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
