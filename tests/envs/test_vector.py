"""Vector envs: sync and async, renderers made lazily in the workers."""

from __future__ import annotations

import subprocess
import sys
import textwrap

import gymnasium as gym
import numpy as np
import pytest

NUM_ENVS = 2


@pytest.mark.parametrize(
    ("mode", "vector_kwargs"),
    [("sync", {}), ("async", {"context": "forkserver"})],
    ids=["sync", "async-forkserver"],
)
def test_vector_env_of_two_runs_and_autoresets(mode, vector_kwargs):
    env = gym.make_vec(
        "LynxReach-v1",
        num_envs=NUM_ENVS,
        vectorization_mode=mode,
        vector_kwargs=vector_kwargs,
        max_episode_steps=5,
        render_mode="rgb_array",
    )
    obs, info = env.reset(seed=[0, 1])
    assert obs["observation"].shape == (NUM_ENVS, 26)
    assert not np.array_equal(obs["desired_goal"][0], obs["desired_goal"][1])
    env.action_space.seed(0)
    for _ in range(7):
        obs, reward, _terminated, _truncated, info = env.step(env.action_space.sample())
        assert reward.shape == (NUM_ENVS,)
        assert info["collision"].dtype == bool
    frames = env.render()
    assert len(frames) == NUM_ENVS
    assert all(f.std() > 5.0 for f in frames)
    env.close()


def test_async_vector_env_with_the_default_start_method():
    # A fresh interpreter: no GL context exists before the workers fork.
    code = textwrap.dedent(
        """
        import gymnasium as gym, lynxsim.envs
        env = gym.make_vec("LynxPickAndPlace-v1", num_envs=2, vectorization_mode="async")
        env.reset(seed=0)
        for _ in range(5):
            env.step(env.action_space.sample())
        env.close()
        """
    )
    run = subprocess.run([sys.executable, "-c", code], timeout=120, check=False)
    assert run.returncode == 0


def test_forking_after_rendering_raises_instead_of_hanging():
    code = textwrap.dedent(
        """
        import gymnasium as gym, lynxsim.envs
        parent = gym.make("LynxReach-v1", render_mode="rgb_array")
        parent.reset(seed=0)
        parent.render()
        env = gym.make_vec(
            "LynxReach-v1", num_envs=2, vectorization_mode="async", render_mode="rgb_array"
        )
        env.reset(seed=0)
        try:
            env.render()
        except Exception as exc:
            print(type(exc).__name__, exc)
        """
    )
    run = subprocess.run(
        [sys.executable, "-c", code], timeout=120, capture_output=True, text=True, check=False
    )
    assert "LynxsimError" in run.stdout, run.stderr[-2000:]
    assert "forkserver" in run.stdout
