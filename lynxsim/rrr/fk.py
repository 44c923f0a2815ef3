"""Forward kinematics of the 3-RRR robot: platform poses from the actuated angles.

With the actuated angles known, the elbows ``E_i`` are fixed and the platform
must put each joint ``P_i`` on the circle of radius ``L`` about ``E_i``: the
forward kinematics of a 3-RPR robot with equal leg lengths, which has at most
six real solutions (**assembly modes**). Two numerical routes:

* :func:`fk_all` finds every assembly mode. Subtracting leg 1's closure
  from those of legs 2 and 3 leaves two equations linear in the platform
  centre; eliminating it leaves one polynomial in ``t = tan((alpha - a0) / 2)``
  (degree 6 times the spurious factor ``(1 + t²)²``). Its real roots, from
  batched companion-matrix eigenvalues, are polished by Newton's method on the
  three closures and de-duplicated. Near a parallel singularity two roots
  merge into one (or a nearly real complex pair), which is reported once.
* :func:`fk_near` and :func:`fk_path` follow one assembly mode by Newton's
  method from a nearby pose (branch continuation), as a controller would.

For the report's robot, random reachable configurations have 2, 4 or 6
assembly modes (see the tests and ``benchmarks/bench_rrr_workspace.py``).
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np
import numpy.typing as npt

from lynxsim.angles import wrap_angle
from lynxsim.bounds import MAX_COORDINATE_M, MAX_SAMPLES
from lynxsim.errors import InvalidInputError
from lynxsim.inputs import count
from lynxsim.rrr.geometry import (
    RRR_ROBOT,
    RRRGeometry,
    _platform_joints,
    as_pose_array,
    as_theta_array,
    check_rrr_geometry,
    platform_joints,
)
from lynxsim.rrr.jacobian import det3
from lynxsim.rrr.modes import mode_index

__all__ = [
    "CLOSURE_TOL",
    "MAX_ASSEMBLY_MODES",
    "FKResult",
    "FKSolutions",
    "elbow_points",
    "fk_all",
    "fk_near",
    "fk_path",
    "loop_residual",
]

FloatArray = npt.NDArray[np.float64]

MAX_ASSEMBLY_MODES = 6
"""Largest number of real forward-kinematics solutions of a planar 3-RRR robot."""

CLOSURE_TOL = 1e-11
"""Largest loop-closure residual ``| |P_i - E_i| - L |`` of a converged pose [m]."""

_DEDUP_M = 1e-7
"""Poses closer than this [m] (and [rad] in alpha) are one solution."""

_ALPHA0 = 0.6180339887498949
"""Offset of the polynomial's parameter [rad]: alpha = _ALPHA0 + pi is its point at infinity."""

_REAL_ROOT_TOL = 1e-4
"""Roots with a relative imaginary part up to this are tried (Newton decides)."""

_MAX_STEP = 0.02
"""Largest Newton step [m] (alpha counted as arc length at the platform radius)."""


class FKSolutions(NamedTuple):
    """Every assembly mode of a batch of actuated-angle triples, batch shape ``B``.

    Attributes:
        pose: Platform poses, shape B + (6, 3) [m, m, rad], sorted by alpha,
            NaN-padded after the first ``num_solutions``.
        num_solutions: Number of solutions found, shape B.
        mode: Working mode (0..7) of each solution, shape B + (6,), -1 padding.
    """

    pose: FloatArray
    num_solutions: npt.NDArray[np.intp]
    mode: npt.NDArray[np.int8]


class FKResult(NamedTuple):
    """One platform pose per actuated-angle triple, batch shape ``B``.

    Attributes:
        pose: Platform poses, shape B + (3,) [m, m, rad]; NaN where not converged.
        converged: Whether Newton's method closed every loop to
            :data:`CLOSURE_TOL`, shape B.
        mode: Working mode (0..7) of the pose, shape B, -1 where not converged.
    """

    pose: FloatArray
    converged: npt.NDArray[np.bool_]
    mode: npt.NDArray[np.int8]


MAX_NEWTON_ITER = 10_000
"""Largest Newton iteration limit :func:`fk_near` accepts."""
MAX_HALVINGS = 16
"""Largest ``max_halvings`` of :func:`fk_path` (2**16 sub-steps of one sample)."""

_as_theta = as_theta_array


def _elbows(th: FloatArray, geometry: RRRGeometry) -> FloatArray:
    """Elbows of checked angles, shape (..., 3, 2) [m]; NaN for non-finite angles."""
    with np.errstate(invalid="ignore"):  # cos(inf): NaN
        return geometry.base + geometry.proximal * np.stack([np.cos(th), np.sin(th)], axis=-1)


def _batch_size(batch: tuple[int, ...]) -> int:
    """Number of items of a batch shape, at most MAX_SAMPLES, or InvalidInputError."""
    n = math.prod(batch)
    if n > MAX_SAMPLES:
        raise InvalidInputError(f"batch of {n:,} items (shape {batch}); at most {MAX_SAMPLES:,}")
    return n


def elbow_points(theta: npt.ArrayLike, geometry: RRRGeometry = RRR_ROBOT) -> FloatArray:
    """Elbows ``E_i = B_i + s_a (cos theta_i, sin theta_i)``.

    Args:
        theta: Actuated angles, shape (..., 3) [rad].
        geometry: The robot description.

    Returns:
        Shape (..., 3, 2) [m]; NaN for NaN or infinite angles.

    Raises:
        InvalidInputError: ``theta`` is not real numbers of shape (..., 3), or
            ``geometry`` not an :class:`~lynxsim.rrr.geometry.RRRGeometry`.
    """
    th = _as_theta(theta)
    return _elbows(th, check_rrr_geometry(geometry))


def loop_residual(
    pose: npt.ArrayLike, theta: npt.ArrayLike, geometry: RRRGeometry = RRR_ROBOT
) -> FloatArray:
    """Loop-closure error of each leg, ``|P_i - E_i| - L``.

    Args:
        pose: Platform poses, shape (..., 3) [m, m, rad].
        theta: Actuated angles, shape (..., 3) [rad]; broadcast against ``pose``.
        geometry: The robot description.

    Returns:
        Shape (..., 3) [m]; zero where the pose and the angles fit together;
        NaN where an input is NaN or infinite.

    Raises:
        InvalidInputError: Bad shapes, types or geometry (as :func:`elbow_points`
            and :func:`~lynxsim.rrr.geometry.as_pose_array`), or shapes that do
            not broadcast.
    """
    geometry = check_rrr_geometry(geometry)
    p = as_pose_array(pose)
    th = _as_theta(theta)
    try:
        _batch_size(np.broadcast_shapes(p.shape[:-1], th.shape[:-1]))
    except ValueError as exc:
        raise InvalidInputError(f"pose and theta do not broadcast: {exc}") from None
    with np.errstate(invalid="ignore"):  # inf - inf: NaN
        n = platform_joints(p, geometry) - _elbows(th, geometry)
        out: FloatArray = np.hypot(n[..., 0], n[..., 1]) - geometry.distal
    return out


def _modes(pose: FloatArray, elbows: FloatArray, geometry: RRRGeometry) -> npt.NDArray[np.int8]:
    """Working modes from the sign of each elbow's bend; -1 for NaN poses."""
    a = elbows - geometry.base
    n = _platform_joints(pose, geometry) - elbows
    bend = a[..., 0] * n[..., 1] - a[..., 1] * n[..., 0]
    signs = np.where(bend < 0.0, -1, 1)
    out = mode_index(signs).astype(np.int8)
    out[~np.isfinite(pose).all(axis=-1)] = -1
    return out


def _newton(
    elbows: FloatArray, pose0: FloatArray, geometry: RRRGeometry, max_iter: int
) -> tuple[FloatArray, npt.NDArray[np.bool_]]:
    """Newton's method on the three closures for flat batches.

    Args:
        elbows: Shape (n, 3, 2) [m].
        pose0: Starting poses, shape (n, 3).
        geometry: The robot description.
        max_iter: Iteration limit.

    Returns:
        Poses (n, 3), NaN where not converged, and the converged mask (n,).
    """
    ell = geometry.distal
    r_p = geometry.platform_radius
    x = pose0.copy()
    # A start beyond MAX_COORDINATE_M (a huge polynomial root) is no pose of a robot
    # under 1 m across; skipping it keeps the squares below from overflowing.
    startable: npt.NDArray[np.bool_] = np.asarray(
        np.isfinite(x).all(axis=-1)
        & (np.abs(x[:, :2]) <= MAX_COORDINATE_M).all(axis=-1)
        & np.isfinite(elbows).all(axis=(-1, -2))
    )
    active = startable.copy()
    x[~active] = 0.0
    for _ in range(max_iter):
        idx = np.flatnonzero(active)
        if idx.size == 0:
            break
        xa = x[idx]
        joints = _platform_joints(xa, geometry)
        n = joints - elbows[idx]
        r = joints - xa[:, None, :2]
        f = 0.5 * (n[..., 0] ** 2 + n[..., 1] ** 2 - ell**2)  # (k, 3) [m²]
        a = np.stack([n[..., 0], n[..., 1], r[..., 0] * n[..., 1] - r[..., 1] * n[..., 0]], -1)
        det = det3(a)
        ok = np.abs(det) > 1e-30
        safe = np.where(ok, det, 1.0)
        step = np.empty_like(xa)
        for k in range(3):
            ak = a.copy()
            ak[..., k] = -f
            step[:, k] = det3(ak) / safe
        size = np.maximum(np.abs(step[:, :2]).max(axis=-1), np.abs(step[:, 2]) * r_p)
        step *= np.minimum(1.0, _MAX_STEP / np.maximum(size, 1e-300))[:, None]
        xa = xa + step
        x[idx] = xa
        done = np.abs(f).max(axis=-1) < 1e-3 * CLOSURE_TOL * ell
        active[idx[done | ~ok]] = False
    x[:, 2] = wrap_angle(x[:, 2])
    n = _platform_joints(x, geometry) - elbows
    residual = np.abs(np.hypot(n[..., 0], n[..., 1]) - ell)
    converged = (
        startable & np.isfinite(residual).all(axis=-1) & (residual.max(axis=-1) <= CLOSURE_TOL)
    )
    x[~converged] = np.nan
    return x, converged


def fk_near(
    theta: npt.ArrayLike,
    guess: npt.ArrayLike,
    geometry: RRRGeometry = RRR_ROBOT,
    *,
    max_iter: int = 50,
) -> FKResult:
    """The platform pose of the assembly mode nearest a guess (Newton's method).

    Newton's method converges to the solution whose basin holds ``guess``; from
    a pose of the previous control step that is the same assembly mode unless
    the motion crossed or grazed a parallel singularity.

    Args:
        theta: Actuated angles, shape (..., 3) [rad].
        guess: Starting poses, shape (..., 3) [m, m, rad]; broadcast against ``theta``.
        geometry: The robot description.
        max_iter: Newton iteration limit (steps are limited to 20 mm).

    Returns:
        The :class:`FKResult` (not converged where an input is NaN or infinite).

    Raises:
        InvalidInputError: Bad shapes, types or geometry, shapes that do not
            broadcast, or ``max_iter`` not an integer from 1 to
            :data:`MAX_NEWTON_ITER`.
    """
    geometry = check_rrr_geometry(geometry)
    th = _as_theta(theta)
    g = as_pose_array(guess, "guess")
    max_iter = count(max_iter, "max_iter", 1, MAX_NEWTON_ITER)
    try:
        batch = np.broadcast_shapes(th.shape[:-1], g.shape[:-1])
    except ValueError as exc:
        raise InvalidInputError(f"theta and guess do not broadcast: {exc}") from None
    n = _batch_size(batch)
    elbows = _elbows(np.broadcast_to(th, batch + (3,)).reshape(n, 3), geometry)
    pose, converged = _newton(
        elbows, np.broadcast_to(g, batch + (3,)).reshape(n, 3).copy(), geometry, max_iter
    )
    mode = _modes(pose, elbows, geometry)
    return FKResult(
        pose=pose.reshape(batch + (3,)),
        converged=converged.reshape(batch),
        mode=mode.reshape(batch),
    )


def fk_path(
    theta_path: npt.ArrayLike,
    start: npt.ArrayLike,
    geometry: RRRGeometry = RRR_ROBOT,
    *,
    max_halvings: int = 6,
) -> FKResult:
    """Follow one assembly mode along a sequence of actuated angles.

    Each sample starts Newton's method from the previous pose; a step that does
    not converge is retried in up to ``2**max_halvings`` linear sub-steps. After
    a failure the rest of the path is NaN (not converged).

    Args:
        theta_path: Actuated angles, shape (T, 3) [rad].
        start: Platform pose near ``theta_path[0]``'s, shape (3,) [m, m, rad].
        geometry: The robot description.
        max_halvings: How often a failed step may be halved.

    Returns:
        The :class:`FKResult`, batch shape (T,); not converged from the first
        sample with a NaN or infinite angle on.

    Raises:
        InvalidInputError: ``theta_path`` is not real numbers of shape (T, 3)
            with 1 <= T <= :data:`~lynxsim.bounds.MAX_SAMPLES`, ``start`` not a
            pose (3,), ``max_halvings`` not an integer from 0 to
            :data:`MAX_HALVINGS`, or a bad ``geometry``.
    """
    geometry = check_rrr_geometry(geometry)
    th = _as_theta(theta_path, "theta_path")
    if th.ndim != 2 or not 1 <= len(th) <= MAX_SAMPLES:
        raise InvalidInputError(
            f"theta_path must have shape (T, 3) with 1 <= T <= {MAX_SAMPLES:,}, got {th.shape}"
        )
    start_pose = as_pose_array(start, "start")
    if start_pose.shape != (3,):
        raise InvalidInputError(f"start must have shape (3,), got {start_pose.shape}")
    max_halvings = count(max_halvings, "max_halvings", 0, MAX_HALVINGS)
    pose = np.full(th.shape, np.nan)
    converged = np.zeros(len(th), dtype=bool)
    current = start_pose.reshape(1, 3)
    previous = th[0]
    finite_rows = np.isfinite(th).all(axis=-1)
    stop = len(th) if finite_rows.all() else int(np.argmin(finite_rows))
    for t in range(stop):
        for halvings in range(max_halvings + 1):
            parts = 2**halvings
            trial = current
            for k in range(1, parts + 1):
                target = previous + (th[t] - previous) * (k / parts)
                trial, ok = _newton(_elbows(target[None], geometry), trial, geometry, 50)
                if not ok[0]:
                    break
            if ok[0]:
                break
        if not ok[0]:
            break
        current, previous = trial, th[t]
        pose[t], converged[t] = current[0], True
    mode = np.full(len(th), -1, dtype=np.int8)
    mode[converged] = _modes(pose[converged], _elbows(th[converged], geometry), geometry)
    return FKResult(pose=pose, converged=converged, mode=mode)


def _trig(k0: FloatArray, kc: FloatArray, ks: FloatArray) -> FloatArray:
    """``k0 + kc cos(alpha) + ks sin(alpha)`` times ``1 + t²`` as a quadratic in ``t``.

    ``alpha = _ALPHA0 + 2 atan(t)``. Returns coefficients, lowest power first,
    shape (n, 3).
    """
    c0, s0 = np.cos(_ALPHA0), np.sin(_ALPHA0)
    kc, ks = kc * c0 + ks * s0, ks * c0 - kc * s0  # rotate by the parameter offset
    return np.stack([k0 + kc, 2.0 * ks, k0 - kc], axis=-1)


def _pmul(a: FloatArray, b: FloatArray) -> FloatArray:
    """Products of batched polynomials (coefficients lowest first, shape (n, deg + 1))."""
    out = np.zeros((a.shape[0], a.shape[1] + b.shape[1] - 1))
    for i in range(a.shape[1]):
        out[:, i : i + b.shape[1]] += a[:, i, None] * b
    return out


def _padd(*polys: FloatArray) -> FloatArray:
    """Sums of batched polynomials of any degrees."""
    out = np.zeros((polys[0].shape[0], max(p.shape[1] for p in polys)))
    for p in polys:
        out[:, : p.shape[1]] += p
    return out


def _cross2(u: FloatArray, v: FloatArray) -> FloatArray:
    out: FloatArray = u[..., 0] * v[..., 1] - u[..., 1] * v[..., 0]
    return out


def _candidates(
    elbows: FloatArray, geometry: RRRGeometry
) -> tuple[npt.NDArray[np.intp], FloatArray]:
    """Roots of the forward-kinematics polynomial, as starting poses for Newton.

    Subtracting leg 1's closure from legs 2 and 3 leaves two equations linear
    in the platform centre C; solving them (Cramer) and substituting into leg
    1's closure gives one polynomial in ``t = tan((alpha - _ALPHA0) / 2)`` of
    degree 10, which is the degree-6 polynomial of the 3-RPR problem times the
    spurious factor ``(1 + t²)²``. Its real roots are the assembly modes.

    Args:
        elbows: Shape (n, 3, 2) [m], finite.
        geometry: The robot description.

    Returns:
        Item index of each candidate (k,) and candidate poses (k, 3).
    """
    c = geometry.platform
    ell = geometry.distal
    e1 = elbows[:, 0, :]
    c1 = np.broadcast_to(c[0], e1.shape)
    rows = []
    rhs = []
    for i in (1, 2):
        ei = elbows[:, i, :]
        ci = np.broadcast_to(c[i], ei.shape)
        g = ci - c1
        e = ei - e1
        one = np.ones(len(e))
        # 2 (R g - e) . C = -(|v_i|² - |v_1|²), with v_i = R c_i - E_i.
        rows.append(
            (
                _trig(-2.0 * e[:, 0], 2.0 * g[:, 0] * one, -2.0 * g[:, 1] * one),
                _trig(-2.0 * e[:, 1], 2.0 * g[:, 1] * one, 2.0 * g[:, 0] * one),
            )
        )
        rhs.append(
            _trig(
                -((ci**2).sum(-1) - (c1**2).sum(-1) + (ei**2).sum(-1) - (e1**2).sum(-1)),
                2.0 * ((ei * ci).sum(-1) - (e1 * c1).sum(-1)),
                2.0 * (_cross2(ci, ei) - _cross2(c1, e1)),
            )
        )
    (m00, m01), (m10, m11) = rows
    den = _padd(_pmul(m00, m11), -_pmul(m01, m10))
    num_x = _padd(_pmul(m11, rhs[0]), -_pmul(m01, rhs[1]))
    num_y = _padd(_pmul(m00, rhs[1]), -_pmul(m10, rhs[0]))
    v1x = _trig(-e1[:, 0], c1[:, 0], -c1[:, 1])
    v1y = _trig(-e1[:, 1], c1[:, 1], c1[:, 0])
    w1 = _trig(
        (c1**2).sum(-1) + (e1**2).sum(-1) - ell**2, -2.0 * (e1 * c1).sum(-1), -2.0 * _cross2(c1, e1)
    )
    one_t2 = np.broadcast_to(np.array([1.0, 0.0, 1.0]), v1x.shape)
    poly = _padd(
        _pmul(_padd(_pmul(num_x, num_x), _pmul(num_y, num_y)), one_t2),
        2.0 * _pmul(_padd(_pmul(num_x, v1x), _pmul(num_y, v1y)), den),
        _pmul(w1, _pmul(den, den)),
    )  # (n, 11), lowest power first

    # Roots: eigenvalues of the companion matrices, batched.
    deg = poly.shape[1] - 1
    scale = np.abs(poly).max(axis=-1, keepdims=True)
    scale = np.where(scale > 0.0, scale, 1.0)
    poly = poly / scale
    lead = poly[:, -1]
    lead = np.where(np.abs(lead) < 1e-14, np.where(lead < 0.0, -1e-14, 1e-14), lead)
    comp = np.zeros((len(poly), deg, deg))
    comp[:, 1:, :-1] = np.eye(deg - 1)
    comp[:, :, -1] = -poly[:, :-1] / lead[:, None]
    roots = np.linalg.eigvals(comp)  # (n, deg)
    real = np.abs(roots.imag) <= _REAL_ROOT_TOL * (1.0 + np.abs(roots.real))
    item, which = np.nonzero(real)
    t = roots.real[item, which]
    alpha = _ALPHA0 + 2.0 * np.arctan(t)
    with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
        # A huge root or a vanishing denominator gives a non-finite seed, which
        # Newton's method skips.
        powers = t[:, None] ** np.arange(5)
        d = (den[item] * powers).sum(-1)
        cx = (num_x[item] * powers).sum(-1) / d
        cy = (num_y[item] * powers).sum(-1) / d
    return item, np.stack([cx, cy, wrap_angle(alpha)], axis=-1)


def fk_all(theta: npt.ArrayLike, geometry: RRRGeometry = RRR_ROBOT) -> FKSolutions:
    """Every assembly mode (platform pose) of a batch of actuated-angle triples.

    Args:
        theta: Actuated angles, shape B + (3,) [rad].
        geometry: The robot description.

    Returns:
        The :class:`FKSolutions` (up to :data:`MAX_ASSEMBLY_MODES` per triple,
        none for non-finite angles or angles no pose fits).

    Raises:
        InvalidInputError: ``theta`` is not real numbers of shape (..., 3), the
            batch exceeds :data:`~lynxsim.bounds.MAX_SAMPLES`, or a bad ``geometry``.
    """
    geometry = check_rrr_geometry(geometry)
    th = _as_theta(theta)
    batch = th.shape[:-1]
    n = _batch_size(batch)
    th = th.reshape(n, 3)
    finite = np.flatnonzero(np.isfinite(th).all(axis=-1))
    elbows = _elbows(th[finite], geometry)
    item, seed = _candidates(elbows, geometry)
    sol, ok = _newton(elbows[item], seed, geometry, max_iter=60)
    item, sol = finite[item[ok]], sol[ok]

    # De-duplicate: sort by item then alpha; drop near-copies of the previous row.
    order = np.lexsort((sol[:, 2], item))
    item, sol = item[order], sol[order]
    diff = np.abs(np.diff(sol, axis=0))
    diff[:, 2] = np.abs(wrap_angle(diff[:, 2]))
    same = (item[1:] == item[:-1]) & (diff.max(axis=-1) < _DEDUP_M)
    keep = np.concatenate([[True], ~same])[: item.size]
    item, sol = item[keep], sol[keep]
    # alpha near +pi and near -pi are the same: compare each item's last with its first.
    if item.size:
        _, first = np.unique(item, return_index=True)
        last = np.append(first[1:], item.size) - 1
        d = np.abs(sol[last] - sol[first])
        d[:, 2] = np.abs(wrap_angle(d[:, 2]))
        dup = (last > first) & (d.max(axis=-1) < _DEDUP_M)
        keep = np.ones(item.size, dtype=bool)
        keep[last[dup]] = False
        item, sol = item[keep], sol[keep]

    pose = np.full((n, MAX_ASSEMBLY_MODES, 3), np.nan)
    mode = np.full((n, MAX_ASSEMBLY_MODES), -1, dtype=np.int8)
    count = np.zeros(n, dtype=np.intp)
    if item.size:
        uniq, first, counts = np.unique(item, return_index=True, return_counts=True)
        rank = np.arange(item.size) - np.repeat(first, counts)
        fits = rank < MAX_ASSEMBLY_MODES
        pose[item[fits], rank[fits]] = sol[fits]
        mode[item[fits], rank[fits]] = _modes(
            sol[fits], _elbows(th[item[fits]], geometry), geometry
        )
        count[uniq] = np.minimum(counts, MAX_ASSEMBLY_MODES)
    return FKSolutions(
        pose=pose.reshape(batch + (MAX_ASSEMBLY_MODES, 3)),
        num_solutions=count.reshape(batch),
        mode=mode.reshape(batch + (MAX_ASSEMBLY_MODES,)),
    )
