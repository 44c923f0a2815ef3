"""Joint trajectories of any number of joints: pure numpy and Ruckig, SI units, no robot.

Every generator takes joint waypoints (an array of shape (N, n) or
:class:`Waypoints`), segment durations (given, or the shortest within the
limits), the joints' ranges (:class:`JointBounds`) and their limits
(:class:`JointLimits`), and returns a checked :class:`Trajectory` sampled by time::

    traj = quintic(q, durations=1.0, bounds=bounds, limits=limits)
    t = traj.times_at_rate(500.0)
    q, qd, qdd, qddd = traj.sample(t)

A robot's task poses become joints in its own room (the arm's:
:mod:`lynxsim.arm.motion`, with its bounds, limits and straight tool lines).
"""

from lynxsim.traj.build import JOINT_KINDS, generate, parse_kind
from lynxsim.traj.check import check_trajectory
from lynxsim.traj.kinds import WAYPOINT_KINDS, TrajectoryKind
from lynxsim.traj.kinematics import Kinematics, ToolFn, ToolReadout
from lynxsim.traj.limits import JointBounds, JointLimits
from lynxsim.traj.lspb import lspb
from lynxsim.traj.motion import Motion
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
from lynxsim.traj.waypoints import Waypoints, WaypointsLike, resolve_waypoints

__all__ = [
    "JOINT_KINDS",
    "WAYPOINT_KINDS",
    "Durations",
    "JointBounds",
    "JointLimits",
    "Kinematics",
    "Motion",
    "PolynomialSegment",
    "Segment",
    "ToolFn",
    "ToolReadout",
    "Trajectory",
    "TrajectoryKind",
    "TrajectorySample",
    "Waypoints",
    "WaypointsLike",
    "check_trajectory",
    "cubic",
    "cubic_coefficients",
    "free_motion",
    "generate",
    "lspb",
    "parse_kind",
    "quintic",
    "quintic_coefficients",
    "resolve_waypoints",
    "ruckig_trajectory",
]
