"""One recorded episode: the scripted expert with Gaussian action noise, stepped in a real env."""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import gymnasium as gym
import numpy as np
import numpy.typing as npt

from lynxsim.envs.noise import add_noise
from lynxsim.errors import InvalidInputError

if TYPE_CHECKING:  # the envs load MuJoCo; the command line reads MAX_NOISE without it
    from lynxsim.envs.evaluation import Policy

__all__ = ["INFO_KEYS", "Episode", "record_episode"]

FloatArray = npt.NDArray[np.float64]

INFO_KEYS: Mapping[str, type] = {
    "is_success": np.bool_,
    "collision": np.bool_,
    "distance": np.float64,
    "reward_goal": np.float64,
    "reward_collision": np.float64,
    "target_status": np.int64,
    "target_held": np.bool_,
}
"""The env's info entries a dataset keeps, with the dtype they are stored as."""


@dataclass(frozen=True)
class Episode:
    """One episode, as the env returned it, with ``T`` steps.

    Attributes:
        seed: Seed of the episode's ``env.reset``.
        observations: The observation dict's entries, each with the reset's
            observation first and the final one last: shape (T + 1, ...).
            For the arm envs: ``observation`` (T + 1, n_obs), ``achieved_goal``
            and ``desired_goal`` (T + 1, 3) [m].
        actions: The actions the env stepped with (the expert's plus noise,
            clipped to the action space), shape (T, n_act), float32.
        rewards: Shape (T,).
        terminations: Shape (T,), bool.
        truncations: Shape (T,), bool (the time limit sets the last one).
        infos: The :data:`INFO_KEYS` entries of the reset's info and of every
            step's, shape (T + 1,), and ``expert_action``, shape (T + 1, n_act),
            float32: row ``t + 1`` is the expert's action before the noise of
            step ``t``; row 0 (the reset, no action) is NaN.
    """

    seed: int
    observations: dict[str, FloatArray]
    actions: npt.NDArray[np.float32]
    rewards: FloatArray
    terminations: npt.NDArray[np.bool_]
    truncations: npt.NDArray[np.bool_]
    infos: dict[str, npt.NDArray[Any]]

    @property
    def steps(self) -> int:
        """Number of steps ``T``."""
        return int(self.rewards.shape[0])

    @property
    def success(self) -> bool:
        """``info["is_success"]`` of the last step."""
        return bool(self.infos["is_success"][-1])

    @property
    def episode_return(self) -> float:
        """Sum of the rewards."""
        return float(np.sum(self.rewards))


def record_episode(
    env: gym.Env[Any, Any],
    policy: Policy,
    seed: int,
    noise_std: npt.ArrayLike,
    rng: np.random.Generator,
) -> Episode:
    """Run one episode with Gaussian action noise and keep everything it returned.

    Every step the action is ``clip(policy(obs) + rng.normal(0, noise_std), low,
    high)``, cast to the space's dtype (the noise is drawn even where its
    standard deviation is 0, so that a stream does not depend on it).

    Args:
        env: A time-limited env (``gym.make`` adds the limit) with a dict
            observation space and a bounded ``Box`` action space.
        policy: The policy (reset here, after ``env.reset``).
        seed: Seed of ``env.reset``, >= 0.
        noise_std: Standard deviation of the noise, shape ``action_space.shape``
            (see :func:`action_noise_std`).
        rng: Source of the noise (see :func:`noise_generator`).

    Returns:
        The :class:`Episode`.

    Raises:
        InvalidInputError: An env that is not time-limited, or whose info lacks
            an entry of :data:`INFO_KEYS`.
    """
    if env.spec is None or env.spec.max_episode_steps is None:
        raise InvalidInputError("record_episode needs a time-limited env (made by gym.make)")
    space = env.action_space
    if not isinstance(space, gym.spaces.Box):
        raise InvalidInputError(f"record_episode needs a Box action space, got {space}")
    std = np.broadcast_to(np.asarray(noise_std, dtype=np.float64), space.shape)
    obs, info = env.reset(seed=seed)
    policy.reset()
    observations = [obs]
    infos = [info]
    nan_action = np.full(space.shape, math.nan, dtype=space.dtype)
    expert_actions = [nan_action]
    actions, rewards, terminations, truncations = [], [], [], []
    while True:
        clean = np.asarray(policy(obs), dtype=space.dtype)
        action = add_noise(clean, space, std, rng)
        obs, reward, terminated, truncated, info = env.step(action)
        observations.append(obs)
        infos.append(info)
        expert_actions.append(clean)
        actions.append(action)
        rewards.append(float(reward))
        terminations.append(bool(terminated))
        truncations.append(bool(truncated))
        if terminated or truncated:
            break
    missing = sorted(set(INFO_KEYS) - set(info))
    if missing:
        raise InvalidInputError(
            f"the env's info lacks {missing}; a dataset keeps {list(INFO_KEYS)}"
        )
    return Episode(
        seed=seed,
        observations={k: np.stack([o[k] for o in observations]) for k in observations[0]},
        actions=np.stack(actions),
        rewards=np.array(rewards, dtype=np.float64),
        terminations=np.array(terminations, dtype=np.bool_),
        truncations=np.array(truncations, dtype=np.bool_),
        infos={
            **{k: np.array([i[k] for i in infos], dtype=t) for k, t in INFO_KEYS.items()},
            "expert_action": np.stack(expert_actions),
        },
    )
