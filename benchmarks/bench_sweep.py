"""Sweep throughput: runs per second, local backend with 1 and 2 workers and Ray local, in one run.

The sweep: the report's cylinder on a 20 mm grid over the table (1,836
placements) for one task and two trajectory types, judged on recorded runs
(:mod:`lynxsim.sim.recorded`). The baseline, measured in the same run: the
same rows played one by one (a physics run each, as ``lynxsim play --no-video``
does), on a sample of them. First, ``planned`` rows (each row planned with the
compiled planner around its placement, then played) on a coarser grid, in rows
per second of wall and of CPU time. Every backend starts from an empty folder (no
shard reused)::

    python benchmarks/bench_sweep.py [--step-mm 20] [--played 12]
"""

from __future__ import annotations

import argparse
import dataclasses
import os
import tempfile
import time

import numpy as np

from lynxsim.robots import motion
from lynxsim.robots.arm import ROBOT as ARM
from lynxsim.scene import Scene
from lynxsim.sim.arm.task import run_arm_trajectory
from lynxsim.sweep.runner import LocalBackend, run_sweep
from lynxsim.sweep.spec import ObstacleSweep, SweepSpec, _digest, table_extent_mm
from lynxsim.tasks import load_task
from lynxsim.traj import TrajectoryKind

TASK = os.path.join(os.path.dirname(__file__), "..", "tasks", "obstacle_avoidance.toml")
KINDS = (TrajectoryKind.LINE, TrajectoryKind.QUINTIC)


def _spec(step_mm: float, kinds: tuple[TrajectoryKind, ...] = KINDS) -> SweepSpec:
    task = load_task(TASK)
    (x0, x1), (y0, y1) = table_extent_mm()
    gx, gy = np.meshgrid(
        x0 + step_mm * np.arange(int((x1 - x0) / step_mm) + 1),
        y0 + step_mm * np.arange(int((y1 - y0) / step_mm) + 1),
    )
    return SweepSpec(
        name="bench",
        description="",
        tasks=(task,),
        task_files=(task.source,) if task.source else (),
        kinds=kinds,
        planner_seeds=(0,),
        obstacle=ObstacleSweep("cylinder", gx.reshape(-1), gy.reshape(-1), None, gx.shape),
        cube_positions=None,
        rows_per_shard=512,
        source=None,
        digest=_digest(b"bench", ()),
    )


def _played(spec: SweepSpec, count: int) -> float:
    """Runs per second of the same rows played one by one (a sample of ``count``)."""
    task = spec.tasks[0]
    obstacle = task.scene.obstacle("cylinder")
    assert spec.obstacle is not None
    rng = np.random.default_rng(0)
    picks = rng.choice(len(spec.obstacle.x_mm), size=count, replace=False)
    start = time.perf_counter()
    done = 0
    for kind in KINDS:
        trajectory = motion(ARM, task, kind)
        for j in picks[: count // len(KINDS)].tolist():
            moved = dataclasses.replace(
                obstacle,
                position=(
                    spec.obstacle.x_mm[j] / 1000,
                    spec.obstacle.y_mm[j] / 1000,
                    obstacle.position[2],
                ),
            )
            try:
                scene = Scene((moved,), task.scene.table, task.scene.cube)
            except ValueError:
                continue
            run_arm_trajectory(trajectory, task=task.name, scene=scene)
            done += 1
    return done / (time.perf_counter() - start)


def _timed(spec: SweepSpec, backend: object) -> tuple[float, dict]:
    with tempfile.TemporaryDirectory() as out:
        start = time.perf_counter()
        outcome = run_sweep(spec, out, backend=backend)  # type: ignore[arg-type]
        elapsed = time.perf_counter() - start
    rows = len(outcome.table["task"])
    return rows / elapsed, outcome.table


def _planned(step_mm: float) -> None:
    """``planned`` rows (each planned, compiled planner, and played) per second, wall and CPU."""
    spec = _spec(step_mm, (TrajectoryKind.PLANNED,))
    with tempfile.TemporaryDirectory() as out:
        start, cpu = time.perf_counter(), time.process_time()
        outcome = run_sweep(spec, out, backend=LocalBackend(1))
        wall, cpu = time.perf_counter() - start, time.process_time() - cpu
    rows = len(outcome.table["task"])
    print(
        f"{'planned rows, local --jobs 1':40s} {rows / wall:10.1f} rows/s wall, {rows / cpu:.1f} "
        f"rows/s of CPU ({rows} rows on a {step_mm:g} mm grid; load average "
        f"{os.getloadavg()[0]:.2f})"
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--step-mm", type=float, default=20.0)
    parser.add_argument("--played", type=int, default=12, help="rows played one by one (baseline)")
    parser.add_argument(
        "--planned-step-mm", type=float, default=100.0, help="grid of the planned rows' sweep"
    )
    args = parser.parse_args()
    _planned(args.planned_step_mm)
    spec = _spec(args.step_mm)
    rows = spec.placements * len(KINDS)
    print(
        f"sweep: {rows:,} runs ({spec.placements:,} placements x {len(KINDS)} types), "
        f"{os.cpu_count()} CPUs"
    )
    baseline = _played(spec, args.played)
    print(f"{'one physics run per row (baseline)':40s} {baseline:10.1f} runs/s   1.00x")
    results: dict[str, float] = {}
    tables = {}
    for label, backend in (
        ("local --jobs 1", LocalBackend(1)),
        ("local --jobs 2", LocalBackend(2)),
    ):
        results[label], tables[label] = _timed(spec, backend)
    try:
        import ray

        from lynxsim.sweep.ray_backend import RayBackend

        ray.init(num_cpus=2, include_dashboard=False, log_to_driver=False)
        try:
            results["ray local (2 CPUs)"], tables["ray"] = _timed(spec, RayBackend())
        finally:
            ray.shutdown()
    except ImportError:
        print("ray not installed: pip install 'lynxsim[cluster]' for the Ray figure")
    one = results["local --jobs 1"]
    for label, rate in results.items():
        print(
            f"{label:40s} {rate:10.1f} runs/s {rate / baseline:7.0f}x baseline  "
            f"{rate / one:5.2f}x jobs 1"
        )
    first = tables["local --jobs 1"]
    same = all(
        all(np.array_equal(first[k], t[k], equal_nan=first[k].dtype.kind == "f") for k in first)
        for t in tables.values()
    )
    print(f"tables identical across backends: {same}")


if __name__ == "__main__":
    main()
