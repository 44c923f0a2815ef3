"""The planar arm's record, registered with lynxsim when this module is imported.

Its tasks give joint poses (``q_deg``, three angles: the ``"joints"`` pose
schema); it builds every joint-space trajectory type (no straight tool line:
it has no inverse kinematics) and plans around the table scene's obstacles.
"""

from __future__ import annotations

import itertools

import numpy as np

from lynxsim.errors import InvalidInputError
from lynxsim.plan import PlanRequest
from lynxsim.poses import JointPose
from lynxsim.registry import RobotInfo
from lynxsim.robots import Robot, register
from lynxsim.run_options import NO_OBSTACLE
from lynxsim.tasks import Task
from lynxsim.traj import Trajectory, TrajectoryKind, Waypoints, generate
from planar_arm.kinematics import BOUNDS, KINEMATICS, LIMITS, lipschitz

__all__ = ["KINDS", "ROBOT", "motion", "planning"]

KINDS = (
    TrajectoryKind.FREE,
    TrajectoryKind.CUBIC,
    TrajectoryKind.QUINTIC,
    TrajectoryKind.LSPB,
    TrajectoryKind.RUCKIG,
    TrajectoryKind.PLANNED,
)
"""The trajectory types it builds (``planned`` through lynxsim's planner)."""


def _waypoints(task: Task) -> Waypoints:
    poses = [p for p in task.poses if isinstance(p, JointPose)]
    if len(poses) != len(task.poses):
        raise InvalidInputError(f"task {task.name!r}: the planar arm takes joint poses only")
    return Waypoints(np.array([p.q for p in poses]), tuple(p.name for p in poses))


def motion(task: Task, kind: TrajectoryKind) -> Trajectory:
    """A task's joint trajectory of a type (every type of :data:`KINDS` but ``planned``).

    Raises:
        InvalidInputError: A type it does not build, or a pose that is not a joint pose.
    """
    if kind not in KINDS or kind is TrajectoryKind.PLANNED:
        built = ", ".join(k.value for k in KINDS if k is not TrajectoryKind.PLANNED)
        raise InvalidInputError(
            f"trajectory type {kind.value!r} is not built for the planar arm; expected one "
            f"of: {built} (planned: lynxsim.robots.plan)"
        )
    return generate(
        kind,
        _waypoints(task),
        task.durations,
        bounds=BOUNDS,
        limits=LIMITS,
        stretch=task.stretch,
        pass_through=task.pass_through,
    )


def planning(task: Task) -> PlanRequest:
    """A task's planning problem: from its first pose through each next one (one goal each)."""
    waypoints = _waypoints(task)
    q, names = waypoints.q, waypoints.names
    return PlanRequest(
        start=q[0],
        goal_sets=tuple(q[i][None] for i in range(1, len(q))),
        grasped=(False,) * (len(q) - 1),
        labels=tuple(f"{a} -> {b}" for a, b in itertools.pairwise(names)),
        pose_names=names,
        bounds=BOUNDS,
        limits=LIMITS,
        lipschitz=lipschitz(),
    )


ROBOT = register(
    Robot(
        info=RobotInfo(
            name="planar_arm",
            title="planar three-link arm",
            poses="joints",
            scene=True,
            entry="planar_arm.robot:ROBOT",
            joints=3,
        ),
        kinds=KINDS,
        motion=motion,
        sim="planar_arm.sim:ADAPTER",
        cameras=("front", "top"),
        run_options=(NO_OBSTACLE,),
        kinematics=KINEMATICS,
        planning=planning,
    )
)
"""The planar arm's record."""
