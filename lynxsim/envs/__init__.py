"""Gymnasium environments of the arm: ``LynxPickAndPlace-v1``/``-v2`` and ``LynxReach-v1``/``-v2``.

``-v0`` of each stays registered: it holds the previous tool target when a
request is out of reach, where ``-v1`` takes the feasible target nearest the
request along it (:class:`~lynxsim.envs.control.TargetFallback`). ``-v2`` adds
the wrist roll to the tool action and takes an unreachable request to the
nearest feasible target, sliding along the reach boundary
(:mod:`lynxsim.envs.tool_action`).

Importing this package registers the envs with Gymnasium (as Gymnasium-Robotics
does)::

    import gymnasium as gym
    import lynxsim.envs

    gym.register_envs(lynxsim.envs)  # a no-op that keeps linters from removing the import
    env = gym.make("LynxPickAndPlace-v1")

or, with no import, ``gym.make("lynxsim.envs:LynxPickAndPlace-v1")``.

The import is light (registration only: Gymnasium, no MuJoCo); the env classes, the
scripted experts and the evaluation helpers load, with MuJoCo, on first use.
"""

from __future__ import annotations

import importlib
from typing import Any

from lynxsim.envs.registration import (
    ENV_IDS,
    LATEST_ENV_IDS,
    PICK_AND_PLACE_ID,
    PICK_AND_PLACE_V2_ID,
    REACH_ID,
    REACH_V2_ID,
    V2_ENV_IDS,
    register_envs,
)

__all__ = [
    "ENV_IDS",
    "LATEST_ENV_IDS",
    "PICK_AND_PLACE_ID",
    "PICK_AND_PLACE_V2_ID",
    "REACH_ID",
    "REACH_V2_ID",
    "V2_ENV_IDS",
    "Domain",
    "EpisodeStats",
    "EvaluationSummary",
    "PickAndPlaceEnv",
    "PickAndPlaceExpert",
    "Randomization",
    "ReachEnv",
    "ReachExpert",
    "ToolLimits",
    "evaluate",
    "record_expert_episode",
    "register_envs",
]

_LAZY = {
    "Domain": "lynxsim.envs.randomization",
    "Randomization": "lynxsim.envs.randomization",
    "PickAndPlaceEnv": "lynxsim.envs.pick_and_place",
    "ReachEnv": "lynxsim.envs.reach",
    "ToolLimits": "lynxsim.envs.tool_action",
    "PickAndPlaceExpert": "lynxsim.envs.expert",
    "ReachExpert": "lynxsim.envs.expert",
    "EpisodeStats": "lynxsim.envs.evaluation",
    "EvaluationSummary": "lynxsim.envs.evaluation",
    "evaluate": "lynxsim.envs.evaluation",
    "record_expert_episode": "lynxsim.envs.evaluation",
}


def __getattr__(name: str) -> Any:
    if name in _LAZY:
        return getattr(importlib.import_module(_LAZY[name]), name)
    raise AttributeError(f"module 'lynxsim.envs' has no attribute {name!r}")


register_envs()
