"""Planning an arm task around its scene: the collision checker as the planner's world.

:mod:`lynxsim.plan` is pure; here the arm's MuJoCo scene answers its clearance
questions (:class:`CheckerOracle`), the task's poses become goal sets (every
valid IK branch of a pose is a goal; the planner picks), and the result is an
ordinary :class:`~lynxsim.traj.Trajectory` of kind ``planned``::

    motion = plan_task(load_task("tasks/obstacle_avoidance.toml"), seed=0)
    playback = run_arm_trajectory(motion.trajectory, task="...", scene=task.scene)

With a cube in the scene the cube is held on every segment (the playback grips
before the motion and releases after it), so it counts as part of the robot.
"""

from __future__ import annotations

import itertools

import numpy as np
import numpy.typing as npt

from lynxsim.arm import LYNX_ARM, ik
from lynxsim.arm.motion import (
    ARM_BOUNDS,
    ARM_LIMITS,
    arm_lipschitz,
    build_trajectory,
    resolve_waypoints,
)
from lynxsim.errors import InvalidInputError
from lynxsim.plan import (
    PlannedMotion,
    PlannerName,
    ProgressCallback,
    plan_through,
)
from lynxsim.poses import ArmPose, JointPose
from lynxsim.sim.arm.model import load_arm_scene
from lynxsim.sim.arm.playback import arm_checker
from lynxsim.sim.collision import CollisionChecker
from lynxsim.tasks import Task
from lynxsim.traj import Trajectory, TrajectoryKind
from lynxsim.traj.build import parse_kind

__all__ = ["DEFAULT_MARGIN_M", "PLANNING_CAP_M", "CheckerOracle", "plan_task", "task_trajectory"]

FloatArray = npt.NDArray[np.float64]

DEFAULT_MARGIN_M = 0.01
"""Clearance every planned configuration keeps from every obstacle [m]."""
PLANNING_CAP_M = 0.15
"""Clearance cap of the planner's world [m] (see :class:`CheckerOracle`)."""


class CheckerOracle:
    """A :class:`~lynxsim.sim.collision.CollisionChecker` as the planner's world.

    The clearance of a joint vector is its smallest distance to any obstacle
    [m]; an obstacle, self or table hit reads as ``-inf`` (the table is no
    obstacle for the verdicts of a run, but a plan that touches it is no plan).

    Args:
        checker: The arm's checker (:func:`~lynxsim.sim.arm.playback.arm_checker`).
        cap_m: Clearances above this read as it [m]: the planner steps at most
            ``cap / L`` along an edge per check, and far geoms cost nothing.
    """

    def __init__(self, checker: CollisionChecker, cap_m: float = PLANNING_CAP_M) -> None:
        self._checker = checker
        self._cap = cap_m
        self.n_joints = checker.n_joints

    def clearance(self, q: FloatArray, *, grasped: bool) -> FloatArray:
        """Smallest clearance of each joint vector, (N, n) -> (N,) [m], at most the cap."""
        return self._checker.min_clearance(q, grasped=grasped, cap=self._cap)


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
    oracle = CheckerOracle(arm_checker(load_arm_scene(task.scene)))
    return plan_through(
        goal_sets,
        start,
        oracle,
        [task.scene.cube is not None] * len(goal_sets),
        LYNX_ARM.q_min,
        LYNX_ARM.q_max,
        lipschitz=arm_lipschitz(),
        margin_m=margin_m,
        planner=planner,
        time_limit_s=time_limit_s,
        seed=seed,
        labels=[f"{a} -> {b}" for a, b in itertools.pairwise(names)],
        bounds=ARM_BOUNDS,
        limits=ARM_LIMITS,
        kind=TrajectoryKind.PLANNED,
        progress=progress,
        pose_names=names,
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
