"""Generation and sampling time of every trajectory type for the report's task.

Run: ``python benchmarks/bench_traj.py [--repeat N]``. Prints, per type, the time
to generate the trajectory through tasks/pick_and_place.toml (limits checked),
to sample it at 500 Hz, per 1000 samples, and with the report's sampling (10
steps per segment). Exits non-zero if sampling the Cartesian line, IK at every
sample, takes longer than 1 ms per 1000 samples.
"""

from __future__ import annotations

import argparse
import sys
import time
from collections.abc import Callable
from pathlib import Path

from lynxsim.robots.arm import build_trajectory
from lynxsim.tasks import load_task
from lynxsim.traj import WAYPOINT_KINDS, TrajectoryKind

TASK = Path(__file__).resolve().parents[1] / "tasks" / "pick_and_place.toml"
RATE_HZ = 500.0
REPORT_STEPS = 10
LINE_BUDGET_MS = 1.0
"""Sampling the Cartesian line may take at most this per 1000 samples [ms]."""


def best_of(fn: Callable[[], object], repeat: int, number: int) -> float:
    """Fastest mean time of ``number`` calls over ``repeat`` rounds [s]."""
    best = float("inf")
    for _ in range(repeat):
        start = time.perf_counter()
        for _ in range(number):
            fn()
        best = min(best, (time.perf_counter() - start) / number)
    return best


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=7, help="timing rounds (best is kept)")
    args = parser.parse_args()
    task = load_task(TASK)
    print(f"task {task.name}: {len(task.poses)} poses, {RATE_HZ:g} Hz, best of {args.repeat}")
    print(
        f"{'type':8s} {'duration':>9s} {'generate':>10s} {'samples':>8s} {'sample':>10s} "
        f"{'per 1000':>10s} {'report grid':>12s}"
    )
    line_ms = float("inf")
    for kind in WAYPOINT_KINDS:  # planned is searched with the scene (bench_plan.py)
        generate_s = best_of(lambda kind=kind: build_trajectory(task, kind), args.repeat, 5)
        traj = build_trajectory(task, kind)
        t = traj.times_at_rate(RATE_HZ)
        report_t = traj.times_per_segment(REPORT_STEPS)
        sample_s = best_of(lambda traj=traj, t=t: traj.sample(t), args.repeat, 50)
        report_s = best_of(lambda traj=traj, t=report_t: traj.sample(t), args.repeat, 200)
        per_1000_ms = 1e3 * sample_s * 1000 / t.size
        if kind is TrajectoryKind.LINE:
            line_ms = per_1000_ms
        print(
            f"{kind.value:8s} {traj.duration:8.3f}s {1e3 * generate_s:8.2f}ms {t.size:8d} "
            f"{1e3 * sample_s:8.3f}ms {per_1000_ms:8.3f}ms {1e6 * report_s:7.1f}us "
            f"({report_t.size} samples)"
        )
    verdict = "ok" if line_ms <= LINE_BUDGET_MS else "TOO SLOW"
    print(
        f"Cartesian line through vectorised IK: {line_ms:.3f} ms per 1000 samples "
        f"(budget {LINE_BUDGET_MS:g} ms): {verdict}"
    )
    return 0 if line_ms <= LINE_BUDGET_MS else 1


if __name__ == "__main__":
    sys.exit(main())
