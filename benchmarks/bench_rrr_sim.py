"""Benchmark: simulation speed of the closed 3-RRR mechanism in MuJoCo.

Three figures from one run, each the median of ``--repeat`` measurements:

* **raw mj_step at rest**: the scene at ``home``, controls held, nothing but
  ``mujoco.mj_step`` in a loop;
* **raw mj_step in motion**: the same loop while the actuated joints follow the
  closed-curve task (``tasks/rrr_closed_curve.toml``), commands precomputed;
* **playback**: :func:`lynxsim.sim.rrr.playback.play_rrr` of that task without
  video, i.e. with the per-step bookkeeping of a run report (contacts, loop
  closure, pose error, link clearance every 5 steps).

Each is given as time per physics step and as real-time factor (simulated
seconds per wall-clock second, 2 ms steps).

Run: ``python benchmarks/bench_rrr_sim.py [--repeat 5] [--steps 20000]``.
"""

from __future__ import annotations

import argparse
import os
import platform
import statistics
import time
from pathlib import Path

import mujoco
import numpy as np

from lynxsim.robots.rrr import path_from_task
from lynxsim.sim.rrr.model import RRRIds, load_rrr_scene
from lynxsim.sim.rrr.playback import play_rrr, start_model
from lynxsim.sim.stepping.commands import physics_grid
from lynxsim.tasks import load_task

TASK = Path(__file__).resolve().parents[1] / "tasks" / "rrr_closed_curve.toml"


def raw_steps(model: mujoco.MjModel, ctrl: np.ndarray, steps: int) -> float:
    """Wall time of ``steps`` calls of mj_step with the given controls [s].

    Args:
        model: The model (state starts at qpos0).
        ctrl: Controls per step, (T, 3) [rad]; cycled if shorter than ``steps``.
        steps: Number of physics steps.
    """
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    n = len(ctrl)
    start = time.perf_counter()
    for k in range(steps):
        data.ctrl[:] = ctrl[k % n]
        mujoco.mj_step(model, data)
    return time.perf_counter() - start


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5, help="measurements per figure")
    parser.add_argument("--steps", type=int, default=20000, help="physics steps of the raw loops")
    args = parser.parse_args()

    path = path_from_task(load_task(TASK))
    mode = 7
    model, theta = start_model(path, mode)
    dt = float(model.opt.timestep)
    home = load_rrr_scene()
    hold = np.array(home.qpos0[RRRIds.from_model(home).base_qpos])[None]
    steps_playback = len(physics_grid(path.duration, dt)) + round(0.5 / dt)

    rest, motion, playback = [], [], []
    for _ in range(args.repeat):
        rest.append(raw_steps(home, hold, args.steps) / args.steps)
        motion.append(raw_steps(model, theta[1:], len(theta) - 1) / (len(theta) - 1))
        start = time.perf_counter()
        report = play_rrr(path, mode, task="bench", model=model).report
        playback.append((time.perf_counter() - start) / steps_playback)
    assert report.healthy

    print(
        f"3-RRR closed mechanism in MuJoCo {mujoco.__version__}, dt = {dt * 1e3:g} ms, "
        f"{model.nv} dofs, {model.neq} connect loops; "
        f"{platform.processor() or platform.machine()}, {os.cpu_count()} CPUs, "
        f"median of {args.repeat}"
    )
    print(f"{'':34s} {'per step':>10s} {'real-time factor':>17s}")
    for label, values in (
        ("raw mj_step, at rest", rest),
        ("raw mj_step, closed-curve motion", motion),
        ("playback with run report", playback),
    ):
        per = statistics.median(values)
        print(f"{label:34s} {per * 1e6:7.1f} us {dt / per:14.0f} x")
    print(
        f"playback overhead over raw motion stepping: "
        f"{statistics.median(playback) / statistics.median(motion):.2f} x; "
        f"loop closure max {report.extra['loop_closure_max_m'] * 1e3:.4f} mm"
    )


if __name__ == "__main__":
    main()
