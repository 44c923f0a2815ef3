"""The ``-v2`` tool action (:mod:`lynxsim.envs.tool_action`) and the ``-v2`` envs that use it."""

from __future__ import annotations

import math

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env
from hypothesis import given, settings
from hypothesis import strategies as st

from lynxsim.arm import LYNX_ARM, ik, tool_pose_of
from lynxsim.envs import PICK_AND_PLACE_V2_ID, REACH_V2_ID, V2_ENV_IDS, ReachEnv, ToolLimits
from lynxsim.envs.control import TargetStatus
from lynxsim.envs.tool_action import PITCH_OFFSETS, ToolRollController, tool_targets
from lynxsim.errors import InvalidInputError

LIMITS = ToolLimits(0.015, 0.1, 0.1, (-0.30, -0.45, -0.004), (0.45, 0.45, 0.50))
"""The envs' steps and target box."""
SOLVED_RAD = 1e-9
"""A target's joints reproduce it through the FK within this [m, rad]."""
GRID_TOLERANCE = 0.5 * (PITCH_OFFSETS[1] - PITCH_OFFSETS[0])
"""How much nearer (in action units) than the search's result a brute-force sample may
be: half the spacing of the pitches the search tries, in pitch steps."""
EDGE_STEPS = 40
"""Steps of the boundary test once the request is out of reach."""
SLIDE_M = 0.020
"""How far y must move over those steps on ``-v2`` [m] (the issue's acceptance)."""


def _stretched(seed: int) -> tuple[np.ndarray, np.ndarray]:
    """A feasible command near the edge of the reach: (target (5,), joints (5,))."""
    rng = np.random.default_rng(seed)
    lo, hi = np.array(LYNX_ARM.q_min), np.array(LYNX_ARM.q_max)
    q = rng.uniform(lo, hi)
    q[2] = rng.uniform(-0.4, 0.0)  # elbow nearly straight: the edge of the reach
    q[0] = rng.uniform(-1.2, 1.2)
    q[4] = rng.uniform(0.5, 5.5)
    bent = q[1] + q[2]  # a wrist in range that keeps the pitch in [-pi/2, pi/2]
    q[3] = rng.uniform(max(lo[3], -math.pi / 2 - bent), min(hi[3], math.pi / 2 - bent))
    return np.array([*tool_pose_of(q.tolist()), q[4]]), q


def _feasible(points: np.ndarray, q_ref: np.ndarray) -> np.ndarray:
    """Which targets (n, 5) the controller takes from joints ``q_ref`` (5,): in range, no jump."""
    r = ik(points[:, :3], points[:, 3], points[:, 4], q_ref=q_ref)
    return r.ok & ~(np.abs(r.q[:, :4] - q_ref[:4]) > LIMITS.max_joint_jump).any(axis=1)


def _miss(points: np.ndarray, request: np.ndarray) -> np.ndarray:
    return np.linalg.norm((points[:, :4] - request[:4]) / LIMITS.steps[:4], axis=1)


@settings(max_examples=40, deadline=None)
@given(st.integers(0, 2**31 - 1), st.lists(st.floats(-1, 1), min_size=5, max_size=5))
def test_the_target_is_feasible_and_no_sampled_feasible_target_is_nearer(seed, action):
    target, q = _stretched(seed)
    a = np.array(action)
    a[:3] = np.sign(a[:3]) + (a[:3] == 0)  # full steps: often past the edge
    out = tool_targets(target[None], q[None], np.append(a, 0.3)[None], LIMITS)
    new, q_new = out.target[0], out.q[0]
    assert np.abs(np.array(tool_pose_of(q_new.tolist())) - new[:4]).max() < SOLVED_RAD
    assert abs(q_new[4] - new[4]) < SOLVED_RAD
    assert _feasible(new[None], q)[0]
    request = np.clip(out.request[0], LIMITS.lower, LIMITS.upper)
    rng = np.random.default_rng(seed)
    spread = 1.5 * LIMITS.steps
    samples = request + rng.uniform(-1.0, 1.0, (20_000, 5)) * spread
    samples = np.clip(samples, LIMITS.lower, LIMITS.upper)
    samples[:, 4] = request[4]
    ok = _feasible(samples, q)
    best = _miss(samples[ok], request).min() if ok.any() else np.inf
    assert _miss(new[None], request)[0] <= best + GRID_TOLERANCE
    np.testing.assert_array_equal(out.correction[0], new - out.request[0])
    assert (out.status[0] == TargetStatus.ACCEPTED) == np.array_equal(new, request)


def test_a_feasible_request_is_taken_in_full_and_the_roll_always_is():
    target, q = _stretched(3)
    inward = np.array([[-0.2, 0.1, -0.1, 0.0, -1.0, 0.0]])
    out = tool_targets(target[None], q[None], inward, LIMITS)
    assert out.status[0] == TargetStatus.ACCEPTED
    np.testing.assert_array_equal(out.target, out.request)
    np.testing.assert_array_equal(out.correction, np.zeros((1, 5)))
    assert out.target[0, 4] == target[4] - LIMITS.roll_step


def test_rows_do_not_depend_on_each_other():
    rng = np.random.default_rng(7)
    states = [_stretched(s) for s in range(24)]
    targets = np.array([t for t, _ in states])
    joints = np.array([q for _, q in states])
    actions = rng.uniform(-1.0, 1.0, (24, 6))
    batch = tool_targets(targets, joints, actions, LIMITS)
    assert (batch.status != TargetStatus.ACCEPTED).any()
    for i in range(24):
        one = tool_targets(targets[i : i + 1], joints[i : i + 1], actions[i : i + 1], LIMITS)
        for field, column in zip(one, batch):
            np.testing.assert_array_equal(field[0], column[i])


@pytest.mark.parametrize(
    ("shapes", "match"),
    [(((1, 4), (1, 5), (1, 6)), "shape"), (((2, 5), (2, 5), (2, 4)), "action"),
     (((2, 5), (1, 5), (2, 6)), "shape")],
)  # fmt: skip
def test_wrong_shapes_raise_a_typed_error(shapes, match):
    t, q, a = (np.zeros(s) for s in shapes)
    with pytest.raises(InvalidInputError, match=match):
        tool_targets(t, q, a, LIMITS)


@pytest.mark.parametrize(
    "kwargs", [{"position_step": 0.0}, {"roll_step": -1.0}, {"box_lower": (1.0, 0.0, 0.0)},
               {"pitch_range": (1.0, -1.0)}, {"max_joint_jump": math.nan}],
)  # fmt: skip
def test_bad_limits_raise_a_typed_error(kwargs):
    base = {"position_step": 0.015, "pitch_step": 0.1, "roll_step": 0.1,
            "box_lower": (-0.3, -0.45, -0.004), "box_upper": (0.45, 0.45, 0.5)}  # fmt: skip
    with pytest.raises(InvalidInputError):
        ToolLimits(**{**base, **kwargs})


def _edge_run(env_id: str) -> tuple[float, float, bool]:
    """Ask +15 mm x and +7.5 mm y per step; from the first step the IK cannot take, 40 more.

    Returns:
        How far the commanded and the measured tool point moved in y over those
        steps [m], and whether the last step held the target.
    """
    env = gym.make(env_id)
    obs, _ = env.reset(seed=0)
    index = ReachEnv.OBS_INDEX
    action = np.zeros(env.action_space.shape, dtype=np.float32)
    action[:2] = (1.0, 0.5)
    for _ in range(100):
        obs, _, _, _, info = env.step(action)
        if info["target_status"] != TargetStatus.ACCEPTED:
            break
    assert info["target_status"] != TargetStatus.ACCEPTED
    cmd_y = obs["observation"][index["commanded_tool_position"]][1]
    tool_y = obs["observation"][index["tool_position"]][1]
    for _ in range(EDGE_STEPS):
        obs, _, _, _, info = env.step(action)
    env.close()
    o = obs["observation"]
    moved_cmd = o[index["commanded_tool_position"]][1] - cmd_y
    moved_tool = o[index["tool_position"]][1] - tool_y
    return float(moved_cmd), float(moved_tool), bool(info["target_held"])


def test_v2_slides_along_the_reach_boundary_where_v1_stops_dead():
    cmd, tool, held = _edge_run(REACH_V2_ID)
    assert cmd >= SLIDE_M
    assert tool >= SLIDE_M
    assert not held
    cmd, tool, held = _edge_run("LynxReach-v1")
    assert cmd == 0.0
    assert held


def test_v2_info_says_what_changed_and_by_how_much():
    env = gym.make(PICK_AND_PLACE_V2_ID)
    env.reset(seed=1)
    for _ in range(30):
        _, _, _, _, info = env.step(np.array([1, 0, 0, 0, 0, 1], dtype=np.float32))
    c = info["target_correction"]
    assert info["target_status"] != TargetStatus.ACCEPTED
    assert c.shape == (5,)
    assert c[0] < 0.0
    assert info["target_shortfall_m"] == pytest.approx(np.linalg.norm(c[:3]))
    assert info["target_shortfall_rad"] == abs(c[3])
    env.close()


@pytest.mark.parametrize("env_id", V2_ENV_IDS)
def test_v2_turns_the_wrist_with_the_roll_action_and_passes_the_checker(env_id):
    env = gym.make(env_id)
    u = env.unwrapped
    assert isinstance(u.controller, ToolRollController)
    assert env.action_space.shape == ((6,) if "Pick" in env_id else (5,))
    check_env(u, skip_render_check=True)
    env.reset(seed=2)
    q5 = u.controller.q_cmd[4]
    action = np.zeros(env.action_space.shape, dtype=np.float32)
    action[4] = 1.0
    for _ in range(5):
        env.step(action)
    assert u.controller.q_cmd[4] == pytest.approx(q5 + 5 * LIMITS.roll_step, abs=1e-12)
    assert u.controller.roll == u.controller.q_cmd[4]
    env.close()


def test_a_dry_run_without_a_roll_value_holds_the_roll():
    c = ToolRollController(LIMITS)
    _target, q = _stretched(5)
    c.reset(q.tolist())
    c.apply([-0.1, 0.0, 0.0, 0.0])
    assert c.q_cmd[4] == q[4]
    assert c.roll == q[4]


def test_tool_roll_refuses_the_hold_fallback():
    with pytest.raises(InvalidInputError, match="target_fallback must be 'nearest'"):
        ReachEnv(control="tool_roll", target_fallback="hold")
