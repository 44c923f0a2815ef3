"""A robot's sphere cover made from its MuJoCo model (see :mod:`lynxsim.sim.cover.build`)."""

from lynxsim.sim.cover.build import CoverReport, cover_world
from lynxsim.sim.cover.spheres import DEFAULT_SLACK_M, GeomCover, cover_geom

__all__ = ["DEFAULT_SLACK_M", "CoverReport", "GeomCover", "cover_geom", "cover_world"]
