"""Planning a task's motion: segments chained end to start, then timed as one trajectory.

A task is a list of segments (approach, carry, retreat, ...), each with its goal
candidates and whether the payload is held. Each segment starts where the
previous one ended; the robot stops at the end of every segment.
"""

from __future__ import annotations

import time
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from lynxsim.errors import InvalidInputError
from lynxsim.plan.ompl_planners import MAX_SEED, PlannerName
from lynxsim.plan.oracle import ClearanceOracle
from lynxsim.plan.problem import make_problem
from lynxsim.plan.progress import PlanProgress, ProgressCallback
from lynxsim.plan.segment import DEFAULT_SHORTCUTS, SegmentPlan, check_search, plan_problem
from lynxsim.plan.timing import DEFAULT_MAX_REPAIRS, TimedSegment, time_paths
from lynxsim.traj.kinds import TrajectoryKind
from lynxsim.traj.limits import JointBounds, JointLimits
from lynxsim.traj.trajectory import Trajectory

__all__ = ["PlannedMotion", "plan_through", "segment_seed"]


@dataclass(frozen=True)
class PlannedMotion:
    """A task's planned and timed motion.

    Attributes:
        trajectory: The timed motion through every segment, stopping at each
            segment's end.
        segments: How each segment's path was planned (time, length, clearance).
        timing: How each segment was timed (start and end times, clearance of
            the timed motion).
        planning_time_s: Wall-clock time of the whole run [s].
    """

    trajectory: Trajectory
    segments: tuple[SegmentPlan, ...]
    timing: tuple[TimedSegment, ...]
    planning_time_s: float


def segment_seed(seed: int, index: int) -> int:
    """The seed of segment ``index`` of a run seeded with ``seed`` (independent streams)."""
    state = np.random.SeedSequence([seed, index]).generate_state(1, dtype=np.uint64)[0]
    return int(state % np.uint64(MAX_SEED + 1))


def plan_through(
    goal_sets: Sequence[npt.ArrayLike],
    start: npt.ArrayLike,
    oracle: ClearanceOracle,
    grasped_per_segment: Sequence[bool],
    lower: npt.ArrayLike,
    upper: npt.ArrayLike,
    *,
    lipschitz: float,
    margin_m: float = 0.01,
    planner: PlannerName = "RRTConnect",
    time_limit_s: float = 5.0,
    seed: int = 0,
    shortcuts: int = DEFAULT_SHORTCUTS,
    labels: Sequence[str] | None = None,
    bounds: JointBounds,
    limits: JointLimits,
    kind: TrajectoryKind = TrajectoryKind.RUCKIG,
    max_repairs: int = DEFAULT_MAX_REPAIRS,
    progress: ProgressCallback | None = None,
    pose_names: Sequence[str] | None = None,
    search_oracle: ClearanceOracle | None = None,
) -> PlannedMotion:
    """Plan every segment of a task in turn, then time the whole motion.

    Segment ``i`` starts where segment ``i - 1`` ended (at the goal candidate its
    planner reached) and is planned by :func:`~lynxsim.plan.segment.plan_segment`
    with seed :func:`segment_seed` ``(seed, i)``. The paths are then timed by
    :func:`~lynxsim.plan.timing.time_paths` (Ruckig, stopping at segment ends).

    Args:
        goal_sets: Goal candidates of each segment, each (K_i, n) [rad].
        start: The robot's start, shape (n,) [rad].
        oracle: The world.
        grasped_per_segment: Whether the payload is held on each segment.
        lower: Lower joint bounds of the search, shape (n,) [rad].
        upper: Upper joint bounds of the search, shape (n,) [rad].
        lipschitz: ``L`` [m/rad]: no point of the robot moves more than
            ``L ||dq||_2`` (the arm's: :func:`lynxsim.arm.motion.arm_lipschitz`).
        margin_m: Clearance margin [m].
        planner: Planner of every segment (``compiled`` needs a cover as ``search_oracle``).
        time_limit_s: Search time limit per segment [s].
        seed: Seeds the run; same inputs and seed give the same trajectory.
        shortcuts: Shortcut attempts per segment.
        labels: Segment names for errors and progress (default "1", "2", ...).
        bounds: The joints (n) and the ranges of the timed trajectory.
        limits: Joint limits of the timing (n joints).
        kind: Trajectory kind of the result.
        max_repairs: Timing repair rounds.
        progress: Called as each segment's planning, shortening and end begin,
            when timing starts and when all is done.
        pose_names: Names of the start and the goals, for the trajectory's
            waypoints (see :func:`~lynxsim.plan.timing.time_paths`).
        search_oracle: The world the searches run in (a robot's sphere cover,
            never more optimistic than ``oracle``); default ``oracle``. Start
            and goals, and the timed motion, are checked in ``oracle``.

    Returns:
        The :class:`PlannedMotion`.

    Raises:
        StartInCollisionError, GoalsInCollisionError, NoPathError: As
            :func:`~lynxsim.plan.segment.plan_segment`, naming the segment.
        TimingClearanceError: The timed motion cannot be kept clear.
        PlanningError: No segment moves.
        InvalidInputError: Malformed arguments.
    """
    started = time.perf_counter()
    count = len(goal_sets)
    if count < 1:
        raise InvalidInputError("goal_sets must hold at least one segment's goals")
    if len(grasped_per_segment) != count:
        raise InvalidInputError(
            f"{count} segments need {count} grasped flags, got {len(grasped_per_segment)}"
        )
    names = tuple(labels) if labels is not None else tuple(str(i + 1) for i in range(count))
    if len(names) != count:
        raise InvalidInputError(f"{count} segments need {count} labels, got {len(names)}")
    name, limit, seed, shortcuts = check_search(planner, time_limit_s, seed, shortcuts)
    plans: list[SegmentPlan] = []
    here = start
    for i, goals in enumerate(goal_sets):
        problem = make_problem(
            here,
            goals,
            oracle,
            lower,
            upper,
            lipschitz=lipschitz,
            margin_m=margin_m,
            grasped=grasped_per_segment[i],
            label=names[i],
        )
        plan = plan_problem(
            problem,
            oracle,
            name,
            limit,
            segment_seed(seed, i),
            shortcuts,
            progress,
            started,
            i,
            count,
            search_oracle,
        )
        plans.append(plan)
        here = plan.path[-1]
    if progress is not None:
        progress(PlanProgress(count, count, "", "timing", time.perf_counter() - started))
    timed = time_paths(
        [p.path for p in plans],
        [p.grasped for p in plans],
        oracle,
        lipschitz=problem.lipschitz,
        margin_m=problem.margin_m,
        bounds=bounds,
        limits=limits,
        kind=kind,
        labels=names,
        max_repairs=max_repairs,
        pose_names=pose_names,
        screen=search_oracle,
    )
    if progress is not None:
        progress(PlanProgress(count, count, "", "done", time.perf_counter() - started))
    return PlannedMotion(
        trajectory=timed.trajectory,
        segments=tuple(plans),
        timing=timed.segments,
        planning_time_s=time.perf_counter() - started,
    )
