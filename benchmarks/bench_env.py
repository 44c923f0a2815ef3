"""Env throughput: steps/s per action mode beside the physics alone, vector envs, pixels, frames/s.

Run: ``python benchmarks/bench_env.py [--steps N]``.

For each env and action mode the same seeded random-action rollout runs twice:
once through ``env.step`` and once as the physics alone (the recorded servo
targets written to ``data.ctrl``, then ``mj_step(model, data, nstep=frame_skip)``),
from the same reset, so both integrate the very same trajectory. The physics
share is physics time / step time (best of several repeats each).
Targets (issue 6): share >= 0.85 with joint actions, >= 0.75 with tool actions.
Image observations (issue 13): steps/s of pick-and-place with one camera at 84x84
and 128x128 beside the state-only env, the same rollout in the same run.
"""

from __future__ import annotations

import argparse
import platform
import time
from collections.abc import Callable
from typing import Any

import gymnasium as gym

# lynxsim.sim chooses the GL backend (MUJOCO_GL), which mujoco reads when first imported.
import lynxsim.sim  # noqa: F401

# isort: split
import mujoco

from lynxsim.envs import LATEST_ENV_IDS, PICK_AND_PLACE_ID
from lynxsim.envs.base import LynxArmEnv

REPEATS = 5
SHARE_TARGET = {"joint": 0.85, "tool": 0.75}
PIXEL_SIZES = (None, 84, 128)
"""Image observation sides [px] timed (None: the state-only env)."""


def best_of(fn: Callable[[], float], repeats: int = REPEATS) -> float:
    """Smallest of ``repeats`` timings returned by ``fn`` [s]."""
    return min(fn() for _ in range(repeats))


def rollout_time(env: gym.Env[Any, Any], steps: int, repeats: int = REPEATS) -> float:
    """Best time per step of ``steps`` seeded random actions from ``reset(seed=0)`` [s]."""
    env.action_space.seed(0)
    actions = [env.action_space.sample() for _ in range(steps)]

    def run() -> float:
        env.reset(seed=0)
        start = time.perf_counter()
        for a in actions:
            env.step(a)
        return time.perf_counter() - start

    return best_of(run, repeats) / steps


def step_vs_physics(env_id: str, control: str, steps: int) -> tuple[float, float]:
    """Best time per env step and per physics-only step of one rollout [s]."""
    env = gym.make(env_id, control=control).unwrapped
    assert isinstance(env, LynxArmEnv)
    env.action_space.seed(0)
    actions = [env.action_space.sample() for _ in range(steps)]
    env.reset(seed=0)
    ctrls = []
    for a in actions:
        env.step(a)
        ctrls.append(env.data.ctrl.copy())
    m, d, n = env.model, env.data, env.frame_skip

    def time_steps() -> float:
        env.reset(seed=0)
        start = time.perf_counter()
        for a in actions:
            env.step(a)
        return time.perf_counter() - start

    def time_physics() -> float:
        env.reset(seed=0)
        start = time.perf_counter()
        for c in ctrls:
            d.ctrl[:] = c
            mujoco.mj_step(m, d, nstep=n)
        return time.perf_counter() - start

    t_step = best_of(time_steps) / steps
    t_phys = best_of(time_physics) / steps
    env.close()
    return t_step, t_phys


def wrapped_step_time(env_id: str, control: str, steps: int) -> float:
    """Best time per step of the same rollout through ``gym.make``'s wrappers [s]."""
    env = gym.make(env_id, control=control, max_episode_steps=steps + 1)
    t = rollout_time(env, steps)
    env.close()
    return t


def vector_steps_per_s(mode: str, num_envs: int, steps: int) -> float:
    """Env steps/s (all sub-envs together) of a vector env of pick-and-place."""
    env = gym.make_vec(PICK_AND_PLACE_ID, num_envs=num_envs, vectorization_mode=mode)
    env.action_space.seed(0)
    actions = [env.action_space.sample() for _ in range(steps)]
    env.reset(seed=0)
    for a in actions[:10]:  # warm up the workers
        env.step(a)
    start = time.perf_counter()
    for a in actions:
        env.step(a)
    t = time.perf_counter() - start
    env.close()
    return num_envs * steps / t


def pixel_steps_per_s(side: int | None, steps: int) -> float:
    """Steps/s of pick-and-place with image observations of camera "front", side x side px.

    ``side`` None times the state-only env. The renderer is made before timing.
    """
    pixels = {} if side is None else {"pixels": ("front",), "pixel_width": side}
    env = gym.make(PICK_AND_PLACE_ID, **pixels, pixel_height=side or 84).unwrapped
    t = rollout_time(env, steps, 3)
    env.close()
    return 1.0 / t


def frames_per_s(quality: str, frames: int) -> float:
    """rgb_array frames/s at the default size (640x480, camera "front")."""
    env = gym.make(PICK_AND_PLACE_ID, render_mode="rgb_array", render_quality=quality)
    env.reset(seed=0)
    env.render()  # creates the context
    start = time.perf_counter()
    for _ in range(frames):
        env.render()
    t = time.perf_counter() - start
    env.close()
    return frames / t


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--steps", type=int, default=2000, help="steps per timed rollout")
    args = parser.parse_args()

    print(f"machine: {platform.processor() or platform.machine()}, mujoco {mujoco.__version__}")
    print(f"random actions, {args.steps} steps per rollout, best of {REPEATS}")
    print("gym.make [us]: the same rollout through the wrappers gym.make adds")
    print(
        f"{'env':22s} {'control':8s} {'step [us]':>10s} {'physics [us]':>13s} {'share':>7s} "
        f"{'target':>7s} {'steps/s':>9s} {'gym.make [us]':>14s}"
    )
    for env_id in LATEST_ENV_IDS:
        for control in ("tool", "joint"):
            t_step, t_phys = step_vs_physics(env_id, control, args.steps)
            share = t_phys / t_step
            target = SHARE_TARGET[control]
            wrapped = wrapped_step_time(env_id, control, args.steps)
            print(
                f"{env_id:22s} {control:8s} {t_step * 1e6:10.0f} {t_phys * 1e6:13.0f} "
                f"{share:7.3f} {'>= ' + format(target, '.2f'):>7s} {1 / t_step:9,.0f} "
                f"{wrapped * 1e6:14.0f}" + ("" if share >= target else "   BELOW TARGET")
            )
    print()
    for mode in ("sync", "async"):
        rate = vector_steps_per_s(mode, 2, args.steps // 2)
        print(f"vector env ({mode:5s}, 2 x {PICK_AND_PLACE_ID}): {rate:9,.0f} env steps/s")
    pixel_steps = max(args.steps // 10, 20)
    print(f"\nimage observations, camera 'front', quality fast, {pixel_steps} steps, best of 3")
    rates = {side: pixel_steps_per_s(side, pixel_steps) for side in PIXEL_SIZES}
    for side, rate in rates.items():
        label = "state only" if side is None else f"pixels {side}x{side}"
        per_image = "" if side is None else f"  (+{(1 / rate - 1 / rates[None]) * 1e3:.2f} ms/step)"
        print(f"{PICK_AND_PLACE_ID} {label:16s}: {rate:9,.0f} steps/s{per_image}")
    print()
    for quality in ("fast", "default"):
        print(f"rgb_array 640x480, quality {quality:7s}: {frames_per_s(quality, 40):6.1f} frames/s")


if __name__ == "__main__":
    main()
