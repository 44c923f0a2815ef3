"""Image observations: space, channels, determinism, laziness, pickling, vector envs, errors."""

from __future__ import annotations

import pickle
import warnings

import gymnasium as gym
import mujoco
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

from lynxsim.envs import PickAndPlaceEnv, ReachEnv
from lynxsim.errors import InvalidInputError
from tests.envs.conftest import ENV_MODE_IDS, ENV_MODES

SIZE = (64, 48)
"""(width, height) of the image observations of these tests [px]; not square, to catch swaps."""
PIXEL_STD_MIN = 5.0
"""Least standard deviation of an image's pixels: not blank."""
STEPS = 5


def _pixel_env(env_id: str = "LynxPickAndPlace-v1", **kwargs: object) -> gym.Env:
    kwargs = {"pixels": ("front",), "pixel_width": SIZE[0], "pixel_height": SIZE[1], **kwargs}
    return gym.make(env_id, **kwargs)


def _actions(env: gym.Env, n: int = STEPS) -> np.ndarray:
    rng = np.random.default_rng(0)
    return rng.uniform(-1.0, 1.0, (n, *env.action_space.shape)).astype(np.float32)


def _pixel_rollout(env: gym.Env, seed: int, actions: np.ndarray) -> list[np.ndarray]:
    frames = [env.reset(seed=seed)[0]["pixels"]]
    frames += [env.step(a)[0]["pixels"] for a in actions]
    return frames


@pytest.mark.parametrize(("env_id", "control"), ENV_MODES, ids=ENV_MODE_IDS)
def test_check_env_passes_with_pixels(env_id, control):
    env = _pixel_env(env_id, control=control)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        check_env(env.unwrapped, skip_render_check=True)
    assert [str(w.message) for w in caught if "infinity" not in str(w.message)] == []
    env.close()


def test_pixels_are_uint8_images_of_the_given_size_in_the_observation_space():
    env = _pixel_env()
    space = env.observation_space["pixels"]
    assert isinstance(space, gym.spaces.Box)
    assert space.shape == (SIZE[1], SIZE[0], 3)
    assert space.dtype == np.uint8
    assert (space.low == 0).all()
    assert (space.high == 255).all()
    obs, _ = env.reset(seed=0)
    assert obs["pixels"].shape == space.shape
    assert obs["pixels"].dtype == np.uint8
    assert obs["pixels"].std() > PIXEL_STD_MIN
    assert set(obs) == {"observation", "achieved_goal", "desired_goal", "pixels"}
    assert env.observation_space.contains(obs)
    env.close()


def test_without_pixels_the_observation_is_unchanged():
    env = PickAndPlaceEnv()
    assert set(env.observation_space) == {"observation", "achieved_goal", "desired_goal"}
    assert set(env.reset(seed=0)[0]) == {"observation", "achieved_goal", "desired_goal"}
    assert env.pixel_cameras == ()


def test_cameras_are_side_by_side_along_the_channels_in_the_order_given():
    both = _pixel_env(pixels=("front", "top"))
    front, top = _pixel_env(pixels="front"), _pixel_env(pixels=["top"])
    assert both.unwrapped.pixel_cameras == ("front", "top")
    assert both.observation_space["pixels"].shape == (SIZE[1], SIZE[0], 6)
    actions = _actions(both)
    for b, f, t in zip(*(_pixel_rollout(e, 4, actions) for e in (both, front, top))):
        np.testing.assert_array_equal(b[..., :3], f)
        np.testing.assert_array_equal(b[..., 3:], t)
    assert not np.array_equal(f, t)
    for e in (both, front, top):
        e.close()


def test_two_envs_with_one_seed_give_identical_pixels():
    a, b = _pixel_env(pixels=("front", "top")), _pixel_env(pixels=("front", "top"))
    actions = _actions(a)
    frames = _pixel_rollout(a, 7, actions)
    for x, y in zip(frames, _pixel_rollout(b, 7, actions)):
        np.testing.assert_array_equal(x, y)
    assert not np.array_equal(frames[0], frames[-1])  # the arm moved
    a.close()
    b.close()


def test_reset_with_one_seed_twice_gives_identical_pixels():
    env = _pixel_env()
    actions = _actions(env)
    first = _pixel_rollout(env, 3, actions)
    for x, y in zip(first, _pixel_rollout(env, 3, actions)):
        np.testing.assert_array_equal(x, y)
    env.close()


def test_the_first_image_of_a_new_renderer_equals_a_rerender_of_the_state():
    # A fresh MuJoCo scene drew its first frame differently (7 % of the pixels at 160x120).
    env = _pixel_env(pixel_width=160, pixel_height=120)
    obs, _ = env.reset(seed=0)
    u = env.unwrapped
    np.testing.assert_array_equal(u._pixels.render(u.data), obs["pixels"])
    env.close()


def test_pixels_do_not_show_the_goal():
    env = _pixel_env()
    obs, _ = env.reset(seed=0)
    u = env.unwrapped
    u._set_goal(u.goal + np.array([0.05, -0.05, 0.0]))  # moves the scene's goal mark
    mujoco.mj_kinematics(u.model, u.data)
    np.testing.assert_array_equal(u._pixels.render(u.data), obs["pixels"])
    env.close()


def test_pixels_are_new_arrays_at_every_step():
    env = _pixel_env()
    before = env.reset(seed=0)[0]["pixels"]
    kept = before.copy()
    after = env.step(env.action_space.sample())[0]["pixels"]
    assert not np.shares_memory(before, after)
    np.testing.assert_array_equal(before, kept)
    env.close()


def test_the_pixel_renderer_is_made_at_the_first_observation_apart_from_render():
    env = _pixel_env(render_mode="rgb_array", width=96, height=72)
    u = env.unwrapped
    assert not u._pixels.started
    obs, _ = env.reset(seed=0)
    assert u._pixels.started
    assert not u._renderer.started
    assert env.render().shape == (72, 96, 3)
    assert obs["pixels"].shape == (SIZE[1], SIZE[0], 3)
    env.close()
    env.close()  # twice is harmless


def test_envs_with_pixels_pickle_without_their_gl_context():
    env = ReachEnv(pixels=("top",), pixel_width=SIZE[0], pixel_height=SIZE[1])
    env.reset(seed=1)
    copy = pickle.loads(pickle.dumps(env))
    assert not copy._pixels.started
    action = np.array([0.4, 0.1, -0.3, 0.0], dtype=np.float32)
    np.testing.assert_array_equal(copy.step(action)[0]["pixels"], env.step(action)[0]["pixels"])
    env.close()
    copy.close()


def test_async_vector_env_with_pixels_renders_in_its_workers():
    env = gym.make_vec(
        "LynxReach-v1",
        num_envs=2,
        vectorization_mode="async",
        vector_kwargs={"context": "forkserver"},
        pixels=("front",),
        pixel_width=SIZE[0],
        pixel_height=SIZE[1],
    )
    obs, _ = env.reset(seed=[0, 1])
    assert obs["pixels"].shape == (2, SIZE[1], SIZE[0], 3)
    obs, *_ = env.step(env.action_space.sample())
    assert obs["pixels"].dtype == np.uint8
    assert obs["pixels"].std() > PIXEL_STD_MIN
    env.close()


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"pixels": ("side",)}, r"no camera named 'side'; cameras: front, top"),
        ({"pixels": ("front", "front")}, r"pixels must name distinct cameras"),
        ({"pixels": 3}, r"pixels must be a camera name or a sequence of them"),
        ({"pixels": ("front", None)}, r"pixels must be a camera name or a sequence of them"),
        ({"pixels": ("front",), "pixel_width": 0}, r"pixel_width"),
        ({"pixels": ("front",), "pixel_height": 84.0}, r"pixel_height"),
        ({"pixels": ("front",), "pixel_height": 2000}, r"exceeds the model's off-screen buffer"),
    ],
    ids=["unknown-camera", "repeated", "not-names", "none-name", "zero-width", "float-height",
         "too-tall"],
)  # fmt: skip
def test_bad_pixel_options_raise(kwargs, message):
    with pytest.raises(InvalidInputError, match=message):
        PickAndPlaceEnv(**kwargs)
