"""Joint trajectories of the arm: pure numpy and Ruckig, SI units, no MuJoCo.

Every generator takes waypoints (task poses solved by the analytic IK, or
joint vectors), segment durations (given, or the shortest within the joint
limits), and returns a checked :class:`Trajectory` sampled by time::

    traj = quintic(poses, durations=1.0)
    t = traj.times_at_rate(500.0)
    q, qd, qdd, qddd = traj.sample(t)
"""

from lynxsim.traj.build import generate
from lynxsim.traj.cartesian import LineSegment, cartesian_line
from lynxsim.traj.check import check_trajectory
from lynxsim.traj.kinds import WAYPOINT_KINDS, TrajectoryKind
from lynxsim.traj.limits import DEFAULT_LIMITS, JointLimits
from lynxsim.traj.lspb import lspb
from lynxsim.traj.polynomial import (
    cubic,
    cubic_coefficients,
    free_motion,
    quintic,
    quintic_coefficients,
)
from lynxsim.traj.ruckig_profile import ruckig_trajectory
from lynxsim.traj.timing import Durations
from lynxsim.traj.trajectory import PolynomialSegment, Segment, Trajectory, TrajectorySample
from lynxsim.traj.waypoints import ArmPose, JointPose, Waypoints, WaypointsLike, resolve_waypoints

__all__ = [
    "DEFAULT_LIMITS",
    "WAYPOINT_KINDS",
    "ArmPose",
    "Durations",
    "JointLimits",
    "JointPose",
    "LineSegment",
    "PolynomialSegment",
    "Segment",
    "Trajectory",
    "TrajectoryKind",
    "TrajectorySample",
    "Waypoints",
    "WaypointsLike",
    "cartesian_line",
    "check_trajectory",
    "cubic",
    "cubic_coefficients",
    "free_motion",
    "generate",
    "lspb",
    "quintic",
    "quintic_coefficients",
    "resolve_waypoints",
    "ruckig_trajectory",
]
