"""A robot's sphere cover and compiled planning on it: pure arrays and numba, no MuJoCo.

The simulation layer builds a :class:`CoverWorld` from a robot's model
(:func:`lynxsim.sim.cover.cover_world`); :class:`CoverOracle` answers the
planner's clearance questions on it, and :func:`plan_cover` runs RRT-Connect
and its shortcutting in one compiled call.
"""

from lynxsim.plan.cover.oracle import CoverOracle
from lynxsim.plan.cover.world import CoverWorld

__all__ = ["CoverOracle", "CoverWorld"]
