"""Reachable workspace of the arm by vectorised sampling of the joint ranges.

The report calls its Figure 5 the "dexterous" workspace; what it computes, and
what this module computes, is the reachable workspace (SPEC section 3.6).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import NamedTuple

import numpy as np
import numpy.typing as npt

from lynxsim.arm.fk import tool_pose
from lynxsim.arm.geometry import LYNX_ARM, ArmGeometry
from lynxsim.errors import InvalidInputError

__all__ = ["WorkspaceSamples", "sample_workspace"]

FloatArray = npt.NDArray[np.float64]

_CHUNK = 250_000


class WorkspaceSamples(NamedTuple):
    """Joint samples and the tool points they reach.

    Attributes:
        q: Joint angles, shape (N, 5) [rad].
        position: Tool points, shape (N, 3) [m].
        pitch: Tool pitch, shape (N,) [rad].
    """

    q: FloatArray
    position: FloatArray
    pitch: FloatArray


def sample_workspace(
    n: int,
    rng: np.random.Generator,
    *,
    geometry: ArmGeometry = LYNX_ARM,
    progress: Callable[[int, int], None] | None = None,
) -> WorkspaceSamples:
    """Draw joint vectors uniformly from the joint ranges and evaluate the FK.

    Args:
        n: Number of samples (> 0).
        rng: Source of randomness.
        geometry: The arm description.
        progress: Called as ``progress(done, n)`` after each chunk.

    Returns:
        The :class:`WorkspaceSamples`.

    Raises:
        InvalidInputError: If ``n`` is not positive.
    """
    if n <= 0:
        raise InvalidInputError(f"number of samples must be positive, got {n}")
    q = rng.uniform(geometry.lower, geometry.upper, size=(n, 5))
    position = np.empty((n, 3))
    pitch = np.empty(n)
    for start in range(0, n, _CHUNK):
        stop = min(start + _CHUNK, n)
        pose = tool_pose(q[start:stop], geometry)
        position[start:stop] = pose.position
        pitch[start:stop] = pose.pitch
        if progress is not None:
            progress(stop, n)
    return WorkspaceSamples(q=q, position=position, pitch=pitch)
