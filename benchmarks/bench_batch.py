"""Batch rollouts beside a Python loop of single playbacks, on 1 and 2 threads.

Run: ``python benchmarks/bench_batch.py``.

The same runs (every shipped arm task with every waypoint trajectory type, the
gripper scheduled where the scene has a cube, reports included) are played in
one process as (a) a loop of :func:`~lynxsim.sim.arm.playback.play_arm`
(each on two threads where it can; (a') again bound to one CPU; (a'') each
stepped in a Python loop, as a step hook makes it, the path every playback
took when issue 12 was filed),
(b) :func:`~lynxsim.sim.arm.batch.play_arm_batch` on one thread, (c) on two; the
wall times (medians) and their ratios are printed, then where the batch's time
goes (one profiled batch on one thread). Issue 12's targets: (c) >= 1.8x (b),
and the batch >= 5x the loop.
"""

from __future__ import annotations

import cProfile
import os
import pstats
import statistics
import time
from collections.abc import Callable
from pathlib import Path

os.environ.setdefault("MUJOCO_GL", "egl")  # MuJoCo reads it once, when first imported

import mujoco

from lynxsim.robots.arm import build_trajectory
from lynxsim.sim.arm.batch import play_arm_batch
from lynxsim.sim.arm.model import load_arm_scene
from lynxsim.sim.arm.playback import play_arm
from lynxsim.sim.arm.task import pick_and_place_gripper
from lynxsim.sim.summary import Playback
from lynxsim.tasks import load_task
from lynxsim.traj import WAYPOINT_KINDS

ROOT = Path(__file__).resolve().parents[1]
REPEATS = 3
PARTS = {
    "native stepping (mujoco.batch)": ("batch.py", "_step_natively"),
    "records of the stepped chunks (Python)": ("records.py", "_process"),
    "  of which bounds of the clearances": ("clearance.py", "_bounds"),
    "  of which exact clearances (mj_geomDistance)": ("clearance.py", "row"),
    "  of which contact lists of gated states (mj_collision)": (
        "~",
        "<built-in method mujoco._functions.mj_collision>",
    ),
    "logs (contacts classified)": ("log.py", "finish_log"),
    "summaries": ("summary.py", "summarize"),
}
"""Where the batch's time goes: label -> profiled (file name, function name)."""


def _nothing(step: int, data: mujoco.MjData) -> None:
    """A step hook that watches nothing (it keeps a playback in its Python loop)."""


def _median_s(fn: Callable[[], object]) -> float:
    times = []
    for _ in range(REPEATS):
        start = time.perf_counter()
        fn()
        times.append(time.perf_counter() - start)
    return statistics.median(times)


def _on_one_cpu(fn: Callable[[], float]) -> float | None:
    """``fn()`` with this process bound to one CPU (None where affinity cannot be set)."""
    if not hasattr(os, "sched_setaffinity"):
        return None
    cpus = os.sched_getaffinity(0)
    os.sched_setaffinity(0, {min(cpus)})
    try:
        return fn()
    finally:
        os.sched_setaffinity(0, cpus)


def main() -> None:
    """Print wall times and ratios of the loop and the batch on 1 and 2 threads."""
    tasks = [t for t in map(load_task, sorted((ROOT / "tasks").glob("*.toml"))) if t.robot == "arm"]
    groups = []  # one batch per scene (a batch plays one model)
    for task in tasks:
        model = load_arm_scene(task.scene)
        trajectories = [build_trajectory(task, kind) for kind in WAYPOINT_KINDS]
        grippers = [
            None if task.scene.cube is None else pick_and_place_gripper(t.duration)
            for t in trajectories
        ]
        groups.append((model, task.name, trajectories, grippers))
    runs = sum(len(g[2]) for g in groups)
    steps = sum(round((t.duration + 0.5) / g[0].opt.timestep) for g in groups for t in g[2])

    def loop() -> list[Playback]:
        return [
            play_arm(model, t, task=name, gripper_cmd=g)
            for model, name, trajectories, grippers in groups
            for t, g in zip(trajectories, grippers, strict=True)
        ]

    def batch(nthread: int) -> list[Playback]:
        return [
            p
            for model, name, trajectories, grippers in groups
            for p in play_arm_batch(
                model, trajectories, task=name, gripper_cmds=grippers, nthread=nthread
            )
        ]

    def python_loop() -> list[Playback]:
        return [
            play_arm(model, t, task=name, gripper_cmd=g, on_step=_nothing)
            for model, name, trajectories, grippers in groups
            for t, g in zip(trajectories, grippers, strict=True)
        ]

    reference = loop()
    assert [p.report for p in python_loop()] == [p.report for p in reference]
    for nthread in (1, 2):
        assert [p.report for p in batch(nthread)] == [p.report for p in reference]
    t_loop = _median_s(loop)
    t_alone = _on_one_cpu(lambda: _median_s(loop))
    t_python = _median_s(python_loop)
    t_one = _median_s(lambda: batch(1))
    t_two = _median_s(lambda: batch(2))
    print(f"{runs} runs, {steps} recorded steps, {os.cpu_count()} CPUs, medians of {REPEATS}")
    print(f"  (a) loop of play_arm     {t_loop:7.3f} s  {t_loop / steps * 1e6:6.1f} us/step")
    if t_alone is not None:
        print(
            f"  (a') the loop on 1 CPU   {t_alone:7.3f} s  {t_alone / steps * 1e6:6.1f} us/step"
            "  (no helper thread)"
        )
    print(
        f"  (a'') loop, Python-stepped {t_python:7.3f} s  {t_python / steps * 1e6:6.1f} us/step"
        "  (a step hook on each run)"
    )
    print(f"  (b) batch, 1 thread      {t_one:7.3f} s  {t_one / steps * 1e6:6.1f} us/step")
    print(f"  (c) batch, 2 threads     {t_two:7.3f} s  {t_two / steps * 1e6:6.1f} us/step")
    print(f"  2 threads / 1 thread: {t_one / t_two:.2f}x (target >= 1.8x)")
    print(f"  batch (2 threads) / loop: {t_loop / t_two:.2f}x (target >= 5x)")
    print(f"  batch (1 thread) / loop:  {t_loop / t_one:.2f}x")
    if t_alone is not None:
        print(f"  batch (2 threads) / loop on 1 CPU: {t_alone / t_two:.2f}x")
    print(f"  batch (2 threads) / Python-stepped loop: {t_python / t_two:.2f}x")

    profile = cProfile.Profile()
    profile.runcall(batch, 1)
    stats = pstats.Stats(profile).stats  # type: ignore[attr-defined]
    total = sum(tt for _, _, tt, _, _ in stats.values())
    print(f"where a 1-thread batch's {total:.3f} s go (profiled):")
    for label, name in PARTS.items():  # name: (file, function)
        cum = sum(
            ct
            for (path, _, fn), (_, _, _, ct, _) in stats.items()
            if fn == name[1] and path.endswith(name[0])
        )
        print(f"  {label:52s} {cum:7.3f} s  {cum / total:5.1%}")


if __name__ == "__main__":
    main()
