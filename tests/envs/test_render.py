"""Rendering: rgb_array frames of the asked size and camera, lazily made; human mode guarded."""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest

from lynxsim.envs import ReachEnv
from lynxsim.errors import InvalidInputError

RENDER_STD_MIN = 5.0
"""Least standard deviation of a frame's pixels: not blank."""


def test_rgb_array_frames_are_not_blank_and_follow_the_arguments():
    env = gym.make("LynxPickAndPlace-v1", render_mode="rgb_array", width=320, height=240)
    env.reset(seed=0)
    assert not env.unwrapped._renderer.started  # nothing made before the first frame
    frame = env.render()
    assert frame.shape == (240, 320, 3)
    assert frame.dtype == np.uint8
    assert frame.std() > RENDER_STD_MIN
    env.step(env.action_space.sample())
    assert not np.array_equal(env.render(), np.zeros_like(frame))
    top = gym.make("LynxPickAndPlace-v1", render_mode="rgb_array", width=320, height=240,
                   camera="top")  # fmt: skip
    top.reset(seed=0)
    assert not np.array_equal(top.render(), frame)
    env.close()
    top.close()
    env.close()  # twice is harmless


def test_render_without_a_mode_gives_none():
    env = ReachEnv()
    env.reset(seed=0)
    assert env.render() is None


def test_human_mode_needs_a_display(monkeypatch):
    monkeypatch.delenv("DISPLAY", raising=False)
    monkeypatch.delenv("WAYLAND_DISPLAY", raising=False)
    with pytest.raises(InvalidInputError, match="render_mode='human' needs a display"):
        ReachEnv(render_mode="human")


def test_envs_pickle_before_and_after_rendering():
    import pickle

    env = ReachEnv(render_mode="rgb_array", width=96, height=72)
    env.reset(seed=3)
    copy = pickle.loads(pickle.dumps(env))  # before any frame
    frame = env.render()
    assert frame is not None
    again = pickle.loads(pickle.dumps(env))  # after: the GL context is dropped, not pickled
    frame_again = again.render()  # and made anew on the next frame
    np.testing.assert_array_equal(frame_again, frame)
    np.testing.assert_array_equal(copy.render(), frame)
    action = np.array([0.3, -0.2, 0.1, 0.0], dtype=np.float32)
    obs, *_ = env.step(action)
    obs_again, *_ = again.step(action)
    np.testing.assert_array_equal(obs_again["observation"], obs["observation"])
    for e in (env, copy, again):
        e.close()
