"""Benchmark: the 3-RRR constant-orientation workspace map, vectorised vs a per-point loop.

The map covers a 600 mm × 600 mm square centred on the base centre C_b at 1 mm
resolution (601 × 601 = 361,201 platform centres) and computes, for every
centre, the reach of each leg, the actuated angles of all 8 working modes, the
leg-singularity measure and the parallel-singularity measure of all 8 modes
(:func:`lynxsim.rrr.workspace_map` with ``with_theta=True``).

Two per-point Python loops compute the same numbers: a pure-Python loop over
``math`` functions (the fast way to write it point by point) and a loop that
calls the library's batch functions once per point (``ik`` +
``singularity_measures``). Both are timed on a random subsample of the grid
and **extrapolated** linearly to the full grid; their results are checked
against the vectorised map on that subsample.

Run: ``python benchmarks/bench_rrr_workspace.py [--repeat 5] [--loop-points 4000]``.
"""

from __future__ import annotations

import argparse
import math
import os
import platform
import statistics
import time

import numpy as np

from lynxsim.rrr import RRR_ROBOT, fk_all, ik, singularity_measures, workspace_map

G = RRR_ROBOT
_BASE = [tuple(b) for b in G.base]
_OFFSETS = [tuple(c) for c in G.platform]


def python_point(x: float, y: float, alpha: float) -> tuple[bool, list[float], list[float], float]:
    """Everything the map computes, for one centre, in pure Python.

    Returns:
        reachable, the 24 actuated angles (mode-major) [rad], the 8 parallel
        measures, the serial measure (NaNs when unreachable).
    """
    s_a, ell, r_p = G.proximal, G.distal, G.platform_radius
    ca, sa = math.cos(alpha), math.sin(alpha)
    rows: list[list[tuple[float, float, float]]] = []
    branches: list[tuple[float, float]] = []
    serial = math.inf
    for (bx, by), (cx, cy) in zip(_BASE, _OFFSETS, strict=True):
        rx, ry = ca * cx - sa * cy, sa * cx + ca * cy
        dx, dy = x + rx - bx, y + ry - by
        rho = math.hypot(dx, dy)
        if not (G.reach_min <= rho <= G.reach_max):
            nan = [math.nan] * 8
            return False, [math.nan] * 24, nan, math.nan
        disc = (s_a + ell - rho) * (rho - s_a + ell) * (rho + s_a - ell) * (rho + s_a + ell)
        root = math.sqrt(max(disc, 0.0))
        gamma = math.atan2(root, rho * rho + s_a * s_a - ell * ell)
        phi = math.atan2(dy, dx)
        branches.append((phi - gamma, phi + gamma))
        serial = min(serial, root / (2.0 * s_a * ell))
        kc = (rho * rho + s_a * s_a - ell * ell) / (2.0 * rho * rho)
        ks = root / (2.0 * rho * rho)
        leg_rows = []
        for sigma in (1.0, -1.0):  # same algebra as the vectorised code, no cos/sin
            nx = dx - (kc * dx + sigma * ks * dy)
            ny = dy - (kc * dy - sigma * ks * dx)
            leg_rows.append((nx / ell, ny / ell, (rx * ny - ry * nx) / (ell * r_p)))
        rows.append(leg_rows)
    thetas: list[float] = []
    parallel: list[float] = []
    for m in range(8):
        b = [(m >> leg) & 1 for leg in range(3)]
        thetas += [math.remainder(branches[leg][b[leg]], math.tau) for leg in range(3)]
        (a0, a1, a2), (b0, b1, b2), (c0, c1, c2) = (rows[leg][b[leg]] for leg in range(3))
        parallel.append(
            a0 * (b1 * c2 - b2 * c1) - a1 * (b0 * c2 - b2 * c0) + a2 * (b0 * c1 - b1 * c0)
        )
    return True, thetas, parallel, serial


def library_point(x: float, y: float, alpha: float) -> tuple[bool, np.ndarray, np.ndarray, float]:
    """The same through the library's batch functions, called for one centre."""
    pose = np.array([x, y, alpha])
    result = ik(pose)
    if not result.ok:
        return False, np.full((8, 3), np.nan), np.full(8, np.nan), math.nan
    meas = singularity_measures(pose, result.theta)
    return True, result.theta, meas.parallel, float(meas.serial[0])


def _check(condition: object, message: str) -> None:
    if not condition:
        raise RuntimeError(f"benchmark self-check failed: {message}")


def _best_of(fn, repeat: int) -> tuple[float, float]:
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        fn()
        times.append(time.perf_counter() - start)
    return min(times), statistics.median(times)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--resolution-mm", type=float, default=1.0)
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--loop-points", type=int, default=4000)
    parser.add_argument("--library-loop-points", type=int, default=600)
    parser.add_argument("--alpha-deg", type=float, default=0.0)
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args()

    cx, cy = G.base_centre
    step = args.resolution_mm * 1e-3
    xs = cx + np.arange(-0.3, 0.3 + step / 2, step)
    ys = cy + np.arange(-0.3, 0.3 + step / 2, step)
    alpha = math.radians(args.alpha_deg)
    n = xs.size * ys.size
    print(
        f"machine: {platform.processor() or platform.machine()}, {os.cpu_count()} CPUs, "
        f"Python {platform.python_version()}, numpy {np.__version__}"
    )
    print(
        f"grid: {xs.size} x {ys.size} = {n:,} platform centres "
        f"(600 mm square about C_b, {args.resolution_mm:g} mm), alpha {args.alpha_deg:g} deg, "
        "all 8 working modes"
    )

    wmap = workspace_map(xs, ys, alpha, with_theta=True)  # warm-up and reference
    best, median = _best_of(lambda: workspace_map(xs, ys, alpha, with_theta=True), args.repeat)
    print(
        f"vectorised workspace_map: best {best:.3f} s, median {median:.3f} s of {args.repeat} "
        f"({best / n * 1e9:.0f} ns per centre); reachable area {wmap.area * 1e6:,.0f} mm²"
    )
    best_nt, _ = _best_of(lambda: workspace_map(xs, ys, alpha), args.repeat)
    print(f"  without the 8x3 angles (measures only): best {best_nt:.3f} s")

    rng = np.random.default_rng(args.seed)
    iy = rng.integers(0, ys.size, args.loop_points)
    ix = rng.integers(0, xs.size, args.loop_points)
    start = time.perf_counter()
    loop = [python_point(float(xs[i]), float(ys[j]), alpha) for i, j in zip(ix, iy, strict=True)]
    t_loop = time.perf_counter() - start
    per_point = t_loop / args.loop_points
    full_loop = per_point * n
    ok = np.array([r[0] for r in loop])
    _check((ok == wmap.reachable[iy, ix]).all(), "loop and map disagree on reach")
    theta = np.array([r[1] for r in loop]).reshape(-1, 8, 3)
    par = np.array([r[2] for r in loop])
    if wmap.theta is None:
        raise RuntimeError("workspace_map returned no angles")
    d_theta = np.abs(np.remainder(theta[ok] - wmap.theta[iy, ix][ok] + np.pi, 2 * np.pi) - np.pi)
    _check(d_theta.max() < 1e-9, f"angles differ by {d_theta.max():.3g} rad")
    d_par = np.abs(par[ok] - wmap.parallel[iy, ix][ok]).max()
    _check(d_par < 1e-9, f"parallel measures differ by {d_par:.3g}")
    print(
        f"pure-Python per-point loop: {args.loop_points:,} random centres in {t_loop:.3f} s "
        f"({per_point * 1e6:.1f} µs each), extrapolated to the full grid: {full_loop:.1f} s "
        f"-> vectorised is {full_loop / best:.0f}x faster (results agree to 1e-9)"
    )

    k = args.library_loop_points
    start = time.perf_counter()
    for i, j in zip(ix[:k], iy[:k], strict=True):
        library_point(float(xs[i]), float(ys[j]), alpha)
    t_lib = time.perf_counter() - start
    full_lib = t_lib / k * n
    print(
        f"per-point calls of ik + singularity_measures: {k:,} centres in {t_lib:.3f} s "
        f"({t_lib / k * 1e6:.0f} µs each), extrapolated: {full_lib:.0f} s "
        f"-> vectorised is {full_lib / best:.0f}x faster"
    )

    # Forward kinematics: assembly modes of the reachable centres' angles.
    reach = np.argwhere(wmap.reachable)
    pick = reach[rng.integers(0, len(reach), 2000)]
    theta_fk = wmap.theta[pick[:, 0], pick[:, 1]].reshape(-1, 3)
    start = time.perf_counter()
    sol = fk_all(theta_fk)
    t_fk = time.perf_counter() - start
    counts = np.bincount(sol.num_solutions, minlength=7)
    print(
        f"fk_all: {len(theta_fk):,} actuated-angle triples (2,000 centres x 8 modes) in "
        f"{t_fk:.2f} s ({t_fk / len(theta_fk) * 1e6:.0f} µs each); assembly modes found: "
        + ", ".join(f"{c} -> {counts[c]:,}" for c in range(7) if counts[c])
    )


if __name__ == "__main__":
    main()
