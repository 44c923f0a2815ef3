"""One planning problem, checked: a start, goal candidates, a joint box, a world.

Malformed arguments raise :class:`~lynxsim.errors.InvalidInputError`; a start or
goals without clearance raise the planning errors of
:mod:`lynxsim.plan.errors`, since they are outcomes of the world, not typos.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from lynxsim.errors import InvalidInputError
from lynxsim.inputs import finite_array, flag, number_in_range, positive_number
from lynxsim.plan.errors import GoalsInCollisionError, StartInCollisionError
from lynxsim.plan.oracle import ClearanceOracle, FloatArray, query

__all__ = ["MAX_LIPSCHITZ", "MAX_MARGIN_M", "Problem", "check_settings", "make_problem"]

MAX_MARGIN_M = 1.0
"""Largest clearance margin [m]."""

MAX_LIPSCHITZ = 1e3
"""Largest Lipschitz constant [m/rad]."""

_BOUND_TOL = 1e-12
"""Slack on the joint box when checking start and goals [rad]."""


@dataclass(frozen=True)
class Problem:
    """A checked planning problem.

    Attributes:
        start: Shape (n,) [rad].
        goals: Goal candidates, shape (K, n) [rad].
        lower: Lower joint bounds, shape (n,) [rad].
        upper: Upper joint bounds, shape (n,) [rad].
        lipschitz: ``L`` [m/rad].
        margin_m: Clearance every checked point keeps [m].
        grasped: Whether the payload is held.
        label: The segment's label for messages.
        start_clearance_m: Clearance of the start [m].
        goal_clearance_m: Clearance of each candidate, shape (K,) [m].
    """

    start: FloatArray
    goals: FloatArray
    lower: FloatArray
    upper: FloatArray
    lipschitz: float
    margin_m: float
    grasped: bool
    label: str
    start_clearance_m: float
    goal_clearance_m: FloatArray

    @property
    def valid_goals(self) -> npt.NDArray[np.intp]:
        """Indices of the candidates with clearance >= the margin, (K',)."""
        return np.flatnonzero(self.goal_clearance_m >= self.margin_m)


def check_settings(lipschitz: object, margin_m: object, label: object) -> tuple[float, float, str]:
    """Check the Lipschitz constant [m/rad], the margin [m] and the label; return them."""
    lip = positive_number(lipschitz, "lipschitz", "m/rad")
    if lip > MAX_LIPSCHITZ:
        raise InvalidInputError(f"lipschitz must be at most {MAX_LIPSCHITZ:g} m/rad, got {lip!r}")
    margin = positive_number(margin_m, "margin_m", "m")
    margin = number_in_range(margin, "margin_m", 0.0, MAX_MARGIN_M, "m")
    if not isinstance(label, str):
        raise InvalidInputError(f"label must be a string, got {label!r}")
    return lip, margin, label


def _in_box(q: FloatArray, lower: FloatArray, upper: FloatArray, what: str) -> None:
    outside = np.flatnonzero(((q < lower - _BOUND_TOL) | (q > upper + _BOUND_TOL)).any(axis=-1))
    if outside.size:
        k = int(outside[0])
        row = q[k] if q.ndim == 2 else q
        name = f"{what} {k}" if q.ndim == 2 else what
        raise InvalidInputError(
            f"{name} {np.array2string(row, precision=4)} rad lies outside the joint box "
            f"[{np.array2string(lower, precision=4)}, {np.array2string(upper, precision=4)}] rad"
        )


def make_problem(
    start: npt.ArrayLike,
    goals: npt.ArrayLike,
    oracle: ClearanceOracle,
    lower: npt.ArrayLike,
    upper: npt.ArrayLike,
    *,
    lipschitz: float,
    margin_m: float,
    grasped: bool,
    label: str,
) -> Problem:
    """Check a planning problem and ask the clearances of its start and goals.

    Args:
        start: Shape (n,) [rad], ``n = oracle.n_joints``.
        goals: Goal candidates, shape (K, n) or (n,) [rad], K >= 1.
        oracle: The world.
        lower: Lower joint bounds, shape (n,) [rad].
        upper: Upper joint bounds, shape (n,) [rad], above ``lower``.
        lipschitz: ``L`` [m/rad], > 0.
        margin_m: Clearance margin [m], in (0, 1].
        grasped: Whether the payload is held.
        label: The segment's label for messages.

    Returns:
        The :class:`Problem`.

    Raises:
        InvalidInputError: Wrong shapes or values, start or goals outside the box.
        NonFiniteInputError: A value is NaN or infinite.
        StartInCollisionError: The start's clearance is below the margin.
        GoalsInCollisionError: Every goal's clearance is below the margin.
    """
    lip, margin, label = check_settings(lipschitz, margin_m, label)
    grasped = flag(grasped, "grasped")
    n = getattr(oracle, "n_joints", None)
    if not isinstance(n, int) or n < 1 or not callable(getattr(oracle, "clearance", None)):
        raise InvalidInputError(
            f"oracle must be a ClearanceOracle (n_joints, clearance), got {oracle!r}"
        )
    q0 = np.array(finite_array(start, "start"))
    g = np.array(finite_array(goals, "goals"))
    lo = np.array(finite_array(lower, "lower"))
    hi = np.array(finite_array(upper, "upper"))
    if g.ndim == 1:
        g = g[None]
    for arr, what in ((q0, "start"), (lo, "lower"), (hi, "upper")):
        if arr.shape != (n,):
            raise InvalidInputError(f"{what} must have shape ({n},), got {arr.shape}")
    if g.ndim != 2 or g.shape[1] != n or g.shape[0] < 1:
        raise InvalidInputError(f"goals must have shape (K, {n}), K >= 1, got {g.shape}")
    if not (lo < hi).all():
        raise InvalidInputError(f"lower must be below upper, got {lo.tolist()} and {hi.tolist()}")
    _in_box(q0, lo, hi, "start")
    _in_box(g, lo, hi, "goal")
    q0, g = np.clip(q0, lo, hi), np.clip(g, lo, hi)
    c = query(oracle, np.concatenate([q0[None], g]), grasped)
    if not c[0] >= margin:
        raise StartInCollisionError(q0, float(c[0]), margin, label)
    if not (c[1:] >= margin).any():
        raise GoalsInCollisionError(c[1:], margin, label)
    for arr in (q0, g, lo, hi):
        arr.setflags(write=False)
    return Problem(q0, g, lo, hi, lip, margin, grasped, label, float(c[0]), c[1:])
