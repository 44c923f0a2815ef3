"""The batched vector env beside one plain env and AsyncVectorEnv, in one run; pixels too.

Run: ``python benchmarks/bench_vector_env.py [--env-steps N] [--repeats R]``.

Every configuration plays seeded random actions of ``LynxPickAndPlace-v2``
(episodes of 200 steps, autoreset) for about ``--env-steps`` env steps in all:

- one plain env (``gym.make``, reset when an episode ends): the baseline;
- ``AsyncVectorEnv`` with 2 workers (``gym.make_vec(..., vectorization_mode="async")``);
- the batched vector env (``vectorization_mode="vector_entry_point"``) with
  N = 1, 2, 8, 32, 128.

Each is timed ``--repeats`` times, the configurations interleaved (so that a
change of the machine's load touches all of them), and the best is kept: env
steps/s in wall time, and CPU time per env step (this process's threads, and the
async workers'). The load average is printed beside each figure: the machine may
be shared. Targets (issue 26): the batch of 32 >= 1.8x one plain env and >= 3x
AsyncVectorEnv(2).

Then ``LynxPickAndPlace-v1`` (the 5-D action, a scalar controller per env): one
plain env beside the batch of 32.

Then image observations (issue 26 item 5), on ``-v1`` (its state-only step is the
cheaper one: the stricter ratio): steps/s of the plain env with one
84x84 camera (``pixels=("front",)``) beside the state-only env, both with the
lean preset ``render_quality="lean"`` and with ``"fast"``, and the batched env of
32 with pixels (all its envs drawn in one pass). Target: >= 0.2x state-only.
"""

from __future__ import annotations

import argparse
import os
import platform
import time
from collections.abc import Callable
from typing import Any

os.environ.setdefault("MUJOCO_GL", "egl")  # MuJoCo reads it once, when first imported

import gymnasium as gym

import lynxsim.envs  # noqa: F401  (registers the envs)

ENV_ID = "LynxPickAndPlace-v2"
V1_ID = "LynxPickAndPlace-v1"
BATCH_SIZES = (1, 2, 8, 32, 128)
TARGET_VS_PLAIN = 1.8
TARGET_VS_ASYNC = 3.0
PIXEL_TARGET = 0.2
_TICKS = os.sysconf("SC_CLK_TCK")


def process_cpu_s(pids: list[int]) -> float:
    """CPU time of other processes so far (user + system, all threads) [s], from /proc."""
    total = 0
    for pid in pids:
        with open(f"/proc/{pid}/stat") as f:
            fields = f.read().rsplit(")", 1)[1].split()
        total += int(fields[11]) + int(fields[12])
    return total / _TICKS


class Timing:
    """Best env steps/s and CPU time per env step of repeated runs, with the load beside."""

    def __init__(self, label: str) -> None:
        self.label = label
        self.rate = 0.0
        self.cpu_us = float("inf")
        self.load = 0.0

    def add(self, env_steps: int, wall_s: float, cpu_s: float) -> None:
        """Take one run: env steps, wall time [s] and CPU time [s]."""
        rate = env_steps / wall_s
        if rate > self.rate:
            self.rate, self.load = rate, os.getloadavg()[0]
        self.cpu_us = min(self.cpu_us, cpu_s / env_steps * 1e6)


def plain_run(
    steps: int, env_id: str = ENV_ID, **kwargs: Any
) -> Callable[[], tuple[int, float, float]]:
    """A timed run of one ``gym.make`` env: (env steps, wall [s], CPU [s])."""
    env = gym.make(env_id, **kwargs)
    env.action_space.seed(0)
    actions = [env.action_space.sample() for _ in range(steps)]
    env.reset(seed=0)

    def run() -> tuple[int, float, float]:
        start, cpu = time.perf_counter(), time.process_time()
        for a in actions:
            _, _, terminated, truncated, _ = env.step(a)
            if terminated or truncated:
                env.reset()
        return steps, time.perf_counter() - start, time.process_time() - cpu

    return run


def vector_run(
    num_envs: int, steps: int, mode: str, env_id: str = ENV_ID, **kwargs: Any
) -> Callable[[], tuple[int, float, float]]:
    """A timed run of a vector env of ``num_envs``: (env steps, wall [s], CPU [s])."""
    env = gym.make_vec(env_id, num_envs=num_envs, vectorization_mode=mode, **kwargs)
    env.action_space.seed(0)
    vector_steps = max(steps // num_envs, 4)
    actions = [env.action_space.sample() for _ in range(vector_steps)]
    env.reset(seed=0)
    for a in actions[:2]:  # warm up (workers, helper thread, renderers)
        env.step(a)
    workers = [p.pid for p in getattr(env.unwrapped, "processes", [])]

    def run() -> tuple[int, float, float]:
        start, cpu = time.perf_counter(), time.process_time() + process_cpu_s(workers)
        for a in actions:
            env.step(a)
        wall = time.perf_counter() - start
        cpu = time.process_time() + process_cpu_s(workers) - cpu
        return num_envs * vector_steps, wall, cpu

    return run


def measure(
    runs: dict[str, Callable[[], tuple[int, float, float]]], repeats: int
) -> dict[str, Timing]:
    """Each run ``repeats`` times, interleaved; the best of each."""
    timings = {label: Timing(label) for label in runs}
    for _ in range(repeats):
        for label, run in runs.items():
            timings[label].add(*run())
    return timings


def report(timings: dict[str, Timing], base: str) -> None:
    """Print steps/s, CPU per step and the ratio to ``base``, with the load average."""
    ref = timings[base].rate
    print(
        f"{'configuration':34s} {'steps/s':>9s} {'x base':>7s} {'CPU us/step':>12s} "
        f"{'x CPU':>7s} {'load':>5s}"
    )
    for t in timings.values():
        print(
            f"{t.label:34s} {t.rate:9,.0f} {t.rate / ref:7.2f} {t.cpu_us:12.0f} "
            f"{timings[base].cpu_us / t.cpu_us:7.2f} {t.load:5.1f}"
        )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--env-steps", type=int, default=3000, help="env steps per timed run")
    parser.add_argument("--repeats", type=int, default=3, help="timed runs of each configuration")
    parser.add_argument("--skip-pixels", action="store_true", help="only the state-only part")
    args = parser.parse_args()
    n = args.env_steps
    print(f"machine: {platform.processor() or platform.machine()}, {os.cpu_count()} CPUs")
    print(f"{ENV_ID}, random actions, ~{n} env steps per run, best of {args.repeats}")
    print(f"load average at start: {os.getloadavg()}")
    runs = {"plain env (gym.make)": plain_run(n)}
    runs["AsyncVectorEnv, 2 workers"] = vector_run(2, n, "async")
    for size in BATCH_SIZES:
        runs[f"batched vector env, N = {size}"] = vector_run(size, n, "vector_entry_point")
    timings = measure(runs, args.repeats)
    report(timings, "plain env (gym.make)")
    plain = timings["plain env (gym.make)"]
    asynced = timings["AsyncVectorEnv, 2 workers"]
    batch = timings["batched vector env, N = 32"]
    print(
        f"N = 32: {batch.rate / plain.rate:.2f}x one plain env in wall time, "
        f"{plain.cpu_us / batch.cpu_us:.2f}x in CPU time (target >= {TARGET_VS_PLAIN}); "
        f"{batch.rate / asynced.rate:.2f}x AsyncVectorEnv(2) in wall time, "
        f"{asynced.cpu_us / batch.cpu_us:.2f}x in CPU time (target >= {TARGET_VS_ASYNC}); "
        f"load average at end: {os.getloadavg()}"
    )
    print(f"\n{V1_ID}: a scalar controller per env")
    runs = {
        "plain v1 env": plain_run(n, V1_ID),
        "batched v1, N = 32": vector_run(32, n, "vector_entry_point", V1_ID),
    }
    timings = measure(runs, args.repeats)
    report(timings, "plain v1 env")
    if args.skip_pixels:
        return
    steps = max(n // 5, 100)
    print(f"\nimage observations, camera 'front' 84x84, ~{steps} env steps per run")
    pixels: dict[str, Any] = {"pixels": ("front",), "pixel_width": 84, "pixel_height": 84}
    runs = {
        "state only (plain env)": plain_run(steps, V1_ID),
        "pixels, lean (plain env)": plain_run(steps, V1_ID, render_quality="lean", **pixels),
        "pixels, fast (plain env)": plain_run(steps, V1_ID, render_quality="fast", **pixels),
        "pixels, lean, batched N = 32": vector_run(
            32, steps, "vector_entry_point", V1_ID, render_quality="lean", **pixels
        ),
    }
    timings = measure(runs, args.repeats)
    report(timings, "state only (plain env)")
    state = timings["state only (plain env)"]
    lean = timings["pixels, lean (plain env)"]
    print(
        f"pixels 84x84, lean: {lean.rate / state.rate:.2f}x state-only in wall time, "
        f"{state.cpu_us / lean.cpu_us:.2f}x in CPU time (target >= {PIXEL_TARGET}); "
        f"load average at end: {os.getloadavg()}"
    )


if __name__ == "__main__":
    main()
