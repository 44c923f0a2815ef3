"""The arm's motion: its poses, joint space, straight tool lines and Lipschitz bound.

Everything here is the arm's side of the robot-free trajectory and planning
layers (:mod:`lynxsim.traj`, :mod:`lynxsim.plan`): its joint ranges and servo
limits (:data:`ARM_BOUNDS`, :data:`ARM_LIMITS`), its task poses solved by its
IK into joint waypoints, the Cartesian line, and generators with the arm's
defaults::

    traj = quintic(poses, durations=1.0)
    traj = generate("line", poses)
"""

from lynxsim.arm.motion.build import build_trajectory, generate
from lynxsim.arm.motion.cartesian import LineSegment, cartesian_line
from lynxsim.arm.motion.generators import (
    arm_joints,
    cubic,
    free_motion,
    lspb,
    quintic,
    ruckig_trajectory,
)
from lynxsim.arm.motion.lipschitz import HAND_EXTENT_M, arm_lipschitz, joint_radii
from lynxsim.arm.motion.space import ARM_BOUNDS, ARM_KINEMATICS, ARM_LIMITS, arm_tool, joint_bounds
from lynxsim.arm.motion.waypoints import (
    ArmWaypoints,
    ArmWaypointsLike,
    resolve_waypoints,
    tool_poses,
)
from lynxsim.poses import ArmPose, JointPose

__all__ = [
    "ARM_BOUNDS",
    "ARM_KINEMATICS",
    "ARM_LIMITS",
    "HAND_EXTENT_M",
    "ArmPose",
    "ArmWaypoints",
    "ArmWaypointsLike",
    "JointPose",
    "LineSegment",
    "arm_joints",
    "arm_lipschitz",
    "arm_tool",
    "build_trajectory",
    "cartesian_line",
    "cubic",
    "free_motion",
    "generate",
    "joint_bounds",
    "joint_radii",
    "lspb",
    "quintic",
    "resolve_waypoints",
    "ruckig_trajectory",
    "tool_poses",
]
