"""Planning any robot's task around its scene: a collision checker as the planner's world.

:mod:`lynxsim.plan` is pure; here a robot's MuJoCo scene answers its clearance
questions (:class:`CheckerOracle`), and :func:`plan_request` plans a robot's
:class:`~lynxsim.plan.PlanRequest` (its start, goal sets, joints, limits and
Lipschitz bound) in that world into an ordinary
:class:`~lynxsim.traj.Trajectory` of kind ``planned``. The robot gives the
request (:attr:`lynxsim.robots.Robot.planning`) and the checker (its
:meth:`~lynxsim.sim.adapter.SimAdapter.checker`); :func:`lynxsim.robots.plan`
puts them together.
"""

from __future__ import annotations

from typing import Literal

import numpy as np
import numpy.typing as npt

from lynxsim.errors import InvalidInputError
from lynxsim.inputs import instance
from lynxsim.plan import PlannedMotion, PlannerName, ProgressCallback, plan_through
from lynxsim.plan.cover import CoverOracle
from lynxsim.plan.ompl_planners import COMPILED
from lynxsim.plan.request import DEFAULT_MARGIN_M, PlanRequest
from lynxsim.sim.collision import CollisionChecker
from lynxsim.sim.cover import cover_world
from lynxsim.traj import TrajectoryKind

__all__ = [
    "DEFAULT_MARGIN_M",
    "PLANNING_CAP_M",
    "SEARCH_WORLDS",
    "CheckerOracle",
    "SearchWorld",
    "cover_oracle",
    "plan_request",
]

SearchWorld = Literal["cover", "exact"]
"""Where the search runs: the robot's sphere cover, or the exact checker."""

SEARCH_WORLDS: tuple[str, ...] = ("cover", "exact")
"""The search worlds, by name."""

FloatArray = npt.NDArray[np.float64]

PLANNING_CAP_M = 0.15
"""Clearance cap of the planner's world [m] (see :class:`CheckerOracle`)."""


class CheckerOracle:
    """A :class:`~lynxsim.sim.collision.CollisionChecker` as the planner's world.

    The clearance of a joint vector is its smallest distance to any obstacle
    [m]; an obstacle, self or table hit reads as ``-inf`` (the table is no
    obstacle for the verdicts of a run, but a plan that touches it is no plan).

    Args:
        checker: The robot's checker (:meth:`lynxsim.sim.adapter.SimAdapter.checker`).
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


def cover_oracle(checker: CollisionChecker, cap_m: float = PLANNING_CAP_M) -> CoverOracle | None:
    """The sphere cover of the checker's robot in its world, or None if the model has none.

    A robot whose colliding geoms, obstacles or supports are not primitives a
    cover handles (or whose joints are not hinges and slides) has no cover;
    its searches run on the exact checker.
    """
    try:
        world, _ = cover_world(checker, cap_m=cap_m)
    except InvalidInputError:
        return None
    return CoverOracle(world)


def plan_request(
    request: PlanRequest,
    checker: CollisionChecker,
    *,
    planner: PlannerName = COMPILED,
    search_world: SearchWorld = "cover",
    margin_m: float = DEFAULT_MARGIN_M,
    seed: int = 0,
    time_limit_s: float = 5.0,
    progress: ProgressCallback | None = None,
) -> PlannedMotion:
    """Plan a robot's request around the world its checker sees.

    Each segment is planned from where the last one ended to one of its goals
    (:func:`lynxsim.plan.plan_through`); the whole motion is timed
    time-optimally within the request's limits (Ruckig) and checked clear on
    the exact checker. The search runs on the robot's sphere cover
    (:func:`cover_oracle`) unless ``search_world`` is ``"exact"`` or the robot
    has no cover (the ``compiled`` planner then gives way to OMPL's RRT-Connect).

    Args:
        request: The robot's planning problem.
        checker: Its collision checker of the task's scene.
        planner: ``compiled`` (default) or an OMPL planner (:data:`lynxsim.plan.PLANNERS`).
        search_world: ``cover`` (default) or ``exact``.
        margin_m: Clearance to keep from every obstacle [m].
        seed: Same request and seed give the same trajectory, bit for bit.
        time_limit_s: Search time per segment [s].
        progress: Called as each segment's stages begin.

    Returns:
        The :class:`~lynxsim.plan.PlannedMotion`; its trajectory's kind is ``planned``.

    Raises:
        InvalidInputError: The request and the checker disagree on the joints, or
            an unknown search world.
        PlanningError: No clear path (names the segment and why).
    """
    request = instance(request, PlanRequest, "request")
    checker = instance(checker, CollisionChecker, "checker")
    if checker.n_joints != request.n_joints:
        raise InvalidInputError(
            f"the request plans {request.n_joints} joints, the checker checks {checker.n_joints}"
        )
    if search_world not in SEARCH_WORLDS:
        raise InvalidInputError(
            f"search_world must be one of {', '.join(SEARCH_WORLDS)}, got {search_world!r}"
        )
    cover = cover_oracle(checker) if search_world == "cover" else None
    if cover is None and planner == COMPILED:
        planner = "RRTConnect"
    bounds = request.bounds
    return plan_through(
        list(request.goal_sets),
        request.start,
        CheckerOracle(checker),
        list(request.grasped),
        bounds.lower_array,
        bounds.upper_array,
        lipschitz=request.lipschitz,
        margin_m=margin_m,
        planner=planner,
        time_limit_s=time_limit_s,
        seed=seed,
        labels=list(request.labels),
        bounds=bounds,
        limits=request.limits,
        kind=TrajectoryKind.PLANNED,
        progress=progress,
        pose_names=list(request.pose_names),
        search_oracle=cover,
    )
