"""Goal-conditioned rewards, vectorised: the same numbers for a step and for a relabelled batch."""

from __future__ import annotations

import enum
from typing import Any

import numpy as np
import numpy.typing as npt

from lynxsim.errors import InvalidInputError

__all__ = ["RewardType", "collision_flags", "goal_distance", "goal_reward"]

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
