"""Registering the lynxsim envs with Gymnasium (string entry points: imports no MuJoCo).

``import lynxsim.envs`` calls :func:`register_envs`, so after it
``gym.make("LynxPickAndPlace-v0")`` works; ``gym.make("lynxsim.envs:LynxPickAndPlace-v0")``
works without it (Gymnasium imports the module named before the colon). The env
modules (and MuJoCo) load on the first ``make``. ``import lynxsim`` registers nothing,
so the math packages stay free of Gymnasium.
"""

from __future__ import annotations

import warnings
from typing import Any

import gymnasium as gym

__all__ = [
    "ENV_IDS",
    "LATEST_ENV_IDS",
    "PICK_AND_PLACE_ID",
    "PICK_AND_PLACE_V2_ID",
    "REACH_ID",
    "REACH_V2_ID",
    "V2_ENV_IDS",
    "make_env",
    "register_envs",
]

PICK_AND_PLACE_ID = "LynxPickAndPlace-v1"
"""The latest pick-and-place env."""
REACH_ID = "LynxReach-v1"
"""The latest reach env."""

_PICK_AND_PLACE = "lynxsim.envs.pick_and_place:PickAndPlaceEnv"
_REACH = "lynxsim.envs.reach:ReachEnv"
PICK_AND_PLACE_V2_ID = "LynxPickAndPlace-v2"
"""Pick-and-place with the wrist-roll tool action (``control="tool_roll"``)."""
REACH_V2_ID = "LynxReach-v2"
"""Reach with the wrist-roll tool action (``control="tool_roll"``)."""
_VECTOR = {
    _PICK_AND_PLACE: "lynxsim.envs.vector:pick_and_place_vector_env",
    _REACH: "lynxsim.envs.vector:reach_vector_env",
}
"""The batched vector env of each env class (``vectorization_mode="vector_entry_point"``)."""
_HOLD = {"target_fallback": "hold"}
"""v0: an infeasible tool request holds the previous target."""
_ROLL = {"control": "tool_roll"}
"""v2: a tool action with the wrist roll; an infeasible request goes to the nearest
feasible target (:mod:`lynxsim.envs.tool_action`)."""

_ENVS: tuple[tuple[str, str, int, dict[str, str]], ...] = (
    ("LynxPickAndPlace-v0", _PICK_AND_PLACE, 200, _HOLD),
    ("LynxReach-v0", _REACH, 100, _HOLD),
    (PICK_AND_PLACE_ID, _PICK_AND_PLACE, 200, {}),
    (REACH_ID, _REACH, 100, {}),
    (PICK_AND_PLACE_V2_ID, _PICK_AND_PLACE, 200, _ROLL),
    (REACH_V2_ID, _REACH, 100, _ROLL),
)

ENV_IDS: tuple[str, ...] = tuple(env_id for env_id, *_ in _ENVS)
"""Every registered id, older versions included."""
LATEST_ENV_IDS: tuple[str, ...] = (PICK_AND_PLACE_ID, REACH_ID)
"""The ``-v1`` of each env: the ids the datasets, examples and commands default to."""
V2_ENV_IDS: tuple[str, ...] = (PICK_AND_PLACE_V2_ID, REACH_V2_ID)
"""The ``-v2`` of each env (the wrist-roll tool action)."""


def register_envs() -> None:
    """Register every lynxsim env that is not registered yet (idempotent)."""
    for env_id, entry_point, steps, kwargs in _ENVS:
        if env_id not in gym.registry:
            gym.register(
                id=env_id,
                entry_point=entry_point,
                vector_entry_point=_VECTOR[entry_point],
                max_episode_steps=steps,
                kwargs=dict(kwargs),
            )


def make_env(env_id: str, **kwargs: Any) -> gym.Env[Any, Any]:
    """``gym.make(env_id, **kwargs)`` without Gymnasium's "out of date" notice.

    lynxsim's commands and library functions choose an env version on purpose (a dataset
    of ``-v1`` stays ``-v1``); Gymnasium would otherwise print a deprecation line on
    stderr whenever a newer version is registered.

    Args:
        env_id: A registered id, e.g. ``"LynxPickAndPlace-v1"``.
        **kwargs: The env's options, as ``gym.make`` takes them.

    Returns:
        The env, wrapped by ``gym.make`` (time limit, order enforcing, checker).
    """
    with warnings.catch_warnings():
        warnings.filterwarnings("ignore", message=".*is out of date", category=DeprecationWarning)
        return gym.make(env_id, **kwargs)
