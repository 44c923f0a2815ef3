"""Batch IK and FK throughput on 10^5 targets against a per-target Python loop.

Run: ``python benchmarks/bench_kinematics.py``. The loop is timed on a
subsample and reported per target, so the ratio compares like with like. The
loops call the single-target functions: :func:`~lynxsim.arm.ik_one` and
:func:`~lynxsim.arm.tool_pose_of` (closed forms in :mod:`math`), and
:func:`~lynxsim.arm.fk` (NumPy, no single-target twin).
Targets: >= 2 million batch IK solutions per second on one core (issue 2);
``ik_one`` <= 10 µs a call (the env's per-step control loop).
"""

from __future__ import annotations

import platform
import time
from collections.abc import Callable

import numpy as np

from lynxsim.arm import LYNX_ARM, fk, ik, ik_one, tool_pose, tool_pose_of

N_BATCH = 100_000
N_LOOP = 2_000
REPEATS = 7


def best_of(fn: Callable[[], object], repeats: int = REPEATS) -> float:
    """Smallest wall time of ``repeats`` calls [s]."""
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        fn()
        times.append(time.perf_counter() - start)
    return min(times)


def main() -> None:
    rng = np.random.default_rng(0)
    q = rng.uniform(LYNX_ARM.lower, LYNX_ARM.upper, size=(N_BATCH, 5))
    pose = tool_pose(q)
    sub = slice(0, N_LOOP)

    rows = []
    t_batch = best_of(lambda: ik(pose.position, pose.pitch, pose.roll))
    t_loop = best_of(
        lambda: [ik_one(pose.position[i], pose.pitch[i], pose.roll[i]) for i in range(N_LOOP)], 3
    )
    rows.append(("IK (ik / ik_one)", t_batch / N_BATCH, t_loop / N_LOOP))
    q_rows = q[:N_LOOP].tolist()
    t_batch = best_of(lambda: tool_pose(q))
    t_loop = best_of(lambda: [tool_pose_of(v) for v in q_rows], 3)
    rows.append(("FK closed (tool_pose[_of])", t_batch / N_BATCH, t_loop / N_LOOP))
    t_batch = best_of(lambda: fk(q))
    t_loop = best_of(lambda: [fk(q[i]) for i in range(N_LOOP)], 3)
    rows.append(("FK DH chain (fk, 4x4)", t_batch / N_BATCH, t_loop / N_LOOP))

    assert ik(pose.position[sub], pose.pitch[sub], pose.roll[sub]).ok.all()
    print(f"machine: {platform.processor() or platform.machine()}, numpy {np.__version__}")
    print(f"batch of {N_BATCH:,} targets (best of {REPEATS}); loop over {N_LOOP:,} targets")
    print(f"{'':28s} {'batch [1/s]':>14s} {'loop [1/s]':>12s} {'loop [us]':>10s} {'ratio':>8s}")
    for name, per_batch, per_loop in rows:
        print(
            f"{name:28s} {1 / per_batch:14,.0f} {1 / per_loop:12,.0f} {per_loop * 1e6:10.2f} "
            f"{per_loop / per_batch:8.0f}x"
        )


if __name__ == "__main__":
    main()
