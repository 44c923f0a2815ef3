"""Running policies in the envs: episode statistics, seeded evaluations, MP4 recordings.

Library functions: no printing and no progress bars; pass ``on_episode`` to
follow progress (the ``lynxsim env`` command draws its bar with it).
"""

from __future__ import annotations

import contextlib
import os
from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass
from typing import Any, Literal, Protocol

import gymnasium as gym
import numpy as np
import numpy.typing as npt

from lynxsim.envs.expert import PickAndPlaceExpert, ReachExpert
from lynxsim.envs.noise import action_noise_std, add_noise, noise_generator
from lynxsim.envs.pick_and_place import PickAndPlaceEnv
from lynxsim.envs.reach import ReachEnv
from lynxsim.envs.registration import PICK_AND_PLACE_ID, make_env
from lynxsim.errors import InvalidInputError
from lynxsim.sim.video import FrameSink, mp4_writer

__all__ = [
    "EpisodeStats",
    "EvaluationSummary",
    "Policy",
    "PolicyKind",
    "evaluate",
    "make_policy",
    "record_expert_episode",
    "run_episode",
]

PolicyKind = Literal["expert", "random"]


class Policy(Protocol):
    """Maps an observation to an action; ``reset`` is called at every episode start."""

    def __call__(self, observation: dict[str, npt.NDArray[np.float64]]) -> npt.NDArray[Any]:
        """The action for an observation."""

    def reset(self) -> None:
        """Forget the previous episode."""


@dataclass(frozen=True)
class EpisodeStats:
    """What happened in one episode.

    Attributes:
        seed: Seed of its ``reset`` (None: the stream continued).
        steps: Control steps taken.
        episode_return: Sum of the rewards.
        success: ``info["is_success"]`` of the last step.
        first_success_step: 1-based step of the first success, or None.
        collision_steps: Steps with arm–obstacle contact.
        frames: Video frames written (0 without video).
    """

    seed: int | None
    steps: int
    episode_return: float
    success: bool
    first_success_step: int | None
    collision_steps: int
    frames: int = 0

    @property
    def collided(self) -> bool:
        """Whether the arm touched the obstacle at all."""
        return self.collision_steps > 0


@dataclass(frozen=True)
class EvaluationSummary:
    """Statistics over episodes.

    Attributes:
        env_id: The env.
        policy: The policy's name.
        episodes: Per-episode statistics, in order.
    """

    env_id: str
    policy: str
    episodes: tuple[EpisodeStats, ...]

    @property
    def success_rate(self) -> float:
        """Fraction of episodes that ended in success."""
        return float(np.mean([e.success for e in self.episodes])) if self.episodes else 0.0

    @property
    def mean_return(self) -> float:
        """Mean episode return."""
        return float(np.mean([e.episode_return for e in self.episodes])) if self.episodes else 0.0

    @property
    def collision_episodes(self) -> int:
        """Episodes in which the arm touched the obstacle."""
        return sum(e.collided for e in self.episodes)

    @property
    def collision_steps(self) -> int:
        """Steps with arm–obstacle contact, over all episodes."""
        return sum(e.collision_steps for e in self.episodes)


class _RandomPolicy:
    """Uniform actions from the env's action space (seeded)."""

    def __init__(self, env: gym.Env[Any, Any], seed: int | None) -> None:
        self._space = env.action_space
        self._space.seed(seed)

    def __call__(self, observation: dict[str, npt.NDArray[np.float64]]) -> npt.NDArray[Any]:
        action: npt.NDArray[Any] = self._space.sample()
        return action

    def reset(self) -> None:
        """Nothing to forget."""


def make_policy(kind: PolicyKind, env: gym.Env[Any, Any], seed: int | None = None) -> Policy:
    """The scripted expert of an env, or a seeded random policy.

    Args:
        kind: ``"expert"`` or ``"random"``.
        env: The env (wrapped or not).
        seed: Seed of the random policy's action sampling.

    Raises:
        InvalidInputError: Unknown kind, or no expert for this env.
    """
    if kind == "random":
        return _RandomPolicy(env, seed)
    if kind != "expert":
        raise InvalidInputError(f"policy must be 'expert' or 'random', got {kind!r}")
    u = env.unwrapped
    if isinstance(u, PickAndPlaceEnv):
        return PickAndPlaceExpert(env)
    if isinstance(u, ReachEnv):
        return ReachExpert(env)
    raise InvalidInputError(f"no scripted expert for {type(u).__name__}")


def run_episode(
    env: gym.Env[Any, Any],
    policy: Policy,
    seed: int | None = None,
    *,
    sink: FrameSink | None = None,
    action_noise: float = 0.0,
) -> EpisodeStats:
    """Run one episode until it terminates or is truncated.

    Args:
        env: The env; it must be time-limited (``gym.make`` adds the limit).
        policy: The policy (reset here).
        seed: Seed of ``env.reset`` (and of the action noise; None: no noise).
        sink: Where rendered frames go (the env needs ``render_mode="rgb_array"``);
            one frame after the reset and one after every step.
        action_noise: Gaussian noise on every action, as a fraction of the action
            range (:mod:`lynxsim.envs.noise`); needs a seed when not 0.

    Returns:
        The :class:`EpisodeStats`.
    """
    std = action_noise_std(env.action_space, action_noise) if action_noise else None
    if std is not None and seed is None:
        raise InvalidInputError("action noise needs a seed (its generator is the episode's)")
    rng = noise_generator(0 if seed is None else seed)
    space = env.action_space
    obs, _ = env.reset(seed=seed)
    policy.reset()
    frames = 0

    def frame() -> None:
        nonlocal frames
        if sink is not None:
            image = env.render()
            if not isinstance(image, np.ndarray):
                raise InvalidInputError("recording needs an env made with render_mode='rgb_array'")
            sink.append_data(image)
            frames += 1

    frame()
    total, steps, collisions, first = 0.0, 0, 0, None
    success = False
    while True:
        action = policy(obs)
        if std is not None and isinstance(space, gym.spaces.Box):
            action = add_noise(action, space, std, rng)
        obs, reward, terminated, truncated, info = env.step(action)
        steps += 1
        total += float(reward)
        collisions += bool(info["collision"])
        success = bool(info["is_success"])
        if success and first is None:
            first = steps
        frame()
        if terminated or truncated:
            break
    return EpisodeStats(seed, steps, total, success, first, collisions, frames)


@contextlib.contextmanager
def _maybe_video(dest: str | os.PathLike[str] | None, fps: float) -> Iterator[FrameSink | None]:
    if dest is None:
        yield None
    else:
        with mp4_writer(dest, fps) as sink:
            yield sink


def evaluate(
    env_id: str,
    policy: PolicyKind,
    episodes: int,
    seed: int = 0,
    *,
    video: str | os.PathLike[str] | None = None,
    video_episodes: int = 1,
    env_kwargs: Mapping[str, Any] | None = None,
    action_noise: float = 0.0,
    on_episode: Callable[[EpisodeStats], None] | None = None,
) -> EvaluationSummary:
    """Run seeded episodes (seeds ``seed``, ``seed + 1``, ...) and summarise them.

    Arm–obstacle contact is checked after every physics step
    (``collision_check="physics_step"``), so a graze is never missed.

    Args:
        env_id: A registered id, e.g. ``"LynxPickAndPlace-v1"``.
        policy: ``"expert"`` or ``"random"``.
        episodes: How many, > 0.
        seed: Seed of the first episode (and of the random policy).
        video: MP4 path for the first ``video_episodes`` episodes, or None.
        video_episodes: Episodes recorded into ``video``.
        env_kwargs: Extra arguments of ``gym.make`` (e.g. ``{"obstacles": ()}``).
        action_noise: Gaussian noise on every action, as a fraction of the action
            range (:mod:`lynxsim.envs.noise`), drawn per episode from its seed.
        on_episode: Called after every episode.

    Returns:
        The :class:`EvaluationSummary`.

    Raises:
        InvalidInputError: Bad counts or policy.
    """
    if episodes <= 0:
        raise InvalidInputError(f"episodes must be positive, got {episodes}")
    if video is not None and video_episodes <= 0:
        raise InvalidInputError(f"video_episodes must be positive, got {video_episodes}")
    kwargs: dict[str, Any] = {"collision_check": "physics_step", **(env_kwargs or {})}
    if video is not None:
        kwargs["render_mode"] = "rgb_array"
    env = make_env(env_id, **kwargs)
    try:
        agent = make_policy(policy, env, seed)
        stats = []
        with _maybe_video(video, float(env.metadata["render_fps"])) as sink:
            for i in range(episodes):
                s = run_episode(
                    env,
                    agent,
                    seed + i,
                    sink=sink if i < video_episodes else None,
                    action_noise=action_noise,
                )
                stats.append(s)
                if on_episode is not None:
                    on_episode(s)
    finally:
        env.close()
    return EvaluationSummary(env_id, policy, tuple(stats))


def record_expert_episode(
    dest: str | os.PathLike[str],
    seed: int = 0,
    *,
    env_id: str = PICK_AND_PLACE_ID,
    width: int = 640,
    height: int = 480,
    camera: str = "front",
    quality: Literal["lean", "fast", "medium", "default"] = "fast",
    env_kwargs: Mapping[str, Any] | None = None,
) -> EpisodeStats:
    """Record one expert episode to an MP4 (real time: one frame per control step).

    Args:
        dest: Output path, ending in ``.mp4``; written atomically.
        seed: Seed of the episode.
        env_id: ``"LynxPickAndPlace-v1"`` (default), ``"LynxReach-v1"`` or an older version.
        width: Frame width [px].
        height: Frame height [px].
        camera: ``"front"`` or ``"top"``.
        quality: ``"fast"`` (~50 frames/s on a CPU), ``"medium"`` (shadows, ~14 frames/s) or
            ``"default"`` (shadows and multisampling, ~7 frames/s).
        env_kwargs: Extra arguments of ``gym.make``.

    Returns:
        The episode's :class:`EpisodeStats` (collisions checked every physics step).
    """
    kwargs: dict[str, Any] = {
        "collision_check": "physics_step",
        **(env_kwargs or {}),
        "render_mode": "rgb_array",
        "width": width,
        "height": height,
        "camera": camera,
        "render_quality": quality,
    }
    env = make_env(env_id, **kwargs)
    try:
        with mp4_writer(dest, float(env.metadata["render_fps"])) as sink:
            return run_episode(env, make_policy("expert", env), seed, sink=sink)
    finally:
        env.close()
