"""Gaussian action noise: one definition for evaluations and datasets.

The noise of an action entry has a standard deviation of ``noise`` times the
entry's range (``high - low``; 0.2 for ``noise=0.1`` on the envs' [-1, 1]
actions), is drawn from a generator of its own per episode
(:func:`noise_generator`, independent of the env's ``np_random``), and the
noisy action is clipped to the action space. ``lynxsim env --action-noise`` and
``lynxsim dataset --noise`` with the same seed step the same noisy episodes.

Light: NumPy and Gymnasium only (the command line reads :data:`MAX_NOISE`
without loading MuJoCo).
"""

from __future__ import annotations

from typing import Any

import gymnasium as gym
import numpy as np
import numpy.typing as npt

from lynxsim.errors import InvalidInputError
from lynxsim.inputs import number_in_range

__all__ = ["MAX_NOISE", "action_noise_std", "add_noise", "check_noise", "noise_generator"]

FloatArray = npt.NDArray[np.float64]

MAX_NOISE = 1.0
"""Largest action noise, as a fraction of the action range (standard deviation)."""


def check_noise(noise: float) -> float:
    """``noise`` as a float if it is a number from 0 to :data:`MAX_NOISE`.

    Raises:
        InvalidInputError: Not one real number (booleans and strings are not), or out
            of range.
        NonFiniteInputError: NaN or infinite.
    """
    return number_in_range(noise, "noise", 0.0, MAX_NOISE)


def action_noise_std(space: gym.Space[Any], noise: float) -> FloatArray:
    """Standard deviation of the action noise: ``noise`` times the range of each action entry.

    Args:
        space: The env's action space, a bounded ``Box``.
        noise: Fraction of the action range, 0 to :data:`MAX_NOISE`.

    Returns:
        Shape ``space.shape``, in the action's units.

    Raises:
        InvalidInputError: ``noise`` is not a number in range, or the space is
            not a bounded ``Box``.
        NonFiniteInputError: ``noise`` is NaN or infinite.
    """
    noise = check_noise(noise)
    if not isinstance(space, gym.spaces.Box) or not space.is_bounded():
        raise InvalidInputError(f"action noise needs a bounded Box action space, got {space}")
    high = np.asarray(space.high, dtype=np.float64)
    low = np.asarray(space.low, dtype=np.float64)
    std: FloatArray = noise * (high - low)
    return std


def noise_generator(seed: int) -> np.random.Generator:
    """The action-noise generator of the episode whose reset seed is ``seed``.

    A stream of its own (``SeedSequence(seed).spawn(1)[0]``), independent of the
    env's ``np_random`` (which Gymnasium seeds from ``SeedSequence(seed)``).
    """
    return np.random.default_rng(np.random.SeedSequence(seed).spawn(1)[0])


def add_noise(
    action: npt.ArrayLike, space: gym.spaces.Box, std: npt.ArrayLike, rng: np.random.Generator
) -> npt.NDArray[Any]:
    """``clip(action + rng.normal(0, std), low, high)`` in the space's dtype.

    The noise is drawn even where its standard deviation is 0, so that a stream
    does not depend on it.

    Args:
        action: The clean action, shape ``space.shape``.
        space: The action space.
        std: Standard deviation, broadcastable to ``space.shape`` (:func:`action_noise_std`).
        rng: The episode's generator (:func:`noise_generator`).

    Returns:
        The noisy action, shape ``space.shape``.
    """
    clean = np.asarray(action, dtype=space.dtype).astype(np.float64)
    noisy = clean + rng.normal(0.0, np.broadcast_to(np.asarray(std, dtype=np.float64), space.shape))
    out: npt.NDArray[Any] = np.clip(noisy, space.low, space.high).astype(space.dtype)
    return out
