"""The scripted experts: success and zero arm–obstacle contact over seeded episodes."""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest

from lynxsim.envs import PickAndPlaceExpert, ReachExpert, evaluate
from lynxsim.envs.evaluation import run_episode
from lynxsim.errors import InvalidInputError

EXPERT_EPISODES = 20
"""Episodes in the test (the CLI and the report use 100; the suite must stay quick)."""
MIN_SUCCESS = 0.95


def test_pick_and_place_expert_succeeds_without_touching_the_obstacle():
    summary = evaluate("LynxPickAndPlace-v0", "expert", EXPERT_EPISODES, seed=1000)
    assert summary.success_rate >= MIN_SUCCESS, [e for e in summary.episodes if not e.success]
    assert summary.collision_steps == 0
    goals_in_air = 0
    for e in summary.episodes:
        assert e.first_success_step is not None
        assert e.first_success_step < 150
    env = gym.make("LynxPickAndPlace-v0")
    for i in range(EXPERT_EPISODES):
        obs, _ = env.reset(seed=1000 + i)
        goals_in_air += obs["desired_goal"][2] > 0.01
    assert 0 < goals_in_air < EXPERT_EPISODES  # both kinds of goal were tried


def test_pick_and_place_expert_needs_no_obstacle_knowledge():
    summary = evaluate("LynxPickAndPlace-v0", "expert", 5, seed=2000, env_kwargs={"obstacles": ()})
    assert summary.success_rate == 1.0


def test_expert_grasps_by_friction_and_holds_goals_in_the_air():
    env = gym.make("LynxPickAndPlace-v0", goal_in_air_prob=1.0)
    expert = PickAndPlaceExpert(env)
    stats = run_episode(env, expert, seed=7)
    u = env.unwrapped
    assert stats.success
    assert u.cube_position[2] > 0.02
    assert u.model.neq == 1  # only the finger coupling: no weld to the cube
    opening = u.data.qpos[u._finger_qpos].sum()
    assert opening == pytest.approx(0.025, abs=0.002)  # the fingers stand on the cube's faces


def test_reach_expert_succeeds_without_touching_the_obstacle():
    summary = evaluate("LynxReach-v0", "expert", 10, seed=0)
    assert summary.success_rate == 1.0
    assert summary.collision_steps == 0


def test_experts_refuse_other_envs_and_joint_control():
    with pytest.raises(InvalidInputError, match="this expert drives a PickAndPlaceEnv"):
        PickAndPlaceExpert(gym.make("LynxReach-v0"))
    with pytest.raises(InvalidInputError, match="the expert needs control='tool'"):
        ReachExpert(gym.make("LynxReach-v0", control="joint"))


def test_random_policy_is_seeded():
    a = evaluate("LynxReach-v0", "random", 2, seed=4)
    b = evaluate("LynxReach-v0", "random", 2, seed=4)
    assert a == b
    assert np.isfinite(a.mean_return)
