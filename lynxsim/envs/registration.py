"""Registering the lynxsim envs with Gymnasium (string entry points: imports no MuJoCo).

``import lynxsim.envs`` calls :func:`register_envs`, so after it
``gym.make("LynxPickAndPlace-v0")`` works; ``gym.make("lynxsim.envs:LynxPickAndPlace-v0")``
works without it (Gymnasium imports the module named before the colon). The env
modules (and MuJoCo) load on the first ``make``. ``import lynxsim`` registers nothing,
so the math packages stay free of Gymnasium.
"""

from __future__ import annotations

import gymnasium as gym

__all__ = ["ENV_IDS", "PICK_AND_PLACE_ID", "REACH_ID", "register_envs"]

PICK_AND_PLACE_ID = "LynxPickAndPlace-v0"
REACH_ID = "LynxReach-v0"

_ENVS = (
    (PICK_AND_PLACE_ID, "lynxsim.envs.pick_and_place:PickAndPlaceEnv", 200),
    (REACH_ID, "lynxsim.envs.reach:ReachEnv", 100),
)

ENV_IDS: tuple[str, ...] = tuple(env_id for env_id, _, _ in _ENVS)
"""Every registered id."""


def register_envs() -> None:
    """Register every lynxsim env that is not registered yet (idempotent)."""
    for env_id, entry_point, steps in _ENVS:
        if env_id not in gym.registry:
            gym.register(id=env_id, entry_point=entry_point, max_episode_steps=steps)
