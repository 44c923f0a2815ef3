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
from lynxsim.arm.geometry import LYNX_ARM, ArmGeometry, check_geometry
from lynxsim.bounds import MAX_SAMPLES
from lynxsim.errors import InvalidInputError
from lynxsim.inputs import count

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
        n: Number of samples, 1 to :data:`~lynxsim.bounds.MAX_SAMPLES`.
        rng: Source of randomness (a :class:`numpy.random.Generator`).
        geometry: The arm description.
        progress: Called as ``progress(done, n)`` after each chunk.

    Returns:
        The :class:`WorkspaceSamples`.

    Raises:
        InvalidInputError: ``n`` is not an integer from 1 to
            :data:`~lynxsim.bounds.MAX_SAMPLES` (checked before anything is
            allocated), ``rng`` not a Generator, ``progress`` not callable, or
            ``geometry`` not an :class:`~lynxsim.arm.geometry.ArmGeometry`.
    """
    n = count(n, "number of samples", 1, MAX_SAMPLES)
    if not isinstance(rng, np.random.Generator):
        raise InvalidInputError(f"rng must be a numpy.random.Generator, got {rng!r}")
    if progress is not None and not callable(progress):
        raise InvalidInputError(f"progress must be callable or None, got {progress!r}")
    geometry = check_geometry(geometry)
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
