"""OMPL's geometric planners run on a joint box, with the planner's own edge check.

OMPL samples and grows its graphs; every edge it asks about goes to a Python
:class:`ompl.base.MotionValidator` that calls back into lynxsim's certified edge
check, and every state it asks about to a validity callback. All goal
candidates are :class:`ompl.base.GoalStates`; the planner picks one.

Determinism: OMPL draws from one process-wide seed generator; seeding it before
building the planner (``ompl.util.RNG.setSeed``) makes every run with the same
inputs and seed take the same samples. Planners that stop at their first
solution (RRTConnect, RRT) then return the same path bit for bit; the
optimising ones (RRTstar, BITstar, PRM, ...) refine until the time limit, so
their result also depends on how far they got. Not thread-safe: OMPL's seed and
log level are process-wide.

Cleanup: nanobind reports OMPL objects still alive at interpreter exit ("leaked
instances") on stderr. :func:`solve` drops every OMPL object it made and runs
the garbage collector before it returns, so nothing outlives the call.
OMPL's own log output is switched off during a call (the caller's level is
restored after): outcomes come back as results or typed errors.
"""

from __future__ import annotations

import gc
import time
from collections.abc import Callable
from typing import Any, Literal, get_args

import numpy as np
from ompl import base as ob
from ompl import geometric as og
from ompl import util as ou

from lynxsim.plan.errors import UnknownPlannerError
from lynxsim.plan.oracle import FloatArray

__all__ = ["COMPILED", "OMPL_PLANNERS", "PLANNERS", "PlannerName", "check_planner", "solve"]

PlannerName = Literal[
    "compiled",
    "RRTConnect",
    "RRT",
    "RRTstar",
    "InformedRRTstar",
    "SORRTstar",
    "BITstar",
    "AORRTC",
    "FMT",
    "BFMT",
]
"""The planners selectable by name: ``compiled`` (RRT-Connect and its shortcutting
compiled on a sphere cover, :mod:`lynxsim.plan.cover.search`), then OMPL's
geometric planners.

Left out: PRM and PRMstar, which check for a solution in a second thread that
calls the Python edge check while the solving thread holds the GIL (a
deadlock), and the KPIECE family, which asks the edge check for the last valid
point of an edge (a C++ out-parameter a Python validator cannot fill)."""

_THREADED = ("PRM", "PRMstar", "LazyPRM", "LazyPRMstar", "SPARS", "SPARStwo")

PLANNERS: tuple[str, ...] = get_args(PlannerName)
"""The selectable planner names, in the order listed by errors."""

COMPILED: Literal["compiled"] = "compiled"
"""The compiled planner's name (it needs a cover world)."""

OMPL_PLANNERS: tuple[str, ...] = PLANNERS[1:]
"""OMPL's planners among them."""

MAX_SEED = 2**32 - 2
"""Largest seed [-]; OMPL's seed is an unsigned 32-bit number above zero (seed + 1)."""


def check_planner(name: object) -> PlannerName:
    """``name`` if it is one of :data:`PLANNERS`, else raise :class:`UnknownPlannerError`."""
    for valid in PLANNERS:
        if name == valid:
            return valid  # type: ignore[return-value]  # one of the Literal's values
    if name in _THREADED:
        raise UnknownPlannerError(
            name, PLANNERS, "it calls the edge check from a second thread (deadlocks with Python)"
        )
    raise UnknownPlannerError(name, PLANNERS)


class _Callbacks:
    """Wraps the Python checks so an exception stops the planner instead of crossing C++."""

    def __init__(
        self,
        n: int,
        state_ok: Callable[[FloatArray], bool],
        motion_ok: Callable[[FloatArray, FloatArray], bool],
        deadline: float,
    ) -> None:
        self.n = n
        self.state_ok = state_ok
        self.motion_ok = motion_ok
        self.deadline = deadline
        self.error: BaseException | None = None

    def vector(self, state: Any) -> FloatArray:
        return np.array([state[i] for i in range(self.n)], dtype=float)

    def state(self, state: Any) -> bool:
        if self.error is not None:
            return False
        try:
            return bool(self.state_ok(self.vector(state)))
        except BaseException as exc:  # re-raised by solve() once OMPL has returned
            self.error = exc
            return False

    def motion(self, s1: Any, s2: Any) -> bool:
        if self.error is not None:
            return False
        try:
            return bool(self.motion_ok(self.vector(s1), self.vector(s2)))
        except BaseException as exc:
            self.error = exc
            return False

    def stop(self) -> bool:
        return self.error is not None or time.perf_counter() > self.deadline


class _MotionValidator(ob.MotionValidator):  # type: ignore[misc]  # OMPL is untyped
    """OMPL's edge check, answered by :meth:`_Callbacks.motion`."""

    def __init__(self, si: Any, callbacks: _Callbacks) -> None:
        super().__init__(si)
        self._callbacks = callbacks

    def checkMotion(self, s1: Any, s2: Any, *args: Any) -> bool:  # OMPL's name
        return self._callbacks.motion(s1, s2)


def solve(
    start: FloatArray,
    goals: FloatArray,
    lower: FloatArray,
    upper: FloatArray,
    *,
    state_ok: Callable[[FloatArray], bool],
    motion_ok: Callable[[FloatArray, FloatArray], bool],
    planner: PlannerName,
    time_limit_s: float,
    seed: int,
) -> FloatArray | None:
    """Find a path from ``start`` to one of ``goals`` with an OMPL planner.

    Args:
        start: Shape (n,) [rad], valid.
        goals: Valid goal candidates, shape (K, n) [rad].
        lower: Lower joint bounds, shape (n,) [rad].
        upper: Upper joint bounds, shape (n,) [rad].
        state_ok: Whether a joint vector (n,) is valid.
        motion_ok: Whether the straight edge between two joint vectors is clear
            (both ends included).
        planner: One of :data:`PLANNERS`.
        time_limit_s: Wall-clock limit [s].
        seed: Seed of OMPL's random numbers, 0 to :data:`MAX_SEED`.

    Returns:
        The path's vertices, shape (M, n) [rad], from ``start`` to a goal; ``None``
        when the planner found no exact solution in time.

    Raises:
        Exception: Whatever ``state_ok`` or ``motion_ok`` raised.
    """
    n = start.shape[0]
    callbacks = _Callbacks(n, state_ok, motion_ok, time.perf_counter() + time_limit_s)
    level = ou.getLogLevel()
    ou.setLogLevel(ou.LOG_NONE)
    try:
        return _run(callbacks, start, goals, lower, upper, planner, seed)
    finally:
        gc.collect()  # the OMPL objects made by _run hold Python callbacks in cycles
        ou.setLogLevel(level)


def _run(
    callbacks: _Callbacks,
    start: FloatArray,
    goals: FloatArray,
    lower: FloatArray,
    upper: FloatArray,
    planner: PlannerName,
    seed: int,
) -> FloatArray | None:
    """Build the OMPL problem, solve it and copy the path out; every OMPL object dies here."""
    n = start.shape[0]
    ou.RNG.setSeed(seed + 1)  # OMPL reads 0 as "pick a random seed"
    space = ob.RealVectorStateSpace(n)
    bounds = ob.RealVectorBounds(n)
    for i in range(n):
        bounds.setLow(i, float(lower[i]))
        bounds.setHigh(i, float(upper[i]))
    space.setBounds(bounds)
    setup = og.SimpleSetup(space)
    si = setup.getSpaceInformation()
    validator = _MotionValidator(si, callbacks)
    si.setMotionValidator(validator)
    setup.setStateValidityChecker(callbacks.state)

    def state_of(q: FloatArray) -> Any:
        s = si.allocState()
        for i in range(n):
            s[i] = float(q[i])
        return s

    setup.setStartState(state_of(start))
    goal = ob.GoalStates(si)
    for q in goals:
        goal.addState(state_of(q))
    setup.setGoal(goal)
    setup.setPlanner(getattr(og, planner)(si))
    stop = ob.PlannerTerminationCondition(callbacks.stop)
    setup.solve(stop)
    if callbacks.error is not None:
        raise callbacks.error
    if not setup.haveExactSolutionPath():
        return None
    path = setup.getSolutionPath()
    return np.array(
        [callbacks.vector(path.getState(k)) for k in range(path.getStateCount())], dtype=float
    )
