"""A 3-RRR motion through its platform poses, of a trajectory type (no task: rrr is below tasks)."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from lynxsim.errors import InvalidInputError
from lynxsim.poses import PlanarPose
from lynxsim.rrr.path import (
    DEFAULT_PLATFORM_LIMITS,
    RRR_TRAJECTORY_KINDS,
    PlatformLimits,
    PlatformPath,
    platform_path,
)
from lynxsim.traj.build import parse_kind
from lynxsim.traj.kinds import TrajectoryKind

__all__ = ["build_path"]


def build_path(
    poses: Sequence[object],
    kind: TrajectoryKind | str,
    durations: float | Sequence[float] | None = None,
    *,
    through: bool = False,
    stretch: bool = False,
    limits: PlatformLimits = DEFAULT_PLATFORM_LIMITS,
) -> PlatformPath:
    """The timed platform path through a task's 3-RRR poses.

    Args:
        poses: The poses, every one a :class:`~lynxsim.poses.PlanarPose`.
        kind: Trajectory type; only :data:`~lynxsim.rrr.path.RRR_TRAJECTORY_KINDS`
            are planned for the 3-RRR.
        durations: Segment durations [s], or ``None`` for the shortest.
        through: One spline through every pose (a task's ``pass_through``).
        stretch: Lengthen durations that are too short for ``limits``.
        limits: Task-space limits for missing or stretched durations.

    Returns:
        The :class:`~lynxsim.rrr.path.PlatformPath`.

    Raises:
        InvalidInputError: A pose is not a platform pose, the type is unknown or
            not planned for the 3-RRR (the message lists those that are).
        LynxsimError: Whatever :func:`~lynxsim.rrr.path.platform_path` raises
            (unreachable poses, durations out of range or too short).
    """
    platform = [p for p in poses if isinstance(p, PlanarPose)]
    if len(platform) != len(poses):
        other = next(p for p in poses if not isinstance(p, PlanarPose))
        raise InvalidInputError(
            f"3-RRR paths are built from platform poses only, got a {type(other).__name__}"
        )
    chosen = parse_kind(kind)
    if chosen not in RRR_TRAJECTORY_KINDS:
        raise InvalidInputError(
            f"trajectory type {chosen.value!r} is not planned for the 3-RRR robot; "
            f"expected one of: {', '.join(k.value for k in RRR_TRAJECTORY_KINDS)}"
        )
    return platform_path(
        np.array([[p.x, p.y, p.alpha] for p in platform]),
        durations,
        names=[p.name for p in platform],
        through=through,
        stretch=stretch,
        limits=limits,
    )
