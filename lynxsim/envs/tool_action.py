"""The ``-v2`` tool action: normalised actions to tool targets and joints, N envs at once.

A ``-v2`` tool action moves the commanded tool target ``(x, y, z, pitch, roll)``
(tool point [m], tool pitch and wrist roll [rad]) by ``action * step``. The
request is clipped to a box, the pitch range and the roll joint's range, then
solved by the analytic IK (:func:`lynxsim.arm.ik`'s closed form and choice,
:func:`lynxsim.arm.ik.ik_unchecked`: the solution nearest the current
command). A request the controller cannot take (out of reach, outside the
joint ranges, or a solution more than ``max_joint_jump`` from the current
command: a configuration flip) goes to the **nearest feasible target**, in
action units (position / ``position_step``, pitch / ``pitch_step``); the roll
never limits the reach and is always taken.

The nearest target is searched among candidates, all at once:

- for each of :data:`PITCH_OFFSETS` (pitches around the requested one) and the
  current pitch, the requested point, and the point nearest it on the boundary
  of the reach at that pitch (closed form: the wrist point drawn radially onto
  the sphere the upper arm and forearm reach, which for a fixed pitch is the
  exact nearest reachable point, :func:`reach_projection`);
- the current point at the requested pitch, and the current target itself;
- the result of a damped Gauss-Newton search in joint space from the current
  command, within the joint ranges and the jump limit (where the joint
  ranges, not the reach, bound the request).

A candidate the controller rejects is replaced by the farthest feasible point
on the segment to it from the current target (bisection; the current target
is feasible), unless no point of that segment is nearer the request than the
best feasible candidate. The candidate nearest the request wins: the target slides along
the reach boundary and the joint and pitch limits instead of stopping. Tested
against brute force (``tests/envs/test_tool_action.py``): no feasible target
among 20,000 sampled around a request is nearer than the result by more than
an eighth of a step. Near the edge the nearest target may tilt the pitch (a
pitch step moves the reach by up to 10 mm); a policy that keeps pushing
outwards tilts the gripper up as it slides.

:func:`tool_targets` is pure and vectorised (arrays of shape (N, ...), no
state, no MuJoCo): the single env calls it with N = 1, a batched env with N.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
import numpy.typing as npt

from lynxsim.arm import LYNX_ARM, jacobian, tool_pose
from lynxsim.arm.ik import ik_unchecked
from lynxsim.envs.control import TargetFallback, TargetStatus, ToolSpaceController
from lynxsim.errors import InvalidInputError

__all__ = [
    "PITCH_OFFSETS",
    "ToolLimits",
    "ToolRollController",
    "ToolTargets",
    "reach_projection",
    "tool_targets",
]

FloatArray = npt.NDArray[np.float64]
StatusArray = npt.NDArray[np.int8]

PITCH_OFFSETS = np.linspace(-2.0, 2.0, 17)
"""Pitches tried around the requested one, in pitch steps (a quarter step apart)."""
_BISECTIONS = 8
"""Halvings of the search along a segment for its farthest feasible point (1/256)."""
_REACH_MARGIN_M = 1e-9
"""A point projected onto the reach boundary lies this far inside it [m]."""
_DESCENT_STEPS = 20
"""Damped Gauss-Newton steps of the search in joint space."""
_DAMPING = 1e-3
"""Initial Levenberg-Marquardt damping [(action units / rad)^2]."""
_CONVERGED = 1e-10
"""A search step that brings the squared miss down by less [action units^2] ends it."""
_MAX_DAMPING = 1e6
"""A search whose damping grew past this (steps kept failing) ends [-]."""
_INSIDE = 1e-9
"""Relative margin inside the joint ranges and the jump limit of the joint-space search."""


def _positive(value: object, name: str) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise InvalidInputError(f"{name} must be a positive number, got {value!r}")
    v = float(value)
    if not (math.isfinite(v) and v > 0.0):
        raise InvalidInputError(f"{name} must be a positive number, got {value!r}")
    return v


@dataclass(frozen=True)
class ToolLimits:
    """Step sizes and limits of the ``-v2`` tool action.

    Attributes:
        position_step: Tool-point move for an action of 1 [m], > 0.
        pitch_step: Pitch change for an action of 1 [rad], > 0.
        roll_step: Wrist-roll change for an action of 1 [rad], > 0.
        box_lower: Lower corner of the box the tool point is clipped to, (3,) [m].
        box_upper: Upper corner, (3,) [m].
        pitch_range: ``(min, max)`` tool pitch [rad].
        roll_range: ``(min, max)`` wrist roll [rad] (default: the roll joint's range,
            0 to just under 2 pi, which the IK would wrap to 0).
        max_joint_jump: Largest change of joints q1..q4 in one step [rad], > 0.

    Raises:
        InvalidInputError: A step not positive, or an empty box or range.
    """

    position_step: float
    pitch_step: float
    roll_step: float
    box_lower: tuple[float, float, float]
    box_upper: tuple[float, float, float]
    pitch_range: tuple[float, float] = (-math.pi / 2, math.pi / 2)
    roll_range: tuple[float, float] = (LYNX_ARM.q_min[4], math.nextafter(LYNX_ARM.q_max[4], 0.0))
    max_joint_jump: float = 0.5

    def __post_init__(self) -> None:
        for name in ("position_step", "pitch_step", "roll_step", "max_joint_jump"):
            object.__setattr__(self, name, _positive(getattr(self, name), name))
        lo, hi = self.box_lower, self.box_upper
        if len(lo) != 3 or len(hi) != 3 or any(a > b for a, b in zip(lo, hi)):
            raise InvalidInputError(f"empty target box {lo} .. {hi}")
        for name in ("pitch_range", "roll_range"):
            a, b = getattr(self, name)
            if not (math.isfinite(a) and math.isfinite(b) and a <= b):
                raise InvalidInputError(f"{name} must be a finite (min, max), got {(a, b)}")

    @property
    def steps(self) -> FloatArray:
        """Move per action unit of the five components, shape (5,) [m, m, m, rad, rad]."""
        s = self.position_step
        return np.array([s, s, s, self.pitch_step, self.roll_step])

    @property
    def lower(self) -> FloatArray:
        """Lower limits of the five components, shape (5,)."""
        return np.array([*self.box_lower, self.pitch_range[0], self.roll_range[0]])

    @property
    def upper(self) -> FloatArray:
        """Upper limits of the five components, shape (5,)."""
        return np.array([*self.box_upper, self.pitch_range[1], self.roll_range[1]])


class ToolTargets(NamedTuple):
    """What :func:`tool_targets` made of N actions.

    Attributes:
        target: The new commanded targets ``(x, y, z, pitch, roll)``, shape (N, 5) [m, rad].
        q: Their joints (the servo targets), shape (N, 5) [rad].
        status: Why each request was not taken in full, shape (N,) int8
            (:class:`~lynxsim.envs.control.TargetStatus` values; ACCEPTED: taken).
        request: The requested targets, before any clipping, shape (N, 5).
        correction: ``target - request``: what changed and by how much, shape (N, 5)
            [m, rad] (zero where the request was taken in full).
    """

    target: FloatArray
    q: FloatArray
    status: StatusArray
    request: FloatArray
    correction: FloatArray


def _solve(
    points: FloatArray, q_ref: FloatArray, max_jump: float
) -> tuple[FloatArray, StatusArray]:
    """Joints of targets (n, 5) nearest ``q_ref`` (n, 5), and the controller's status (n,)."""
    q, status = ik_unchecked(points[:, :3], points[:, 3], points[:, 4], q_ref)
    jumped = (status == TargetStatus.ACCEPTED) & (np.abs(q[:, :4] - q_ref[:, :4]) > max_jump).any(
        axis=1
    )
    status[jumped] = TargetStatus.JOINT_JUMP
    return q, status


def reach_projection(position: FloatArray, pitch: FloatArray) -> FloatArray:
    """The tool points nearest ``position`` within the arm's reach at a fixed pitch.

    For a fixed pitch the reachable tool points (joint ranges aside) are those
    whose wrist point lies within the upper arm and forearm's reach of the
    shoulder: in the arm's vertical plane a disc, the same on both sides of the
    base (:func:`lynxsim.arm.ik.ik_candidates`). A point outside is drawn
    radially onto the disc's edge, which is the nearest reachable point.

    Args:
        position: Tool points, shape (n, 3) [m].
        pitch: Tool pitches, shape (n,) [rad].

    Returns:
        The projected tool points, shape (n, 3) [m] (points within reach unchanged).
    """
    g = LYNX_ARM
    x, y, z = position[:, 0], position[:, 1], position[:, 2]
    rho = np.hypot(x, y)
    heading = np.where(rho > 0.0, np.arctan2(y, x), 0.0)
    folded = np.abs(heading) > np.pi / 2
    base = np.where(folded, heading - np.copysign(np.pi, heading), heading)
    reach = np.where(folded, -rho, rho)
    r_w = reach - g.tool_length * np.cos(pitch)
    z_w = z - g.shoulder_height - g.tool_length * np.sin(pitch)
    d = np.hypot(r_w, z_w)
    outer = g.upper_arm + g.forearm - _REACH_MARGIN_M
    inner = abs(g.upper_arm - g.forearm) + _REACH_MARGIN_M
    outside = (d > outer) | ((d < inner) & (d > 0.0))
    scale = np.where(outside, np.clip(d, inner, outer) / np.where(d > 0.0, d, 1.0), 1.0)
    reach_new = r_w * scale + g.tool_length * np.cos(pitch)
    z_new = z_w * scale + g.shoulder_height + g.tool_length * np.sin(pitch)
    out = np.stack([reach_new * np.cos(base), reach_new * np.sin(base), z_new], axis=-1)
    return np.where(outside[:, None], out, position)


def _farthest(
    start: FloatArray, end: FloatArray, q_ref: FloatArray, max_jump: float
) -> tuple[FloatArray, FloatArray]:
    """The farthest feasible points on segments from feasible ``start`` to ``end`` (n, 5).

    Returns:
        The points (``start`` where no fraction of the segment is feasible) and
        their joints, shapes (n, 5).
    """
    n = start.shape[0]
    low, high = np.zeros(n), np.ones(n)
    best, best_q = start.copy(), q_ref.copy()
    for _ in range(_BISECTIONS):
        mid = 0.5 * (low + high)
        point = start + mid[:, None] * (end - start)
        q, status = _solve(point, q_ref, max_jump)
        ok = status == TargetStatus.ACCEPTED
        low = np.where(ok, mid, low)
        high = np.where(ok, high, mid)
        best[ok] = point[ok]
        best_q[ok] = q[ok]
    return best, best_q


def _pose(q: FloatArray) -> FloatArray:
    """Tool point and pitch of joints (n, 5), shape (n, 4)."""
    p = tool_pose(q)
    return np.concatenate([p.position, p.pitch[:, None]], axis=1)


def _descend(
    q_cmd: FloatArray, request: FloatArray, limits: ToolLimits
) -> tuple[FloatArray, FloatArray]:
    """The joints nearest the requests in action units, by a search in joint space.

    Damped Gauss-Newton on ``|(pose(q) - request) / step|^2`` over q1..q4 within
    the joint ranges and ``max_joint_jump`` of the command (a box: the reach
    boundary is the elbow's straight limit, the pitch limits are the wrist's),
    starting at the command; variables at a bound that the step pushes out are
    held there, and a step's pitch is brought into the pitch range by the wrist.
    Each step is kept only if it brings the pose nearer.

    Returns:
        The tool targets (m, 5) and their joints (m, 5); the roll is the request's.
    """
    m = request.shape[0]
    w = 1.0 / limits.steps[:4]
    jump = limits.max_joint_jump * (1.0 - _INSIDE)
    lo = np.maximum(np.asarray(LYNX_ARM.q_min[:4]), q_cmd[:, :4] - jump)
    hi = np.minimum(np.asarray(LYNX_ARM.q_max[:4]), q_cmd[:, :4] + jump)
    pitch_lo, pitch_hi = limits.pitch_range
    q = q_cmd.copy()
    q[:, 4] = request[:, 4]
    error = (request[:, :4] - _pose(q)) * w
    cost = np.einsum("ij,ij->i", error, error)
    damping = np.full(m, _DAMPING)
    done = np.zeros(m, dtype=bool)
    eye = np.eye(4)
    for _ in range(_DESCENT_STEPS):
        if done.all():
            break
        jac = jacobian(q)[:, :, :4] * w[:, None]
        free = np.ones((m, 4), dtype=bool)
        for _ in range(2):  # solve, hold the bounded variables that would leave, solve again
            jf = jac * free[:, None, :]
            normal = np.einsum("nki,nkj->nij", jf, jf) + damping[:, None, None] * eye
            dq = np.linalg.solve(normal, np.einsum("nki,nk->ni", jf, error)[..., None])[..., 0]
            dq *= free
            free &= ~(((q[:, :4] <= lo) & (dq < 0.0)) | ((q[:, :4] >= hi) & (dq > 0.0)))
        trial = q.copy()
        trial[:, :4] = np.clip(q[:, :4] + dq, lo, hi)
        # Into the pitch range by the wrist (pitch = q2 + q3 + q4), else rejected.
        bent = trial[:, 1] + trial[:, 2]
        wrist = np.clip(bent + trial[:, 3], pitch_lo, pitch_hi) - bent
        trial[:, 3] = np.clip(wrist, lo[:, 3], hi[:, 3])
        pitch = bent + trial[:, 3]
        trial_error = (request[:, :4] - _pose(trial)) * w
        trial_cost = np.einsum("ij,ij->i", trial_error, trial_error)
        trial_cost[(pitch < pitch_lo) | (pitch > pitch_hi)] = np.inf
        better = (trial_cost < cost) & ~done
        # A row is done (and left alone: rows never depend on each other) when a step
        # gains next to nothing or the damping has grown past any useful step.
        done |= (better & (cost - trial_cost < _CONVERGED)) | (damping > _MAX_DAMPING)
        q[better] = trial[better]
        error[better] = trial_error[better]
        cost = np.where(better, trial_cost, cost)
        damping = np.where(better, 0.3 * damping, 10.0 * damping)
    return np.concatenate([_pose(q), q[:, 4:]], axis=1), q


def _nearest(
    current: FloatArray, q_cmd: FloatArray, request: FloatArray, limits: ToolLimits
) -> tuple[FloatArray, FloatArray]:
    """The feasible targets nearest the requests (m, 5) and their joints (module docstring)."""
    m = request.shape[0]
    lo, hi = limits.pitch_range
    pitches = np.concatenate(
        [request[:, 3:4] + limits.pitch_step * PITCH_OFFSETS, current[:, 3:4]], axis=1
    )
    pitches = np.clip(pitches, lo, hi)  # (m, P)
    p = pitches.shape[1]
    flat_pitch = pitches.reshape(-1)
    raw = np.repeat(request[:, :3], p, axis=0)
    projected = np.clip(
        reach_projection(raw, flat_pitch), limits.box_lower, limits.box_upper
    ).reshape(m, p, 3)
    cand = np.empty((m, 2 * p + 3, 5))
    cand[:, :p, :3] = raw.reshape(m, p, 3)
    cand[:, p : 2 * p, :3] = projected
    cand[:, : 2 * p, 3] = np.tile(pitches, 2)
    cand[:, 2 * p, :3] = current[:, :3]
    cand[:, 2 * p, 3] = request[:, 3]
    cand[:, :, 4] = request[:, None, 4]
    descended, _ = _descend(q_cmd, request, limits)
    cand[:, 2 * p + 1, :4] = np.clip(descended[:, :4], limits.lower[:4], limits.upper[:4])
    cand[:, 2 * p + 2, :4] = current[:, :4]  # feasible: the fallback
    k = cand.shape[1]
    flat = cand.reshape(-1, 5)
    starts = np.repeat(current, k, axis=0)
    refs = np.repeat(q_cmd, k, axis=0)
    q, status = _solve(flat, refs, limits.max_joint_jump)
    scale = limits.steps[:4]
    wanted = np.repeat(request, k, axis=0)[:, :4] / scale
    miss = np.linalg.norm(flat[:, :4] / scale - wanted, axis=1)
    ok = status == TargetStatus.ACCEPTED
    # The best feasible miss of each row so far (the current target is feasible) ...
    best = np.minimum(
        np.linalg.norm((current[:, :4] - request[:, :4]) / scale, axis=1),
        np.where(ok, miss, np.inf).reshape(m, k).min(axis=1),
    )
    # ... and a rejected candidate is searched only if its segment can come nearer.
    start, end = starts[:, :4] / scale, flat[:, :4] / scale
    span = end - start
    along = np.einsum("ij,ij->i", wanted - start, span) / np.maximum(
        np.einsum("ij,ij->i", span, span), 1e-300
    )
    closest = start + np.clip(along, 0.0, 1.0)[:, None] * span
    bound = np.linalg.norm(closest - wanted, axis=1)
    bad = np.flatnonzero(~ok & (bound < np.repeat(best, k)))
    if bad.size:
        starts_bad = starts[bad].copy()
        starts_bad[:, 4] = flat[bad, 4]  # the roll is always taken
        flat[bad], q[bad] = _farthest(starts_bad, flat[bad], refs[bad], limits.max_joint_jump)
        ok[bad] = True
        miss[bad] = np.linalg.norm(flat[bad, :4] / scale - wanted[bad], axis=1)
    miss[~ok] = np.inf
    pick = np.argmin(miss.reshape(m, k), axis=1) + np.arange(m) * k
    return flat[pick], q[pick]


def tool_targets(
    target: npt.ArrayLike, q_cmd: npt.ArrayLike, action: npt.ArrayLike, limits: ToolLimits
) -> ToolTargets:
    """Move N commanded tool targets by N ``-v2`` actions (module docstring).

    Pure and vectorised: row i depends on row i of the inputs only, and one row
    gives the same numbers whatever the other rows are.

    Args:
        target: Current commanded targets ``(x, y, z, pitch, roll)``, shape (N, 5)
            [m, rad]; feasible (each the target of ``q_cmd``).
        q_cmd: Current commanded joints, shape (N, 5) [rad].
        action: Actions, shape (N, A) with A >= 5: columns 0-4 move x, y, z, pitch
            and roll (+1 = + one step); further columns (the gripper) are ignored.
            Values are clipped to [-1, 1]; they must be finite.
        limits: Steps and limits.

    Returns:
        The new targets, their joints, statuses, requests and corrections.

    Raises:
        InvalidInputError: Shapes that do not match (N, 5), (N, 5), (N, >= 5).
    """
    t = np.asarray(target, dtype=np.float64)
    q0 = np.asarray(q_cmd, dtype=np.float64)
    a = np.asarray(action, dtype=np.float64)
    if t.ndim != 2 or t.shape[1] != 5 or q0.shape != t.shape:
        raise InvalidInputError(
            f"target and q_cmd must have shape (N, 5), got {t.shape} and {q0.shape}"
        )
    if a.ndim != 2 or a.shape[0] != t.shape[0] or a.shape[1] < 5:
        raise InvalidInputError(f"action must have shape ({t.shape[0]}, >= 5), got {a.shape}")
    request = t + np.clip(a[:, :5], -1.0, 1.0) * limits.steps
    clipped = np.clip(request, limits.lower, limits.upper)
    q, status = _solve(clipped, q0, limits.max_joint_jump)
    new = clipped.copy()
    bad = np.flatnonzero(status != TargetStatus.ACCEPTED)
    if bad.size:
        new[bad], q[bad] = _nearest(t[bad], q0[bad], clipped[bad], limits)
    return ToolTargets(new, q, status, request, new - request)


class ToolRollController(ToolSpaceController):
    """The ``-v2`` tool-space controller of one env: :func:`tool_targets` with N = 1.

    A :class:`~lynxsim.envs.control.ToolSpaceController` whose wrist roll moves
    with the action and whose infeasible requests go to the nearest feasible
    target; :attr:`roll` is the commanded roll.

    Args:
        limits: Steps and limits of the action.

    Attributes:
        correction: After :meth:`apply`: commanded minus requested target
            ``(x, y, z, pitch, roll)`` [m, rad] (zeros when taken in full).
    """

    def __init__(self, limits: ToolLimits) -> None:
        super().__init__(
            limits.position_step,
            limits.pitch_step,
            0.5 * (limits.roll_range[0] + limits.roll_range[1]),
            limits.box_lower,
            limits.box_upper,
            limits.pitch_range,
            limits.max_joint_jump,
            TargetFallback.NEAREST,
        )
        self.limits = limits
        self.roll_step = limits.roll_step
        self.correction: tuple[float, ...] = (0.0,) * 5

    def reset(self, q: Sequence[float]) -> None:
        """Command the joints ``q`` (5 values [rad]), the tool pose and roll they give."""
        super().reset(q)
        self.roll = self.q_cmd[4]
        self.correction = (0.0,) * 5

    def apply(self, action: Sequence[float]) -> TargetStatus:
        """Move the target by an action ``(dx, dy, dz, dpitch[, droll])`` in [-1, 1].

        Without ``droll`` (a dry run of a planned route) the roll is held. Further
        values (the gripper) are ignored.

        Returns:
            ACCEPTED, or why the request could not be taken in full (then the
            target went to the nearest feasible one: :attr:`correction`,
            :attr:`shortfall_m` and :attr:`shortfall_rad` say by how much).
        """
        return self.apply_many([self], [action])[0]

    @staticmethod
    def apply_many(
        controllers: Sequence[ToolRollController], actions: Sequence[Sequence[float]]
    ) -> list[TargetStatus]:
        """:meth:`apply` of each controller to its action, in one :func:`tool_targets` call.

        The controllers must share :attr:`limits`; each ends as its own
        :meth:`apply` would leave it (:func:`tool_targets` is row by row).
        """
        limits = controllers[0].limits
        if any(c.limits != limits for c in controllers):
            raise InvalidInputError("controllers applied together must share their limits")
        arm = [[*a[:5]] if len(a) >= 5 else [*a[:4], 0.0] for a in actions]
        out = tool_targets(
            np.array([[*c.target, c.roll] for c in controllers]),
            np.array([c.q_cmd for c in controllers]),
            np.array(arm),
            limits,
        )
        targets, joints = out.target.tolist(), out.q.tolist()
        corrections, statuses = out.correction.tolist(), out.status.tolist()
        for c, target, q, correction in zip(controllers, targets, joints, corrections, strict=True):
            x, y, z, pitch, roll = target
            c.target = (x, y, z, pitch)
            c.roll = roll
            c.q_cmd = tuple(q)
            dx, dy, dz, d_pitch, d_roll = correction
            c.correction = (dx, dy, dz, d_pitch, d_roll)
            c.shortfall_m = math.sqrt(dx * dx + dy * dy + dz * dz)
            c.shortfall_rad = abs(d_pitch)
        return [TargetStatus(int(v)) for v in statuses]
