"""Long random rollouts: no exception, no NaN, no MuJoCo warning (menagerie-style)."""

from __future__ import annotations

import mujoco
import numpy as np
import pytest

from lynxsim.envs import PickAndPlaceEnv, ReachEnv

STEPS = 10_000
EPISODE_STEPS = 200


def _warnings(data: mujoco.MjData) -> dict[str, int]:
    counts = np.asarray(data.warning.number)
    return {mujoco.mjtWarning(i).name: int(n) for i, n in enumerate(counts) if n}


@pytest.mark.parametrize(
    ("cls", "control", "steps"),
    [
        (PickAndPlaceEnv, "tool", STEPS),
        (PickAndPlaceEnv, "joint", STEPS),
        (ReachEnv, "tool", STEPS // 5),
        (ReachEnv, "joint", STEPS // 5),
    ],
    ids=["pick-and-place-tool", "pick-and-place-joint", "reach-tool", "reach-joint"],
)
def test_random_actions_keep_the_simulation_healthy(cls, control, steps):
    env = cls(control=control, collision_check="physics_step")
    rng = np.random.default_rng(0)
    actions = rng.uniform(-1.0, 1.0, (steps, *env.action_space.shape))
    env.reset(seed=0)
    for k, a in enumerate(actions, start=1):
        obs, reward, *_ = env.step(a)
        if k % EPISODE_STEPS == 0 or k == steps:  # warnings are cleared by reset
            assert _warnings(env.data) == {}, f"step {k}"
            assert np.isfinite(env.data.qpos).all()
            assert np.isfinite(env.data.qvel).all()
            assert all(np.isfinite(v).all() for v in obs.values())
            assert np.isfinite(reward)
            env.reset()
