"""The arm's trajectory of any type through its poses (no task: the arm is below tasks)."""

from __future__ import annotations

from collections.abc import Sequence

from lynxsim.arm.geometry import LYNX_ARM, ArmGeometry
from lynxsim.arm.motion.cartesian import cartesian_line
from lynxsim.arm.motion.generators import arm_joints
from lynxsim.arm.motion.space import ARM_LIMITS
from lynxsim.arm.motion.waypoints import ArmWaypointsLike
from lynxsim.errors import InvalidInputError
from lynxsim.inputs import flag
from lynxsim.poses import ArmPose, JointPose
from lynxsim.traj import build as _build
from lynxsim.traj.build import parse_kind
from lynxsim.traj.kinds import TrajectoryKind
from lynxsim.traj.limits import JointLimits
from lynxsim.traj.timing import Durations
from lynxsim.traj.trajectory import Trajectory

__all__ = ["build_trajectory", "generate"]


def generate(
    kind: TrajectoryKind | str,
    waypoints: ArmWaypointsLike,
    durations: Durations = None,
    *,
    limits: JointLimits = ARM_LIMITS,
    stretch: bool = False,
    pass_through: bool = False,
    geometry: ArmGeometry = LYNX_ARM,
) -> Trajectory:
    """Generate an arm trajectory of the given type through waypoints.

    ``line`` is the straight tool line (:func:`~lynxsim.arm.motion.cartesian.cartesian_line`);
    the joint-space types go through :func:`lynxsim.traj.generate` with the
    arm's joint ranges.

    Args:
        kind: The trajectory type (a :class:`~lynxsim.traj.TrajectoryKind` or its name).
        waypoints: Poses or joints, shape (N, 5) [rad]; see :mod:`lynxsim.arm.motion.waypoints`.
        durations: Segment durations [s]; see :mod:`lynxsim.traj.timing`.
        limits: Joint limits to respect (default: the servos').
        stretch: Lengthen given durations that are too short for the limits.
        pass_through: Ruckig only: pass intermediate waypoints without stopping.
        geometry: The arm description.

    Returns:
        The checked :class:`~lynxsim.traj.Trajectory`.

    Raises:
        InvalidInputError: Unknown type, ``planned`` (searched around a scene's
            obstacles: :func:`lynxsim.robots.plan`), ``pass_through``
            not a bool or given for a type that stops.
        LynxsimError: Whatever the generator raises (see each generator).
    """
    kind = parse_kind(kind)
    pass_through = flag(pass_through, "pass_through")
    if kind is TrajectoryKind.LINE:
        if pass_through:
            raise InvalidInputError("pass_through applies to ruckig trajectories, not line")
        return cartesian_line(
            waypoints, durations, limits=limits, stretch=stretch, geometry=geometry
        )
    _build.require_joint_kind(kind)  # planned: searched, not generated
    joints, bounds = arm_joints(waypoints, geometry)
    return _build.generate(
        kind,
        joints,
        durations,
        bounds=bounds,
        limits=limits,
        stretch=stretch,
        pass_through=pass_through,
    )


def build_trajectory(
    poses: Sequence[object],
    kind: TrajectoryKind | str,
    durations: Durations = None,
    *,
    limits: JointLimits = ARM_LIMITS,
    stretch: bool = False,
    pass_through: bool = False,
) -> Trajectory:
    """The trajectory of a task's arm poses, as a task file asks for it.

    As :func:`generate` with the report's arm, except that ``pass_through`` (a
    task's flag) applies to ``ruckig`` only: the other types stop at every pose.

    Args:
        poses: The task's poses, every one an :class:`~lynxsim.poses.ArmPose`
            or a :class:`~lynxsim.poses.JointPose`.
        kind: The trajectory type.
        durations: Segment durations [s], or ``None`` for the shortest.
        limits: Joint limits (default: the servos').
        stretch: Lengthen given durations that are too short for the limits.
        pass_through: Ruckig: pass intermediate poses without stopping.

    Raises:
        InvalidInputError: A pose is not an arm pose (names its type), or the
            type is unknown or ``planned``.
        LynxsimError: Whatever the generator raises (unreachable pose, limits).
    """
    arm = [p for p in poses if isinstance(p, ArmPose | JointPose)]
    if len(arm) != len(poses):
        other = next(p for p in poses if not isinstance(p, ArmPose | JointPose))
        raise InvalidInputError(
            f"joint trajectories are built from arm poses only, got a {type(other).__name__}"
        )
    chosen = parse_kind(kind)
    return generate(
        chosen,
        arm,
        durations,
        limits=limits,
        stretch=stretch,
        pass_through=flag(pass_through, "pass_through") and chosen is TrajectoryKind.RUCKIG,
    )
