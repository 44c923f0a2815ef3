"""Expert episodes per second with random obstacles: moves searched on the cover vs exactly.

Run: ``python benchmarks/bench_expert.py [--episodes N] [--repeats R] [--noise F]``.

The scripted pick-and-place expert of ``LynxPickAndPlace-v2`` with
``random_obstacles=(1, 3)`` plays seeded episodes (seeds 0..N-1, 200 steps each,
collisions checked every physics step as in :func:`lynxsim.envs.evaluate`),
once with its moves searched on the episode's sphere cover (``search="cover"``,
the default: one cover built per episode) and once with every check on MuJoCo
(``search="exact"``, the baseline). The two are interleaved ``--repeats`` times
and the best of each kept: episodes/s in wall time and in CPU time (this
process), with the load average (the machine may be shared), and the share of
the CPU time spent in the expert's planning (``Planner.route``). Target
(issue 24): >= 3x end to end.
"""

from __future__ import annotations

import argparse
import os
import time
from typing import Any

import gymnasium as gym

import lynxsim.envs
from lynxsim.envs import PickAndPlaceExpert
from lynxsim.envs.evaluation import run_episode
from lynxsim.envs.routes import Planner, SearchWorld


def _run(search: SearchWorld, episodes: int, noise: float) -> tuple[float, float, float, int]:
    """Wall [s], CPU [s], planning CPU [s] and successes of the episodes."""
    env: gym.Env[Any, Any] = gym.make(
        lynxsim.envs.PICK_AND_PLACE_V2_ID, random_obstacles=(1, 3), collision_check="physics_step"
    )
    expert = PickAndPlaceExpert(env, search)
    planning = 0.0
    route = Planner.route

    def timed(self: Planner, *args: Any, **kwargs: Any) -> Any:
        nonlocal planning
        t = time.process_time()
        try:
            return route(self, *args, **kwargs)
        finally:
            planning += time.process_time() - t

    Planner.route = timed  # type: ignore[method-assign]
    try:
        wall, cpu = time.perf_counter(), time.process_time()
        ok = sum(run_episode(env, expert, s, action_noise=noise).success for s in range(episodes))
        wall, cpu = time.perf_counter() - wall, time.process_time() - cpu
    finally:
        Planner.route = route  # type: ignore[method-assign]
        env.close()
    return wall, cpu, planning, ok


def main() -> None:
    """Print the comparison."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--episodes", type=int, default=30)
    parser.add_argument("--repeats", type=int, default=2)
    parser.add_argument("--noise", type=float, default=0.0)
    args = parser.parse_args()
    _run("cover", 1, 0.0)  # numba's first-call compile, not timed
    best: dict[str, tuple[float, float, float, int]] = {}
    for _ in range(args.repeats):
        for search in ("exact", "cover"):
            r = _run(search, args.episodes, args.noise)
            if search not in best or r[0] < best[search][0]:
                best[search] = r
            load = "{:.1f} {:.1f} {:.1f}".format(*os.getloadavg())
            print(
                f"{search:5s}  {args.episodes / r[0]:5.2f} ep/s wall  {args.episodes / r[1]:5.2f} "
                f"ep/s CPU  planning {100 * r[2] / r[1]:4.1f} % of CPU  success {r[3]}/"
                f"{args.episodes}  load {load}",
                flush=True,
            )
    (we, ce, pe, _), (wc, cc, pc, _) = best["exact"], best["cover"]
    print(
        f"cover / exact: {we / wc:.2f}x wall, {ce / cc:.2f}x CPU; planning CPU "
        f"{pe / args.episodes * 1e3:.0f} -> {pc / args.episodes * 1e3:.0f} ms per episode "
        f"({pe / max(pc, 1e-9):.1f}x); target 3x end to end"
    )


if __name__ == "__main__":
    main()
