"""The joint-space generators of :mod:`lynxsim.traj` for the arm: poses in, its joints held.

Each takes the arm's waypoints (poses solved by its IK, or joint vectors,
:mod:`lynxsim.arm.motion.waypoints`) and calls the generic generator with the
arm's joint ranges (:func:`~lynxsim.arm.motion.space.joint_bounds`) and, unless
given others, its servo limits (:data:`~lynxsim.arm.motion.space.ARM_LIMITS`)::

    traj = quintic(poses, durations=1.0)
"""

from __future__ import annotations

from lynxsim.arm.geometry import LYNX_ARM, ArmGeometry
from lynxsim.arm.motion.space import ARM_LIMITS, joint_bounds
from lynxsim.arm.motion.waypoints import ArmWaypointsLike, resolve_waypoints
from lynxsim.traj import lspb as joint_lspb
from lynxsim.traj.limits import JointBounds, JointLimits
from lynxsim.traj.polynomial import cubic as joint_cubic
from lynxsim.traj.polynomial import free_motion as joint_free_motion
from lynxsim.traj.polynomial import quintic as joint_quintic
from lynxsim.traj.ruckig_profile import ruckig_trajectory as joint_ruckig
from lynxsim.traj.timing import Durations
from lynxsim.traj.trajectory import Trajectory
from lynxsim.traj.waypoints import Waypoints

__all__ = ["arm_joints", "cubic", "free_motion", "lspb", "quintic", "ruckig_trajectory"]


def arm_joints(
    waypoints: ArmWaypointsLike, geometry: ArmGeometry = LYNX_ARM
) -> tuple[Waypoints, JointBounds]:
    """The arm's waypoints as joints (IK solved, ranges checked), and its joint bounds."""
    bounds = joint_bounds(geometry)
    return resolve_waypoints(waypoints, geometry).joints, bounds


def free_motion(
    waypoints: ArmWaypointsLike,
    durations: Durations = None,
    *,
    limits: JointLimits = ARM_LIMITS,
    stretch: bool = False,
    geometry: ArmGeometry = LYNX_ARM,
) -> Trajectory:
    """The arm's free motion; see :func:`lynxsim.traj.free_motion`.

    Args:
        waypoints: Poses or joints, shape (N, 5) [rad]; see :mod:`lynxsim.arm.motion.waypoints`.
        durations: Segment durations [s]; see :mod:`lynxsim.traj.timing`.
        limits: Joint limits to respect.
        stretch: Lengthen given durations that are too short for the limits.
        geometry: The arm description (its joint ranges and names).

    Returns:
        The checked :class:`~lynxsim.traj.Trajectory`.

    Raises:
        LimitViolationError: Given durations break a limit (names joint, time, excess).
        UnreachablePoseError: A pose has no IK solution (names the pose).
        InvalidInputError: Malformed waypoints, durations or options.
    """
    joints, bounds = arm_joints(waypoints, geometry)
    return joint_free_motion(joints, durations, bounds=bounds, limits=limits, stretch=stretch)


def cubic(
    waypoints: ArmWaypointsLike,
    durations: Durations = None,
    *,
    limits: JointLimits = ARM_LIMITS,
    stretch: bool = False,
    geometry: ArmGeometry = LYNX_ARM,
) -> Trajectory:
    """The arm's cubic trajectory: :func:`lynxsim.traj.cubic`; arguments as :func:`free_motion`."""
    joints, bounds = arm_joints(waypoints, geometry)
    return joint_cubic(joints, durations, bounds=bounds, limits=limits, stretch=stretch)


def quintic(
    waypoints: ArmWaypointsLike,
    durations: Durations = None,
    *,
    limits: JointLimits = ARM_LIMITS,
    stretch: bool = False,
    geometry: ArmGeometry = LYNX_ARM,
) -> Trajectory:
    """The arm's quintic: :func:`lynxsim.traj.quintic`; arguments as :func:`free_motion`."""
    joints, bounds = arm_joints(waypoints, geometry)
    return joint_quintic(joints, durations, bounds=bounds, limits=limits, stretch=stretch)


def lspb(
    waypoints: ArmWaypointsLike,
    durations: Durations = None,
    *,
    limits: JointLimits = ARM_LIMITS,
    stretch: bool = False,
    geometry: ArmGeometry = LYNX_ARM,
) -> Trajectory:
    """The arm's LSPB trajectory: :func:`lynxsim.traj.lspb`; arguments as :func:`free_motion`."""
    joints, bounds = arm_joints(waypoints, geometry)
    return joint_lspb(joints, durations, bounds=bounds, limits=limits, stretch=stretch)


def ruckig_trajectory(
    waypoints: ArmWaypointsLike,
    durations: Durations = None,
    *,
    limits: JointLimits = ARM_LIMITS,
    stretch: bool = False,
    pass_through: bool = False,
    geometry: ArmGeometry = LYNX_ARM,
) -> Trajectory:
    """The arm's Ruckig trajectory; see :func:`lynxsim.traj.ruckig_trajectory`.

    Arguments as :func:`free_motion`; ``pass_through`` passes intermediate
    waypoints without stopping.
    """
    joints, bounds = arm_joints(waypoints, geometry)
    return joint_ruckig(
        joints,
        durations,
        bounds=bounds,
        limits=limits,
        stretch=stretch,
        pass_through=pass_through,
    )
