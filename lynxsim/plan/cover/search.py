"""RRT-Connect and its shortcutting on a sphere cover, in one compiled call.

:func:`search_cover` does what :func:`lynxsim.plan.segment.plan_segment` does
with OMPL's RRT-Connect and :func:`lynxsim.plan.shortcut.shorten_path`, with no
Python between the checks: the clearances of start and goals, the straight
edge to the nearest goal it reaches, else RRT-Connect (a tree from the start,
one from every valid goal, each grown by at most ``step`` toward a uniform
sample, the other greedily connected to it), then vertex removal, seeded
random shortcuts and vertex removal again. Every edge it keeps is certified
clear on the cover by the rule of :mod:`lynxsim.plan.edges`. Random numbers
come from a SplitMix64 generator seeded by ``seed``: same world, problem and
seed give the same path bit for bit.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np
from numba import njit

from lynxsim.plan.cover.kernels import Scratch, _clearance, _edge_clear
from lynxsim.plan.cover.world import FloatArray, WorldTuple

__all__ = [
    "BLOCKED_GOALS",
    "BLOCKED_START",
    "DEFAULT_SAMPLES",
    "DIRECT",
    "FOUND",
    "NOT_FOUND",
    "CoverSearch",
    "search_cover",
]

FOUND = 0
"""Status: RRT-Connect found a path."""
DIRECT = 1
"""Status: the straight edge to a goal is clear."""
BLOCKED_START = 2
"""Status: the start's cover clearance is below the margin."""
BLOCKED_GOALS = 3
"""Status: every goal's cover clearance is below the margin."""
NOT_FOUND = 4
"""Status: no path within the sample budget."""

DEFAULT_SAMPLES = 20000
"""Samples RRT-Connect draws before it gives up [-]."""

_DUPLICATE_TOL = 1e-9  # as lynxsim.plan.shortcut.DUPLICATE_TOL_RAD
_MIN_GAIN = 1e-9  # as lynxsim.plan.shortcut._MIN_GAIN_RAD
_RANGE_FRACTION = 0.2  # OMPL's RRT-Connect: a step is at most 0.2 of the box's diagonal


@dataclass(frozen=True)
class CoverSearch:
    """What one compiled search returned.

    Attributes:
        status: :data:`FOUND`, :data:`DIRECT`, :data:`BLOCKED_START`,
            :data:`BLOCKED_GOALS` or :data:`NOT_FOUND`.
        raw: The path found, (M, n) [rad] (empty unless found or direct).
        path: The shortened path, (M', n) [rad].
        goal_index: The goal it reaches (-1 if none).
        checks: Configurations checked on the cover.
        samples: Samples drawn by RRT-Connect.
        search_time_s: Wall-clock time of the compiled call [s].
        search_cpu_s: CPU time of the compiled call [s] (this process's).
    """

    status: int
    raw: FloatArray
    path: FloatArray
    goal_index: int
    checks: int
    samples: int
    search_time_s: float
    search_cpu_s: float


@njit(cache=True, inline="always", error_model="numpy")
def _next(state):  # type: ignore[no-untyped-def]  # numba
    """A uniform number in [0, 1) from the SplitMix64 state (1,) uint64, advanced."""
    state[0] += np.uint64(0x9E3779B97F4A7C15)
    z = state[0]
    z = (z ^ (z >> np.uint64(30))) * np.uint64(0xBF58476D1CE4E5B9)
    z = (z ^ (z >> np.uint64(27))) * np.uint64(0x94D049BB133111EB)
    z = z ^ (z >> np.uint64(31))
    return float(z >> np.uint64(11)) * (1.0 / 9007199254740992.0)


@njit(cache=True, inline="always", error_model="numpy")
def _distance(a, b):  # type: ignore[no-untyped-def]  # numba
    s = 0.0
    for i in range(a.shape[0]):
        s += (a[i] - b[i]) ** 2
    return math.sqrt(s)


@njit(cache=True, error_model="numpy")
def _extend(w, nodes, parent, clear, size, target, tc, step, lip, margin, grasped, work, counter):  # type: ignore[no-untyped-def]  # numba
    """Grow a tree one step toward ``target``: (new node index or -1, whether it reached it).

    ``tc`` is the target's clearance when known (a node of the other tree), else NaN.
    """
    best, near = math.inf, 0
    for k in range(size[0]):
        d = _distance(nodes[k], target)
        if d < best:
            best, near = d, k
    n = target.shape[0]
    q = np.empty(n)
    reached = best <= step
    for i in range(n):
        q[i] = target[i] if reached else nodes[near, i] + (target[i] - nodes[near, i]) * step / best
    if size[0] >= nodes.shape[0]:
        return -1, False
    c = _edge_clear(
        w, nodes[near], q, clear[near], tc if reached else math.nan, lip, margin, grasped,
        work, counter,
    )  # fmt: skip
    if not c >= margin:
        return -1, False
    k = size[0]
    nodes[k] = q
    parent[k] = near
    clear[k] = c
    size[0] += 1
    return k, reached


@njit(cache=True, error_model="numpy")
def _branch(nodes, parent, clear, k):  # type: ignore[no-untyped-def]  # numba
    """The nodes from node ``k`` back to its root, (m, n), and their clearances, (m,)."""
    count, j = 1, k
    while parent[j] >= 0:
        j = parent[j]
        count += 1
    out, out_c = np.empty((count, nodes.shape[1])), np.empty(count)
    j = k
    for i in range(count):
        out[i], out_c[i] = nodes[j], clear[j]
        j = parent[j]
    return out, out_c


@njit(cache=True, error_model="numpy")
def _dedupe(path):  # type: ignore[no-untyped-def]  # numba
    """Indices (m',) of the vertices of ``path`` kept (as drop_duplicates).

    A vertex is kept when beyond the tolerance of the last kept; the last always is.
    """
    m = path.shape[0]
    kept = np.empty(m, dtype=np.int64)
    kept[0] = 0
    count = 1
    for k in range(1, m):
        if _distance(path[k], path[kept[count - 1]]) > _DUPLICATE_TOL:
            kept[count] = k
            count += 1
    if kept[count - 1] != m - 1:
        if count > 1:
            kept[count - 1] = m - 1
        else:
            kept[count] = m - 1
            count += 1
    return kept[:count].copy()


@njit(cache=True, error_model="numpy")
def _checked(w, q, c, grasped, work, counter):  # type: ignore[no-untyped-def]  # numba
    """``c``, the clearance of ``q`` when known, else checked (NaN: not known)."""
    if math.isnan(c):
        counter[0] += 1
        return _clearance(w, q, grasped, work)
    return c


@njit(cache=True, error_model="numpy")
def _edge(w, a, b, ca, cb, lip, margin, grasped, work, counter):  # type: ignore[no-untyped-def]  # numba
    """Whether edge ``a -> b`` is certified clear (``ca``, ``cb`` known clearances)."""
    return _edge_clear(w, a, b, ca, cb, lip, margin, grasped, work, counter) >= margin


@njit(cache=True, error_model="numpy")
def _length(path):  # type: ignore[no-untyped-def]  # numba
    total = 0.0
    for k in range(path.shape[0] - 1):
        total += _distance(path[k], path[k + 1])
    return total


@njit(cache=True, error_model="numpy")
def _reduce(w, path, pc, lip, margin, grasped, work, counter):  # type: ignore[no-untyped-def]  # numba
    """Drop interior vertices whose neighbours see each other (as reduce_vertices).

    ``pc``: the vertices' clearances, (m,); returns the path and its clearances.
    """
    while path.shape[0] > 2:
        m = path.shape[0]
        ok = np.zeros(m - 2, dtype=np.bool_)
        for k in range(m - 2):
            ok[k] = _edge(
                w, path[k], path[k + 2], pc[k], pc[k + 2], lip, margin, grasped, work, counter
            )
        drop = np.zeros(m, dtype=np.bool_)
        for k in range(m - 2):
            if ok[k] and not drop[k]:
                drop[k + 1] = True
        if not drop.any():
            break
        path, pc = path[~drop].copy(), pc[~drop].copy()
    return path, pc


@njit(cache=True, error_model="numpy")
def _shorten(w, path, pc, lip, margin, grasped, state, shortcuts, work, counter):  # type: ignore[no-untyped-def]  # numba
    """Vertex removal, random shortcuts, vertex removal (as shorten_path).

    ``pc``: the clearances of the vertices of ``path`` (m,), each checked once.
    """
    kept = _dedupe(path)
    path, pc = path[kept], pc[kept]
    if shortcuts > 0:
        path, pc = _reduce(w, path, pc, lip, margin, grasped, work, counter)
    for _ in range(shortcuts):
        m = path.shape[0]
        if m <= 2:
            break
        cum = np.zeros(m)
        for k in range(m - 1):
            cum[k + 1] = cum[k] + _distance(path[k], path[k + 1])
        t1, t2 = _next(state) * cum[-1], _next(state) * cum[-1]
        if t2 < t1:
            t1, t2 = t2, t1
        i1 = min(np.searchsorted(cum, t1, side="right") - 1, m - 2)
        i2 = min(np.searchsorted(cum, t2, side="right") - 1, m - 2)
        if i1 == i2:
            continue
        e1, e2 = cum[i1 + 1] - cum[i1], cum[i2 + 1] - cum[i2]
        p1 = path[i1] + (t1 - cum[i1]) / e1 * (path[i1 + 1] - path[i1])
        p2 = path[i2] + (t2 - cum[i2]) / e2 * (path[i2 + 1] - path[i2])
        joined = np.empty((i1 + 1 + 2 + m - i2 - 1, path.shape[1]))
        joined[: i1 + 1] = path[: i1 + 1]
        joined[i1 + 1] = p1
        joined[i1 + 2] = p2
        joined[i1 + 3 :] = path[i2 + 1 :]
        kept = _dedupe(joined)
        candidate = joined[kept]
        if _length(candidate) > _length(path) - _MIN_GAIN:
            continue
        c1 = _checked(w, p1, math.nan, grasped, work, counter)
        c2 = _checked(w, p2, math.nan, grasped, work, counter)
        if (
            _edge(w, p1, p2, c1, c2, lip, margin, grasped, work, counter)
            and _edge(w, path[i1], p1, pc[i1], c1, lip, margin, grasped, work, counter)
            and _edge(w, p2, path[i2 + 1], c2, pc[i2 + 1], lip, margin, grasped, work, counter)
        ):
            joined_c = np.empty(joined.shape[0])
            joined_c[: i1 + 1] = pc[: i1 + 1]
            joined_c[i1 + 1], joined_c[i1 + 2] = c1, c2
            joined_c[i1 + 3 :] = pc[i2 + 1 :]
            path, pc = candidate, joined_c[kept]
    return _reduce(w, path, pc, lip, margin, grasped, work, counter)[0]


@njit(cache=True, error_model="numpy")
def _search(w, start, goals, lower, upper, lip, margin, grasped, seed, samples, shortcuts, work):  # type: ignore[no-untyped-def]  # numba
    n = start.shape[0]
    counter = np.zeros(1, dtype=np.int64)
    empty = np.empty((0, n))
    c0 = _clearance(w, start, grasped, work)
    counter[0] += 1
    if not c0 >= margin:
        return BLOCKED_START, empty, empty, -1, counter[0], 0
    k_goals = goals.shape[0]
    cg = np.empty(k_goals)
    for k in range(k_goals):
        cg[k] = _clearance(w, goals[k], grasped, work)
        counter[0] += 1
    dist = np.empty(k_goals)
    for k in range(k_goals):
        dist[k] = _distance(goals[k], start) if cg[k] >= margin else math.inf
    if not (cg >= margin).any():
        return BLOCKED_GOALS, empty, empty, -1, counter[0], 0
    state = np.array([np.uint64(seed)], dtype=np.uint64)
    for k in np.argsort(dist, kind="mergesort"):
        if not dist[k] < math.inf:
            break
        if (
            dist[k] <= 0.0
            or _edge_clear(w, start, goals[k], c0, cg[k], lip, margin, grasped, work, counter)
            >= margin
        ):
            raw = np.empty((2, n))
            raw[0], raw[1] = start, goals[k]
            path = raw[_dedupe(raw)]
            return DIRECT, raw, path, k, counter[0], 0
    step = _RANGE_FRACTION * _distance(lower, upper)
    cap = samples + 2
    nodes_a, parent_a, clear_a = np.empty((cap, n)), np.full(cap, -1), np.empty(cap)
    nodes_b, parent_b, clear_b = (
        np.empty((cap + k_goals, n)),
        np.full(cap + k_goals, -1),
        np.empty(cap + k_goals),
    )
    nodes_a[0], clear_a[0] = start, c0
    size_a, size_b = np.zeros(1, dtype=np.int64), np.zeros(1, dtype=np.int64)
    size_a[0] = 1
    for k in range(k_goals):
        if cg[k] >= margin:
            nodes_b[size_b[0]], clear_b[size_b[0]] = goals[k], cg[k]
            size_b[0] += 1
    target = np.empty(n)
    for it in range(samples):
        for i in range(n):
            target[i] = lower[i] + _next(state) * (upper[i] - lower[i])
        from_start = it % 2 == 0
        if from_start:
            grown, reached = _extend(
                w,
                nodes_a,
                parent_a,
                clear_a,
                size_a,
                target,
                math.nan,
                step,
                lip,
                margin,
                grasped,
                work,
                counter,
            )
        else:
            grown, reached = _extend(
                w,
                nodes_b,
                parent_b,
                clear_b,
                size_b,
                target,
                math.nan,
                step,
                lip,
                margin,
                grasped,
                work,
                counter,
            )
        if grown < 0:
            continue
        tip = nodes_a[grown].copy() if from_start else nodes_b[grown].copy()
        tip_c = clear_a[grown] if from_start else clear_b[grown]
        while True:
            if from_start:
                other, reached = _extend(
                    w,
                    nodes_b,
                    parent_b,
                    clear_b,
                    size_b,
                    tip,
                    tip_c,
                    step,
                    lip,
                    margin,
                    grasped,
                    work,
                    counter,
                )
            else:
                other, reached = _extend(
                    w,
                    nodes_a,
                    parent_a,
                    clear_a,
                    size_a,
                    tip,
                    tip_c,
                    step,
                    lip,
                    margin,
                    grasped,
                    work,
                    counter,
                )
            if other < 0:
                break
            if reached:
                ia, ib = (grown, other) if from_start else (other, grown)
                head, head_c = _branch(nodes_a, parent_a, clear_a, ia)
                head, head_c = head[::-1], head_c[::-1]
                tail, tail_c = _branch(nodes_b, parent_b, clear_b, ib)
                raw = np.empty((head.shape[0] + tail.shape[0] - 1, n))
                raw_c = np.empty(raw.shape[0])
                raw[: head.shape[0]], raw_c[: head.shape[0]] = head, head_c
                raw[head.shape[0] :], raw_c[head.shape[0] :] = tail[1:], tail_c[1:]
                root = tail[-1]
                goal = 0
                for k in range(k_goals):
                    if _distance(goals[k], root) <= 0.0:
                        goal = k
                        break
                path = _shorten(
                    w, raw, raw_c, lip, margin, grasped, state, shortcuts, work, counter
                )
                return FOUND, raw, path, goal, counter[0], it + 1
    return NOT_FOUND, empty, empty, -1, counter[0], samples


def search_cover(
    world: WorldTuple,
    start: FloatArray,
    goals: FloatArray,
    lower: FloatArray,
    upper: FloatArray,
    *,
    lipschitz: float,
    margin_m: float,
    grasped: bool,
    seed: int,
    shortcuts: int,
    work: Scratch,
    samples: int = DEFAULT_SAMPLES,
) -> CoverSearch:
    """Plan from ``start`` (n,) to one of ``goals`` (K, n) in the box on the cover, compiled.

    Args:
        world: The cover (:meth:`~lynxsim.plan.cover.CoverWorld.as_tuple`).
        start: Shape (n,) [rad].
        goals: Goal candidates, (K, n) [rad].
        lower: Lower joint bounds, (n,) [rad].
        upper: Upper joint bounds, (n,) [rad].
        lipschitz: ``L`` [m/rad].
        margin_m: Clearance every checked point keeps [m].
        grasped: Whether the payload is held.
        seed: Seeds the samples and the shortcuts, >= 0.
        shortcuts: Random shortcut attempts.
        work: Scratch of the world (:func:`~lynxsim.plan.cover.kernels.scratch`).
        samples: RRT-Connect's sample budget.

    Returns:
        The :class:`CoverSearch`.
    """
    started, cpu = time.perf_counter(), time.process_time()
    status, raw, path, goal, checks, drawn = _search(
        world,
        np.ascontiguousarray(start, dtype=float),
        np.ascontiguousarray(goals, dtype=float),
        np.ascontiguousarray(lower, dtype=float),
        np.ascontiguousarray(upper, dtype=float),
        float(lipschitz),
        float(margin_m),
        bool(grasped),
        int(seed),
        int(samples),
        int(shortcuts),
        work,
    )
    elapsed, cpu = time.perf_counter() - started, time.process_time() - cpu
    return CoverSearch(int(status), raw, path, int(goal), int(checks), int(drawn), elapsed, cpu)
