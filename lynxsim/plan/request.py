"""What a robot asks the planner for a task: start, goal sets, segments, joints, limits, bound.

A robot that plans (:attr:`lynxsim.robots.Robot.planning`) turns a task into a
:class:`PlanRequest`, pure (no MuJoCo): where it starts, the goal candidates of
each segment (every joint vector that reaches the segment's pose), whether the
payload is held on each, the names of segments and poses, its joints and
limits, and its Lipschitz bound. The simulation layer adds the world (a
collision checker) and plans it (:func:`lynxsim.sim.planning.plan_request`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from lynxsim.errors import InvalidInputError, InvalidTypeError, short
from lynxsim.inputs import instance, real_array, real_number
from lynxsim.traj.limits import JointBounds, JointLimits

__all__ = ["DEFAULT_MARGIN_M", "PlanRequest"]

FloatArray = npt.NDArray[np.float64]

DEFAULT_MARGIN_M = 0.01
"""Clearance every planned configuration keeps from every obstacle, by default [m]."""


@dataclass(frozen=True, eq=False)
class PlanRequest:
    """A task's planning problem, without the world.

    Attributes:
        start: The robot's start, shape (n,) [rad], within ``bounds``.
        goal_sets: Goal candidates of each of the S segments, each (K_i, n) [rad].
        grasped: Whether the payload is held on each segment, (S,).
        labels: Name of each segment (errors, progress, ``lynxsim plan``'s table), (S,).
        pose_names: Names of the start and each segment's goal, (S + 1,).
        bounds: The joints (n): the search's box and the timed trajectory's ranges.
        limits: Joint limits of the timing (n joints).
        lipschitz: ``L`` [m/rad]: no point of the robot (or its held payload)
            moves more than ``L ||dq||_2`` for a joint step ``dq``.

    Raises:
        InvalidInputError: A shape, count or type disagrees, or a value is not finite.
    """

    start: FloatArray
    goal_sets: tuple[FloatArray, ...]
    grasped: tuple[bool, ...]
    labels: tuple[str, ...]
    pose_names: tuple[str, ...]
    bounds: JointBounds
    limits: JointLimits
    lipschitz: float

    def __post_init__(self) -> None:
        bounds = instance(self.bounds, JointBounds, "bounds")
        instance(self.limits, JointLimits, "limits")
        n = bounds.n_joints
        if self.limits.n_joints != n:
            raise InvalidInputError(f"limits of {self.limits.n_joints} joints for {n} joints")
        for name in ("goal_sets", "grasped", "labels", "pose_names"):
            value = getattr(self, name)
            if not isinstance(value, tuple | list):
                raise InvalidTypeError(f"{name} must be a tuple, got {short(value)}")
        start = np.array(real_array(self.start, "start"))  # a copy, made read-only below
        if start.shape != (n,) or not np.isfinite(start).all():
            raise InvalidInputError(f"start must be {n} finite joint angles, got {start!r}")
        goals = []
        for i, g in enumerate(self.goal_sets):
            arr = np.array(real_array(g, f"goal set {i + 1}"))
            if arr.ndim != 2 or arr.shape[1] != n or len(arr) == 0 or not np.isfinite(arr).all():
                raise InvalidInputError(
                    f"goal set {i + 1} must be K >= 1 finite joint vectors of {n} joints, "
                    f"got shape {arr.shape}"
                )
            goals.append(arr)
        segments = len(goals)
        if segments == 0:
            raise InvalidInputError("a plan needs at least one segment")
        if len(self.grasped) != segments or not all(isinstance(g, bool) for g in self.grasped):
            raise InvalidInputError(f"grasped must be {segments} bools, got {self.grasped!r}")
        if len(self.labels) != segments or not all(isinstance(s, str) for s in self.labels):
            raise InvalidInputError(f"labels must be {segments} strings, got {self.labels!r}")
        if len(self.pose_names) != segments + 1 or not all(
            isinstance(s, str) for s in self.pose_names
        ):
            raise InvalidInputError(
                f"pose_names must be {segments + 1} strings, got {self.pose_names!r}"
            )
        lipschitz = real_number(self.lipschitz, "lipschitz")
        if not (math.isfinite(lipschitz) and lipschitz > 0.0):
            raise InvalidInputError(f"lipschitz must be positive and finite, got {lipschitz!r}")
        start.setflags(write=False)
        for arr in goals:
            arr.setflags(write=False)
        object.__setattr__(self, "start", start)
        object.__setattr__(self, "goal_sets", tuple(goals))
        object.__setattr__(self, "grasped", tuple(self.grasped))
        object.__setattr__(self, "labels", tuple(self.labels))
        object.__setattr__(self, "pose_names", tuple(self.pose_names))
        object.__setattr__(self, "lipschitz", float(lipschitz))

    @property
    def n_joints(self) -> int:
        """The number of joints n."""
        return self.bounds.n_joints
