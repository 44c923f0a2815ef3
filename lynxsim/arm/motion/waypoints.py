"""The arm's waypoints: task poses or joint vectors, turned into joints by the arm's IK.

An arm generator accepts either an array of joint vectors, shape (N, 5) [rad],
or a sequence of :class:`~lynxsim.poses.ArmPose` (tool point, pitch, optional
roll, solved by the analytic IK) and :class:`~lynxsim.poses.JointPose` (joints
given directly), mixed freely. :func:`resolve_waypoints` gives the generic
joint :class:`~lynxsim.traj.Waypoints` the trajectory layer moves through, and
the tool pose of every waypoint (where the straight tool lines run, what the
videos and plots mark).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from lynxsim.arm.fk import tool_pose
from lynxsim.arm.geometry import LYNX_ARM, ArmGeometry
from lynxsim.arm.ik import IKStatus, ik
from lynxsim.arm.motion.space import joint_bounds
from lynxsim.errors import (
    InvalidInputError,
    JointRangeError,
    OutOfReachError,
)
from lynxsim.inputs import instance
from lynxsim.poses import ArmPose, JointPose
from lynxsim.traj.waypoints import Waypoints, check_range, check_waypoint_count, joint_array

__all__ = ["ArmWaypoints", "ArmWaypointsLike", "resolve_waypoints", "tool_poses"]

FloatArray = npt.NDArray[np.float64]

ArmWaypointsLike = Sequence[ArmPose | JointPose] | npt.ArrayLike
"""What the arm's generators accept: poses, or joint vectors of shape (N, 5) [rad]."""


@dataclass(frozen=True)
class ArmWaypoints:
    """The arm's waypoints resolved into joints, with their tool poses.

    Attributes:
        joints: The joint waypoints (shape (N, 5) [rad], names) for :mod:`lynxsim.traj`.
        poses: The tool pose of every waypoint (the targets as given, or from the
            forward kinematics where joints were given), roll filled in.

    Raises:
        InvalidInputError: ``joints`` is not :class:`~lynxsim.traj.Waypoints`, or
            ``poses`` not one :class:`~lynxsim.poses.ArmPose` per waypoint.
    """

    joints: Waypoints
    poses: tuple[ArmPose, ...]

    def __post_init__(self) -> None:
        joints = instance(self.joints, Waypoints, "joints")
        poses = self.poses
        if not (
            isinstance(poses, tuple)
            and len(poses) == joints.q.shape[0]
            and all(isinstance(p, ArmPose) for p in poses)
        ):
            raise InvalidInputError(f"poses must be a tuple of {joints.q.shape[0]} ArmPose")

    @property
    def q(self) -> FloatArray:
        """Joints at the waypoints, shape (N, 5) [rad], read-only."""
        return self.joints.q

    @property
    def names(self) -> tuple[str, ...]:
        """Waypoint labels."""
        return self.joints.names


def _solve(pose: ArmPose, q_prev: FloatArray | None, geometry: ArmGeometry) -> FloatArray:
    """Joints of a named pose, the solution closest to ``q_prev`` (if given)."""
    result = ik(np.asarray(pose.position), pose.pitch, pose.roll, q_ref=q_prev, geometry=geometry)
    status = IKStatus(int(result.status))
    if status is IKStatus.OK:
        return result.q
    message = f"pose {pose.describe()} is unreachable: {result.reason()}"
    if status is IKStatus.OUT_OF_REACH:
        raise OutOfReachError(message)
    raise JointRangeError(message, joint=int(result.joint))


def _pose_of(q: FloatArray, name: str, geometry: ArmGeometry) -> ArmPose:
    pose = tool_pose(q, geometry)
    return ArmPose(tuple(pose.position), float(pose.pitch), float(pose.roll), name)


def tool_poses(waypoints: Waypoints, geometry: ArmGeometry = LYNX_ARM) -> tuple[ArmPose, ...]:
    """The tool pose of every joint waypoint (forward kinematics), named as the waypoints.

    For a trajectory's waypoints (``traj.waypoints``): the tool points agree with
    poses given as targets to the IK's precision (~1e-15 m).

    Raises:
        InvalidInputError: Not :class:`~lynxsim.traj.Waypoints` of the arm's joints.
    """
    waypoints = instance(waypoints, Waypoints, "waypoints")
    if waypoints.n_joints != 5:
        raise InvalidInputError(f"the arm's waypoints have 5 joints, got {waypoints.n_joints}")
    return tuple(_pose_of(q, name, geometry) for q, name in zip(waypoints.q, waypoints.names))


def resolve_waypoints(
    waypoints: ArmWaypointsLike, geometry: ArmGeometry = LYNX_ARM
) -> ArmWaypoints:
    """Turn poses or joint vectors into joints, checking reach and joint ranges.

    Poses are solved in order; each IK picks the solution closest to the previous
    waypoint's joints (the first takes the IK's default branch).

    Args:
        waypoints: At least two poses, or joints of shape (N, 5) [rad].
        geometry: The arm description.

    Returns:
        The resolved :class:`ArmWaypoints`; unnamed poses are named ``P1``, ``P2``, ...

    Raises:
        OutOfReachError: A pose's wrist point is out of reach (names the pose).
        JointRangeError: A pose needs, or a joint vector has, a joint out of range.
        InvalidInputError: Fewer than two or more than
            :data:`~lynxsim.traj.waypoints.MAX_WAYPOINTS` waypoints, a wrong shape,
            values that are not real numbers, or a geometry that is not an
            :class:`~lynxsim.arm.ArmGeometry`.
        NonFiniteInputError: A value is NaN or infinite.
    """
    bounds = joint_bounds(geometry)
    items: list[ArmPose | JointPose]
    if (
        isinstance(waypoints, Sequence)
        and not isinstance(waypoints, str | bytes)
        and all(isinstance(w, ArmPose | JointPose) for w in waypoints)
    ):
        items = [w for w in waypoints if isinstance(w, ArmPose | JointPose)]
    else:
        arr = joint_array(waypoints, 5, "ArmPose/JointPose objects")
        items = [JointPose(tuple(row)) for row in arr]
    check_waypoint_count(len(items))
    qs: list[FloatArray] = []
    poses: list[ArmPose] = []
    for i, item in enumerate(items):
        name = item.name or f"P{i + 1}"
        if isinstance(item, JointPose):
            if len(item.q) != 5:
                raise InvalidInputError(
                    f"waypoint {name}: the arm has 5 joints, got a joint pose of {len(item.q)}"
                )
            q = np.asarray(item.q)
            check_range(q, name, bounds)
            poses.append(_pose_of(q, name, geometry))
        else:
            q = _solve(dataclasses.replace(item, name=name), qs[-1] if qs else None, geometry)
            poses.append(ArmPose(item.position, item.pitch, float(q[4]), name))
        qs.append(q)
    joints = Waypoints(np.array(qs), tuple(p.name for p in poses))
    return ArmWaypoints(joints, tuple(poses))
