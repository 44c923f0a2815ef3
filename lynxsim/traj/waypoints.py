"""Waypoints of a trajectory: task poses or joint vectors, turned into joints.

A generator accepts either an array of joint vectors, shape (N, 5) [rad], or a
sequence of :class:`ArmPose` (tool point, pitch, optional roll, solved by the
analytic IK) and :class:`JointPose` (joints given directly), mixed freely.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from lynxsim.angles import LIMIT_TOL
from lynxsim.arm import LYNX_ARM, ArmGeometry, IKStatus, ik, tool_pose
from lynxsim.errors import (
    InvalidInputError,
    JointRangeError,
    NonFiniteInputError,
    OutOfReachError,
)

__all__ = ["ArmPose", "JointPose", "Waypoints", "WaypointsLike", "resolve_waypoints"]

FloatArray = npt.NDArray[np.float64]


def _floats(values: npt.ArrayLike, n: int, what: str) -> tuple[float, ...]:
    arr = np.asarray(values, dtype=float)
    if arr.shape != (n,):
        raise InvalidInputError(f"{what} must have shape ({n},), got {arr.shape}")
    if not np.isfinite(arr).all():
        raise NonFiniteInputError(f"{what} must be finite, got {arr.tolist()}")
    return tuple(float(v) for v in arr)


@dataclass(frozen=True)
class ArmPose:
    """A task pose of the arm's tool, solved by the analytic IK.

    Attributes:
        position: Tool point in the base frame, (x, y, z) [m].
        pitch: Tool pitch above the horizontal [rad] (see :func:`lynxsim.arm.ik`).
        roll: Wrist roll ``q5`` [rad]; ``None`` keeps the previous pose's roll
            (0 for the first pose).
        name: Label used in messages and plots (default ``P1``, ``P2``, ...).
    """

    position: tuple[float, float, float]
    pitch: float
    roll: float | None = None
    name: str = ""

    def __post_init__(self) -> None:
        object.__setattr__(self, "position", _floats(self.position, 3, "pose position"))
        (pitch,) = _floats([self.pitch], 1, "pose pitch")
        object.__setattr__(self, "pitch", pitch)
        if self.roll is not None:
            (roll,) = _floats([self.roll], 1, "pose roll")
            object.__setattr__(self, "roll", roll)

    def describe(self) -> str:
        """The pose in the report's units, e.g. ``P3 (x 250, y 0, z 300 mm, pitch 0 deg)``."""
        x, y, z = (1e3 * v for v in self.position)
        roll = "" if self.roll is None else f", roll {math.degrees(self.roll):.4g} deg"
        return (
            f"{self.name} (x {x:.4g}, y {y:.4g}, z {z:.4g} mm, "
            f"pitch {math.degrees(self.pitch):.4g} deg{roll})"
        )


@dataclass(frozen=True)
class JointPose:
    """A waypoint given by its joints.

    Attributes:
        q: Joint angles q1..q5 [rad].
        name: Label used in messages and plots.
    """

    q: tuple[float, ...]
    name: str = ""

    def __post_init__(self) -> None:
        object.__setattr__(self, "q", _floats(self.q, 5, "joint pose q"))


WaypointsLike = Sequence[ArmPose | JointPose] | npt.ArrayLike
"""What generators accept: poses, or joint vectors of shape (N, 5) [rad]."""


@dataclass(frozen=True)
class Waypoints:
    """Waypoints resolved into joints.

    Attributes:
        q: Joints at the waypoints, shape (N, 5) [rad], read-only.
        poses: The tool pose of every waypoint (the targets as given, or from the
            forward kinematics where joints were given), roll filled in.
    """

    q: FloatArray
    poses: tuple[ArmPose, ...]

    @property
    def names(self) -> tuple[str, ...]:
        """Waypoint labels."""
        return tuple(p.name for p in self.poses)


def _check_range(q: FloatArray, name: str, geometry: ArmGeometry) -> None:
    below = geometry.lower - q
    above = q - geometry.upper
    excess = np.maximum(below, above)
    j = int(np.argmax(excess))
    if excess[j] > LIMIT_TOL:
        lo, hi = np.degrees(geometry.lower[j]), np.degrees(geometry.upper[j])
        raise JointRangeError(
            f"waypoint {name}: joint {j + 1} ({geometry.joint_names[j]}) = "
            f"{np.degrees(q[j]):.4g} deg is outside its range [{lo:.4g}, {hi:.4g}] deg "
            f"by {np.degrees(excess[j]):.4g} deg",
            joint=j + 1,
        )


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


def resolve_waypoints(waypoints: WaypointsLike, geometry: ArmGeometry = LYNX_ARM) -> Waypoints:
    """Turn poses or joint vectors into joints, checking reach and joint ranges.

    Poses are solved in order; each IK picks the solution closest to the previous
    waypoint's joints (the first takes the IK's default branch).

    Args:
        waypoints: At least two poses, or joints of shape (N, 5) [rad].
        geometry: The arm description.

    Returns:
        The resolved :class:`Waypoints`; unnamed poses are named ``P1``, ``P2``, ...

    Raises:
        OutOfReachError: A pose's wrist point is out of reach (names the pose).
        JointRangeError: A pose needs, or a joint vector has, a joint out of range.
        InvalidInputError: Fewer than two waypoints, or a wrong shape.
        NonFiniteInputError: A value is NaN or infinite.
    """
    items: list[ArmPose | JointPose]
    if isinstance(waypoints, Sequence) and all(
        isinstance(w, ArmPose | JointPose) for w in waypoints
    ):
        items = [w for w in waypoints if isinstance(w, ArmPose | JointPose)]
    else:
        try:
            arr = np.asarray(waypoints, dtype=float)
        except (TypeError, ValueError):
            raise InvalidInputError(
                "waypoints must be ArmPose/JointPose objects or joints of shape (N, 5)"
            ) from None
        if arr.ndim != 2 or arr.shape[1] != 5:
            raise InvalidInputError(f"joint waypoints must have shape (N, 5), got {arr.shape}")
        items = [JointPose(tuple(row)) for row in arr]
    if len(items) < 2:
        raise InvalidInputError(f"a trajectory needs at least two waypoints, got {len(items)}")
    qs: list[FloatArray] = []
    poses: list[ArmPose] = []
    for i, item in enumerate(items):
        name = item.name or f"P{i + 1}"
        if isinstance(item, JointPose):
            q = np.asarray(item.q)
            _check_range(q, name, geometry)
            poses.append(_pose_of(q, name, geometry))
        else:
            q = _solve(dataclasses.replace(item, name=name), qs[-1] if qs else None, geometry)
            poses.append(ArmPose(item.position, item.pitch, float(q[4]), name))
        qs.append(q)
    q_all = np.array(qs)
    q_all.setflags(write=False)
    return Waypoints(q=q_all, poses=tuple(poses))
