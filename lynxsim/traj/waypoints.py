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
from lynxsim.bounds import MAX_COORDINATE_M, MAX_SAMPLES
from lynxsim.errors import (
    InvalidInputError,
    JointRangeError,
    NonFiniteInputError,
    OutOfReachError,
)
from lynxsim.inputs import finite_array, instance, real_array, real_number
from lynxsim.traj.check import CHECK_POINTS

__all__ = [
    "MAX_WAYPOINTS",
    "ArmPose",
    "JointPose",
    "Waypoints",
    "WaypointsLike",
    "check_geometry",
    "resolve_waypoints",
]

FloatArray = npt.NDArray[np.float64]

MAX_WAYPOINTS = 1 + MAX_SAMPLES // CHECK_POINTS
"""Most waypoints of one trajectory: the check evaluates ``CHECK_POINTS`` samples per
segment, at most :data:`~lynxsim.bounds.MAX_SAMPLES` in all (9,757 waypoints)."""


def _floats(values: object, n: int, what: str) -> tuple[float, ...]:
    arr = finite_array(values, what)
    if arr.shape != (n,):
        raise InvalidInputError(f"{what} must have shape ({n},), got {arr.shape}")
    return tuple(float(v) for v in arr)


def _angle(value: object, what: str) -> float:
    v = real_number(value, what)
    if not math.isfinite(v):
        raise NonFiniteInputError(f"{what} must be finite, got {v!r}")
    return v


def _name(value: object) -> str:
    if not isinstance(value, str):
        raise InvalidInputError(f"a waypoint name must be a string, got {value!r}")
    return value


def check_geometry(geometry: object) -> ArmGeometry:
    """``geometry`` if it is an :class:`~lynxsim.arm.ArmGeometry`, else raise InvalidInputError."""
    return instance(geometry, ArmGeometry, "geometry")


@dataclass(frozen=True)
class ArmPose:
    """A task pose of the arm's tool, solved by the analytic IK.

    Attributes:
        position: Tool point in the base frame, (x, y, z) [m].
        pitch: Tool pitch above the horizontal [rad] (see :func:`lynxsim.arm.ik`).
        roll: Wrist roll ``q5`` [rad]; ``None`` keeps the previous pose's roll
            (0 for the first pose).
        name: Label used in messages and plots (default ``P1``, ``P2``, ...).

    Raises:
        InvalidInputError: A value is not a real number, the position has not
            three of them or a coordinate exceeds
            :data:`~lynxsim.bounds.MAX_COORDINATE_M`, or the name is not a string.
        NonFiniteInputError: A value is NaN or infinite.
    """

    position: tuple[float, float, float]
    pitch: float
    roll: float | None = None
    name: str = ""

    def __post_init__(self) -> None:
        position = _floats(self.position, 3, "pose position")
        if max(abs(v) for v in position) > MAX_COORDINATE_M:
            raise InvalidInputError(
                f"pose position coordinates must be within ±{MAX_COORDINATE_M:g} m "
                f"(the arm reaches under 1 m), got {position} m"
            )
        object.__setattr__(self, "position", position)
        object.__setattr__(self, "pitch", _angle(self.pitch, "pose pitch"))
        if self.roll is not None:
            object.__setattr__(self, "roll", _angle(self.roll, "pose roll"))
        _name(self.name)

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
        _name(self.name)


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

    def __post_init__(self) -> None:
        q = np.array(finite_array(self.q, "waypoint joints"))  # a copy: frozen below
        if q.ndim != 2 or q.shape[1] != 5 or q.shape[0] < 2:
            raise InvalidInputError(
                f"waypoint joints must have shape (N, 5), N >= 2, got {q.shape}"
            )
        poses = self.poses
        if not (
            isinstance(poses, tuple)
            and len(poses) == q.shape[0]
            and all(isinstance(p, ArmPose) for p in poses)
        ):
            raise InvalidInputError(f"poses must be a tuple of {q.shape[0]} ArmPose")
        q.setflags(write=False)
        object.__setattr__(self, "q", q)

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
        lo, hi = math.degrees(geometry.lower[j]), math.degrees(geometry.upper[j])
        raise JointRangeError(  # math.degrees: inf for a joint beyond 1e306 rad, no warning
            f"waypoint {name}: joint {j + 1} ({geometry.joint_names[j]}) = "
            f"{math.degrees(q[j]):.4g} deg is outside its range [{lo:.4g}, {hi:.4g}] deg "
            f"by {math.degrees(excess[j]):.4g} deg",
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


def _check_count(n: int) -> None:
    if not 2 <= n <= MAX_WAYPOINTS:
        raise InvalidInputError(f"a trajectory needs 2 to {MAX_WAYPOINTS:,} waypoints, got {n:,}")


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
        InvalidInputError: Fewer than two or more than :data:`MAX_WAYPOINTS`
            waypoints, a wrong shape, values that are not real numbers, or a
            geometry that is not an :class:`~lynxsim.arm.ArmGeometry`.
        NonFiniteInputError: A value is NaN or infinite.
    """
    geometry = check_geometry(geometry)
    items: list[ArmPose | JointPose]
    if (
        isinstance(waypoints, Sequence)
        and not isinstance(waypoints, str | bytes)
        and all(isinstance(w, ArmPose | JointPose) for w in waypoints)
    ):
        items = [w for w in waypoints if isinstance(w, ArmPose | JointPose)]
    else:
        try:
            arr = real_array(waypoints, "joint waypoints")
        except InvalidInputError as exc:  # keeps its class (InvalidTypeError for a wrong type)
            raise type(exc)(
                f"waypoints must be ArmPose/JointPose objects or joints of shape (N, 5): {exc}"
            ) from None
        if arr.ndim != 2 or arr.shape[1] != 5:
            raise InvalidInputError(f"joint waypoints must have shape (N, 5), got {arr.shape}")
        _check_count(arr.shape[0])
        if not np.isfinite(arr).all():
            raise NonFiniteInputError("joint waypoints must be finite")
        items = [JointPose(tuple(row)) for row in arr]
    _check_count(len(items))
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
