"""Collision-safe straight edges in joint space, certified by a Lipschitz bound.

The rule. Let ``L`` bound how far any point of the robot moves per joint-space
length (:func:`~lynxsim.arm.motion.arm_lipschitz`), so the clearance ``c``
changes by at most ``L |s - s'|`` between points at arc lengths ``s, s'`` of an
edge [rad]. Between two checked points ``a, b`` at distance ``h`` apart, every
point lies within ``h/2`` of one of them along the edge, and::

    c(s) >= max(c_a - L (s - s_a), c_b - L (s_b - s)) >= (c_a + c_b - L h) / 2.

An interval is **certified** when both ends have clearance ``>= margin`` and
``L h <= c_a + c_b - margin``: the whole interval then keeps clearance
``>= margin / 2 > 0``, so no collision hides between the checks. An edge is
accepted when every point checked on it has clearance ``>= margin`` and its
checked points split it into certified intervals.

The checks are batched: each round asks the oracle once for new points in every
interval not yet certified, of every edge still undecided, spaced by the
larger of the smaller end clearance and the margin over ``L`` (conservative
advancement from both ends; in free space a long edge needs few points, near an
obstacle the spacing falls to ``margin / L``, where an interval between two
points of clearance ``>= margin`` is always certified, so the rounds end). An
edge is rejected as soon as a checked point has clearance below the margin.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from lynxsim.plan.oracle import ClearanceOracle, FloatArray, query

__all__ = ["MAX_SPLIT", "EdgeCheck", "check_edges", "check_path"]

MAX_SPLIT = 64
"""Most new points one round puts into one interval [-]."""

BoolArray = npt.NDArray[np.bool_]


@dataclass(frozen=True)
class EdgeCheck:
    """Verdicts on E straight edges.

    Attributes:
        clear: Whether each edge is certified clear, shape (E,).
        min_clearance_m: Smallest clearance checked on each edge, shape (E,) [m]
            (on a rejected edge, the one that rejected it or lower).
        bound_m: Certified lower bound of the clearance over each accepted edge,
            ``>= margin / 2``; ``-inf`` on a rejected edge, shape (E,) [m].
        queries: Joint vectors the oracle was asked about.
    """

    clear: BoolArray
    min_clearance_m: FloatArray
    bound_m: FloatArray
    queries: int


def check_edges(
    starts: FloatArray,
    ends: FloatArray,
    oracle: ClearanceOracle,
    *,
    lipschitz: float,
    margin_m: float,
    grasped: bool,
    start_clearance_m: FloatArray | None = None,
) -> EdgeCheck:
    """Certify straight joint-space edges clear by the module's rule.

    Args:
        starts: First ends, shape (E, n) [rad].
        ends: Second ends, shape (E, n) [rad].
        oracle: The world.
        lipschitz: ``L`` [m/rad], > 0.
        margin_m: Clearance every checked point must keep [m], > 0.
        grasped: Passed to the oracle.
        start_clearance_m: Known clearances of ``starts``, shape (E,) [m]; asked
            of the oracle when ``None``.

    Returns:
        The :class:`EdgeCheck`.
    """
    e_count = starts.shape[0]
    length = np.linalg.norm(ends - starts, axis=1)
    queries = 0
    if start_clearance_m is None:
        c_ends = query(oracle, np.concatenate([starts, ends]), grasped)
        queries += 2 * e_count
        c0, c1 = c_ends[:e_count], c_ends[e_count:]
    else:
        c0 = np.asarray(start_clearance_m, dtype=float)
        c1 = query(oracle, ends, grasped)
        queries += e_count
    min_c = np.minimum(c0, c1)
    bound = np.full(e_count, np.inf)
    alive = min_c >= margin_m
    # Open intervals: edge, arc lengths of the ends [rad], clearances of the ends [m].
    edge = np.flatnonzero(alive)
    s_a, s_b = np.zeros(edge.size), length[edge]
    c_a, c_b = c0[edge], c1[edge]
    direction = np.zeros_like(starts)
    moving = length > 0.0
    direction[moving] = (ends[moving] - starts[moving]) / length[moving, None]
    while edge.size:
        h = s_b - s_a
        done = lipschitz * h <= c_a + c_b - margin_m
        np.minimum.at(bound, edge[done], 0.5 * (c_a[done] + c_b[done] - lipschitz * h[done]))
        keep = ~done & alive[edge]
        edge, s_a, s_b, c_a, c_b, h = (x[keep] for x in (edge, s_a, s_b, c_a, c_b, h))
        if not edge.size:
            break
        spacing = np.maximum(np.minimum(c_a, c_b), margin_m) / lipschitz
        k = np.clip(np.ceil(h / spacing) - 1.0, 1.0, MAX_SPLIT).astype(np.intp)
        # k new points per interval: interval i gets fractions j / (k_i + 1), j = 1..k_i.
        owner = np.repeat(np.arange(edge.size), k)
        j = np.arange(owner.size) - np.repeat(np.cumsum(k) - k, k) + 1
        s_new = s_a[owner] + h[owner] * j / (k[owner] + 1)
        e_new = edge[owner]
        q_new = starts[e_new] + s_new[:, None] * direction[e_new]
        c_new = query(oracle, q_new, grasped)
        queries += q_new.shape[0]
        np.minimum.at(min_c, e_new, c_new)
        alive[e_new[c_new < margin_m]] = False
        # Split every interval at its new points: ends (a, p1), (p1, p2), ..., (pk, b).
        first = np.concatenate([[True], owner[1:] != owner[:-1]])
        last = np.concatenate([owner[1:] != owner[:-1], [True]])
        left_s = np.where(first, s_a[owner], np.roll(s_new, 1))
        left_c = np.where(first, c_a[owner], np.roll(c_new, 1))
        tail = np.flatnonzero(last)
        edge = np.concatenate([e_new, edge[owner[tail]]])
        s_a = np.concatenate([left_s, s_new[tail]])
        s_b = np.concatenate([s_new, s_b[owner[tail]]])
        c_a = np.concatenate([left_c, c_new[tail]])
        c_b = np.concatenate([c_new, c_b[owner[tail]]])
    bound = np.where(alive, bound, -np.inf)
    return EdgeCheck(clear=alive, min_clearance_m=min_c, bound_m=bound, queries=queries)


def check_path(
    path: FloatArray,
    oracle: ClearanceOracle,
    *,
    lipschitz: float,
    margin_m: float,
    grasped: bool,
) -> EdgeCheck:
    """Certify every edge of a polyline ``path`` (M, n) [rad]; see :func:`check_edges`.

    A single-vertex path has one zero-length edge.
    """
    if path.shape[0] == 1:
        return check_edges(
            path, path, oracle, lipschitz=lipschitz, margin_m=margin_m, grasped=grasped
        )
    return check_edges(
        path[:-1], path[1:], oracle, lipschitz=lipschitz, margin_m=margin_m, grasped=grasped
    )
