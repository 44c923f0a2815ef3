"""Randomised obstacles in the arm envs: drawn from np_random, clear of the task, exact physics."""

from __future__ import annotations

import gymnasium as gym
import mujoco
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

from lynxsim.envs import PickAndPlaceExpert
from lynxsim.envs.base import READY_TOOL_POSE, WORK_CLEARANCE_M
from lynxsim.envs.evaluation import run_episode
from lynxsim.envs.workspace import work_column
from lynxsim.scene import Box, Cylinder, Sphere
from lynxsim.sim.arm.model import load_arm_scene
from lynxsim.sim.arm.playback import arm_checker

SEEDS = range(30)


@pytest.fixture(scope="module")
def env() -> gym.Env:
    e = gym.make("LynxPickAndPlace-v1", random_obstacles=(1, 3))
    yield e
    e.close()


def test_every_reset_draws_a_new_scene_within_the_range(env: gym.Env) -> None:
    scenes = set()
    for seed in SEEDS:
        env.reset(seed=seed)
        obstacles = env.unwrapped.obstacles
        assert 1 <= len(obstacles) <= 3
        assert all(isinstance(o, Cylinder | Box | Sphere) for o in obstacles)
        scenes.add(obstacles)
    assert len(scenes) == len(SEEDS)
    assert {type(o) for s in scenes for o in s} == {Cylinder, Box, Sphere}


def test_the_same_seed_gives_the_same_scene_and_observation(env: gym.Env) -> None:
    other = gym.make("LynxPickAndPlace-v1", random_obstacles=(1, 3))
    for seed in (3, 17):
        a, _ = env.reset(seed=seed)
        env.reset(seed=seed + 1)  # a different scene in between
        a2, _ = env.reset(seed=seed)
        b, _ = other.reset(seed=seed)
        assert env.unwrapped.obstacles == other.unwrapped.obstacles
        for key in a:
            np.testing.assert_array_equal(a[key], b[key])
            np.testing.assert_array_equal(a[key], a2[key])


def test_obstacles_keep_clear_of_the_cube_goal_and_where_the_arm_works(env: gym.Env) -> None:
    for seed in SEEDS:
        obs, _ = env.reset(seed=seed)
        u = env.unwrapped
        cube, goal = obs["achieved_goal"], obs["desired_goal"]
        for obstacle in u.obstacles:
            for point in (cube, goal, READY_TOOL_POSE[:3]):
                assert obstacle.distance(tuple(point)) >= 0.06
        # Judged by a model compiled with the episode's obstacles (not the slots).
        checker = arm_checker(load_arm_scene(u.scene))
        q = np.concatenate(
            [
                np.array([u.q_ready]),
                work_column(cube, 0.07, u.q_ready),
            ]
        )
        assert checker.min_clearance(q).min() >= WORK_CLEARANCE_M
        held = work_column(goal, max(goal[2], 0.07), u.q_ready)
        assert checker.min_clearance(held, grasped=True).min() >= WORK_CLEARANCE_M


def test_the_physics_sees_the_drawn_obstacles(env: gym.Env) -> None:
    """Poses touching an obstacle of the compiled scene touch it in the env, and only those."""
    env.reset(seed=5)
    u = env.unwrapped
    target = u.obstacles[0]
    d = u.data
    reference = arm_checker(load_arm_scene(u.scene))  # compiled with the episode's obstacles
    rng = np.random.default_rng(0)
    q = rng.uniform(-1.5, 1.5, (4000, 5))
    q[:, 4] = np.pi
    hits = reference.check(q)
    column = reference.groups.obstacle_names.index(target.name)
    touching = q[hits.clearance_m[:, column] <= 0.0]
    assert len(touching) > 0
    for joints in touching[:20]:
        d.qpos[list(u.ids.arm_qpos)] = joints
        mujoco.mj_forward(u.model, d)
        assert u._touching_obstacle()
    free = q[~hits.obstacle & ~hits.self_hit & ~hits.support][:20]
    for joints in free:
        d.qpos[list(u.ids.arm_qpos)] = joints
        mujoco.mj_forward(u.model, d)
        assert not u._touching_obstacle()


def test_check_env_passes_with_random_obstacles(env: gym.Env) -> None:
    check_env(env.unwrapped, skip_render_check=True)


def test_rendering_shows_the_episode_obstacles() -> None:
    def frame(seed: int) -> np.ndarray:
        env = gym.make(
            "LynxPickAndPlace-v1",
            random_obstacles=3,
            render_mode="rgb_array",
            width=160,
            height=120,
        )
        env.reset(seed=seed)
        image = env.render()
        env.close()
        return image

    first, second, again = frame(1), frame(2), frame(1)
    np.testing.assert_array_equal(first, again)
    assert (first != second).any(axis=2).sum() > 500  # other obstacles, cube and goal


@pytest.mark.slow
def test_expert_succeeds_around_random_obstacles_without_contact(env: gym.Env) -> None:
    """Issue acceptance: >= 95 % of 100 seeded episodes, no arm-obstacle contact at all."""
    expert = PickAndPlaceExpert(env)
    episodes = [run_episode(env, expert, seed) for seed in range(100)]
    success = sum(e.success for e in episodes) / len(episodes)
    assert success >= 0.95, [e for e in episodes if not e.success]
    assert sum(e.collision_steps for e in episodes) == 0
