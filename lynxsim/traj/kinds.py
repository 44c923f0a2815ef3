"""The trajectory types lynxsim generates, and what each one promises."""

from __future__ import annotations

import enum

__all__ = ["WAYPOINT_KINDS", "TrajectoryKind"]


class TrajectoryKind(enum.StrEnum):
    """A trajectory type, named as in task files and at the command line.

    ``continuity`` is the highest derivative of ``q`` that is continuous over the
    whole trajectory, segment joints included. The derivative one above it is
    bounded (it may jump at segment joints), so a trajectory is checked against
    the limits of derivatives ``1 .. continuity + 1`` (jerk at most); any higher
    derivative has impulses at the segment joints that samples cannot show.
    """

    FREE = "free"
    CUBIC = "cubic"
    QUINTIC = "quintic"
    LSPB = "lspb"
    LINE = "line"
    RUCKIG = "ruckig"
    PLANNED = "planned"

    @property
    def continuity(self) -> int:
        """Order of the highest derivative of ``q`` that is continuous everywhere."""
        return _CONTINUITY[self]

    @property
    def limited_orders(self) -> tuple[int, ...]:
        """Derivative orders (1 velocity, 2 acceleration, 3 jerk) held to limits."""
        return tuple(range(1, min(self.continuity + 1, 3) + 1))

    @property
    def description(self) -> str:
        """One line for ``lynxsim traj --list``."""
        return _DESCRIPTIONS[self]


_CONTINUITY = {
    TrajectoryKind.FREE: 0,
    TrajectoryKind.CUBIC: 1,
    TrajectoryKind.QUINTIC: 2,
    TrajectoryKind.LSPB: 1,
    TrajectoryKind.LINE: 2,
    TrajectoryKind.RUCKIG: 2,
    TrajectoryKind.PLANNED: 2,
}

_DESCRIPTIONS = {
    TrajectoryKind.FREE: "free motion: joints move at constant speed between poses "
    "(the report's linear joint increments); velocity jumps at every pose",
    TrajectoryKind.CUBIC: "cubic polynomial per segment in joint space, zero velocity "
    "at every pose; acceleration jumps at the poses",
    TrajectoryKind.QUINTIC: "quintic polynomial per segment in joint space, zero velocity "
    "and acceleration at every pose",
    TrajectoryKind.LSPB: "linear segments with parabolic blends (trapezoidal velocity) "
    "in joint space, blends at the acceleration limit, stops at every pose",
    TrajectoryKind.LINE: "straight tool line in Cartesian space, IK at every sample, "
    "quintic time scaling per segment (stops at every pose)",
    TrajectoryKind.RUCKIG: "time-optimal jerk-limited joint motion (Ruckig), "
    "optionally passing via poses without stopping",
    TrajectoryKind.PLANNED: "collision-free motion around the task's obstacles: joint-space "
    "path found by OMPL (RRT-Connect), shortened, timed with Ruckig, checked clear",
}


WAYPOINT_KINDS: tuple[TrajectoryKind, ...] = tuple(
    k for k in TrajectoryKind if k is not TrajectoryKind.PLANNED
)
"""The types generated through given waypoints (every type but ``planned``, which is
searched around a scene's obstacles by :func:`lynxsim.robots.plan`)."""
