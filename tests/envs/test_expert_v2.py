"""The scripted experts on the ``-v2`` envs: the wrist roll turned to the cube's yaw."""

from __future__ import annotations

import math

import gymnasium as gym
import mujoco
import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from lynxsim.angles import quat_yaw
from lynxsim.envs import PICK_AND_PLACE_V2_ID, REACH_V2_ID, PickAndPlaceExpert, evaluate
from lynxsim.envs.expert_moves import grasp_roll
from lynxsim.envs.workspace import GRIP_ROLL_RAD
from lynxsim.errors import InvalidInputError

QUARTER = 0.5 * math.pi
ALIGNED_RAD = 0.05
"""The fingers close across the cube's faces within this [rad] (the expert's roll
tolerance plus the servo's lag)."""


def _off_quarter(angle: float) -> float:
    """Distance of an angle from the nearest multiple of a quarter turn [rad]."""
    return abs((angle + 0.5 * QUARTER) % QUARTER - 0.5 * QUARTER)


@given(st.floats(-1.5, 1.5), st.floats(-math.pi, math.pi), st.floats(math.pi - 1.1, math.pi + 1.1))
def test_the_grasp_roll_puts_the_closing_axis_on_a_face_normal_near_the_held_roll(base, yaw, roll):
    new = grasp_roll(base, yaw, roll)
    closing = base - (new - GRIP_ROLL_RAD)
    assert _off_quarter(closing - yaw) < 1e-9
    assert abs(new - GRIP_ROLL_RAD) <= 0.75 * QUARTER + 1e-9
    # the representative nearest the held roll, unless that is too far from mid-range
    nearest = min((new + k * QUARTER for k in (-1, 0, 1)), key=lambda r: abs(r - roll))
    if abs(nearest - GRIP_ROLL_RAD) <= 0.75 * QUARTER:
        assert abs(new - nearest) < 1e-9
    else:
        assert abs(abs(new - nearest) - QUARTER) < 1e-9


def test_the_v2_expert_turns_the_fingers_to_a_turned_cube_and_places_it():
    env = gym.make(PICK_AND_PLACE_V2_ID, goal_in_air_prob=0.0)
    u = env.unwrapped
    expert = PickAndPlaceExpert(env)
    obs, _ = env.reset(seed=3)
    a = u.ids.cube_qpos
    yaw = quat_yaw(*u.data.qpos[a + 3 : a + 7].tolist()) + math.radians(30.0)
    u.data.qpos[a + 3 : a + 7] = (math.cos(0.5 * yaw), 0.0, 0.0, math.sin(0.5 * yaw))
    mujoco.mj_forward(u.model, u.data)
    obs = u._observation()
    expert.reset()
    grasped_roll = None
    for _ in range(200):
        obs, _, _, _, info = env.step(expert(obs))
        if expert.phase.value == "lift" and grasped_roll is None:
            q = u.data.qpos[u._arm_qpos].tolist()
            grasped_roll = q[0] - (q[4] - GRIP_ROLL_RAD)  # the closing azimuth
            cube_yaw = quat_yaw(*u.data.qpos[a + 3 : a + 7].tolist())
    assert info["is_success"]
    assert grasped_roll is not None
    assert _off_quarter(grasped_roll - cube_yaw) < ALIGNED_RAD
    assert abs(u.controller.q_cmd[4] - GRIP_ROLL_RAD) > math.radians(15.0)  # it did turn
    env.close()


def test_the_v2_experts_succeed_without_contact_in_both_scene_kinds():
    for kwargs in ({}, {"random_obstacles": (1, 3)}):
        summary = evaluate(PICK_AND_PLACE_V2_ID, "expert", 4, seed=100, env_kwargs=kwargs)
        assert summary.success_rate == 1.0, summary.episodes
        assert summary.collision_steps == 0
    reach = evaluate(REACH_V2_ID, "expert", 4, seed=0)
    assert reach.success_rate == 1.0
    assert reach.collision_steps == 0


def test_the_v2_expert_picks_and_places_under_action_noise_without_contact():
    # Seeded noise 0.1 (0.2 on [-1, 1]): the 100-episode rates live in
    # tools/expert_noise_table.py; these episodes are deterministic.
    for kwargs in ({}, {"random_obstacles": (1, 3)}):
        summary = evaluate(
            PICK_AND_PLACE_V2_ID, "expert", 2, seed=0, env_kwargs=kwargs, action_noise=0.1
        )
        assert summary.success_rate == 1.0, summary.episodes
        assert summary.collision_steps == 0


def test_the_expert_refuses_an_unknown_search_world():
    env = gym.make(PICK_AND_PLACE_V2_ID)
    with pytest.raises(InvalidInputError, match="search must be 'cover' or 'exact'"):
        PickAndPlaceExpert(env, "fast")  # type: ignore[arg-type]
    env.close()


def test_v2_expert_actions_are_six_values_in_range():
    env = gym.make(PICK_AND_PLACE_V2_ID)
    expert = PickAndPlaceExpert(env)
    obs, _ = env.reset(seed=0)
    expert.reset()
    for _ in range(30):
        action = expert(obs)
        assert action.shape == (6,)
        assert np.all(np.abs(action) <= 1.0)
        obs, *_ = env.step(action)
    env.close()
