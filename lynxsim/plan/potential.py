"""An artificial potential-field planner: a baseline that can get stuck.

The robot descends ``U(q) = 1/2 ||q - g||^2 + 1/2 eta (1/c(q) - 1/c0)^2`` (the
second term only where the clearance ``c < c0``), attracted to the nearest valid
goal ``g`` in joint space and repelled by the oracle's clearance, whose gradient
comes from central finite differences (2n extra points per step, one oracle
batch). Each step moves at most ``step_rad`` along ``-grad U``, every step is a
certified clear edge (the step halves until it is), and when the best distance
to the goal has not shrunk by ``stall_rad`` within ``stall_steps`` steps the
planner gives up with :class:`~lynxsim.plan.errors.LocalMinimumError`.
"""

from __future__ import annotations

import time

import numpy as np
import numpy.typing as npt

from lynxsim.errors import InvalidInputError
from lynxsim.inputs import positive_number
from lynxsim.plan.edges import check_edges
from lynxsim.plan.errors import LocalMinimumError
from lynxsim.plan.oracle import ClearanceOracle, FloatArray, query
from lynxsim.plan.problem import make_problem
from lynxsim.plan.progress import PlanProgress, ProgressCallback
from lynxsim.plan.segment import DEFAULT_SHORTCUTS, SegmentPlan, check_seed, finish_segment

__all__ = ["potential_field_segment"]

_HALVINGS = 6
"""Times a blocked step is halved before the planner counts it as stuck [-]."""


def potential_field_segment(
    start: npt.ArrayLike,
    goals: npt.ArrayLike,
    oracle: ClearanceOracle,
    lower: npt.ArrayLike,
    upper: npt.ArrayLike,
    *,
    lipschitz: float,
    margin_m: float = 0.01,
    grasped: bool = False,
    step_rad: float = 0.02,
    influence_m: float = 0.1,
    repulsion: float = 0.01,
    fd_step_rad: float = 1e-4,
    max_steps: int = 5000,
    stall_steps: int = 50,
    stall_rad: float = 1e-3,
    seed: int = 0,
    shortcuts: int = DEFAULT_SHORTCUTS,
    label: str = "",
    progress: ProgressCallback | None = None,
) -> SegmentPlan:
    """Descend a potential field from ``start`` to the nearest valid goal.

    Args:
        start: Shape (n,) [rad].
        goals: Goal candidates, shape (K, n) [rad]; the nearest with clearance
            >= the margin attracts.
        oracle: The world.
        lower: Lower joint bounds, shape (n,) [rad]; steps are clipped to the box.
        upper: Upper joint bounds, shape (n,) [rad].
        lipschitz: ``L`` [m/rad] of the edge check.
        margin_m: Clearance every checked point keeps [m].
        grasped: Whether the payload is held.
        step_rad: Longest step [rad].
        influence_m: Clearance ``c0`` below which the obstacles repel [m].
        repulsion: Gain ``eta`` of the repulsion [rad^2 m^2].
        fd_step_rad: Finite-difference step of the clearance gradient [rad].
        max_steps: Most steps [-].
        stall_steps: Steps without progress after which it gives up [-].
        stall_rad: Progress that counts, in distance to the goal [rad].
        seed: Seeds the shortcuts of the path found.
        shortcuts: Random shortcut attempts on the path found (0: keep it).
        label: Names the segment in errors and progress reports.
        progress: Called when shortening starts.

    Returns:
        The :class:`SegmentPlan` (``planner`` reads "potential").

    Raises:
        LocalMinimumError: No progress for ``stall_steps`` steps, or ``max_steps``
            used up (gives where it stopped).
        StartInCollisionError: The start has clearance below the margin.
        GoalsInCollisionError: Every goal candidate has clearance below the margin.
        InvalidInputError: Malformed arguments.
    """
    started = time.perf_counter()
    p = make_problem(
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
    step = positive_number(step_rad, "step_rad", "rad")
    c0 = positive_number(influence_m, "influence_m", "m")
    eta = positive_number(repulsion, "repulsion")
    h = positive_number(fd_step_rad, "fd_step_rad", "rad")
    stall = positive_number(stall_rad, "stall_rad", "rad")
    for value, name in ((max_steps, "max_steps"), (stall_steps, "stall_steps")):
        if isinstance(value, bool) or not isinstance(value, int) or value < 1:
            raise InvalidInputError(f"{name} must be a positive integer, got {value!r}")
    seed = check_seed(seed)
    if progress is not None:
        progress(PlanProgress(0, 1, p.label, "planning", time.perf_counter() - started))
    valid = p.valid_goals
    goal = p.goals[valid[np.argmin(np.linalg.norm(p.goals[valid] - p.start, axis=1))]]
    n = p.start.shape[0]
    offsets = np.concatenate([np.zeros((1, n)), h * np.eye(n), -h * np.eye(n)])

    def clear(a: FloatArray, b: FloatArray, c_a: float) -> bool:
        verdict = check_edges(
            a[None],
            b[None],
            oracle,
            lipschitz=p.lipschitz,
            margin_m=p.margin_m,
            grasped=p.grasped,
            start_clearance_m=np.array([c_a]),
        )
        return bool(verdict.clear[0])

    q = p.start
    path = [q]
    best = float(np.linalg.norm(goal - q))
    since_best = 0
    for _ in range(max_steps):
        c_all = query(oracle, q + offsets, p.grasped)
        c = float(c_all[0])
        if np.linalg.norm(goal - q) <= step and clear(q, goal, c):
            path.append(goal)
            return finish_segment(
                p,
                oracle,
                np.array(path),
                planner="potential",
                started=started,
                rng=np.random.default_rng(seed),
                shortcuts=shortcuts,
                progress=progress,
            )
        force = goal - q
        if c < c0:
            grad_c = (c_all[1 : n + 1] - c_all[n + 1 :]) / (2.0 * h)
            force = force + eta * (1.0 / c - 1.0 / c0) / (c * c) * grad_c
        norm = float(np.linalg.norm(force))
        moved = False
        if norm > 0.0:
            length = step
            for _ in range(_HALVINGS):
                target = np.clip(q + (length / norm) * force, p.lower, p.upper)
                if np.linalg.norm(target - q) > 0.0 and clear(q, target, c):
                    q = target
                    path.append(q)
                    moved = True
                    break
                length *= 0.5
        distance = float(np.linalg.norm(goal - q))
        if distance < best - stall:
            best, since_best = distance, 0
        else:
            since_best += 1
        if not moved or since_best >= stall_steps:
            break
    raise LocalMinimumError(q, float(np.linalg.norm(goal - q)), len(path) - 1, p.label)
