"""Every assembly mode of the 3-RRR: the forward kinematics as one polynomial.

Subtracting leg 1's closure from those of legs 2 and 3 leaves two equations
linear in the platform centre; eliminating it leaves one polynomial in
``t = tan((alpha - a0) / 2)`` (degree 6 times the spurious factor
``(1 + t²)²``). Its real roots, from batched companion-matrix eigenvalues, are
polished by Newton's method on the three closures (:mod:`lynxsim.rrr.closure`)
and de-duplicated. Near a parallel singularity two roots merge into one (or a
nearly real complex pair), which is reported once.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
import numpy.typing as npt

from lynxsim.angles import wrap_angle
from lynxsim.rrr.closure import batch_size, elbows_of, newton, pose_modes
from lynxsim.rrr.geometry import RRR_ROBOT, RRRGeometry, as_theta_array, check_rrr_geometry

__all__ = ["MAX_ASSEMBLY_MODES", "FKSolutions", "fk_all"]

FloatArray = npt.NDArray[np.float64]

MAX_ASSEMBLY_MODES = 6
"""Largest number of real forward-kinematics solutions of a planar 3-RRR robot."""

_DEDUP_M = 1e-7
"""Poses closer than this [m] (and [rad] in alpha) are one solution."""

_ALPHA0 = 0.6180339887498949
"""Offset of the polynomial's parameter [rad]: alpha = _ALPHA0 + pi is its point at infinity."""

_REAL_ROOT_TOL = 1e-4
"""Roots with a relative imaginary part up to this are tried (Newton decides)."""


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
    th = as_theta_array(theta)
    batch = th.shape[:-1]
    n = batch_size(batch)
    th = th.reshape(n, 3)
    finite = np.flatnonzero(np.isfinite(th).all(axis=-1))
    elbows = elbows_of(th[finite], geometry)
    item, seed = _candidates(elbows, geometry)
    sol, ok = newton(elbows[item], seed, geometry, max_iter=60)
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
        mode[item[fits], rank[fits]] = pose_modes(
            sol[fits], elbows_of(th[item[fits]], geometry), geometry
        )
        count[uniq] = np.minimum(counts, MAX_ASSEMBLY_MODES)
    return FKSolutions(
        pose=pose.reshape(batch + (MAX_ASSEMBLY_MODES, 3)),
        num_solutions=count.reshape(batch),
        mode=mode.reshape(batch + (MAX_ASSEMBLY_MODES,)),
    )
