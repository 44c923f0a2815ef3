"""What a sweep says of each run: one :class:`Verdict`, its code and the name written.

The sweep judge (:mod:`lynxsim.sim.sweep_judge`) gives codes, the runner
(:mod:`lynxsim.sweep.runner`) writes names into the table's ``verdict`` column
(:mod:`lynxsim.sweep.table`), and the maps (:mod:`lynxsim.plots.sweep_map`)
and summaries read them back: all from this one definition. Pure Python.
"""

from __future__ import annotations

import enum

__all__ = ["Verdict"]


class Verdict(enum.IntEnum):
    """A run's verdict: an integer code (stored in arrays), and its name (:attr:`label`).

    CLEAR: never touched an obstacle (its clearance is exact).
    COLLIDED: touched an obstacle during the run (the first contact time is exact).
    START_OVERLAP: touched the swept obstacle during the hold before the motion
        (the obstacle overlaps the start).
    INVALID: no scene: the obstacle would enclose the robot's base or the cube's start.
    NO_MOTION: no motion to play (it could not be built or planned, or not played).
    """

    CLEAR = 0
    COLLIDED = 1
    START_OVERLAP = 2
    INVALID = 3
    NO_MOTION = 4

    @property
    def label(self) -> str:
        """The name the sweep table writes: ``clear``, ``collided``, ``start_overlap``..."""
        return self.name.lower()

    @classmethod
    def labels(cls) -> tuple[str, ...]:
        """Every name, in code order."""
        return tuple(v.label for v in cls)
