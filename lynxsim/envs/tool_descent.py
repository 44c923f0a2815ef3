"""The ``-v2`` tool action's search in joint space, compiled: no Python per step or row.

:func:`descend` is the damped Gauss-Newton search of
:mod:`lynxsim.envs.tool_action` (the candidate where the joint ranges, not the
reach, bound a request): it minimises ``|(pose(q) - request) / step|^2`` over
q1..q4 within the joint ranges and ``max_joint_jump`` of the command, starting
at the command. Compiled by numba, row by row, so that its cost is the rows'
own and not a fixed cost of ~40 NumPy calls per step of the search (which the
single env, with one row, paid in full). Each row is computed alone: one row
gives the same numbers whatever the other rows are (the single env and the
batched env agree bit for bit).

The tool pose and its Jacobian inside are the closed forms of
:func:`lynxsim.arm.tool_pose` and :func:`lynxsim.arm.jacobian` (the same
expressions; ``tests/envs/test_tool_descent.py`` holds them to those functions);
the targets the caller takes from the result are :func:`lynxsim.arm.tool_pose`'s.
"""

from __future__ import annotations

import math

import numpy as np
import numpy.typing as npt
from numba import njit

from lynxsim.arm import LYNX_ARM

__all__ = ["DescentLimits", "descend", "kernel_jacobian", "kernel_pose"]

FloatArray = npt.NDArray[np.float64]

_STEPS = 20
"""Damped Gauss-Newton steps of the search."""
_DAMPING = 1e-3
"""Initial Levenberg-Marquardt damping [(action units / rad)^2]."""
_CONVERGED = 1e-10
"""A search step that brings the squared miss down by less [action units^2] ends it."""
_MAX_DAMPING = 1e6
"""A search whose damping grew past this (steps kept failing) ends [-]."""
_INSIDE = 1e-9
"""Relative margin inside the joint ranges and the jump limit of the search."""

_L2, _L3, _LT, _H = (
    LYNX_ARM.upper_arm,
    LYNX_ARM.forearm,
    LYNX_ARM.tool_length,
    LYNX_ARM.shoulder_height,
)


@njit(cache=True, error_model="numpy")
def _pose_into(q, out):  # type: ignore[no-untyped-def]  # numba
    """Tool point and pitch of joints q (5,) into out (4,): :func:`lynxsim.arm.tool_pose`."""
    a23 = q[1] + q[2]
    pitch = a23 + q[3]
    reach = _L2 * np.cos(q[1]) + _L3 * np.cos(a23) + _LT * np.cos(pitch)
    height = _H + _L2 * np.sin(q[1]) + _L3 * np.sin(a23) + _LT * np.sin(pitch)
    out[0] = reach * np.cos(q[0])
    out[1] = reach * np.sin(q[0])
    out[2] = height
    out[3] = pitch


@njit(cache=True, error_model="numpy")
def _jacobian_into(q, out):  # type: ignore[no-untyped-def]  # numba
    """d(x, y, z, pitch)/d(q1..q4) of joints q (5,) into out (4, 4): ``lynxsim.arm.jacobian``."""
    a2, a23 = q[1], q[1] + q[2]
    a234 = a23 + q[3]
    reach = _L2 * np.cos(a2) + _L3 * np.cos(a23) + _LT * np.cos(a234)
    # d(reach)/d(q2, q3, q4) and d(height)/d(q2, q3, q4): partial sums from the tip.
    dr2 = -(_L2 * np.sin(a2) + _L3 * np.sin(a23) + _LT * np.sin(a234))
    dr3 = -(_L3 * np.sin(a23) + _LT * np.sin(a234))
    dr4 = -_LT * np.sin(a234)
    dz2 = _L2 * np.cos(a2) + _L3 * np.cos(a23) + _LT * np.cos(a234)
    dz3 = _L3 * np.cos(a23) + _LT * np.cos(a234)
    dz4 = _LT * np.cos(a234)
    c1, s1 = np.cos(q[0]), np.sin(q[0])
    out[0, 0] = -reach * np.sin(q[0])
    out[1, 0] = reach * np.cos(q[0])
    out[2, 0] = 0.0
    out[3, 0] = 0.0
    out[0, 1], out[0, 2], out[0, 3] = dr2 * c1, dr3 * c1, dr4 * c1
    out[1, 1], out[1, 2], out[1, 3] = dr2 * s1, dr3 * s1, dr4 * s1
    out[2, 1], out[2, 2], out[2, 3] = dz2, dz3, dz4
    out[3, 1], out[3, 2], out[3, 3] = 1.0, 1.0, 1.0


@njit(cache=True, error_model="numpy")
def _solve_spd(a, b, out):  # type: ignore[no-untyped-def]  # numba
    """Solve ``a out = b`` for a symmetric positive definite ``a`` (4, 4), by Cholesky."""
    n = 4
    low = np.zeros((n, n))
    for i in range(n):
        for j in range(i + 1):
            s = a[i, j]
            for k in range(j):
                s -= low[i, k] * low[j, k]
            low[i, j] = math.sqrt(s) if i == j else s / low[j, j]
    y = np.empty(n)
    for i in range(n):
        s = b[i]
        for k in range(i):
            s -= low[i, k] * y[k]
        y[i] = s / low[i, i]
    for i in range(n - 1, -1, -1):
        s = y[i]
        for k in range(i + 1, n):
            s -= low[k, i] * out[k]
        out[i] = s / low[i, i]


@njit(cache=True, error_model="numpy")
def _descend_rows(q_cmd, request, w, q_min, q_max, jump, pitch_lo, pitch_hi):  # type: ignore[no-untyped-def]  # numba
    """The search of :func:`descend`, row by row; the joints found, (m, 5)."""
    m = request.shape[0]
    out = np.empty((m, 5))
    pose = np.empty(4)
    jac = np.empty((4, 4))
    jf = np.empty((4, 4))
    normal = np.empty((4, 4))
    grad = np.empty(4)
    dq = np.empty(4)
    error = np.empty(4)
    trial_error = np.empty(4)
    lo = np.empty(4)
    hi = np.empty(4)
    free = np.empty(4, dtype=np.bool_)
    for r in range(m):
        q = q_cmd[r].copy()
        q[4] = request[r, 4]
        for i in range(4):
            lo[i] = max(q_min[i], q_cmd[r, i] - jump)
            hi[i] = min(q_max[i], q_cmd[r, i] + jump)
        _pose_into(q, pose)
        cost = 0.0
        for i in range(4):
            error[i] = (request[r, i] - pose[i]) * w[i]
            cost += error[i] * error[i]
        damping = _DAMPING
        for _ in range(_STEPS):
            _jacobian_into(q, jac)
            for k in range(4):
                for i in range(4):
                    jac[k, i] *= w[k]
            for i in range(4):
                free[i] = True
            for _ in range(2):  # solve, hold the bounded variables that would leave, solve again
                for k in range(4):
                    for i in range(4):
                        jf[k, i] = jac[k, i] if free[i] else 0.0
                for i in range(4):
                    g = 0.0
                    for k in range(4):
                        g += jf[k, i] * error[k]
                    grad[i] = g
                    for j in range(4):
                        s = 0.0
                        for k in range(4):
                            s += jf[k, i] * jf[k, j]
                        normal[i, j] = s + (damping if i == j else 0.0)
                _solve_spd(normal, grad, dq)
                for i in range(4):
                    if not free[i]:
                        dq[i] = 0.0
                for i in range(4):
                    if (q[i] <= lo[i] and dq[i] < 0.0) or (q[i] >= hi[i] and dq[i] > 0.0):
                        free[i] = False
            trial = q.copy()
            for i in range(4):
                trial[i] = min(max(q[i] + dq[i], lo[i]), hi[i])
            # Into the pitch range by the wrist (pitch = q2 + q3 + q4), else rejected.
            bent = trial[1] + trial[2]
            wrist = min(max(bent + trial[3], pitch_lo), pitch_hi) - bent
            trial[3] = min(max(wrist, lo[3]), hi[3])
            pitch = bent + trial[3]
            _pose_into(trial, pose)
            trial_cost = 0.0
            for i in range(4):
                trial_error[i] = (request[r, i] - pose[i]) * w[i]
                trial_cost += trial_error[i] * trial_error[i]
            if pitch < pitch_lo or pitch > pitch_hi:
                trial_cost = np.inf
            better = trial_cost < cost
            # Done when a step gains next to nothing or the damping has grown past any
            # useful step (the step is still taken).
            done = (better and cost - trial_cost < _CONVERGED) or damping > _MAX_DAMPING
            if better:
                q[:] = trial
                error[:] = trial_error
                cost = trial_cost
                damping *= 0.3
            else:
                damping *= 10.0
            if done:
                break
        out[r] = q
    return out


class DescentLimits:
    """What the search needs of the action's limits, as arrays (made once per controller).

    Args:
        steps: Move per action unit of x, y, z and pitch, (4,) [m, m, m, rad].
        pitch_range: ``(min, max)`` tool pitch [rad].
        max_joint_jump: Largest change of q1..q4 in one step [rad].
    """

    def __init__(
        self, steps: FloatArray, pitch_range: tuple[float, float], max_joint_jump: float
    ) -> None:
        self.weights = 1.0 / np.asarray(steps, dtype=np.float64)[:4]
        self.q_min = np.asarray(LYNX_ARM.q_min[:4], dtype=np.float64)
        self.q_max = np.asarray(LYNX_ARM.q_max[:4], dtype=np.float64)
        self.jump = float(max_joint_jump) * (1.0 - _INSIDE)
        self.pitch_range = (float(pitch_range[0]), float(pitch_range[1]))


def descend(q_cmd: FloatArray, request: FloatArray, limits: DescentLimits) -> FloatArray:
    """The joints nearest the requests in action units, by a search in joint space.

    Damped Gauss-Newton on ``|(pose(q) - request) / step|^2`` over q1..q4 within
    the joint ranges and ``max_joint_jump`` of the command (a box: the reach
    boundary is the elbow's straight limit, the pitch limits are the wrist's),
    starting at the command; variables at a bound that the step pushes out are
    held there, and a step's pitch is brought into the pitch range by the wrist.
    Each step is kept only if it brings the pose nearer.

    Args:
        q_cmd: Commanded joints, shape (m, 5) [rad].
        request: Requested targets ``(x, y, z, pitch, roll)``, shape (m, 5) [m, rad].
        limits: The action's limits (:class:`DescentLimits`).

    Returns:
        The joints found, shape (m, 5) [rad]; the roll is the request's.
    """
    lo, hi = limits.pitch_range
    out: FloatArray = _descend_rows(
        np.ascontiguousarray(q_cmd, dtype=np.float64),
        np.ascontiguousarray(request, dtype=np.float64),
        limits.weights,
        limits.q_min,
        limits.q_max,
        limits.jump,
        lo,
        hi,
    )
    return out


def kernel_pose(q: FloatArray) -> FloatArray:
    """The compiled tool pose ``(x, y, z, pitch)`` of joints (5,), shape (4,) (for tests)."""
    out = np.empty(4)
    _pose_into(np.asarray(q, dtype=np.float64), out)
    return out


def kernel_jacobian(q: FloatArray) -> FloatArray:
    """The compiled d(x, y, z, pitch)/d(q1..q4) of joints (5,), shape (4, 4) (for tests)."""
    out = np.empty((4, 4))
    _jacobian_into(np.asarray(q, dtype=np.float64), out)
    return out
