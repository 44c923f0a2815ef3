"""Timing planned joint paths with Ruckig, then checking the timed motion against the world.

Each planning segment's path is timed by
:func:`~lynxsim.traj.ruckig_profile.ruckig_trajectory` through its vertices
without stopping (``pass_through``); the robot stops at the segment's ends (where
it grasps or releases). Ruckig's time-optimal motion leaves the straight edges
near the vertices it passes (it cuts corners) and, between stops, follows no
straight line, so the timed motion is checked again, densely.

The check. Joint speeds are bounded by the velocity limits ``v`` (the trajectory
layer checks them), so between samples ``dt`` apart the joints move at most
``d = ||v||_2 dt`` in joint space and the robot at most ``L d``. Samples are
spaced so that ``L d <= margin / 2``; a motion passes when every sample keeps
clearance ``>= margin / 2``. Between two samples the clearance is then at least
``(c_a + c_b - L d) / 2 >= margin / 4 > 0`` (the bound of :mod:`lynxsim.plan.edges`).

The repair. Where a sample falls short, the robot stops at both vertices of the
path edge it lies on (there Ruckig moves from rest to rest, every joint
monotonic, inside the box the edge spans); where it already stops at both, the
edge's midpoint (on the certified path) becomes a stop too, which shrinks that
box. The motion is re-timed and checked again, at most ``max_repairs`` times,
then :class:`~lynxsim.plan.errors.TimingClearanceError`.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from lynxsim.errors import InvalidInputError
from lynxsim.plan.errors import PlanningError, TimingClearanceError
from lynxsim.plan.oracle import ClearanceOracle, FloatArray, query
from lynxsim.traj.kinds import TrajectoryKind
from lynxsim.traj.limits import JointBounds, JointLimits
from lynxsim.traj.ruckig_profile import ruckig_trajectory
from lynxsim.traj.trajectory import Segment, Trajectory
from lynxsim.traj.waypoints import Waypoints, check_bounds, resolve_waypoints

__all__ = ["DEFAULT_MAX_REPAIRS", "SPEED_SLACK", "TimedMotion", "TimedSegment", "time_paths"]

DEFAULT_MAX_REPAIRS = 6
"""Repair rounds before giving up [-]."""

SPEED_SLACK = 1e-6
"""Relative slack on the speed bound ``||v||_2`` (the limit check admits 1e-9) [-]."""


@dataclass(frozen=True)
class TimedSegment:
    """How one planning segment was timed and how clear its timed motion is.

    Attributes:
        start_s: When the segment starts in the trajectory [s].
        end_s: When it ends [s].
        stops: Vertices where the robot stops, ends included [-].
        midpoints: Vertices added by repairs [-].
        repairs: Repair rounds it needed [-].
        samples: Samples checked against the world [-].
        min_clearance_m: Smallest clearance of those samples [m] (``inf`` without motion).
        clearance_bound_m: Certified lower bound of the clearance between samples [m].
    """

    start_s: float
    end_s: float
    stops: int
    midpoints: int
    repairs: int
    samples: int
    min_clearance_m: float
    clearance_bound_m: float


@dataclass(frozen=True)
class TimedMotion:
    """A timed motion through planned paths.

    Attributes:
        trajectory: The motion, stopping at every segment's end.
        segments: One :class:`TimedSegment` per path.
    """

    trajectory: Trajectory
    segments: tuple[TimedSegment, ...]


@dataclass
class _Chunk:
    """Rest-to-rest motion through path vertices ``first..last`` of path ``path``."""

    path: int
    first: int
    last: int
    trajectory: Trajectory


@dataclass
class _Verdict:
    samples: int
    min_c: float
    bound: float
    failing: list[int]  # path edges (index of their first vertex) with a failing sample
    worst_t: float  # when the smallest clearance occurs, from the chunk's start [s]


def _screened(
    q: FloatArray,
    oracle: ClearanceOracle,
    screen: ClearanceOracle,
    grasped: bool,
    margin_m: float,
    step_m: float,
) -> FloatArray:
    """The exact clearances of ``q`` (N, n) wherever the verdict, minimum or bound need them.

    ``screen`` never exceeds ``oracle``: a sample whose screened clearance is at
    least half the margin passes exactly too, and the smallest clearance and the
    bound ``(c_i + c_{i+1} - step) / 2`` are found by asking ``oracle`` only for
    the samples (and neighbours) whose screened values could be at or below the
    best exact ones (branch and bound). Every sample not asked keeps its lower
    bound, above the minimum, so the verdict, minimum and bound are those of
    ``oracle`` on every sample.
    """
    low = query(screen, q, grasped)
    c = low.copy()
    known = np.zeros(len(q), dtype=bool)

    def ask(index: npt.NDArray[np.intp]) -> None:
        index = index[~known[index]]
        if index.size:
            c[index] = query(oracle, q[index], grasped)
            known[index] = True

    first = int(np.argmin(0.5 * (low[:-1] + low[1:] - step_m)))
    ask(np.concatenate([np.flatnonzero(low < 0.5 * margin_m), [int(np.argmin(low))],
                        [first, first + 1]]).astype(np.intp))  # fmt: skip
    while True:
        best = c[known].min() if known.any() else np.inf
        pair = 0.5 * (c[:-1] + c[1:] - step_m)
        both = known[:-1] & known[1:]
        best_pair = pair[both].min() if both.any() else np.inf
        need = np.flatnonzero(~known & (c <= best))
        pairs = np.flatnonzero(~both & (pair <= best_pair))
        wanted = np.unique(np.concatenate([need, pairs, pairs + 1]))
        if not (~known[wanted]).any():
            return c
        ask(wanted)


def _check_chunk(
    chunk: _Chunk,
    oracle: ClearanceOracle,
    grasped: bool,
    speed: float,
    lipschitz: float,
    margin_m: float,
    screen: ClearanceOracle | None = None,
) -> _Verdict:
    traj = chunk.trajectory
    duration = traj.duration
    n = max(2, math.ceil(duration * speed * lipschitz / (0.5 * margin_m)) + 1)
    t = np.linspace(0.0, duration, n)
    d = speed * duration / (n - 1)
    q = traj.sample(t).q
    c = (
        query(oracle, q, grasped)
        if screen is None
        else _screened(q, oracle, screen, grasped, margin_m, lipschitz * d)
    )
    bound = float(np.min(0.5 * (c[:-1] + c[1:] - lipschitz * d)))
    bad = c < 0.5 * margin_m
    edges = np.searchsorted(traj.waypoint_times, t[bad], side="right") - 1
    edges = np.clip(edges, 0, len(traj.segments) - 1) + chunk.first
    worst = int(np.argmin(c))
    return _Verdict(n, float(c[worst]), bound, sorted(set(edges.tolist())), float(t[worst]))


def _chunks(
    paths: list[FloatArray],
    stops: list[FloatArray],
    bounds: JointBounds,
    limits: JointLimits,
) -> list[_Chunk]:
    """Time every rest-to-rest stretch; each starts exactly where the previous one ends."""
    out: list[_Chunk] = []
    here: FloatArray | None = None
    for i, (path, stop) in enumerate(zip(paths, stops)):
        if path.shape[0] < 2:
            continue
        at = np.flatnonzero(stop)
        for a, b in itertools.pairwise(at.tolist()):
            q = np.array(path[a : b + 1])
            if here is not None:
                q[0] = here
            traj = ruckig_trajectory(q, pass_through=True, bounds=bounds, limits=limits)
            here = traj.sample(np.array([traj.duration])).q[0]
            out.append(_Chunk(i, int(a), int(b), traj))
    return out


def time_paths(
    paths: Sequence[FloatArray],
    grasped: Sequence[bool],
    oracle: ClearanceOracle,
    *,
    lipschitz: float,
    margin_m: float,
    bounds: JointBounds,
    limits: JointLimits,
    kind: TrajectoryKind = TrajectoryKind.RUCKIG,
    labels: Sequence[str] | None = None,
    max_repairs: int = DEFAULT_MAX_REPAIRS,
    pose_names: Sequence[str] | None = None,
    screen: ClearanceOracle | None = None,
) -> TimedMotion:
    """Time planned paths with Ruckig and check the timed motion clear (see the module).

    Args:
        paths: One path per planning segment, each (M_i, n) [rad], each starting
            where the previous one ends, every edge certified clear.
        grasped: Whether the payload is held on each path.
        oracle: The world.
        lipschitz: ``L`` [m/rad].
        margin_m: The planning margin [m]; timed samples keep half of it.
        bounds: The joints (n) and their ranges (those of the trajectory).
        limits: Joint velocity, acceleration and jerk limits (n joints).
        kind: The trajectory kind to label the result with.
        labels: Names of the segments for errors.
        max_repairs: Repair rounds before giving up.
        pose_names: Names of the poses the paths join (one more than paths): the
            trajectory's waypoints keep them, and the vertices between are named
            ``v1``, ``v2``, ... (default: ``P1``, ``P2``, ... for every vertex).
        screen: A world never more optimistic than ``oracle`` (a robot's sphere
            cover): ``oracle`` is asked only about the samples whose screened
            clearance could decide the verdict, the smallest clearance or the
            bound, which all come out as ``oracle`` alone gives them.

    Returns:
        The :class:`TimedMotion`.

    Raises:
        TimingClearanceError: A timed sample keeps less than ``margin / 2`` after
            every repair (names the segment).
        PlanningError: No path moves at all.
        InvalidInputError: Paths not of shape (M, n), or lengths that disagree.
        LimitViolationError: The motion breaks a limit (a bug of the timing).
    """
    if len(grasped) != len(paths):
        raise InvalidInputError(f"{len(paths)} paths need {len(paths)} grasped flags")
    names = tuple(labels) if labels is not None else tuple(str(i + 1) for i in range(len(paths)))
    if len(names) != len(paths):
        raise InvalidInputError(f"{len(paths)} paths need {len(paths)} labels")
    bounds = check_bounds(bounds)
    n = bounds.n_joints
    work = [np.array(p, dtype=float) for p in paths]
    for i, p in enumerate(work):
        if p.ndim != 2 or p.shape[1] != n or p.shape[0] < 1:
            raise InvalidInputError(f"path {i + 1} must have shape (M, {n}), got {p.shape}")
    if all(p.shape[0] < 2 for p in work):
        raise PlanningError("no segment moves: the start already is every segment's goal")
    stops = [np.zeros(p.shape[0], dtype=bool) for p in work]
    for s in stops:
        s[0] = s[-1] = True
    midpoints = [0] * len(work)
    repairs = [0] * len(work)
    speed = float(np.linalg.norm(limits.velocity)) * (1.0 + SPEED_SLACK)
    rounds = 0
    while True:
        chunks = _chunks(work, stops, bounds, limits)
        verdicts = [
            _check_chunk(ch, oracle, bool(grasped[ch.path]), speed, lipschitz, margin_m, screen)
            for ch in chunks
        ]
        failing = [(ch, v) for ch, v in zip(chunks, verdicts) if v.failing]
        if not failing:
            break
        if rounds == max_repairs:
            ch, v = min(failing, key=lambda cv: cv[1].min_c)
            start = sum(
                c.trajectory.duration for c in chunks if c.path == ch.path and c.first < ch.first
            )
            raise TimingClearanceError(
                start + v.worst_t, v.min_c, 0.5 * margin_m, rounds, names[ch.path]
            )
        rounds += 1
        for i in sorted({ch.path for ch, _ in failing}):
            repairs[i] += 1
            edges = sorted({k for ch, v in failing if ch.path == i for k in v.failing})
            insert: list[int] = []
            for k in edges:
                if stops[i][k] and stops[i][k + 1]:
                    insert.append(k)
                stops[i][k] = stops[i][k + 1] = True
            if insert:
                mids = 0.5 * (work[i][insert] + work[i][np.array(insert) + 1])
                work[i] = np.insert(work[i], np.array(insert) + 1, mids, axis=0)
                stops[i] = np.insert(stops[i], np.array(insert) + 1, True)
                midpoints[i] += len(insert)
    return _assemble(
        work, stops, chunks, verdicts, midpoints, repairs, bounds, limits, kind, pose_names
    )


def _vertex_names(
    paths: Sequence[FloatArray], pose_names: Sequence[str] | None
) -> list[str] | None:
    """Pose names at the ends of the paths, ``v1``, ``v2``, ... between (None: no names)."""
    if pose_names is None:
        return None
    if len(pose_names) != len(paths) + 1:
        raise InvalidInputError(
            f"{len(paths)} paths join {len(paths) + 1} poses, got {len(pose_names)} names"
        )
    names: list[str] = []
    via = 0
    for i, path in enumerate(paths):
        for k in range(len(path) - 1):
            if k == 0:
                names.append(pose_names[i])
            else:
                via += 1
                names.append(f"v{via}")
    names.append(pose_names[-1])
    return names


def _assemble(
    paths: list[FloatArray],
    stops: list[FloatArray],
    chunks: list[_Chunk],
    verdicts: list[_Verdict],
    midpoints: list[int],
    repairs: list[int],
    bounds: JointBounds,
    limits: JointLimits,
    kind: TrajectoryKind,
    pose_names: Sequence[str] | None = None,
) -> TimedMotion:
    """One trajectory from the chunks, and the per-segment report."""
    segments: list[Segment] = []
    q_parts: list[FloatArray] = []
    for ch in chunks:
        segments.extend(ch.trajectory.segments)
        q_parts.append(np.asarray(ch.trajectory.waypoints.q)[:-1])
    q_parts.append(np.asarray(chunks[-1].trajectory.waypoints.q)[-1:])
    q_all = np.concatenate(q_parts)
    names = _vertex_names(paths, pose_names)
    waypoints = resolve_waypoints(
        q_all if names is None or len(names) != len(q_all) else Waypoints(q_all, tuple(names)),
        bounds,
    )
    # Not checked again: each chunk's segments were checked against the same ranges and
    # limits by ruckig_trajectory (every order, 1-3, that any kind limits), and a
    # trajectory's check is that of its segments.
    trajectory = Trajectory(TrajectoryKind(kind), tuple(segments), waypoints, bounds, limits)
    report: list[TimedSegment] = []
    clock = 0.0
    for i, path in enumerate(paths):
        mine = [(ch, v) for ch, v in zip(chunks, verdicts) if ch.path == i]
        duration = sum(ch.trajectory.duration for ch, _ in mine)
        report.append(
            TimedSegment(
                start_s=clock,
                end_s=clock + duration,
                stops=int(np.count_nonzero(stops[i])) if path.shape[0] > 1 else 0,
                midpoints=midpoints[i],
                repairs=repairs[i],
                samples=sum(v.samples for _, v in mine),
                min_clearance_m=min((v.min_c for _, v in mine), default=math.inf),
                clearance_bound_m=min((v.bound for _, v in mine), default=math.inf),
            )
        )
        clock += duration
    return TimedMotion(trajectory, tuple(report))
