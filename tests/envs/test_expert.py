"""The scripted experts: success and zero arm–obstacle contact over seeded episodes."""

from __future__ import annotations

import math

import gymnasium as gym
import numpy as np
import pytest

from lynxsim.arm import LYNX_ARM, ik_nearest
from lynxsim.envs import PickAndPlaceExpert, Randomization, ReachExpert, evaluate
from lynxsim.envs.evaluation import run_episode
from lynxsim.envs.routes import Planner
from lynxsim.envs.workspace import CARRY_HEIGHT_M, TOP_DOWN_PITCH_RAD
from lynxsim.errors import InvalidInputError

EXPERT_EPISODES = 20
"""Episodes in the test (the CLI and the report use 100; the suite must stay quick)."""
MIN_SUCCESS = 0.95


def test_pick_and_place_expert_succeeds_without_touching_the_obstacle():
    summary = evaluate("LynxPickAndPlace-v1", "expert", EXPERT_EPISODES, seed=1000)
    assert summary.success_rate >= MIN_SUCCESS, [e for e in summary.episodes if not e.success]
    assert summary.collision_steps == 0
    goals_in_air = 0
    for e in summary.episodes:
        assert e.first_success_step is not None
        assert e.first_success_step < 150
    env = gym.make("LynxPickAndPlace-v1")
    for i in range(EXPERT_EPISODES):
        obs, _ = env.reset(seed=1000 + i)
        goals_in_air += obs["desired_goal"][2] > 0.01
    assert 0 < goals_in_air < EXPERT_EPISODES  # both kinds of goal were tried


def test_pick_and_place_expert_works_without_obstacles():
    summary = evaluate("LynxPickAndPlace-v1", "expert", 5, seed=2000, env_kwargs={"obstacles": ()})
    assert summary.success_rate == 1.0


def test_expert_grasps_by_friction_and_holds_goals_in_the_air():
    env = gym.make("LynxPickAndPlace-v1", goal_in_air_prob=1.0)
    expert = PickAndPlaceExpert(env)
    stats = run_episode(env, expert, seed=7)
    u = env.unwrapped
    assert stats.success
    assert u.cube_position[2] > 0.02
    assert u.model.neq == 1  # only the finger coupling: no weld to the cube
    opening = u.data.qpos[u._finger_qpos].sum()
    assert opening == pytest.approx(0.025, abs=0.002)  # the fingers stand on the cube's faces


def test_reach_expert_succeeds_without_touching_the_obstacle():
    summary = evaluate("LynxReach-v1", "expert", 10, seed=0)
    assert summary.success_rate == 1.0
    assert summary.collision_steps == 0


def test_experts_refuse_other_envs_and_joint_control():
    with pytest.raises(InvalidInputError, match="this expert drives a PickAndPlaceEnv"):
        PickAndPlaceExpert(gym.make("LynxReach-v1"))
    with pytest.raises(InvalidInputError, match="the expert needs control='tool'"):
        ReachExpert(gym.make("LynxReach-v1", control="joint"))


def test_random_policy_is_seeded():
    a = evaluate("LynxReach-v1", "random", 2, seed=4)
    b = evaluate("LynxReach-v1", "random", 2, seed=4)
    assert a == b
    assert np.isfinite(a.mean_return)


def test_noisy_episodes_are_seeded_and_differ_from_clean_ones():
    clean = evaluate("LynxPickAndPlace-v1", "expert", 2, seed=40)
    noisy = evaluate("LynxPickAndPlace-v1", "expert", 2, seed=40, action_noise=0.05)
    again = evaluate("LynxPickAndPlace-v1", "expert", 2, seed=40, action_noise=0.05)
    assert noisy == again
    assert noisy != clean


@pytest.mark.slow
def test_closed_loop_expert_recovers_from_perturbed_actions():
    """Noise of 5 % of the action range (std 0.1) on every action, random obstacles."""
    summary = evaluate(
        "LynxPickAndPlace-v1",
        "expert",
        EXPERT_EPISODES,
        seed=3000,
        action_noise=0.05,
        env_kwargs={"random_obstacles": (1, 3)},
    )
    assert summary.success_rate >= 0.9, [e for e in summary.episodes if not e.success]
    assert summary.collision_episodes == 0


@pytest.mark.slow
def test_expert_grasps_cubes_of_randomised_size_mass_and_friction():
    randomize = Randomization(
        cube_size_m=(0.018, 0.028), cube_mass_kg=(0.005, 0.05), cube_friction=(0.6, 1.5)
    )
    summary = evaluate(
        "LynxPickAndPlace-v1",
        "expert",
        EXPERT_EPISODES,
        seed=0,
        env_kwargs={"randomize": randomize},
    )
    assert summary.success_rate >= 0.9, [e for e in summary.episodes if not e.success]
    assert summary.collision_episodes == 0


def test_expert_plans_from_a_command_a_rounding_error_past_a_joint_limit():
    # Seed 100 with action noise 0.1 once stopped the expert with an InvalidInputError:
    # a tool pitch clipped to -pi/2 left the commanded wrist 3.6e-8 rad below its
    # lower limit, and the planner refused that start as outside the joint box.
    env = gym.make("LynxPickAndPlace-v1")
    env.reset(seed=100)
    u = env.unwrapped
    start = (1.5297280286926855, 0.7392911065009873, -0.7392910707371163,
             -1.5707963625587675, math.pi)  # fmt: skip
    assert start[3] < LYNX_ARM.q_min[3]
    status, goal = ik_nearest(0.149, -0.145, CARRY_HEIGHT_M, TOP_DOWN_PITCH_RAD, math.pi, start)
    assert status == 0
    assert goal is not None
    route = Planner(u, u.controller).route(start, tuple(goal), grasped=True)
    assert route is not None
    assert math.dist(route.end[:3], (0.149, -0.145, CARRY_HEIGHT_M)) < 1e-6
