"""Planning blocked segments: compiled RRT-Connect on the cover, OMPL on the exact checker, field.

Run: ``python benchmarks/bench_plan.py [--scenes 1000] [--dense 200] [--seed 0] [--jobs 2]
[--every N] [--no-compile-time] [--planners compiled RRTConnect potential RRTConnect@cover]``
(a subset of planners, or the others on every N-th scene only: a quicker run).

Each scene has 1-3 random obstacles (``--scenes`` of them) or 10 (``--dense``;
cylinders, boxes, spheres; no cube) and a start and goal tool pose (random
reachable targets, pitch -90..0 deg) whose joints keep the margin but whose
straight joint-space motion collides (checked densely with the exact checker).
Every planner plans the same segment in the same run; a scene counts as
solvable when any planner solves it.

* ``compiled``: the default of ``lynxsim plan`` -- RRT-Connect and its seeded
  shortcutting compiled on the robot's sphere cover, one call per segment (OMPL
  RRT-Connect on the exact checker where the cover cannot plan it: counted apart,
  and left out of ns per check);
* ``RRTConnect``: OMPL's RRT-Connect on the exact MuJoCo checker (the reference);
* ``RRTConnect@cover``: OMPL's RRT-Connect on the cover (Python around each check);
* ``potential``: the potential field on the exact checker.

Per planner and per blocked segment: median / p95 of search + shortening (for
``compiled`` the compiled call alone), of the whole ``plan`` call (start and goal
checks, search, shortening, Ruckig timing, the exact re-check of the timed
motion; not the cover's build, reported apart), checks per plan and ns per check, in
wall time and in CPU time (the machine may be shared: CPU time is the fairer clock);
wall and CPU time of all planning. Every ``compiled`` solution is timed and
played in physics: the run must be collision-free with clearance at least the
margin less the tracking error. The first call's compile time (a fresh numba
cache, in a subprocess) and the load average are printed with the figures.
"""

from __future__ import annotations

import argparse
import math
import multiprocessing
import os
import platform
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass, replace
from typing import Any

import numpy as np
from tqdm import tqdm

from lynxsim.arm import LYNX_ARM, ik, tool_pose
from lynxsim.arm.motion import ARM_BOUNDS, ARM_LIMITS, arm_lipschitz
from lynxsim.errors import LynxsimError
from lynxsim.plan import PlanningError, path_length, plan_through, potential_field_segment
from lynxsim.random_scenes import random_obstacles
from lynxsim.scene import TABLE, Scene
from lynxsim.sim.arm.model import load_arm_scene
from lynxsim.sim.arm.playback import arm_checker, play_arm
from lynxsim.sim.planning import DEFAULT_MARGIN_M, CheckerOracle, cover_oracle
from lynxsim.traj import TrajectoryKind

PLANNERS = ("compiled", "RRTConnect", "potential", "RRTConnect@cover")
TIME_LIMIT_S = 5.0
"""Time limit of RRT-Connect [s]."""
TRACKING_ALLOWANCE_M = 0.005
"""Clearance the physics run may lose against the margin (servo tracking error) [m]."""


class CountingOracle:
    """An oracle that counts the joint vectors it is asked about."""

    def __init__(self, inner: Any) -> None:
        self.inner = inner
        self.n_joints = inner.n_joints
        self.asked = 0

    def clearance(self, q: np.ndarray, *, grasped: bool) -> np.ndarray:
        """The inner oracle's clearances, counted."""
        self.asked += len(q)
        return self.inner.clearance(q, grasped=grasped)


@dataclass
class Outcome:
    """One planner on one scene."""

    solved: bool
    search_s: float
    whole_s: float
    cpu_s: float
    checks: int
    length_ratio: float
    why: str
    fallback: bool = False
    search_cpu_s: float = math.nan


@dataclass
class SceneResult:
    """Every planner on one scene, and the physics verdict of the compiled path."""

    index: int
    dense: bool
    outcomes: dict[str, Outcome]
    build_s: float
    physics_clearance_m: float
    physics_collided: bool


def _target(rng: np.random.Generator) -> np.ndarray | None:
    """A random reachable tool target's default IK joints, or None."""
    r, h = rng.uniform(0.12, 0.32), rng.uniform(-math.pi, math.pi)
    p = np.array([r * math.cos(h), r * math.sin(h), rng.uniform(0.02, 0.35)])
    result = ik(p, math.radians(rng.uniform(-90.0, 0.0)))
    return result.q if result.ok else None


def _obstacles(rng: np.random.Generator, dense: bool, ends: np.ndarray) -> tuple[Any, ...]:
    if not dense:
        return random_obstacles(rng, int(rng.integers(1, 4)), keep_free=ends)
    first = random_obstacles(rng, 5, keep_free=ends)
    second = random_obstacles(rng, 5, keep_free=ends)
    return first + tuple(replace(o, name=f"obstacle{6 + i}") for i, o in enumerate(second))


def _scene(
    index: int, seed: int, dense: bool
) -> tuple[Any, Any, CheckerOracle, np.ndarray, np.ndarray]:
    """Draw scene ``index`` of the seeded set: obstacles, start and goal joints."""
    rng = np.random.default_rng([seed, index, int(dense)])
    lipschitz = arm_lipschitz()
    while True:
        q0, q1 = _target(rng), _target(rng)
        if q0 is None or q1 is None or np.linalg.norm(q1 - q0) < 0.5:
            continue
        ends = tool_pose(np.stack([q0, q1])).position
        try:
            obstacles = _obstacles(rng, dense, ends)
            model = load_arm_scene(Scene(obstacles, TABLE, cube=None))
        except LynxsimError:
            continue
        checker = arm_checker(model)
        oracle = CheckerOracle(checker)
        if (oracle.clearance(np.stack([q0, q1]), grasped=False) < DEFAULT_MARGIN_M).any():
            continue
        steps = max(2, int(np.linalg.norm(q1 - q0) * lipschitz / 0.002))
        line = q0 + np.linspace(0.0, 1.0, steps)[:, None] * (q1 - q0)
        if oracle.clearance(line, grasped=False).min() > 0.0:
            continue  # the straight motion is clear: not a planning problem
        return model, checker, oracle, q0, q1


def _plan(name: str, q0: np.ndarray, q1: np.ndarray, exact: Any, cover: Any, seed: int) -> Any:
    planner = "RRTConnect" if name.startswith("RRTConnect") else name
    return plan_through(
        [q1[None]], q0, exact, [False], LYNX_ARM.q_min, LYNX_ARM.q_max,
        lipschitz=arm_lipschitz(), planner=planner, seed=seed, time_limit_s=TIME_LIMIT_S,
        bounds=ARM_BOUNDS, limits=ARM_LIMITS, kind=TrajectoryKind.PLANNED,
        search_oracle=cover if name in ("compiled", "RRTConnect@cover") else None,
    )  # fmt: skip


def _run(args: tuple[int, int, bool, tuple[str, ...], int]) -> SceneResult:
    index, seed, dense, all_planners, every = args
    planners = tuple(p for p in all_planners if p == "compiled" or index % every == 0)
    model, checker, oracle, q0, q1 = _scene(index, seed, dense)
    started = time.perf_counter()
    cover = cover_oracle(checker)  # the scene's cover, built once per scene
    build_s = time.perf_counter() - started
    straight = float(np.linalg.norm(q1 - q0))
    outcomes: dict[str, Outcome] = {}
    compiled_traj = None
    for name in planners:
        exact = CountingOracle(oracle)
        counted = CountingOracle(cover) if name == "RRTConnect@cover" else cover
        wall, cpu = time.perf_counter(), time.process_time()
        try:
            if name == "potential":
                seg = potential_field_segment(
                    q0, q1[None], exact, LYNX_ARM.q_min, LYNX_ARM.q_max,
                    lipschitz=arm_lipschitz(), seed=index,
                )  # fmt: skip
                search, path, fallback, checks = seg.planning_time_s, seg.path, False, exact.asked
                search_cpu = math.nan
                whole = time.perf_counter() - wall
            else:
                motion = _plan(name, q0, q1, exact, counted, index)
                seg = motion.segments[0]
                whole = time.perf_counter() - wall
                fallback = name == "compiled" and seg.planner == "RRTConnect"
                search_cpu = math.nan
                if seg.planner == "compiled":
                    search, checks = seg.search_time_s, seg.checks
                    search_cpu = seg.search_cpu_s
                else:  # OMPL (or direct): its segment's time, the checks its world was asked
                    search = seg.planning_time_s
                    checks = counted.asked if name == "RRTConnect@cover" else exact.asked
                path = seg.path
                if name == "compiled":
                    compiled_traj = motion.trajectory
        except PlanningError as exc:
            outcomes[name] = Outcome(False, math.nan, math.nan, math.nan, 0, math.nan,
                                     type(exc).__name__)  # fmt: skip
            continue
        cpu_s = time.process_time() - cpu
        outcomes[name] = Outcome(
            True,
            search,
            whole,
            cpu_s,
            checks,
            path_length(path) / straight,
            "",
            fallback,
            search_cpu,
        )
    clearance, collided = math.nan, False
    if compiled_traj is not None:
        report = play_arm(model, compiled_traj, task=f"scene{index}").report
        clearance, collided = report.min_clearance_m, report.collided
    return SceneResult(index, dense, outcomes, build_s, clearance, collided)


def _warm() -> None:
    """Load the compiled planner in a worker (numba's cache) before it is timed."""
    _, checker, oracle, q0, q1 = _scene(0, 0, False)
    _plan("compiled", q0, q1, oracle, cover_oracle(checker), 0)


def _compile_time() -> tuple[float, float]:
    """First-call time of the compiled planner with a fresh numba cache, then a second call [s]."""
    code = (
        "import time, numpy as np, sys; sys.path.insert(0, 'benchmarks'); import bench_plan as b\n"
        "m, k, o, q0, q1 = b._scene(0, 0, False); c = b.cover_oracle(k)\n"
        "t = time.perf_counter(); b._plan('compiled', q0, q1, o, c, 0); a = time.perf_counter()-t\n"
        "t = time.perf_counter(); b._plan('compiled', q0, q1, o, c, 0); s = time.perf_counter()-t\n"
        "print(a, s)\n"
    )
    with tempfile.TemporaryDirectory() as cache:
        env = {**os.environ, "NUMBA_CACHE_DIR": cache}
        out = subprocess.run(
            [sys.executable, "-c", code], env=env, capture_output=True, text=True, check=True
        )
    first, second = (float(x) for x in out.stdout.split())
    return first, second


def _row(name: str, got: list[Outcome], total: int, solvable: int, solvable_solved: int) -> str:
    def stat(values: list[float], q: float) -> float:
        return float(np.percentile(values, q)) * 1e3 if values else math.nan

    search = [o.search_s for o in got]
    whole = [o.whole_s for o in got]
    checks = [o.checks for o in got]
    own = [o for o in got if not o.fallback]  # the compiled calls (fallbacks are OMPL's)
    per_check = sum(o.search_s for o in own) / max(sum(o.checks for o in own), 1) * 1e9
    ratio = np.median([o.length_ratio for o in got]) if got else math.nan
    search_cpu = [o.search_cpu_s for o in own if not math.isnan(o.search_cpu_s)]
    cpu = [o.cpu_s for o in got]
    return (
        f"{name:17s} {len(got) / max(total, 1):7.1%} {solvable_solved / max(solvable, 1):8.1%} "
        f"{stat(search, 50):9.2f} {stat(search, 95):8.2f} {stat(whole, 50):9.2f} "
        f"{stat(whole, 95):8.2f} {np.median(checks) if got else math.nan:8.0f} "
        f"{per_check:8.0f} {ratio:6.2f} {stat(search_cpu, 50):9.2f} {stat(search_cpu, 95):8.2f} "
        f"{stat(cpu, 50):9.2f} {stat(cpu, 95):8.2f}"
    )


def _report(results: list[SceneResult], planners: tuple[str, ...], what: str) -> None:
    solvable = [r for r in results if any(o.solved for o in r.outcomes.values())]
    print(f"\n{what}: {len(results)} blocked scenes, {len(solvable)} solvable")
    print(f"{'planner':17s} {'solved':>7s} {'of solv.':>8s} {'search':>9s} {'p95':>8s} "
          f"{'whole':>9s} {'p95':>8s} {'checks':>8s} {'ns/chk':>8s} {'len':>6s} "
          f"{'CPU srch':>9s} {'p95':>8s} {'CPU whole':>9s} {'p95':>8s}")  # fmt: skip
    print(f"{'':17s} {'':>7s} {'':>8s} {'med [ms]':>9s} {'[ms]':>8s} {'med [ms]':>9s} "
          f"{'[ms]':>8s} {'median':>8s} {'':>8s} {'ratio':>6s} {'med [ms]':>9s} {'[ms]':>8s} "
          f"{'med [ms]':>9s} {'[ms]':>8s}")  # fmt: skip
    for name in planners:
        ran = [r for r in results if name in r.outcomes]
        got = [r.outcomes[name] for r in ran if r.outcomes[name].solved]
        mine = [r for r in solvable if name in r.outcomes]
        in_solvable = sum(r.outcomes[name].solved for r in mine)
        print(_row(name, got, len(ran), len(mine), in_solvable))
    base = [
        r
        for r in results
        if all(p in r.outcomes and r.outcomes[p].solved for p in ("compiled", "RRTConnect"))
    ]
    if base and "RRTConnect" in planners:
        a = np.median([r.outcomes["RRTConnect"].search_s for r in base])
        b = np.median([r.outcomes["compiled"].search_s for r in base])
        wa = np.median([r.outcomes["RRTConnect"].whole_s for r in base])
        wb = np.median([r.outcomes["compiled"].whole_s for r in base])
        ca = np.median([r.outcomes["RRTConnect"].cpu_s for r in base])
        cb = np.median([r.outcomes["compiled"].cpu_s for r in base])
        own = [r for r in base if not math.isnan(r.outcomes["compiled"].search_cpu_s)]
        cs = np.median([r.outcomes["compiled"].search_cpu_s for r in own]) if own else math.nan
        print(f"compiled vs OMPL RRT-Connect on the exact checker, same {len(base)} scenes: "
              f"search + shortening median {a / b:.0f}x faster (wall), "
              f"whole plan call {wa / wb:.1f}x (wall), {ca / cb:.1f}x (CPU); OMPL's whole call "
              f"in CPU time against the compiled search's CPU time: {ca / cs:.0f}x")  # fmt: skip
    own = [r.outcomes["compiled"] for r in results if r.outcomes["compiled"].solved]
    own = [o for o in own if not o.fallback]
    if own:
        per_check_cpu = sum(o.search_cpu_s for o in own) / max(sum(o.checks for o in own), 1)
        print(f"compiled: {per_check_cpu * 1e9:.0f} ns per check in CPU time "
              f"(the table's ns/chk is wall time)")  # fmt: skip
    fell = sum(r.outcomes["compiled"].fallback for r in results)
    build = np.median([r.build_s for r in results]) * 1e3
    print(f"compiled: {fell} segments fell back to OMPL on the exact checker (cover too tight); "
          f"cover build median {build:.1f} ms per scene")  # fmt: skip
    played = [r for r in results if not math.isnan(r.physics_clearance_m)]
    unplayed = [r for r in results if "compiled" in r.outcomes and r.outcomes["compiled"].solved
                and math.isnan(r.physics_clearance_m)]  # fmt: skip
    assert not unplayed
    if played:
        low = [r for r in played
               if r.physics_clearance_m < DEFAULT_MARGIN_M - TRACKING_ALLOWANCE_M]  # fmt: skip
        print(
            f"compiled paths played in physics: {len(played)}, collisions "
            f"{sum(r.physics_collided for r in played)}, clearance min "
            f"{min(r.physics_clearance_m for r in played) * 1e3:.1f} mm, median "
            f"{np.median([r.physics_clearance_m for r in played]) * 1e3:.1f} mm; below margin - "
            f"{TRACKING_ALLOWANCE_M * 1e3:.0f} mm: {len(low)}"
        )
    failures: dict[str, int] = {}
    for r in results:
        for name, o in r.outcomes.items():
            if not o.solved:
                failures[f"{name}: {o.why}"] = failures.get(f"{name}: {o.why}", 0) + 1
    print("failures: " + (", ".join(f"{k} {v}" for k, v in sorted(failures.items())) or "none"))


def main() -> None:
    """Plan every scene with every planner and print the tables."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scenes", type=int, default=1000, help="scenes with 1-3 obstacles")
    parser.add_argument("--dense", type=int, default=200, help="scenes with 10 obstacles")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--jobs", type=int, default=os.cpu_count() or 1)
    parser.add_argument("--planners", nargs="+", choices=PLANNERS, default=list(PLANNERS))
    parser.add_argument(
        "--every",
        type=int,
        default=1,
        help="the planners other than compiled plan every N-th scene",
    )
    parser.add_argument(
        "--no-compile-time",
        action="store_true",
        help="skip measuring the first call with an empty numba cache",
    )
    args = parser.parse_args()
    planners = tuple(args.planners)
    if "compiled" not in planners:
        parser.error("--planners must include compiled")
    load_before = os.getloadavg()
    first, second = (math.nan, math.nan) if args.no_compile_time else _compile_time()
    jobs = [(i, args.seed, False, planners, args.every) for i in range(args.scenes)]
    jobs += [(i, args.seed, True, planners, args.every) for i in range(args.dense)]
    wall, cpu = time.perf_counter(), time.process_time()
    with multiprocessing.get_context("spawn").Pool(args.jobs, initializer=_warm) as pool:
        results = list(
            tqdm(pool.imap_unordered(_run, jobs), total=len(jobs), file=sys.stderr, unit="scene")
        )
    wall, cpu = time.perf_counter() - wall, time.process_time() - cpu
    results.sort(key=lambda r: (r.dense, r.index))
    load_after = os.getloadavg()
    print(f"machine: {platform.machine()}, {os.cpu_count()} cores, {args.jobs} worker processes; "
          f"load average {load_before[0]:.1f} before, {load_after[0]:.1f} after "
          f"(1 min; the machine is shared)")  # fmt: skip
    print(f"compiled planner's first call with an empty numba cache: {first:.1f} s "
          f"(compiling, then cached on disk); the same call again: "
          f"{second * 1e3:.1f} ms")  # fmt: skip
    _report([r for r in results if not r.dense], planners, "1-3 obstacles")
    if args.dense:
        _report([r for r in results if r.dense], planners, "10 obstacles")
    print("\nwall and CPU time of all planning per planner (sum over scenes, worker processes):")
    for name in planners:
        got = [r.outcomes[name] for r in results if name in r.outcomes and r.outcomes[name].solved]
        print(f"  {name:17s} wall {sum(o.whole_s for o in got):8.1f} s, "
              f"CPU {sum(o.cpu_s for o in got):8.1f} s over {len(got)} solved")  # fmt: skip
    print(f"whole run: wall {wall:.0f} s")


if __name__ == "__main__":
    main()
