"""The batched vector env: bit-identical to SyncVectorEnv of gym.make envs, autoreset included."""

from __future__ import annotations

from typing import Any

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.vector import AutoresetMode
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp

from lynxsim.envs import Randomization
from lynxsim.envs.reach import ReachEnv
from lynxsim.envs.vector import LynxVectorEnv
from lynxsim.errors import InvalidInputError, NonFiniteInputError

NUM_ENVS = 3
EPISODE_STEPS = 6
"""Short episodes: every run below truncates and autoresets."""


def assert_same(a: Any, b: Any, where: str = "") -> None:
    """Equal bit for bit, with the same dtypes and the same keys (dicts of arrays)."""
    if isinstance(a, dict):
        assert isinstance(b, dict), where
        assert set(a) == set(b), f"{where}: {set(a) ^ set(b)}"
        for key in a:
            assert_same(a[key], b[key], f"{where}/{key}")
        return
    if isinstance(a, tuple):
        assert isinstance(b, tuple), where
        assert len(a) == len(b), where
        for k, (u, v) in enumerate(zip(a, b)):
            assert_same(u, v, f"{where}[{k}]")
        return
    x, y = np.asarray(a), np.asarray(b)
    assert x.dtype == y.dtype, f"{where}: {x.dtype} != {y.dtype}"
    assert x.shape == y.shape, f"{where}: {x.shape} != {y.shape}"
    assert np.array_equal(x, y), f"{where}: {x} != {y}"


def pair(
    env_id: str,
    episode_steps: int = EPISODE_STEPS,
    batch: dict[str, int] | None = None,
    **kwargs: Any,
) -> tuple[gym.vector.VectorEnv, gym.vector.VectorEnv]:
    """The batched vector env (and its ``batch`` options) and SyncVectorEnv of one id, options."""
    made = [
        gym.make_vec(
            env_id,
            num_envs=NUM_ENVS,
            vectorization_mode=mode,
            max_episode_steps=episode_steps,
            **extra,
            **kwargs,
        )
        for mode, extra in (("vector_entry_point", batch or {}), ("sync", {}))
    ]
    return made[0], made[1]


def run_both(
    batched: gym.vector.VectorEnv,
    sync: gym.vector.VectorEnv,
    steps: int,
    *,
    seed: int = 7,
    push: np.ndarray | None = None,
) -> list[tuple[Any, ...]]:
    """Reset both with one seed and step both with the same random actions; compare everything.

    ``push``: added to env 0's action (drives it somewhere on purpose). Returns
    the batched env's steps.
    """
    assert_same(batched.reset(seed=seed), sync.reset(seed=seed), "reset")
    rng = np.random.default_rng(seed)
    shape = batched.action_space.shape
    infos = []
    for t in range(steps):
        actions = rng.uniform(-1.0, 1.0, shape).astype(np.float32)
        if push is not None:
            actions[0] = np.clip(actions[0] + push, -1.0, 1.0)
        got, want = batched.step(actions), sync.step(actions)
        for name, x, y in zip(("obs", "reward", "terminated", "truncated", "info"), got, want):
            assert_same(x, y, f"step {t} {name}")
        infos.append(got)
    return infos


@pytest.mark.parametrize(
    ("env_id", "kwargs"),
    [
        ("LynxPickAndPlace-v1", {}),
        ("LynxReach-v1", {}),
        ("LynxPickAndPlace-v0", {"control": "joint"}),
        (
            "LynxPickAndPlace-v1",
            {
                "random_obstacles": (1, 3),
                "randomize": Randomization(
                    cube_size_m=(0.02, 0.03), servo_gain_tolerance=0.1, joint_damping_tolerance=0.1
                ),
                "reward_type": "dense",
            },
        ),
        ("LynxReach-v1", {"random_obstacles": 2, "collision_penalty": 1.0}),
        ("LynxPickAndPlace-v2", {}),
        ("LynxReach-v2", {"random_obstacles": (0, 2)}),
    ],
    ids=[
        "pick",
        "reach",
        "pick-v0-joint",
        "pick-random-scenes",
        "reach-random-obstacles",
        "pick-v2",
        "reach-v2",
    ],
)
@pytest.mark.parametrize(
    "batch", [{}, {"nthread": 1, "chunks": 1}, {"chunks": 3}], ids=["default", "serial", "chunks-3"]
)
def test_batched_env_equals_sync_vector_env_bit_for_bit(env_id, kwargs, batch):
    batched, sync = pair(env_id, batch=batch, **kwargs)
    assert isinstance(batched.unwrapped, LynxVectorEnv)
    assert batched.metadata["autoreset_mode"] is AutoresetMode.NEXT_STEP
    assert batched.observation_space == sync.observation_space
    assert batched.action_space == sync.action_space
    steps = run_both(batched, sync, 2 * EPISODE_STEPS + 3)
    assert [bool(truncated.all()) for *_, truncated, _ in steps].count(True) == 2
    assert_same_data(batched, sync)
    batched.close()
    sync.close()


def assert_same_data(batched: gym.vector.VectorEnv, sync: gym.vector.VectorEnv) -> None:
    """Each env's MjData as mj_step left it: the state, positions and contacts."""
    for mine, theirs in zip(batched.unwrapped.envs, sync.envs, strict=True):
        a, b = mine.data, theirs.unwrapped.data
        for name in ("time", "qpos", "qvel", "ctrl", "qacc_warmstart", "xpos", "geom_xpos", "ncon"):
            assert_same(getattr(a, name), getattr(b, name), name)
        assert_same(a.contact.geom[: a.ncon], b.contact.geom[: b.ncon], "contact.geom")
        assert_same(a.contact.dist[: a.ncon], b.contact.dist[: b.ncon], "contact.dist")


def test_collisions_terminate_and_autoreset_bit_for_bit():
    batched, sync = pair(
        "LynxPickAndPlace-v1",
        30,
        control="joint",
        collision_penalty=3.0,
        terminate_on_collision=True,
        collision_check="physics_step",
    )
    turn = np.array([2.0, 0, 0, 0, 0, 2.0])  # base towards +y: through the obstacle at 45 deg
    steps = run_both(batched, sync, 45, push=turn)
    hit = [bool(info["collision"][0]) for *_, info in steps]
    assert any(hit)
    ended = hit.index(True)
    _, reward, terminated, _, _ = steps[ended]
    assert terminated[0]
    assert reward[0] <= -3.0
    _, reward, terminated, _, info = steps[ended + 1]  # env 0 reset, the others stepped
    assert reward[0] == 0.0
    assert not terminated[0]
    assert not info["collision"][0]
    assert_same_data(batched, sync)
    batched.close()
    sync.close()


def test_reset_mask_and_seed_lists_as_sync():
    batched, sync = pair("LynxReach-v1")
    run_both(batched, sync, 2)
    mask = np.array([False, True, False])
    for env in (batched, sync):
        env.action_space.seed(1)
    got = batched.reset(seed=[None, 5, None], options={"reset_mask": mask})
    want = sync.reset(seed=[None, 5, None], options={"reset_mask": mask})
    assert_same(got, want, "masked reset")
    actions = batched.action_space.sample()
    assert_same(batched.step(actions), sync.step(actions), "step after masked reset")


def test_compute_reward_of_the_batch_is_the_steps_reward():
    batched, _ = pair("LynxPickAndPlace-v1", reward_type="dense", collision_penalty=2.0)
    batched.reset(seed=0)
    actions = np.zeros(batched.action_space.shape, dtype=np.float32)
    obs, rewards, _, _, infos = batched.step(actions)
    again = batched.unwrapped.compute_reward(obs["achieved_goal"], obs["desired_goal"], infos)
    np.testing.assert_array_equal(again, rewards)
    singles = batched.unwrapped.call(
        "compute_reward", obs["achieved_goal"], obs["desired_goal"], infos
    )
    for single in singles:
        np.testing.assert_array_equal(single, rewards)


@pytest.mark.parametrize(
    ("make", "message"),
    [
        (lambda: LynxVectorEnv(ReachEnv, num_envs=0), "num_envs"),
        (
            lambda: gym.make_vec(
                "LynxReach-v1", num_envs=2, vectorization_mode="vector_entry_point",
                render_mode="human",
            ),
            "rgb_array frames only",
        ),
        (
            lambda: gym.make_vec(
                "LynxReach-v1", num_envs=2, vectorization_mode="vector_entry_point", nthread=0
            ),
            "nthread",
        ),
        (lambda: LynxVectorEnv(ReachEnv, num_envs=2, chunks=0), "chunks"),
    ],
    ids=["no-envs", "human", "no-threads", "no-chunks"],
)  # fmt: skip
def test_bad_construction_is_refused(make, message):
    with pytest.raises(InvalidInputError, match=message):
        make()


@pytest.fixture(scope="module")
def reach_batch():
    env = gym.make_vec("LynxReach-v1", num_envs=2, vectorization_mode="vector_entry_point")
    yield env
    env.close()


def test_step_before_reset_and_bad_seeds_are_refused():
    env = gym.make_vec("LynxReach-v1", num_envs=2, vectorization_mode="vector_entry_point")
    with pytest.raises(InvalidInputError, match="reset"):
        env.step(np.zeros((2, 4), dtype=np.float32))
    with pytest.raises(InvalidInputError, match="seed"):
        env.reset(seed=[1, 2, 3])
    with pytest.raises(InvalidInputError, match="reset_mask"):
        env.reset(options={"reset_mask": np.array([True, False])})
    env.reset(seed=0)
    with pytest.raises(InvalidInputError, match="reset_mask"):
        env.reset(options={"reset_mask": [True, False]})


@settings(max_examples=40, deadline=None)
@given(
    actions=hnp.arrays(
        dtype=np.float64,
        shape=hnp.array_shapes(min_dims=1, max_dims=3, max_side=5),
        elements=st.floats(allow_nan=True, allow_infinity=True),
    )
)
def test_fuzzed_actions_step_or_raise_a_typed_error(reach_batch, actions):
    reach_batch.reset(seed=0)
    try:
        obs, *_ = reach_batch.step(actions)
    except (InvalidInputError, NonFiniteInputError):
        return
    assert actions.shape == (2, 4)
    assert np.isfinite(obs["observation"]).all()


@pytest.mark.parametrize(
    ("quality", "side"),
    [("lean", (84, 84)), ("fast", (128, 96))],
    ids=["lean-84", "fast-128x96"],
)
def test_image_observations_of_the_batch_equal_each_envs_own(quality, side):
    batched, sync = pair(
        "LynxPickAndPlace-v1",
        3,
        pixels=("front", "top"),
        pixel_width=side[0],
        pixel_height=side[1],
        render_quality=quality,
        random_obstacles=(1, 2),
    )
    steps = run_both(batched, sync, 5)
    pixels = steps[-1][0]["pixels"]
    assert pixels.shape == (NUM_ENVS, side[1], side[0], 6)
    assert pixels.std() > 20.0  # a scene, not a blank frame
    assert not np.array_equal(pixels[0], pixels[1])
    batched.close()
    sync.close()


def test_make_vec_without_a_mode_gives_the_batch():
    env = gym.make_vec("LynxReach-v2", num_envs=2)
    assert isinstance(env.unwrapped, LynxVectorEnv)
    assert env.unwrapped.max_episode_steps == 100  # the registered time limit
    env.close()
