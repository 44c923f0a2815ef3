"""Collision-free joint motion planning: pure numpy and OMPL, no MuJoCo.

The planner asks a :class:`ClearanceOracle` for clearances of batches of joint
vectors (the simulation layer adapts its collision checker to it; tests use fake
worlds), certifies straight edges clear with a Lipschitz bound
(:mod:`lynxsim.plan.edges`), searches with OMPL (:func:`plan_segment`),
shortens, and times the result with Ruckig into an ordinary
:class:`~lynxsim.traj.Trajectory`, checked clear again (:func:`plan_through`)::

    motion = plan_through([q_pick, q_place], q_home, oracle, [False, True],
                          bounds.lower, bounds.upper, lipschitz=L, bounds=bounds,
                          limits=limits, seed=0)
    q, qd, qdd, qddd = motion.trajectory.sample(t)
"""

from lynxsim.plan.chain import PlannedMotion, plan_through, segment_seed
from lynxsim.plan.edges import EdgeCheck, check_edges, check_path
from lynxsim.plan.errors import (
    GoalsInCollisionError,
    LocalMinimumError,
    NoPathError,
    PlanningError,
    StartInCollisionError,
    TimingClearanceError,
    UnknownPlannerError,
)
from lynxsim.plan.ompl_planners import PLANNERS, PlannerName
from lynxsim.plan.oracle import ClearanceOracle
from lynxsim.plan.potential import potential_field_segment
from lynxsim.plan.progress import PlanProgress, ProgressCallback
from lynxsim.plan.request import DEFAULT_MARGIN_M, PlanRequest
from lynxsim.plan.segment import SegmentPlan, plan_segment
from lynxsim.plan.shortcut import path_length, shorten_path
from lynxsim.plan.timing import TimedMotion, TimedSegment, time_paths

__all__ = [
    "DEFAULT_MARGIN_M",
    "PLANNERS",
    "ClearanceOracle",
    "EdgeCheck",
    "GoalsInCollisionError",
    "LocalMinimumError",
    "NoPathError",
    "PlanProgress",
    "PlanRequest",
    "PlannedMotion",
    "PlannerName",
    "PlanningError",
    "ProgressCallback",
    "SegmentPlan",
    "StartInCollisionError",
    "TimedMotion",
    "TimedSegment",
    "TimingClearanceError",
    "UnknownPlannerError",
    "check_edges",
    "check_path",
    "path_length",
    "plan_segment",
    "plan_through",
    "potential_field_segment",
    "segment_seed",
    "shorten_path",
    "time_paths",
]
