"""Planning an arm task around its scene (the arm's side of :mod:`lynxsim.sim.planning`).

The task's poses become the arm's planning problem
(:func:`lynxsim.arm.motion.planning.arm_plan_request`: every valid IK branch of
a pose is a goal; the planner picks); the arm's scene answers the clearance
questions (:func:`~lynxsim.sim.arm.playback.arm_checker`); the result is an
ordinary :class:`~lynxsim.traj.Trajectory` of kind ``planned``::

    motion = plan_task(load_task("tasks/obstacle_avoidance.toml"), seed=0)
    playback = run_arm_trajectory(motion.trajectory, task="...", scene=task.scene)

With a cube in the scene the cube is held on every segment (the playback grips
before the motion and releases after it), so it counts as part of the robot.
"""

from __future__ import annotations

from lynxsim.arm.motion import build_trajectory
from lynxsim.arm.motion.planning import arm_plan_request
from lynxsim.errors import InvalidInputError
from lynxsim.plan import PlannedMotion, PlannerName, ProgressCallback
from lynxsim.poses import ArmPose, JointPose
from lynxsim.sim.arm.model import load_arm_scene
from lynxsim.sim.arm.playback import arm_checker
from lynxsim.sim.planning import DEFAULT_MARGIN_M, plan_request
from lynxsim.tasks import Task
from lynxsim.traj import Trajectory, TrajectoryKind
from lynxsim.traj.build import parse_kind

__all__ = ["plan_task", "task_trajectory"]


def plan_task(
    task: Task,
    *,
    planner: PlannerName = "RRTConnect",
    margin_m: float = DEFAULT_MARGIN_M,
    seed: int = 0,
    time_limit_s: float = 5.0,
    progress: ProgressCallback | None = None,
) -> PlannedMotion:
    """Plan an arm task's poses in order around its scene's obstacles.

    The start is the first pose's IK solution (the one every other trajectory
    type starts from); every later pose is a set of goals, all its valid IK
    branches. The task's segment durations do not apply: the motion is timed
    time-optimally within the servo limits (Ruckig).

    Args:
        task: An arm task (its scene gives the obstacles and the cube).
        planner: OMPL planner (:data:`lynxsim.plan.PLANNERS`).
        margin_m: Clearance to keep from every obstacle [m].
        seed: Same task and seed give the same trajectory, bit for bit.
        time_limit_s: Search time per segment [s].
        progress: Called as each segment's stages begin.

    Returns:
        The :class:`~lynxsim.plan.PlannedMotion`; its trajectory's kind is ``planned``.

    Raises:
        InvalidInputError: Not an arm task.
        UnreachablePoseError: A pose has no IK solution.
        PlanningError: No clear path (names the segment and why).
    """
    poses = [p for p in task.poses if isinstance(p, ArmPose | JointPose)]
    if len(poses) != len(task.poses):
        raise InvalidInputError(f"task {task.name!r} is for robot {task.robot!r}, not the arm")
    return plan_request(
        arm_plan_request(poses, grasped=task.scene.cube is not None),
        arm_checker(load_arm_scene(task.scene)),
        planner=planner,
        margin_m=margin_m,
        seed=seed,
        time_limit_s=time_limit_s,
        progress=progress,
    )


def task_trajectory(task: Task, kind: TrajectoryKind | str | None = None) -> Trajectory:
    """An arm task's trajectory of any type, ``planned`` included (seed 0, default planner).

    The other types come from :func:`lynxsim.arm.motion.build_trajectory` (pure);
    ``planned`` needs the scene's collision checker, so it is built here.
    """
    chosen = task.trajectory if kind is None else parse_kind(kind)
    if chosen is TrajectoryKind.PLANNED:
        return plan_task(task).trajectory
    return build_trajectory(
        task.poses,
        chosen,
        task.durations,
        stretch=task.stretch,
        pass_through=task.pass_through,
    )
