"""Planning around random obstacles: RRT-Connect, an optimal planner and the potential field.

Run: ``python benchmarks/bench_plan.py [--scenes 1000] [--seed 0] [--jobs 2]
[--planners RRTConnect BITstar potential]`` (a subset of planners: a quicker run).

Each scene has 1-3 random obstacles (cylinders, boxes, spheres; no cube) and a
start and goal tool pose (random reachable targets, pitch -90..0 deg) whose
joints keep the margin but whose straight joint-space motion collides (checked
densely with the collision checker). Every planner plans the same segment in
the same run; a scene counts as solvable when any planner solves it. Every
RRT-Connect solution is timed (Ruckig) and played in physics: the run must be
collision-free with clearance at least the margin less the tracking error.
Prints per planner: success rate (of all scenes and of the solvable ones),
planning time median and p95, path length against the straight motion.
"""

from __future__ import annotations

import argparse
import math
import multiprocessing
import os
import platform
import sys
from dataclasses import dataclass
from typing import Any

import numpy as np
from tqdm import tqdm

from lynxsim.arm import LYNX_ARM, ik, tool_pose
from lynxsim.arm.motion import ARM_BOUNDS, ARM_LIMITS, arm_lipschitz
from lynxsim.errors import LynxsimError
from lynxsim.plan import (
    PlanningError,
    path_length,
    plan_segment,
    potential_field_segment,
    time_paths,
)
from lynxsim.random_scenes import random_obstacles
from lynxsim.scene import TABLE, Scene
from lynxsim.sim.arm.model import load_arm_scene
from lynxsim.sim.arm.playback import arm_checker, play_arm
from lynxsim.sim.planning import DEFAULT_MARGIN_M, CheckerOracle
from lynxsim.traj import TrajectoryKind

PLANNERS = ("RRTConnect", "BITstar", "potential")
OPTIMAL_TIME_S = 1.0
"""Time given to the asymptotically optimal planner (it uses all of it) [s]."""
TIME_LIMIT_S = 5.0
"""Time limit of RRT-Connect [s]."""
TRACKING_ALLOWANCE_M = 0.005
"""Clearance the physics run may lose against the margin (servo tracking error) [m]."""


@dataclass
class Outcome:
    """One planner on one scene."""

    solved: bool
    time_s: float
    length_ratio: float
    why: str


@dataclass
class SceneResult:
    """Every planner on one scene, and the physics verdict of RRT-Connect's path."""

    index: int
    outcomes: dict[str, Outcome]
    physics_clearance_m: float
    physics_collided: bool


def _target(rng: np.random.Generator) -> np.ndarray | None:
    """A random reachable tool target's default IK joints, or None."""
    r, h = rng.uniform(0.12, 0.32), rng.uniform(-math.pi, math.pi)
    p = np.array([r * math.cos(h), r * math.sin(h), rng.uniform(0.02, 0.35)])
    result = ik(p, math.radians(rng.uniform(-90.0, 0.0)))
    return result.q if result.ok else None


def _scene(index: int, seed: int) -> tuple[Any, CheckerOracle, np.ndarray, np.ndarray]:
    """Draw scene ``index`` of the seeded set: obstacles, start and goal joints."""
    rng = np.random.default_rng([seed, index])
    lipschitz = arm_lipschitz()
    while True:
        q0, q1 = _target(rng), _target(rng)
        if q0 is None or q1 is None or np.linalg.norm(q1 - q0) < 0.5:
            continue
        ends = tool_pose(np.stack([q0, q1])).position
        try:
            obstacles = random_obstacles(rng, int(rng.integers(1, 4)), keep_free=ends)
        except LynxsimError:
            continue
        model = load_arm_scene(Scene(obstacles, TABLE, cube=None))
        oracle = CheckerOracle(arm_checker(model))
        if (oracle.clearance(np.stack([q0, q1]), grasped=False) < DEFAULT_MARGIN_M).any():
            continue
        steps = max(2, int(np.linalg.norm(q1 - q0) * lipschitz / 0.002))
        line = q0 + np.linspace(0.0, 1.0, steps)[:, None] * (q1 - q0)
        if oracle.clearance(line, grasped=False).min() > 0.0:
            continue  # the straight motion is clear: not a planning problem
        return model, oracle, q0, q1


def _run(args: tuple[int, int, tuple[str, ...]]) -> SceneResult:
    index, seed, planners = args
    model, oracle, q0, q1 = _scene(index, seed)
    lipschitz = arm_lipschitz()
    straight = float(np.linalg.norm(q1 - q0))
    outcomes: dict[str, Outcome] = {}
    rrt_path = None
    for name in planners:
        try:
            if name == "potential":
                plan = potential_field_segment(
                    q0, q1[None], oracle, LYNX_ARM.q_min, LYNX_ARM.q_max,
                    lipschitz=lipschitz, seed=index,
                )  # fmt: skip
            else:
                plan = plan_segment(
                    q0, q1[None], oracle, LYNX_ARM.q_min, LYNX_ARM.q_max, lipschitz=lipschitz,
                    planner=name, seed=index,
                    time_limit_s=OPTIMAL_TIME_S if name == "BITstar" else TIME_LIMIT_S,
                )  # fmt: skip
        except PlanningError as exc:
            outcomes[name] = Outcome(False, math.nan, math.nan, type(exc).__name__)
            continue
        outcomes[name] = Outcome(True, plan.planning_time_s, path_length(plan.path) / straight, "")
        if name == "RRTConnect":
            rrt_path = plan.path
    clearance, collided = math.nan, False
    if rrt_path is not None:
        timed = time_paths(
            [rrt_path], [False], oracle, lipschitz=lipschitz, margin_m=DEFAULT_MARGIN_M,
            bounds=ARM_BOUNDS, limits=ARM_LIMITS, kind=TrajectoryKind.PLANNED,
        )  # fmt: skip
        report = play_arm(model, timed.trajectory, task=f"scene{index}").report
        clearance, collided = report.min_clearance_m, report.collided
    return SceneResult(index, outcomes, clearance, collided)


def main() -> None:
    """Plan every scene with every planner and print the table."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scenes", type=int, default=1000)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--jobs", type=int, default=os.cpu_count() or 1)
    parser.add_argument("--planners", nargs="+", choices=PLANNERS, default=list(PLANNERS))
    args = parser.parse_args()
    planners = tuple(args.planners)
    jobs = [(i, args.seed, planners) for i in range(args.scenes)]
    with multiprocessing.get_context("spawn").Pool(args.jobs) as pool:
        results = list(
            tqdm(pool.imap_unordered(_run, jobs), total=len(jobs), file=sys.stderr, unit="scene")
        )
    solvable = [r for r in results if any(o.solved for o in r.outcomes.values())]
    print(f"machine: {platform.machine()}, {os.cpu_count()} cores, {args.jobs} worker processes")
    print(f"{args.scenes} scenes (seed {args.seed}), 1-3 obstacles each, straight motion blocked; "
          f"{len(solvable)} solvable (by some planner of: {' '.join(planners)})")  # fmt: skip
    print(f"{'planner':12s} {'solved':>8s} {'of solvable':>12s} {'median [s]':>11s} "
          f"{'p95 [s]':>8s} {'length / straight':>18s}")  # fmt: skip
    for name in planners:
        got = [r.outcomes[name] for r in results if r.outcomes[name].solved]
        times = np.array([o.time_s for o in got])
        ratio = np.array([o.length_ratio for o in got])
        in_solvable = sum(r.outcomes[name].solved for r in solvable) / max(len(solvable), 1)
        print(
            f"{name:12s} {len(got) / len(results):8.1%} {in_solvable:12.1%} "
            f"{np.median(times) if len(got) else math.nan:11.3f} "
            f"{np.percentile(times, 95) if len(got) else math.nan:8.3f} "
            f"{np.median(ratio) if len(got) else math.nan:18.2f}"
        )
    played = [r for r in results if not math.isnan(r.physics_clearance_m)]
    low = [r for r in played if r.physics_clearance_m < DEFAULT_MARGIN_M - TRACKING_ALLOWANCE_M]
    print(
        f"RRT-Connect paths played in physics: {len(played)}, collisions "
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
    print("failures: " + ", ".join(f"{k} {v}" for k, v in sorted(failures.items())))


if __name__ == "__main__":
    main()
