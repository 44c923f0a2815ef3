"""What every robot's motion offers the commands: a label, a duration, named waypoints.

A robot builds its tasks into a motion of its own kind (a joint
:class:`~lynxsim.traj.Trajectory` for the arm, a
:class:`~lynxsim.rrr.path.PlatformPath` for the 3-RRR); the commands that only
name, time or file a motion read it through :class:`Motion`, and hand it back
to the robot's simulation side (:class:`lynxsim.sim.adapter.SimAdapter`) to play.
"""

from __future__ import annotations

from typing import Protocol, runtime_checkable

__all__ = ["Motion"]


@runtime_checkable
class Motion(Protocol):
    """A robot's motion, as the commands see it."""

    @property
    def label(self) -> str:
        """Name of the motion's type, for file names and reports (``quintic``, ``line``, ...)."""
        ...

    @property
    def duration(self) -> float:
        """Length of the motion [s]."""
        ...

    @property
    def waypoint_names(self) -> tuple[str, ...]:
        """Names of the poses it passes, in order."""
        ...
