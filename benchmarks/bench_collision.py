"""CollisionChecker: 10^4 joint vectors in one batch call against a per-vector loop.

Run: ``python benchmarks/bench_collision.py``. Joint vectors are drawn uniformly
from the joint ranges (seeded) in the report's scene (cylinder and cube); both
ways give the same verdicts and clearances (checked), so the ratio compares like
with like. Target (issue 9): 10^4 vectors well under a second.
"""

from __future__ import annotations

import platform
import time

import numpy as np

from lynxsim.arm import LYNX_ARM
from lynxsim.scene import REPORT_SCENE
from lynxsim.sim.arm.model import load_arm_scene
from lynxsim.sim.arm.playback import arm_checker

N = 10_000
N_LOOP = 1_000
REPEATS = 3


def main() -> None:
    """Print the timings and their ratio."""
    rng = np.random.default_rng(0)
    q = rng.uniform(LYNX_ARM.q_min, LYNX_ARM.q_max, size=(N, 5))
    checker = arm_checker(load_arm_scene(REPORT_SCENE))
    batch_s = []
    for _ in range(REPEATS):
        start = time.perf_counter()
        result = checker.check(q)
        batch_s.append(time.perf_counter() - start)
    start = time.perf_counter()
    loop = [checker.check(v) for v in q[:N_LOOP]]
    loop_per_vector = (time.perf_counter() - start) / N_LOOP
    assert all(
        r.obstacle[0] == result.obstacle[i] and r.clearance_m[0, 0] == result.clearance_m[i, 0]
        for i, r in enumerate(loop)
    )
    best = min(batch_s)
    print(f"machine: {platform.machine()}, {platform.processor() or 'cpu'}; numpy {np.__version__}")
    print(
        f"batch:  {N} vectors in {best * 1e3:.1f} ms ({best / N * 1e6:.1f} us per vector); "
        f"{result.in_collision.mean() * 100:.1f} % in collision, "
        f"{result.obstacle.mean() * 100:.1f} % touching the cylinder"
    )
    print(f"loop:   {loop_per_vector * 1e6:.1f} us per vector (one check() call each)")
    print(f"ratio batch/loop speed: {loop_per_vector * N / best:.2f}x")


if __name__ == "__main__":
    main()
