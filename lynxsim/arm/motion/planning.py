"""The arm's planning problem of its task poses: start, goal sets, joints, limits, bound.

Pure (no MuJoCo): the start is the first pose's IK solution (the one every
other trajectory type starts from); every later pose is a set of goals, all its
valid IK branches (the planner picks); a joint-space pose is its one goal. The
simulation layer plans it around a scene (:func:`lynxsim.sim.planning.plan_request`).
"""

from __future__ import annotations

import itertools
from collections.abc import Sequence

import numpy as np
import numpy.typing as npt

from lynxsim.arm.geometry import LYNX_ARM
from lynxsim.arm.ik import ik
from lynxsim.arm.motion.lipschitz import arm_lipschitz
from lynxsim.arm.motion.space import ARM_BOUNDS, ARM_LIMITS
from lynxsim.arm.motion.waypoints import resolve_waypoints
from lynxsim.errors import InvalidInputError
from lynxsim.inputs import flag
from lynxsim.plan.request import PlanRequest
from lynxsim.poses import ArmPose, JointPose

__all__ = ["arm_plan_request"]

FloatArray = npt.NDArray[np.float64]


def _goals(pose: ArmPose, resolved: FloatArray) -> FloatArray:
    """Every valid IK branch of a pose, (K, 5) [rad], clipped into the joint ranges.

    ``resolved`` is the pose's joints as every other trajectory type reaches it
    (its roll fills in a pose without one); joint-space poses have that one goal.
    """
    result = ik(np.asarray(pose.position, dtype=float), pose.pitch, float(resolved[4]))
    branches = result.candidates[result.valid] if result.ok else resolved[None]
    if not np.any(np.all(np.isclose(branches, resolved, atol=1e-9), axis=1)):
        branches = np.vstack([resolved[None], branches])
    clipped: FloatArray = np.clip(branches, LYNX_ARM.q_min, LYNX_ARM.q_max)
    return clipped


def arm_plan_request(poses: Sequence[ArmPose | JointPose], *, grasped: bool) -> PlanRequest:
    """The planning problem of the arm's poses, in order.

    Args:
        poses: At least two tool or joint poses.
        grasped: Whether the cube is held on every segment (a scene with a cube:
            the playback grips before the motion and releases after it).

    Returns:
        The :class:`~lynxsim.plan.PlanRequest` (the arm's bounds, servo limits and
        :func:`~lynxsim.arm.motion.arm_lipschitz`).

    Raises:
        InvalidInputError: A pose is not the arm's.
        UnreachablePoseError: A pose has no IK solution.
    """
    poses = list(poses)
    if not all(isinstance(p, ArmPose | JointPose) for p in poses):
        raise InvalidInputError("the arm plans tool or joint poses only")
    grasped = flag(grasped, "grasped")
    waypoints = resolve_waypoints(poses)
    names = [p.name for p in waypoints.poses]
    start = np.clip(waypoints.q[0], LYNX_ARM.q_min, LYNX_ARM.q_max)
    goal_sets = [
        waypoints.q[i][None]
        if isinstance(pose, JointPose)
        else _goals(waypoints.poses[i], waypoints.q[i])
        for i, pose in enumerate(poses)
        if i > 0
    ]
    return PlanRequest(
        start=start,
        goal_sets=tuple(goal_sets),
        grasped=(grasped,) * len(goal_sets),
        labels=tuple(f"{a} -> {b}" for a, b in itertools.pairwise(names)),
        pose_names=tuple(names),
        bounds=ARM_BOUNDS,
        limits=ARM_LIMITS,
        lipschitz=arm_lipschitz(),
    )
