"""Planning one segment: a planner finds a clear path, shortcuts shorten it, a check verifies it.

The planner works in a joint box with a :class:`~lynxsim.plan.oracle.ClearanceOracle`.
Every state it keeps has clearance ``>= margin`` and every edge it accepts is
certified by :func:`~lynxsim.plan.edges.check_edges` to keep ``>= margin / 2``.

The search may run in a second world, a robot's sphere cover
(:class:`~lynxsim.plan.cover.CoverOracle`), whose clearances are never above
the exact ones: a path certified on it is certified in the exact world. The
``compiled`` planner searches and shortens on the cover in one compiled call
(:func:`~lynxsim.plan.cover.search.search_cover`); where the cover is too
pessimistic for it (start or goals without the margin on the cover, or no path
within its sample budget), OMPL's RRT-Connect plans the segment in the exact
world instead. Start and goals are always checked in the exact world (its
errors are today's).
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from lynxsim.errors import InvalidInputError
from lynxsim.inputs import number_in_range
from lynxsim.plan.cover.oracle import CoverOracle
from lynxsim.plan.cover.search import DIRECT, FOUND
from lynxsim.plan.edges import check_edges, check_path
from lynxsim.plan.errors import NoPathError, PlanningError, clearance_text
from lynxsim.plan.ompl_planners import COMPILED, MAX_SEED, PlannerName, check_planner, solve
from lynxsim.plan.oracle import ClearanceOracle, FloatArray, query
from lynxsim.plan.problem import Problem, make_problem
from lynxsim.plan.progress import PlanProgress, ProgressCallback
from lynxsim.plan.shortcut import drop_duplicates, path_length, shorten_path

__all__ = [
    "DEFAULT_SHORTCUTS",
    "MAX_TIME_LIMIT_S",
    "SegmentPlan",
    "check_search",
    "check_seed",
    "finish_segment",
    "plan_problem",
    "plan_segment",
]

MAX_TIME_LIMIT_S = 3600.0
"""Longest time limit of one segment [s]."""

DEFAULT_SHORTCUTS = 30
"""Random shortcut attempts per segment [-] (after the vertices that can go are dropped)."""


@dataclass(frozen=True)
class SegmentPlan:
    """A clear joint path for one segment and how it was found.

    Attributes:
        path: Vertices from the start to the reached goal, shape (M, n) [rad],
            read-only; every edge certified clear (M = 1 when the start is a goal).
        goal_index: Which goal candidate the path reaches (index into the goals given).
        planner: The planner's name ("direct" when the straight edge to a goal was
            clear, "potential" for the potential field).
        grasped: Whether the payload was held.
        label: The segment's label ("" if none).
        planning_time_s: Wall-clock time to find, shorten and verify the path [s].
        raw_length_rad: Joint-space length before shortening [rad].
        length_rad: Joint-space length of ``path`` [rad].
        min_clearance_m: Smallest clearance at the points checked along ``path`` [m].
        clearance_bound_m: Certified lower bound of the clearance everywhere along
            ``path`` [m], ``>= margin / 2``.
        checks: Configurations the compiled search checked (0 for another planner).
        search_time_s: Time of the compiled search and shortening [s] (0 for another).
        search_cpu_s: Its CPU time [s] (0 for another planner).
    """

    path: FloatArray
    goal_index: int
    planner: str
    grasped: bool
    label: str
    planning_time_s: float
    raw_length_rad: float
    length_rad: float
    min_clearance_m: float
    clearance_bound_m: float
    checks: int = 0
    search_time_s: float = 0.0
    search_cpu_s: float = 0.0


def check_seed(seed: object) -> int:
    """``seed`` if it is an integer in ``[0, MAX_SEED]``, else raise InvalidInputError."""
    if (
        isinstance(seed, bool)
        or not isinstance(seed, int | np.integer)
        or not (0 <= int(seed) <= MAX_SEED)
    ):
        raise InvalidInputError(f"seed must be an integer in [0, {MAX_SEED}], got {seed!r}")
    return int(seed)


def check_search(
    planner: object, time_limit_s: object, seed: object, shortcuts: object
) -> tuple[PlannerName, float, int, int]:
    """Check the search settings of :func:`plan_segment`; return them typed.

    Raises:
        UnknownPlannerError: ``planner`` is not selectable.
        InvalidInputError: A time limit outside (0, 3600] s, a seed outside
            [0, MAX_SEED], or a negative or non-integer ``shortcuts``.
    """
    name = check_planner(planner)
    limit = number_in_range(time_limit_s, "time_limit_s", 0.0, MAX_TIME_LIMIT_S, "s")
    if limit <= 0.0:
        raise InvalidInputError(f"time_limit_s must be positive, got {limit!r}")
    if isinstance(shortcuts, bool) or not isinstance(shortcuts, int) or shortcuts < 0:
        raise InvalidInputError(f"shortcuts must be a non-negative integer, got {shortcuts!r}")
    return name, limit, check_seed(seed), shortcuts


def _report(progress: ProgressCallback | None, report: PlanProgress) -> None:
    if progress is not None:
        progress(report)


def finish_segment(
    problem: Problem,
    oracle: ClearanceOracle,
    raw: FloatArray,
    *,
    planner: str,
    started: float,
    rng: np.random.Generator,
    shortcuts: int,
    progress: ProgressCallback | None = None,
    index: int = 0,
    count: int = 1,
    segment_started: float | None = None,
) -> SegmentPlan:
    """Shorten a found path, verify it and return its :class:`SegmentPlan`.

    Args:
        problem: The problem solved.
        oracle: The world.
        raw: The path found, shape (M, n) [rad], from the start to a goal candidate.
        planner: Who found it.
        started: ``time.perf_counter()`` when the run began (progress reports) [s].
        rng: Draws the shortcuts.
        shortcuts: Shortcut attempts (0: keep the path as found).
        progress: Optional callback.
        index: The segment's index, for progress reports.
        count: Segments of the run, for progress reports.
        segment_started: ``time.perf_counter()`` when this segment began [s]
            (default ``started``): its planning time counts from there.

    Raises:
        PlanningError: The path fails its final verification (a bug, never expected).
    """
    p = problem
    goal_index = int(np.argmin(np.linalg.norm(p.goals - raw[-1], axis=1)))
    raw = np.array(raw, dtype=float)
    raw[0], raw[-1] = p.start, p.goals[goal_index]  # exact ends
    raw = drop_duplicates(raw)
    path = raw
    if shortcuts > 0 and raw.shape[0] > 2:
        _report(
            progress,
            PlanProgress(index, count, p.label, "shortening", time.perf_counter() - started),
        )
        path = shorten_path(
            raw,
            oracle,
            lipschitz=p.lipschitz,
            margin_m=p.margin_m,
            grasped=p.grasped,
            rng=rng,
            shortcuts=shortcuts,
        )
    verdict = check_path(
        path, oracle, lipschitz=p.lipschitz, margin_m=p.margin_m, grasped=p.grasped
    )
    if not verdict.clear.all():
        bad = int(np.flatnonzero(~verdict.clear)[0])
        raise PlanningError(
            f"internal error: edge {bad + 1} of the planned path failed its final check "
            f"(clearance {clearance_text(float(verdict.min_clearance_m[bad]))})",
            label=p.label,
        )
    path.setflags(write=False)
    return SegmentPlan(
        path=path,
        goal_index=goal_index,
        planner=planner,
        grasped=p.grasped,
        label=p.label,
        planning_time_s=time.perf_counter()
        - (started if segment_started is None else segment_started),
        raw_length_rad=path_length(raw),
        length_rad=path_length(path),
        min_clearance_m=float(verdict.min_clearance_m.min()),
        clearance_bound_m=float(verdict.bound_m.min()),
    )


def direct_goal(problem: Problem, oracle: ClearanceOracle) -> int | None:
    """The nearest valid goal reachable by one clear straight edge from the start, or None."""
    p = problem
    valid = p.valid_goals
    distance = np.linalg.norm(p.goals[valid] - p.start, axis=1)
    if (distance <= 0.0).any():
        return int(valid[np.argmin(distance)])
    starts = np.repeat(p.start[None], valid.size, axis=0)
    verdict = check_edges(
        starts,
        p.goals[valid],
        oracle,
        lipschitz=p.lipschitz,
        margin_m=p.margin_m,
        grasped=p.grasped,
        start_clearance_m=np.full(valid.size, p.start_clearance_m),
    )
    if not verdict.clear.any():
        return None
    candidates = np.flatnonzero(verdict.clear)
    return int(valid[candidates[np.argmin(distance[candidates])]])


def plan_segment(
    start: npt.ArrayLike,
    goals: npt.ArrayLike,
    oracle: ClearanceOracle,
    lower: npt.ArrayLike,
    upper: npt.ArrayLike,
    *,
    lipschitz: float,
    margin_m: float = 0.01,
    planner: PlannerName = "RRTConnect",
    time_limit_s: float = 5.0,
    seed: int = 0,
    grasped: bool = False,
    shortcuts: int = DEFAULT_SHORTCUTS,
    label: str = "",
    progress: ProgressCallback | None = None,
) -> SegmentPlan:
    """Plan a clear joint path from ``start`` to one of ``goals``.

    If the straight edge from the start to a goal candidate is clear, the nearest
    such goal is taken without asking OMPL (``planner`` reads "direct").
    Otherwise the OMPL planner searches, every valid candidate a goal state. The
    path is then shortened (seeded random shortcuts) and verified edge by edge.

    Args:
        start: Shape (n,) [rad].
        goals: Goal candidates, shape (K, n) [rad]; those with clearance below the
            margin are left out.
        oracle: The world.
        lower: Lower joint bounds, shape (n,) [rad].
        upper: Upper joint bounds, shape (n,) [rad].
        lipschitz: ``L`` [m/rad]: no point of the robot moves more than
            ``L ||dq||_2`` (for the arm: :func:`~lynxsim.arm.motion.arm_lipschitz`).
        margin_m: Clearance every checked point keeps [m]; the whole path keeps
            half of it.
        planner: One of :data:`~lynxsim.plan.ompl_planners.PLANNERS`.
        time_limit_s: Wall-clock limit of the search [s], (0, 3600].
        seed: Seeds OMPL and the shortcuts; same inputs and seed give the same
            path bit for bit (with planners that stop at their first solution).
        grasped: Whether the payload is held.
        shortcuts: Random shortcut attempts (0 keeps the path as found).
        label: Names the segment in errors and progress reports.
        progress: Called when shortening starts and when done.

    Returns:
        The :class:`SegmentPlan`.

    Raises:
        StartInCollisionError: The start has clearance below the margin.
        GoalsInCollisionError: Every goal candidate has clearance below the margin.
        NoPathError: No path within the time limit.
        UnknownPlannerError: ``planner`` is not a selectable planner (lists them).
        InvalidInputError: Malformed arguments.
    """
    started = time.perf_counter()
    name, limit, seed, shortcuts = check_search(planner, time_limit_s, seed, shortcuts)
    problem = make_problem(
        start,
        goals,
        oracle,
        lower,
        upper,
        lipschitz=lipschitz,
        margin_m=margin_m,
        grasped=grasped,
        label=label,
    )
    return plan_problem(problem, oracle, name, limit, seed, shortcuts, progress, started)


def plan_problem(
    problem: Problem,
    oracle: ClearanceOracle,
    planner: PlannerName,
    time_limit_s: float,
    seed: int,
    shortcuts: int,
    progress: ProgressCallback | None,
    started: float,
    index: int = 0,
    count: int = 1,
    search_oracle: ClearanceOracle | None = None,
) -> SegmentPlan:
    """Plan a checked problem with settings from :func:`check_search`; see :func:`plan_segment`.

    Args:
        problem: The problem.
        oracle: The world.
        planner: The OMPL planner.
        time_limit_s: Search time limit [s].
        seed: Seeds OMPL and the shortcuts.
        shortcuts: Shortcut attempts.
        progress: Optional callback.
        started: ``time.perf_counter()`` when the run began [s].
        index: The segment's index in the run, for progress reports.
        count: Segments of the run, for progress reports.
        search_oracle: The world the search runs in (default ``oracle``); the
            ``compiled`` planner needs a :class:`~lynxsim.plan.cover.CoverOracle`.

    Raises:
        InvalidInputError: The ``compiled`` planner without a cover.
    """
    p = problem
    segment_started = time.perf_counter()
    _report(progress, PlanProgress(index, count, p.label, "planning", segment_started - started))
    if planner == COMPILED:
        if not isinstance(search_oracle, CoverOracle):
            raise InvalidInputError("the compiled planner searches a cover: give a CoverOracle")
        plan = _compiled(p, search_oracle, seed, shortcuts, segment_started)
        if plan is not None:
            _report(
                progress,
                PlanProgress(index, count, p.label, "done", time.perf_counter() - started),
            )
            return plan
        planner, search_oracle = "RRTConnect", oracle  # the cover is too pessimistic here
    world = oracle if search_oracle is None else search_oracle
    rng = np.random.default_rng(seed)
    direct = direct_goal(p, world)
    if direct is not None:
        raw = np.array([p.start, p.goals[direct]])
        found = "direct"
    else:

        def state_ok(q: FloatArray) -> bool:
            return bool(query(world, q[None], p.grasped)[0] >= p.margin_m)

        def motion_ok(a: FloatArray, b: FloatArray) -> bool:
            verdict = check_edges(
                a[None],
                b[None],
                world,
                lipschitz=p.lipschitz,
                margin_m=p.margin_m,
                grasped=p.grasped,
            )
            return bool(verdict.clear[0])

        path = solve(
            p.start,
            p.goals[p.valid_goals],
            p.lower,
            p.upper,
            state_ok=state_ok,
            motion_ok=motion_ok,
            planner=planner,
            time_limit_s=time_limit_s,
            seed=seed,
        )
        if path is None:
            raise NoPathError(planner, time_limit_s, p.label)
        raw, found = path, planner
    plan = finish_segment(
        p,
        world,
        raw,
        planner=found,
        started=started,
        segment_started=segment_started,
        rng=rng,
        shortcuts=shortcuts,
        progress=progress,
        index=index,
        count=count,
    )
    _report(progress, PlanProgress(index, count, p.label, "done", time.perf_counter() - started))
    return plan


def _compiled(
    problem: Problem, cover: CoverOracle, seed: int, shortcuts: int, started: float
) -> SegmentPlan | None:
    """The compiled planner's segment on the cover, or None where the cover cannot plan it."""
    p = problem
    found = cover.search(
        p.start,
        p.goals[p.valid_goals],
        p.lower,
        p.upper,
        lipschitz=p.lipschitz,
        margin_m=p.margin_m,
        grasped=p.grasped,
        seed=seed,
        shortcuts=shortcuts,
    )
    if found.status not in (FOUND, DIRECT):
        return None
    path = np.array(found.path)
    goal_index = int(p.valid_goals[found.goal_index])
    path[0], path[-1] = p.start, p.goals[goal_index]  # exact ends (they are, bit for bit)
    verdict = check_path(path, cover, lipschitz=p.lipschitz, margin_m=p.margin_m, grasped=p.grasped)
    if not verdict.clear.all():
        bad = int(np.flatnonzero(~verdict.clear)[0])
        raise PlanningError(
            f"internal error: edge {bad + 1} of the compiled path failed its final check "
            f"(clearance {float(verdict.min_clearance_m[bad]):.4g} m)",
            label=p.label,
        )
    path.setflags(write=False)
    return SegmentPlan(
        path=path,
        goal_index=goal_index,
        planner="direct" if found.status == DIRECT else COMPILED,
        grasped=p.grasped,
        label=p.label,
        planning_time_s=time.perf_counter() - started,
        raw_length_rad=path_length(found.raw),
        length_rad=path_length(path),
        min_clearance_m=float(verdict.min_clearance_m.min()),
        clearance_bound_m=float(verdict.bound_m.min()),
        checks=found.checks,
        search_time_s=found.search_time_s,
        search_cpu_s=found.search_cpu_s,
    )
