"""Shortening a clear joint path: dropping vertices, seeded random shortcuts, dropping again.

Every change replaces part of the path by straight edges that pass the same
certified edge check as the planner's (:func:`~lynxsim.plan.edges.check_edges`),
and is kept only if the path gets shorter, so shortening never lengthens a path
and keeps every edge certified clear. Randomness comes from the caller's
:class:`numpy.random.Generator`.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import numpy.typing as npt

from lynxsim.plan.edges import check_edges
from lynxsim.plan.oracle import ClearanceOracle, FloatArray

__all__ = [
    "DUPLICATE_TOL_RAD",
    "EdgeTest",
    "drop_duplicates",
    "path_length",
    "reduce_vertices",
    "shorten_path",
]

DUPLICATE_TOL_RAD = 1e-9
"""Consecutive vertices closer than this merge [rad]."""

EdgeTest = Callable[[npt.NDArray[np.float64], npt.NDArray[np.float64]], npt.NDArray[np.bool_]]
"""Whether straight edges (E, n) -> (E, n) are clear, (E,)."""

_MIN_GAIN_RAD = 1e-9
"""A shortcut must save at least this much length [rad]."""


def path_length(path: FloatArray) -> float:
    """Joint-space length of a polyline (M, n) [rad] (sum of the edges' 2-norms)."""
    return float(np.linalg.norm(np.diff(path, axis=0), axis=1).sum())


def drop_duplicates(path: FloatArray) -> FloatArray:
    """``path`` (M, n) without vertices within :data:`DUPLICATE_TOL_RAD` of the last kept one.

    The first and last vertices stay exactly (start and goal), the last one in
    place of a kept vertex it duplicates.
    """
    kept = [0]
    for k in range(1, path.shape[0]):
        if np.linalg.norm(path[k] - path[kept[-1]]) > DUPLICATE_TOL_RAD:
            kept.append(k)
    last = path.shape[0] - 1
    if kept[-1] != last:
        if len(kept) > 1:
            kept[-1] = last
        else:
            kept.append(last)
    return path[kept]


def shorten_path(
    path: FloatArray,
    oracle: ClearanceOracle,
    *,
    lipschitz: float,
    margin_m: float,
    grasped: bool,
    rng: np.random.Generator,
    shortcuts: int = 30,
) -> FloatArray:
    """Shorten a clear path: vertex removal, random shortcuts, vertex removal.

    Args:
        path: Vertices, shape (M, n) [rad], every edge certified clear.
        oracle: The world.
        lipschitz: ``L`` [m/rad].
        margin_m: The edge check's margin [m].
        grasped: Passed to the oracle.
        rng: Draws the shortcut points.
        shortcuts: Shortcut attempts [-].

    Returns:
        The shorter (or the same) path, same first and last vertex, shape (M', n).
    """
    path = drop_duplicates(np.array(path, dtype=float))

    def clear(starts: FloatArray, ends: FloatArray) -> npt.NDArray[np.bool_]:
        return check_edges(
            starts, ends, oracle, lipschitz=lipschitz, margin_m=margin_m, grasped=grasped
        ).clear

    if shortcuts > 0:
        # A planner's path has many short edges: dropping vertices first (a few
        # batched rounds) leaves the random shortcuts fewer, longer edges to cut.
        path = reduce_vertices(path, clear)
    for _ in range(shortcuts):
        if path.shape[0] <= 2:
            break
        edge_len = np.linalg.norm(np.diff(path, axis=0), axis=1)
        cum = np.concatenate([[0.0], np.cumsum(edge_len)])
        t1, t2 = np.sort(rng.uniform(0.0, cum[-1], size=2))
        i1 = min(int(np.searchsorted(cum, t1, side="right")) - 1, len(edge_len) - 1)
        i2 = min(int(np.searchsorted(cum, t2, side="right")) - 1, len(edge_len) - 1)
        if i1 == i2:
            continue
        p1 = path[i1] + (t1 - cum[i1]) / edge_len[i1] * (path[i1 + 1] - path[i1])
        p2 = path[i2] + (t2 - cum[i2]) / edge_len[i2] * (path[i2 + 1] - path[i2])
        candidate = drop_duplicates(np.concatenate([path[: i1 + 1], [p1, p2], path[i2 + 1 :]]))
        if path_length(candidate) > path_length(path) - _MIN_GAIN_RAD:
            continue
        # The new middle edge fails most often: check it first, its neighbours
        # (pieces of edges already certified, but with new ends) only if it passes.
        if (
            clear(p1[None], p2[None])[0]
            and clear(np.array([path[i1], p2]), np.array([p1, path[i2 + 1]])).all()
        ):
            path = candidate
    return reduce_vertices(path, clear)


def reduce_vertices(path: FloatArray, clear: EdgeTest) -> FloatArray:
    """Drop interior vertices whose neighbours see each other by a clear edge.

    Each round checks, in one batch, the edge that would replace every interior
    vertex, and drops those that pass, never two neighbours (their replacement
    edges would differ from the ones checked).

    Args:
        path: Vertices, shape (M, n) [rad].
        clear: Whether each straight edge ``(starts[e], ends[e])`` is clear.

    Returns:
        The path without the dropped vertices, shape (M', n).
    """
    while path.shape[0] > 2:
        ok = clear(path[:-2], path[2:])
        drop = np.zeros(path.shape[0], dtype=bool)
        for k in np.flatnonzero(ok).tolist():
            if not drop[k]:  # vertex k + 1 goes unless its left neighbour goes already
                drop[k + 1] = True
        if not drop.any():
            break
        path = path[~drop]
    return path
