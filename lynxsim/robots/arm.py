"""The arm's record: its task's motions (every trajectory type), planning, simulation, real arm."""

from __future__ import annotations

from lynxsim.arm.motion import ARM_KINEMATICS, ARM_LIMITS
from lynxsim.arm.motion import build_trajectory as build_from_poses
from lynxsim.arm.motion.planning import arm_plan_request
from lynxsim.errors import InvalidInputError
from lynxsim.inputs import instance
from lynxsim.plan.request import PlanRequest
from lynxsim.poses import ArmPose, JointPose
from lynxsim.registry import info
from lynxsim.robots.catalog import register
from lynxsim.robots.robot import Robot
from lynxsim.run_options import NO_OBSTACLE
from lynxsim.tasks import Task
from lynxsim.traj.build import parse_kind
from lynxsim.traj.kinds import TrajectoryKind
from lynxsim.traj.limits import JointLimits
from lynxsim.traj.trajectory import Trajectory

__all__ = ["ROBOT", "build_trajectory", "plan_request"]


def _arm_poses(task: Task, what: str) -> tuple[ArmPose | JointPose, ...]:
    task = instance(task, Task, "task")
    poses = tuple(p for p in task.poses if isinstance(p, ArmPose | JointPose))
    if len(poses) != len(task.poses):
        raise InvalidInputError(f"task {task.name!r} is for robot {task.robot!r}; {what}")
    return poses


def build_trajectory(
    task: Task,
    kind: TrajectoryKind | str | None = None,
    limits: JointLimits | None = None,
) -> Trajectory:
    """The trajectory of a task, of its own type or another (every type but ``planned``).

    Args:
        task: The task (see :func:`lynxsim.tasks.load_task`).
        kind: Trajectory type overriding the task's; ``None`` keeps it.
        limits: Joint limits; ``None`` for :data:`~lynxsim.arm.motion.ARM_LIMITS`.

    Returns:
        The checked :class:`~lynxsim.traj.Trajectory`, with the task's poses as its targets.

    Raises:
        InvalidInputError: The task is not for the arm, or the type is unknown.
        LynxsimError: Whatever the generator raises (unreachable pose, limits).
    """
    poses = _arm_poses(task, "joint trajectories are built from arm poses only")
    return build_from_poses(
        poses,
        task.trajectory if kind is None else parse_kind(kind),
        task.durations,
        limits=ARM_LIMITS if limits is None else limits,
        stretch=task.stretch,
        pass_through=task.pass_through,
    )


def plan_request(task: Task) -> PlanRequest:
    """The planning problem of an arm task (:func:`lynxsim.arm.motion.planning.arm_plan_request`).

    With a cube in the scene the cube is held on every segment (the playback
    grips before the motion and releases after it).

    Raises:
        InvalidInputError: Not an arm task.
        UnreachablePoseError: A pose has no IK solution.
    """
    poses = _arm_poses(task, "not the arm")
    return arm_plan_request(poses, grasped=task.scene.cube is not None)


ROBOT = register(
    Robot(
        info=info("arm"),
        kinds=tuple(TrajectoryKind),
        motion=build_trajectory,
        sim="lynxsim.sim.arm.adapter:ADAPTER",
        cameras=("front", "top"),
        run_options=(NO_OBSTACLE,),
        kinematics=ARM_KINEMATICS,
        planning=plan_request,
        real="lynxsim.sim.arm.ssc32:BACKEND",
    )
)
"""The arm's record (its row: :mod:`lynxsim.registry`)."""
