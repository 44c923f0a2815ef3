"""Goal-conditioned rewards, vectorised: the same numbers for a step and for a relabelled batch."""

from __future__ import annotations

import enum
from typing import Any

import numpy as np
import numpy.typing as npt

from lynxsim.errors import InvalidInputError

__all__ = ["GoalRewards", "RewardType", "collision_flags", "goal_distance", "goal_reward"]

FloatArray = npt.NDArray[np.float64]


class RewardType(enum.Enum):
    """SPARSE: -1 until the goal is within the threshold, then 0. DENSE: minus the distance [m]."""

    SPARSE = "sparse"
    DENSE = "dense"


def goal_distance(achieved: npt.ArrayLike, desired: npt.ArrayLike) -> FloatArray:
    """Euclidean distance of goals, shape (...) [m].

    Written out component by component, so that one goal and a batch of goals give
    bit-identical results (``np.linalg.norm`` takes a BLAS path for a single vector),
    and so that a step's ``math.sqrt(dx * dx + dy * dy + dz * dz)`` equals it.

    Args:
        achieved: Achieved goals, shape (..., 3) [m].
        desired: Desired goals, shape (..., 3) [m].
    """
    a = np.asarray(achieved, dtype=np.float64)
    b = np.asarray(desired, dtype=np.float64)
    dx = a[..., 0] - b[..., 0]
    dy = a[..., 1] - b[..., 1]
    dz = a[..., 2] - b[..., 2]
    distance: FloatArray = np.sqrt(dx * dx + dy * dy + dz * dz)
    return distance


def goal_reward(distance: FloatArray, threshold: float, reward_type: RewardType) -> FloatArray:
    """The goal term of the reward for distances [m]: sparse -1/0 or dense ``-distance``."""
    if reward_type is RewardType.SPARSE:
        sparse: FloatArray = np.where(distance > threshold, -1.0, 0.0)
        return sparse
    dense: FloatArray = -distance
    return dense


def collision_flags(info: Any, shape: tuple[int, ...]) -> npt.NDArray[np.bool_]:
    """The ``"collision"`` entries of infos, shaped like the goals' batch.

    Args:
        info: One info dict, a dict of arrays (a vector env's infos), or a sequence
            (or object array) of info dicts in the goals' C order.
        shape: Batch shape of the goals.

    Raises:
        InvalidInputError: The number of flags fits neither one nor the batch.
    """
    if isinstance(info, dict):
        flags = np.asarray(info.get("collision", False), dtype=bool)
    else:
        flags = np.asarray([bool(i.get("collision", False)) for i in np.ravel(info)], dtype=bool)
    if flags.size == 1:
        return np.broadcast_to(flags.reshape(()), shape)
    try:
        return flags.reshape(shape)
    except ValueError:
        raise InvalidInputError(
            f"info holds {flags.size} collision flags for goals of batch shape {shape}"
        ) from None


class GoalRewards:
    """The goal-conditioned API of an env (Gymnasium-Robotics' ``GoalEnv``), vectorised.

    The env sets the four attributes below; :meth:`compute_reward` then gives
    the reward of any goals and infos, for a step or a relabelled batch.

    Attributes:
        distance_threshold: Success radius around the goal [m].
        reward_type: Sparse or dense.
        collision_penalty: Subtracted on a step with arm–obstacle contact, >= 0.
        terminate_on_collision: Whether such a contact ends the episode.
    """

    distance_threshold: float
    reward_type: RewardType
    collision_penalty: float
    terminate_on_collision: bool

    def compute_reward(
        self, achieved_goal: npt.ArrayLike, desired_goal: npt.ArrayLike, info: Any
    ) -> FloatArray:
        """Reward of goals, vectorised over leading axes (for hindsight relabelling).

        Equals the reward the env's ``step`` returned for the same goals and info, bit for bit.

        Args:
            achieved_goal: Achieved goals, shape (..., 3) [m].
            desired_goal: Desired goals, shape (..., 3) [m].
            info: The step's info dict, a sequence (or object array) of such dicts,
                or a dict of arrays (a vector env's infos). Read only when
                ``collision_penalty > 0`` (its ``"collision"`` entries).

        Returns:
            Rewards, shape (...).
        """
        d = goal_distance(achieved_goal, desired_goal)
        reward = goal_reward(d, self.distance_threshold, self.reward_type)
        if self.collision_penalty == 0.0:
            return reward + 0.0
        flags = collision_flags(info, d.shape)
        total: FloatArray = reward + np.where(flags, -self.collision_penalty, 0.0)
        return total

    def compute_terminated(
        self, achieved_goal: npt.ArrayLike, desired_goal: npt.ArrayLike, info: Any
    ) -> npt.NDArray[np.bool_]:
        """Termination of goals and infos (vectorised like :meth:`compute_reward`).

        True only on arm–obstacle contact with ``terminate_on_collision``;
        reaching the goal does not end an episode.
        """
        shape = np.shape(np.asarray(achieved_goal))[:-1]
        if not self.terminate_on_collision:
            return np.zeros(shape, dtype=bool)
        return np.asarray(collision_flags(info, shape), dtype=bool)

    def compute_truncated(
        self, achieved_goal: npt.ArrayLike, desired_goal: npt.ArrayLike, info: Any
    ) -> npt.NDArray[np.bool_]:
        """Always False: the time limit is ``max_episode_steps`` (a wrapper)."""
        return np.zeros(np.shape(np.asarray(achieved_goal))[:-1], dtype=bool)
