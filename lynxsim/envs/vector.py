"""The arm envs batched: N envs whose physics MuJoCo steps together on its native threads.

``gym.make_vec("LynxPickAndPlace-v1", num_envs=N, vectorization_mode="vector_entry_point")``
(or any registered lynxsim id) makes a :class:`LynxVectorEnv`. It holds N envs
of the id's class and steps them as Gymnasium's ``SyncVectorEnv`` of ``gym.make``
envs would, with the same results bit for bit (tested), but with the physics of
all N (the 0.8 of a step's time) in one native call
(:class:`~lynxsim.sim.arm.env_batch.EnvBatch`, the GIL released, one thread
per CPU). The actions of all N are checked and clipped by one call
(:func:`~lynxsim.envs.base.clipped_actions`), and with ``-v2`` their tool targets
moved by one :func:`~lynxsim.envs.tool_action.tool_targets` call (the single env
calls both with one row). What is per env is the single env's own code, not a
copy of it: the ``-v0``/``-v1`` action turned into servo targets
(:meth:`LynxArmEnv._command <lynxsim.envs.base.LynxArmEnv._command>`), the
observation, reward, success and
info (:meth:`LynxArmEnv._outcome <lynxsim.envs.base.LynxArmEnv._outcome>`), and
the reset with its draws (cube, goal, random obstacles, randomisation) from each
env's own ``np_random``.

Semantics (Gymnasium 1.x, ``AutoresetMode.NEXT_STEP``, ``SyncVectorEnv``'s
default): an env whose episode ended (terminated, or truncated at
``max_episode_steps``) is reset by the next :meth:`~LynxVectorEnv.step`, which
returns its reset observation and info, reward 0 and neither flag; ``reset(seed=s)``
seeds env i with ``s + i`` (or takes a list of seeds), and
``options={"reset_mask": mask}`` resets only some envs. ``infos`` is a dict of
arrays, each key with its ``_key`` mask, as ``SyncVectorEnv`` builds it.
:meth:`~LynxVectorEnv.compute_reward` is the envs' (vectorised, for HER).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import gymnasium as gym
import numpy as np
import numpy.typing as npt
from gymnasium.vector import AutoresetMode
from gymnasium.vector.utils import batch_space

from lynxsim.envs.base import LynxArmEnv, clipped_actions
from lynxsim.envs.control import TargetStatus
from lynxsim.envs.pick_and_place import PickAndPlaceEnv
from lynxsim.envs.reach import ReachEnv
from lynxsim.envs.reward import GoalRewards
from lynxsim.envs.tool_action import ToolRollController
from lynxsim.errors import InvalidInputError
from lynxsim.inputs import count, real_array
from lynxsim.sim.arm.env_batch import EnvBatch

__all__ = ["MAX_ENVS", "LynxVectorEnv", "pick_and_place_vector_env", "reach_vector_env"]

_SCALARS = (bool, int, float)
"""Info value types batched in one go (``_add_info`` makes arrays of exactly these types)."""
MAX_ENVS = 4096
"""Most envs one vector env may hold."""

BatchObs = dict[str, npt.NDArray[Any]]
"""Observations of all envs: each entry of the single env's, stacked on a first axis (N, ...)."""


class LynxVectorEnv(
    GoalRewards, gym.vector.VectorEnv[BatchObs, npt.NDArray[Any], npt.NDArray[Any]]
):
    """N arm envs of one class and options, stepped together (see the module docstring).

    Args:
        env_class: The env (:class:`~lynxsim.envs.PickAndPlaceEnv`,
            :class:`~lynxsim.envs.ReachEnv`).
        num_envs: How many, 1..:data:`MAX_ENVS`.
        max_episode_steps: Steps after which an episode is truncated (None: never),
            as ``gym.make``'s ``TimeLimit``.
        nthread: Threads stepping the physics, this one included (None: one per
            CPU).
        chunks: Pieces a step's physics is cut into, 1..num_envs: a helper thread
            steps each natively while this thread finishes the stepped ones
            (1: no overlap). The actions of all envs are turned into servo
            targets before, in one go.
        **kwargs: The env's keyword arguments (every env gets the same);
            ``render_mode`` None or ``"rgb_array"``.

    Raises:
        InvalidInputError: A bad count, ``render_mode="human"``, or a bad env argument.
    """

    metadata: dict[str, Any] = {  # noqa: RUF012  (Gymnasium's convention)
        "autoreset_mode": AutoresetMode.NEXT_STEP,
        "render_modes": ["rgb_array"],
    }

    def __init__(
        self,
        env_class: type[LynxArmEnv],
        *,
        num_envs: int,
        max_episode_steps: int | None = None,
        nthread: int | None = None,
        chunks: int = 2,
        **kwargs: Any,
    ) -> None:
        self.num_envs = count(num_envs, "num_envs", 1, MAX_ENVS)
        self.max_episode_steps = (
            None
            if max_episode_steps is None
            else count(max_episode_steps, "max_episode_steps", 1, 2**62)
        )
        if kwargs.get("render_mode") == "human":
            raise InvalidInputError(
                "a batched vector env renders rgb_array frames only, got render_mode='human'"
            )
        self.envs: tuple[LynxArmEnv, ...] = tuple(env_class(**kwargs) for _ in range(num_envs))
        """The envs, in order (each its own model, data and ``np_random``)."""
        first = self.envs[0]
        self.render_mode = first.render_mode
        self.metadata = {**self.metadata, "render_fps": first.metadata["render_fps"]}
        self.distance_threshold = first.distance_threshold
        self.reward_type = first.reward_type
        self.collision_penalty = first.collision_penalty
        self.terminate_on_collision = first.terminate_on_collision
        self.single_action_space = first.action_space
        self.action_space = batch_space(first.action_space, self.num_envs)
        self.single_observation_space = first.observation_space
        self.observation_space = batch_space(first.observation_space, self.num_envs)
        self._physics = EnvBatch([env._scene for env in self.envs], nthread)
        self._chunks = count(chunks, "chunks", 1, MAX_ENVS)
        controllers = [env.controller for env in self.envs]
        roll = [c for c in controllers if isinstance(c, ToolRollController)]
        self._roll: list[ToolRollController] = roll if len(roll) == len(controllers) else []
        """The envs' ``-v2`` controllers, moved by one
        :func:`~lynxsim.envs.tool_action.tool_targets` call per chunk (empty for the others)."""
        spaces: gym.Space[Any] = first.observation_space
        self._keys: tuple[str, ...] = (
            tuple(spaces.spaces) if isinstance(spaces, gym.spaces.Dict) else ()
        )
        self._action_shape = (self.num_envs, first._n_act)
        self._elapsed: list[int] = [0] * self.num_envs
        self._ended: list[bool] = [False] * self.num_envs
        self._started: bool = False
        self._obs: list[dict[str, npt.NDArray[Any]]] = []

    @property
    def nthread(self) -> int:
        """Threads stepping the physics, this one included."""
        return self._physics.nthread

    # ------------------------------------------------------------------ reset

    def reset(
        self,
        *,
        seed: int | Sequence[int | None] | None = None,
        options: dict[str, Any] | None = None,
    ) -> tuple[BatchObs, dict[str, Any]]:
        """Reset every env (or those of ``options["reset_mask"]``), as ``SyncVectorEnv``.

        Args:
            seed: None, an int ``s`` (env i gets ``s + i``) or one seed (or None) per env.
            options: The envs' reset options (``"randomize"``), and optionally
                ``"reset_mask"``: a bool array (num_envs,), True for the envs to reset.

        Returns:
            The observations of all envs (those not reset: their last ones)
            and the infos of those reset.

        Raises:
            InvalidInputError: Bad seeds or mask, or what an env's ``reset`` raises.
        """
        seeds = self._seeds(seed)
        opts = None if options is None else dict(options)
        mask = self._reset_mask(opts.pop("reset_mask") if opts and "reset_mask" in opts else None)
        if not self._started and not mask.all():
            raise InvalidInputError("the first reset must reset every env (no reset_mask)")
        ids = np.flatnonzero(mask).tolist()
        infos: dict[str, Any] = {}
        results: list[tuple[dict[str, npt.NDArray[Any]], dict[str, Any]]] = []
        for i in ids:
            results.append(self.envs[i].reset(seed=seeds[i], options=opts))
            self._elapsed[i] = 0
            self._ended[i] = False
        self._physics.load(ids)
        if not self._started:
            self._obs = [obs for obs, _ in results]
        else:
            for i, (obs, _) in zip(ids, results, strict=True):
                self._obs[i] = obs
        self._started = True
        for i, (_, info) in zip(ids, results, strict=True):
            infos = self._add_info(infos, info, i)
        return self._stacked(), infos

    def _seeds(self, seed: object) -> list[int | None]:
        if seed is None:
            return [None] * self.num_envs
        if isinstance(seed, int | np.integer) and not isinstance(seed, bool | np.bool_):
            return [int(seed) + i for i in range(self.num_envs)]
        if not isinstance(seed, list | tuple) or len(seed) != self.num_envs:
            raise InvalidInputError(
                f"seed must be None, an integer or {self.num_envs} seeds, got {seed!r}"
            )
        return list(seed)

    def _reset_mask(self, mask: object) -> npt.NDArray[np.bool_]:
        if mask is None:
            return np.ones(self.num_envs, dtype=bool)
        if (
            not isinstance(mask, np.ndarray)
            or mask.dtype != np.bool_
            or mask.shape != (self.num_envs,)
            or not mask.any()
        ):
            raise InvalidInputError(
                f"options['reset_mask'] must be a bool array of shape ({self.num_envs},) "
                f"with a True, got {mask!r}"
            )
        return mask

    # ------------------------------------------------------------------- step

    def step(
        self, actions: npt.ArrayLike
    ) -> tuple[
        BatchObs,
        npt.NDArray[np.float64],
        npt.NDArray[np.bool_],
        npt.NDArray[np.bool_],
        dict[str, Any],
    ]:
        """Step every env whose episode goes on, and reset those whose episode ended.

        Args:
            actions: Shape (num_envs, *single action shape); each row as the env's ``step``.

        Returns:
            ``(observations, rewards, terminations, truncations, infos)``, each
            with a first axis of num_envs.

        Raises:
            InvalidInputError: Not reset yet, or an action the env refuses (the
                message names it).
            NonFiniteInputError: An action holds NaN or infinity.
        """
        if not self._started:
            raise InvalidInputError("call reset() before step()")
        a = real_array(actions, "actions")
        shape = self._action_shape
        if a.shape != shape:
            raise InvalidInputError(f"actions must have shape {shape}, got {a.shape}")
        envs = self.envs
        going = [i for i in range(self.num_envs) if not self._ended[i]]
        rewards = np.zeros(self.num_envs)
        terminated = np.zeros(self.num_envs, dtype=bool)
        truncated = np.zeros(self.num_envs, dtype=bool)
        infos: list[dict[str, Any] | None] = [None] * self.num_envs
        commands: dict[int, tuple[TargetStatus, bool]] = {}
        limit = self.max_episode_steps

        rows = clipped_actions(a[going])
        if self._roll:  # the -v2 tool targets of all envs in one vectorised call
            values = rows
            controllers = [self._roll[i] for i in going]
            targets = [c.target for c in controllers]
            statuses = ToolRollController.apply_many(controllers, values) if going else []
            for i, v, status, target in zip(going, values, statuses, targets, strict=True):
                commands[i] = envs[i]._commanded(v, status, target)
        else:
            for i, v in zip(going, rows, strict=True):
                commands[i] = envs[i]._command_values(v)

        def after(part: Sequence[int], hits: list[bool]) -> None:
            for i, hit in zip(part, hits, strict=True):
                obs, reward, term, _, info = envs[i]._outcome(commands[i], hit)
                self._obs[i], rewards[i], terminated[i], infos[i] = obs, reward, term, info
                self._elapsed[i] += 1
                truncated[i] = limit is not None and self._elapsed[i] >= limit

        first = envs[0]
        self._physics.pipeline(
            going,
            first.frame_skip,
            every_step=first._physics_step_contacts,
            after=after,
            chunks=self._chunks,
        )
        resetting = [i for i in range(self.num_envs) if self._ended[i]]
        for i in resetting:
            self._obs[i], infos[i] = envs[i].reset()
            self._elapsed[i] = 0
        self._physics.load(resetting)
        self._ended = (terminated | truncated).tolist()
        return self._stacked(), rewards, terminated, truncated, self._infos(infos)

    def _stacked(self) -> BatchObs:
        """The envs' last observations, each entry stacked (new arrays)."""
        return {k: np.stack([o[k] for o in self._obs]) for k in self._keys}

    def _infos(self, infos: list[dict[str, Any] | None]) -> dict[str, Any]:
        """The infos of every env as ``SyncVectorEnv``'s ``_add_info`` batches them.

        When every env has an info with the first one's keys, each a scalar of
        one type or arrays of one shape and dtype (the step's infos), each key is
        batched in one go; otherwise env by env through ``_add_info``.
        """
        first = infos[0]
        if first is not None and all(i is not None and i.keys() == first.keys() for i in infos):
            rows = [i for i in infos if i is not None]
            out: dict[str, Any] = {}
            every = np.ones(self.num_envs, dtype=bool)
            for k, v in first.items():
                values = [i[k] for i in rows]
                kind = type(v)
                if kind in _SCALARS and all(type(x) is kind for x in values):
                    out[k] = np.array(values, dtype=kind)
                elif kind is np.ndarray and all(
                    type(x) is np.ndarray and x.dtype == v.dtype and x.shape == v.shape
                    for x in values
                ):
                    out[k] = np.stack(values)
                else:
                    break
                out[f"_{k}"] = every.copy()
            else:
                return out
        out = {}
        for n, info in enumerate(infos):
            if info is not None:
                out = self._add_info(out, info, n)
        return out

    # ------------------------------------------------------- rendering, calls

    def render(self) -> tuple[npt.NDArray[Any], ...] | None:
        """Each env's ``rgb_array`` frame, or None without a render mode."""
        frames = [env.render() for env in self.envs]
        return None if self.render_mode is None else tuple(f for f in frames if f is not None)

    def call(self, name: str, *args: Any, **kwargs: Any) -> tuple[Any, ...]:
        """Each env's attribute ``name``, called with the arguments if callable (as Sync's)."""
        out = []
        for env in self.envs:
            value = getattr(env, name)
            out.append(value(*args, **kwargs) if callable(value) else value)
        return tuple(out)

    def get_attr(self, name: str) -> tuple[Any, ...]:
        """Each env's attribute ``name``."""
        return tuple(getattr(env, name) for env in self.envs)

    def close_extras(self, **kwargs: Any) -> None:
        """Close every env (their renderers)."""
        self._physics.close()
        for env in self.envs:
            env.close()


def pick_and_place_vector_env(*, num_envs: int, **kwargs: Any) -> LynxVectorEnv:
    """The vector entry point of ``LynxPickAndPlace``: a :class:`LynxVectorEnv` of it."""
    return LynxVectorEnv(PickAndPlaceEnv, num_envs=num_envs, **kwargs)


def reach_vector_env(*, num_envs: int, **kwargs: Any) -> LynxVectorEnv:
    """The vector entry point of ``LynxReach``: a :class:`LynxVectorEnv` of it."""
    return LynxVectorEnv(ReachEnv, num_envs=num_envs, **kwargs)
