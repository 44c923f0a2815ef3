"""The Gymnasium API of the arm envs: checker, seeding, reset state, copies, rewards, arguments."""

from __future__ import annotations

import math
import warnings

import gymnasium as gym
import mujoco
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

from lynxsim.arm import tool_pose
from lynxsim.envs import PickAndPlaceEnv, ReachEnv
from lynxsim.envs.base import READY_TOOL_POSE, check_control_dt
from lynxsim.envs.control import TargetStatus
from lynxsim.errors import InvalidInputError, NonFiniteInputError
from lynxsim.scene import REPORT_CYLINDER, TABLE, Cylinder
from tests.envs.conftest import ENV_MODE_IDS, ENV_MODES
from tests.helpers import assert_close

POSE_M = 1e-12
"""Agreement of a set pose with its definition [m] (and [rad])."""
SITE_M = 1e-9
"""Agreement of the analytic tool point with MuJoCo's tool site [m]."""
ROLLOUT_STEPS = 40


def _actions(env: gym.Env, n: int, seed: int = 0) -> np.ndarray:
    rng = np.random.default_rng(seed)
    return rng.uniform(-1.0, 1.0, (n, *env.action_space.shape)).astype(np.float32)


def _rollout(env: gym.Env, seed: int | None, actions: np.ndarray) -> list:
    out = [env.reset(seed=seed)]
    out += [env.step(a) for a in actions]
    return out


def _assert_same(a: object, b: object) -> None:
    if isinstance(a, dict):
        assert a.keys() == b.keys()
        for k in a:
            _assert_same(a[k], b[k])
    elif isinstance(a, tuple | list):
        assert len(a) == len(b)
        for x, y in zip(a, b):
            _assert_same(x, y)
    else:
        np.testing.assert_array_equal(a, b)


def _state(env: gym.Env) -> np.ndarray:
    u = env.unwrapped
    spec = int(mujoco.mjtState.mjSTATE_INTEGRATION)
    state = np.empty(mujoco.mj_stateSize(u.model, spec))
    mujoco.mj_getState(u.model, u.data, state, spec)
    return state


@pytest.mark.parametrize(("env_id", "control"), ENV_MODES, ids=ENV_MODE_IDS)
def test_check_env_passes(env_id, control):
    env = gym.make(env_id, control=control)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        check_env(env.unwrapped, skip_render_check=True)
    # Unbounded observation boxes are deliberate (Gymnasium's MuJoCo envs have them too).
    assert [str(w.message) for w in caught if "infinity" not in str(w.message)] == []
    env.close()


@pytest.mark.parametrize(("env_id", "control"), ENV_MODES, ids=ENV_MODE_IDS)
def test_two_envs_with_one_seed_roll_out_identically(env_id, control):
    a, b = gym.make(env_id, control=control), gym.make(env_id, control=control)
    actions = _actions(a, ROLLOUT_STEPS)
    _assert_same(_rollout(a, 11, actions), _rollout(b, 11, actions))


@pytest.mark.parametrize(("env_id", "control"), ENV_MODES, ids=ENV_MODE_IDS)
def test_reset_with_a_seed_restores_the_whole_state(env_id, control):
    env = gym.make(env_id, control=control)
    actions = _actions(env, ROLLOUT_STEPS)
    first = _rollout(env, 5, actions)
    for a in _actions(env, 25, seed=1):  # disturb: velocities, warm start, contacts
        env.step(a)
    env.reset(seed=5)
    after_reset = _state(env)
    second = _rollout(env, 5, actions)
    _assert_same(first, second)
    fresh = gym.make(env_id, control=control)
    fresh.reset(seed=5)
    np.testing.assert_array_equal(after_reset, _state(fresh))


def test_unseeded_resets_continue_the_seeded_stream():
    a, b = gym.make("LynxPickAndPlace-v1"), gym.make("LynxPickAndPlace-v1")
    goals_a = [a.reset(seed=3)[0]["desired_goal"]] + [
        a.reset()[0]["desired_goal"] for _ in range(4)
    ]
    goals_b = [b.reset(seed=3)[0]["desired_goal"]] + [
        b.reset()[0]["desired_goal"] for _ in range(4)
    ]
    np.testing.assert_array_equal(goals_a, goals_b)
    assert len({tuple(g) for g in goals_a}) == len(goals_a)  # the stream moves on


@pytest.mark.parametrize("seed", range(40))
def test_pick_and_place_starts_as_the_manual_says(seed):
    env = PickAndPlaceEnv()
    obs, info = env.reset(seed=seed)
    d, ix = env.data, env.OBS_INDEX
    o = obs["observation"]
    q = d.qpos[list(env.ids.arm_qpos)]
    pose = tool_pose(q)
    assert_close(pose.position, READY_TOOL_POSE[:3], atol=POSE_M)
    assert pose.pitch == pytest.approx(READY_TOOL_POSE[3], abs=POSE_M)
    assert q[4] == pytest.approx(math.pi, abs=POSE_M)  # wrist roll
    assert_close(d.site_xpos[env.ids.tool_site], READY_TOOL_POSE[:3], atol=SITE_M)
    assert_close(o[ix["tool_position"]], READY_TOOL_POSE[:3], atol=POSE_M)
    assert o[ix["gripper_opening"]][0] == pytest.approx(0.03, abs=POSE_M)
    assert not d.qvel.any()
    assert not d.qacc_warmstart.any()
    assert d.time == 0.0
    assert_close(d.ctrl[list(env.ids.arm_actuators)], q, atol=0.0)
    assert d.ctrl[env.ids.gripper_actuator] == 0.03
    assert_close(o[ix["commanded_joint_angles"]], q, atol=0.0)
    assert not o[ix["tool_velocity"]].any()
    assert not o[ix["joint_velocities"]].any()

    cube, goal = obs["achieved_goal"], obs["desired_goal"]
    assert_close(cube, env.cube_position, atol=0.0)
    assert cube[2] == pytest.approx(0.0, abs=POSE_M)  # resting on the table top z = -12.5 mm
    for p in (cube, goal):
        assert 0.13 <= math.hypot(p[0], p[1]) <= 0.25
        assert abs(math.atan2(p[1], p[0])) <= math.radians(80)
    assert goal[2] == pytest.approx(0.0, abs=POSE_M) or 0.03 <= goal[2] <= 0.09
    yaw = 2 * math.atan2(d.qpos[env._cube_qpos + 6], d.qpos[env._cube_qpos + 3])
    assert yaw == pytest.approx(math.atan2(cube[1], cube[0]), abs=1e-12)  # faces the base
    assert info["distance"] > env.distance_threshold
    assert np.linalg.norm(goal - cube) > env.distance_threshold
    assert not env._touching_obstacle()


def test_reach_starts_as_the_manual_says():
    env = ReachEnv()
    assert env.model.nbody == PickAndPlaceEnv().model.nbody - 1  # no cube
    for seed in range(20):
        obs, info = env.reset(seed=seed)
        assert_close(obs["achieved_goal"], READY_TOOL_POSE[:3], atol=POSE_M)
        goal = obs["desired_goal"]
        assert 0.10 <= math.hypot(goal[0], goal[1]) <= 0.25
        assert 0.0 <= goal[2] <= 0.10
        assert info["distance"] > env.distance_threshold
    assert env.action_space.shape == (4,)
    assert ReachEnv(control="joint").action_space.shape == (5,)


def test_observations_are_fresh_copies(pick_and_place):
    env = pick_and_place
    u = env.unwrapped
    obs, _ = env.reset(seed=0)
    twin = gym.make("LynxPickAndPlace-v1")
    twin_obs, _ = twin.reset(seed=0)
    sim_arrays = [u.data.qpos, u.data.qvel, u.data.ctrl, u.data.site_xpos, u._goal]
    action = env.action_space.sample()
    for _ in range(3):
        arrays = list(obs.values())
        for x in arrays:
            assert x.flags.writeable
            assert not any(np.shares_memory(x, s) for s in sim_arrays)
            assert sum(np.shares_memory(x, y) for y in arrays) == 1
            x[...] = np.nan  # scribbling on an observation changes nothing
        obs, *_ = env.step(action)
        twin_obs, *_ = twin.step(action)
        _assert_same(obs, twin_obs)


@pytest.mark.parametrize("reward_type", ["sparse", "dense"])
@pytest.mark.parametrize("penalty", [0.0, 2.5], ids=["no-penalty", "penalty"])
def test_compute_reward_reproduces_step_rewards(reward_type, penalty):
    env = gym.make(
        "LynxPickAndPlace-v1", reward_type=reward_type, collision_penalty=penalty, control="joint"
    )
    u = env.unwrapped
    achieved, desired, infos, rewards = [], [], [], []
    rng = np.random.default_rng(0)
    for episode in range(3):
        env.reset(seed=episode)
        for k in range(60):
            # Sweep the base into the obstacle now and then, so collisions occur.
            a = rng.uniform(-1, 1, 6) if k % 20 < 12 else np.array([1, 0.3, 0, 0, 0, 0])
            obs, reward, _, _, info = env.step(a)
            achieved.append(obs["achieved_goal"])
            desired.append(obs["desired_goal"])
            infos.append(info)
            rewards.append(reward)
            assert reward == u.compute_reward(obs["achieved_goal"], obs["desired_goal"], info)
            assert reward == info["reward_goal"] + info["reward_collision"]
    achieved, desired, rewards = np.array(achieved), np.array(desired), np.array(rewards)
    np.testing.assert_array_equal(u.compute_reward(achieved, desired, infos), rewards)
    np.testing.assert_array_equal(u.compute_reward(achieved, desired, np.array(infos)), rewards)
    as_dict = {"collision": np.array([i["collision"] for i in infos])}
    np.testing.assert_array_equal(u.compute_reward(achieved, desired, as_dict), rewards)
    batched = u.compute_reward(achieved.reshape(3, 60, 3), desired.reshape(3, 60, 3), infos)
    np.testing.assert_array_equal(batched.ravel(), rewards)
    if penalty:
        assert any(i["collision"] for i in infos)
    # Hindsight: relabelled goals give the reward of being there.
    assert (u.compute_reward(achieved, achieved, infos) <= 0.0).all()


def test_arm_obstacle_contact_is_reported_penalised_and_can_terminate():
    env = gym.make(
        "LynxPickAndPlace-v1",
        control="joint",
        collision_penalty=3.0,
        terminate_on_collision=True,
        collision_check="physics_step",
    )
    env.reset(seed=0)
    turn = np.array([1.0, 0, 0, 0, 0, 1.0])  # base towards +y: through the obstacle at 45 deg
    for _ in range(40):
        obs, reward, terminated, truncated, info = env.step(turn)
        if info["collision"]:
            break
    assert info["collision"]
    assert terminated
    assert not truncated
    assert info["reward_collision"] == -3.0
    assert reward == info["reward_goal"] - 3.0
    u = env.unwrapped
    assert u.compute_terminated(obs["achieved_goal"], obs["desired_goal"], info)
    assert not u.compute_truncated(obs["achieved_goal"], obs["desired_goal"], info)
    q1 = env.unwrapped.data.qpos[0]
    assert math.radians(15) < q1 < math.radians(45)  # the arm met the cylinder on its way


def test_no_obstacle_means_no_collisions_and_a_moved_one_is_avoided():
    env = gym.make("LynxPickAndPlace-v1", control="joint", obstacles=())
    env.reset(seed=0)
    assert env.unwrapped.ids.obstacle_geoms == ()
    for _ in range(40):
        *_, info = env.step(np.array([1.0, 0, 0, 0, 0, 1.0]))
        assert not info["collision"]
    moved = Cylinder("cylinder", (0.2, -0.1, TABLE.top_z), 0.03, 0.3 - TABLE.top_z)
    env = PickAndPlaceEnv(obstacles=(moved,))
    for seed in range(20):
        obs, _ = env.reset(seed=seed)
        for p in (obs["achieved_goal"], obs["desired_goal"]):
            assert math.dist(p[:2], moved.position[:2]) > moved.radius + 0.03


def test_v0_holds_unreachable_tool_targets_instead_of_raising():
    env = gym.make("LynxReach-v0")
    env.reset(seed=0)
    u = env.unwrapped
    ix = u.OBS_INDEX
    held = []
    for _ in range(60):  # straight out along +x, beyond the reach
        obs, _, _, _, info = env.step(np.array([1.0, 0.0, 0.3, 0.0], dtype=np.float32))
        held.append(info["target_held"])
        if info["target_held"]:
            assert info["target_status"] in (TargetStatus.OUT_OF_REACH, TargetStatus.JOINT_RANGE)
    assert held[0] is False
    assert held[-1] is True
    target = obs["observation"][ix["commanded_tool_position"]]
    obs, *_ = env.step(np.array([1.0, 0.0, 0.3, 0.0], dtype=np.float32))
    assert_close(obs["observation"][ix["commanded_tool_position"]], target, atol=0.0)
    assert np.isfinite(obs["observation"]).all()
    # The way back is open.
    *_, info = env.step(np.array([-1.0, 0.0, 0.0, 0.0], dtype=np.float32))
    assert info["target_status"] == TargetStatus.ACCEPTED


def test_v1_moves_an_unreachable_request_as_far_as_is_feasible():
    """Out along +x beyond the reach: the target stops at the boundary, info says by how much."""
    env = gym.make("LynxReach-v1")
    env.reset(seed=0)
    ix = env.unwrapped.OBS_INDEX
    statuses, shortfalls = [], []
    for _ in range(60):
        obs, _, _, _, info = env.step(np.array([1.0, 0.0, 0.3, 0.0], dtype=np.float32))
        statuses.append(info["target_status"])
        shortfalls.append(info["target_shortfall_m"])
        if info["target_status"] == TargetStatus.ACCEPTED:
            assert info["target_shortfall_m"] == 0.0
            assert info["target_shortfall_rad"] == 0.0
    assert statuses[0] == TargetStatus.ACCEPTED
    assert statuses[-1] != TargetStatus.ACCEPTED
    assert 0.0 < shortfalls[-1] <= np.hypot(0.015, float(np.float32(0.3)) * 0.015) + 1e-12
    target = obs["observation"][ix["commanded_tool_position"]]
    v0 = gym.make("LynxReach-v0")
    v0.reset(seed=0)
    for _ in range(60):
        held, *_ = v0.step(np.array([1.0, 0.0, 0.3, 0.0], dtype=np.float32))
    # v0 stops at its last whole step; v1 presses on to the edge of the workspace
    assert target[0] > held["observation"][ix["commanded_tool_position"]][0]
    obs, *_ = env.step(np.array([1.0, 0.0, 0.3, 0.0], dtype=np.float32))
    assert np.isfinite(obs["observation"]).all()
    *_, info = env.step(np.array([-1.0, 0.0, 0.0, 0.0], dtype=np.float32))
    assert info["target_status"] == TargetStatus.ACCEPTED


def test_v1_always_unreachable_pitch_still_moves_the_tool_toward_the_commanded_position():
    """A policy that always asks for more pitch than the IK allows keeps moving in x, y, z."""
    env = gym.make("LynxReach-v1")
    env.reset(seed=0)
    ix = env.unwrapped.OBS_INDEX
    start = None
    held = 0
    for k in range(40):
        obs, _, _, _, info = env.step(np.array([0.0, 0.5, 0.0, 1.0], dtype=np.float32))
        if k == 0:
            start = obs["observation"][ix["commanded_tool_position"]].copy()
        held += info["target_held"]
    end = obs["observation"][ix["commanded_tool_position"]]
    tool = obs["observation"][ix["tool_position"]]
    assert held == 0
    assert end[1] - start[1] > 0.15  # 39 steps of 7.5 mm along +y, most of them taken
    assert abs(end[0] - start[0]) < 0.02
    assert tool[1] - start[1] > 0.1  # and the simulated tool follows


def test_actions_are_clipped_and_checked():
    a, b = gym.make("LynxReach-v1"), gym.make("LynxReach-v1")
    a.reset(seed=0)
    b.reset(seed=0)
    _assert_same(a.step(np.full(4, 7.0)), b.step(np.ones(4)))
    u = a.unwrapped
    with pytest.raises(InvalidInputError, match=r"action must have shape \(4,\), got \(5,\)"):
        u.step(np.zeros(5))
    with pytest.raises(NonFiniteInputError, match="action must be finite"):
        u.step(np.array([0.0, np.nan, 0.0, 0.0]))


def test_control_period_must_be_a_multiple_of_the_physics_step():
    assert check_control_dt(0.04, 0.002) == 20
    env = ReachEnv(control_dt=0.02)
    assert env.frame_skip == 10
    assert env.dt == pytest.approx(0.02)
    assert env.metadata["render_fps"] == 50
    with pytest.raises(InvalidInputError, match=r"control_dt = 0.035 s is not a whole multiple"):
        ReachEnv(control_dt=0.035)
    with pytest.raises(
        InvalidInputError, match=r"control_dt must be between 0.002 and 1 s, got 0 s"
    ):
        ReachEnv(control_dt=0.0)


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"control": "cartesian"}, r"control must be one of 'tool', 'joint', 'tool_roll', got"),
        ({"reward_type": "shaped"}, r"reward_type must be one of 'sparse', 'dense'"),
        ({"collision_check": "never"}, "collision_check must be one of"),
        ({"render_mode": "ansi"}, "render_mode must be None or one of"),
        (
            {"render_quality": "ultra"},
            "render_quality must be one of 'lean', 'fast', 'medium', 'default'",
        ),
        ({"distance_threshold": 0.0}, "distance_threshold must be > 0 m"),
        ({"collision_penalty": -1.0}, "collision_penalty must be between 0 and 1e"),
        ({"obstacles": (0.1, 0.1)}, "obstacles must be a sequence of Cylinder, Box or Sphere"),
        ({"obstacles": REPORT_CYLINDER}, "obstacles must be a sequence of Cylinder, Box or Sphere"),
        ({"goal_in_air_prob": 1.5}, "goal_in_air_prob must be between 0 and 1, got 1.5"),
        ({"position_step": 0.0}, "position_step must be a positive number"),
        ({"camera": "side"}, "no camera named 'side'; cameras: front, top"),
    ],
    ids=lambda v: next(iter(v)) if isinstance(v, dict) else "",
)
def test_bad_arguments_raise_with_the_valid_choices(kwargs, message):
    with pytest.raises(InvalidInputError, match=message):
        PickAndPlaceEnv(**kwargs)


def test_compute_reward_rejects_infos_that_do_not_fit_the_goals():
    env = PickAndPlaceEnv(collision_penalty=1.0)
    goals = np.zeros((5, 3))
    with pytest.raises(InvalidInputError, match=r"info holds 3 collision flags for goals of batch"):
        env.compute_reward(goals, goals, [{"collision": False}] * 3)
    no_penalty = PickAndPlaceEnv()
    assert (no_penalty.compute_reward(goals, goals, None) == 0.0).all()  # info unused


# ------------------------------------------------------------ odd inputs (fuzz campaign)


@pytest.mark.parametrize(
    ("control_dt", "error", "match"),
    [
        (1e9, InvalidInputError, r"control_dt must be between 0.002 and 1 s, got 1e\+09 s"),
        (0.001, InvalidInputError, "control_dt must be between 0.002 and 1 s"),
        (math.nan, NonFiniteInputError, "control_dt must be finite"),
        (math.inf, NonFiniteInputError, "control_dt must be finite"),
        ("0.04", InvalidInputError, "control_dt must be a number"),
        (10**400, InvalidInputError, "control_dt must be a number"),
        (None, InvalidInputError, "control_dt must be a number"),
    ],
    ids=["1e9", "below-step", "nan", "inf", "str", "int-beyond-float64", "none"],
)
def test_control_period_is_bounded_with_a_typed_error(control_dt, error, match):
    with pytest.raises(error, match=match):
        ReachEnv(control_dt=control_dt)


def test_the_longest_control_period_is_accepted():
    env = ReachEnv(control_dt=1.0)
    assert env.frame_skip == 500


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"distance_threshold": "0.02"}, "distance_threshold must be a number"),
        ({"distance_threshold": 1e300}, "distance_threshold must be between 0 and 10 m"),
        ({"collision_penalty": math.nan}, "collision_penalty must be finite"),
        ({"position_step": math.inf}, "position_step must be finite"),
        ({"pitch_step": 100.0}, "pitch_step must be between 0 and 6.28319 rad"),
        ({"joint_step": 1 + 1j}, "joint_step must be a number"),
        ({"width": 10**9}, "width must be between 1 and 16,384"),
        ({"width": 64.5}, "width must be an integer"),
        ({"height": "480"}, "height must be an integer"),
        ({"width": 4000}, "exceeds the model's off-screen buffer"),
        ({"camera": None}, "camera must be a camera name"),
        ({"render_mode": ["rgb_array"]}, "render_mode must be None or one of"),
        ({"control": ["tool"]}, "control must be one of"),
        ({"terminate_on_collision": "yes"}, "terminate_on_collision must be True or False"),
        ({"obstacles": "cylinder"}, "obstacles must be a sequence"),
        ({"random_obstacles": "3"}, r"random_obstacles \(fewest\) must be"),
        ({"random_obstacles": (2, 1)}, r"random_obstacles \(most\)"),
        ({"random_obstacles": 5}, "random_obstacles"),
        ({"random_obstacles": (1, 2, 3)}, r"a count or \(fewest, most\)"),
        ({"random_obstacles": 2, "obstacles": ()}, "not both"),
        ({"goal_in_air_prob": "half"}, "goal_in_air_prob must be a number"),
        ({"goal_in_air_prob": math.nan}, "goal_in_air_prob must be finite"),
    ],
    ids=lambda v: "-".join(f"{k}={v[k]!r}"[:24] for k in v) if isinstance(v, dict) else "",
)
def test_constructor_arguments_of_odd_types_raise_typed_errors(kwargs, match):
    with pytest.raises(InvalidInputError, match=match):
        PickAndPlaceEnv(**kwargs)


@pytest.mark.parametrize(
    ("action", "error"),
    [
        ("0 0 0 0", InvalidInputError),
        (None, InvalidInputError),
        ([0.0, [0.0, 0.0], 0.0], InvalidInputError),
        (np.array([True, False, True, False]), InvalidInputError),
        (np.zeros(4, dtype=complex), InvalidInputError),
        (np.zeros(4, dtype=object), InvalidInputError),
        ([10**400, 0, 0, 0], InvalidInputError),
        (np.zeros((1, 4)), InvalidInputError),
        ([math.inf, 0.0, 0.0, 0.0], NonFiniteInputError),
    ],
    ids=["str", "none", "ragged", "bool", "complex", "object", "huge-int", "batch", "inf"],
)
def test_step_refuses_odd_actions_with_typed_errors(action, error):
    env = ReachEnv()
    env.reset(seed=0)
    with pytest.raises(error):
        env.step(action)
    obs, *_ = env.step([1e308, -1e308, 0.0, 0.0])  # finite, clipped to [-1, 1]
    assert np.isfinite(obs["observation"]).all()


@pytest.mark.parametrize(
    "seed", [-1, "1", 1.5, True, [1]], ids=["negative", "str", "float", "bool", "list"]
)
def test_reset_refuses_odd_seeds_with_a_typed_error(seed):
    with pytest.raises(InvalidInputError, match="seed must be None or an integer >= 0"):
        ReachEnv().reset(seed=seed)


def test_reset_accepts_numpy_integer_seeds():
    a, b = ReachEnv(), ReachEnv()
    _assert_same(a.reset(seed=np.int64(3)), b.reset(seed=3))
