"""How costs grow with run length and with the number of obstacles, each beside a baseline.

Run: ``python benchmarks/bench_scaling.py [--repeats 5] [--lengths-s 1 4 16] [--no-video]``.

All in one run, on scenes with 0, 1, 3 and 10 obstacles: ``obstacle1..8`` drawn
by :func:`~lynxsim.random_scenes.random_obstacles` (seeded, kept 60 mm from the
two targets and the cube; a scene of n <= 8 takes the first n), and for 10 two
spheres placed here behind the base (x = -0.2 m, y = +-0.25 m, 0.1 m up), clear
of the motion, which turns the arm in front of the base (x >= 0). The motion is
a quintic between P2 (0, 250, 300) mm and P3 (250, 0, 300) mm of the report's
task, pitch 0, 1 s per segment, back and forth: a run of T s is T segments of
the same motion, so each step costs alike whatever the length.

* (a) ``play_arm`` (contacts, clearance, logging and the report) in us per
  physics step (the 0.5 s hold before the record and the 0.5 s settle counted),
  beside bare ``mj_step`` on a fresh data of the same scene compiled without
  the recording sensors (:mod:`lynxsim.sim.stepping.sensors`) for as many steps,
  the two taken in turn in every repeat; a line fitted through the lengths
  splits each run into a fixed cost and a cost per step.
* (b) :class:`~lynxsim.sim.collision.CollisionChecker` ``check`` and
  ``min_clearance`` in us per joint vector (one batch of vectors drawn uniformly
  from the joint ranges), beside ``mj_kinematics`` + ``mj_collision`` alone per
  vector in a Python loop on the same model.
* (c) :class:`~lynxsim.sim.render.SceneRenderer` frames (fast preset, 640x480,
  no overlay) per second, beside the scene without obstacle.

Every figure is the best of ``--repeats`` (least disturbed by other work on the
machine); ratios compare figures of the same run.
"""

from __future__ import annotations

import argparse
import os
import platform
import time
from collections.abc import Callable
from functools import partial

os.environ.setdefault("MUJOCO_GL", "egl")  # MuJoCo reads it once, when first imported

import mujoco
import numpy as np

from lynxsim.arm import LYNX_ARM
from lynxsim.arm.motion import ArmPose, quintic
from lynxsim.random_scenes import random_obstacles
from lynxsim.scene import REPORT_CUBE, Obstacle, Scene, Sphere
from lynxsim.sim.arm.model import load_arm_scene, load_arm_spec
from lynxsim.sim.arm.playback import arm_binding, arm_checker, play_arm
from lynxsim.sim.render import Quality, RenderSettings, SceneRenderer
from lynxsim.traj import Trajectory

SEED = 12
OBSTACLE_COUNTS = (0, 1, 3, 10)
P2 = ArmPose((0.0, 0.25, 0.3), pitch=0.0, name="P2")
P3 = ArmPose((0.25, 0.0, 0.3), pitch=0.0, name="P3")
PRESETTLE_S = 0.5
"""The hold before a playback's record (``rollout``'s default)."""
CHECK_VECTORS = 2000
FRAMES = 40


def scenes() -> dict[int, Scene]:
    """Nested scenes: n obstacles for n in OBSTACLE_COUNTS."""
    rng = np.random.default_rng(SEED)
    keep_free = (P2.position, P3.position, REPORT_CUBE.position)
    drawn = random_obstacles(rng, 8, keep_free=keep_free, gap_m=0.06)
    behind: tuple[Obstacle, ...] = (
        Sphere("behind1", (-0.2, 0.25, 0.1), radius=0.03),
        Sphere("behind2", (-0.2, -0.25, 0.1), radius=0.03),
    )
    pool = drawn + behind
    return {n: Scene(obstacles=pool[:n]) for n in OBSTACLE_COUNTS}


def back_and_forth(length_s: int) -> Trajectory:
    """``length_s`` 1 s quintic segments P2 -> P3 -> P2 -> ..."""
    poses = [P2 if k % 2 == 0 else P3 for k in range(length_s + 1)]
    return quintic(poses, durations=1.0)


def best(fn: Callable[[], object], repeats: int) -> float:
    """Least wall time of ``repeats`` calls [s]."""
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        fn()
        times.append(time.perf_counter() - start)
    return min(times)


def bare_steps(model: mujoco.MjModel, steps: int) -> None:
    """``mj_step`` alone on a fresh data (the arm uncommanded)."""
    data = mujoco.MjData(model)
    for _ in range(steps):
        mujoco.mj_step(model, data)


def playback_table(all_scenes: dict[int, Scene], lengths: list[int], repeats: int) -> None:
    """(a) Playback per step against bare ``mj_step`` by length and obstacle count."""
    print(
        f"\n(a) play_arm vs bare mj_step, same model, best of {repeats}; speed ratio: wall "
        f"time, CPU ratio: CPU time of all threads (load average {os.getloadavg()[0]:.2f})"
    )
    print(
        f"{'obst':>4} {'len s':>5} {'steps':>6} {'play us/st':>10} {'bare us/st':>10} "
        f"{'speed ratio':>11} {'CPU ratio':>9} {'play ms':>8} {'min clr mm':>10} "
        f"{'contact steps':>13}"
    )
    fits = {}
    for n, scene in all_scenes.items():
        model = load_arm_scene(scene)
        plain = load_arm_spec(scene).compile()  # without the recording sensors
        hold = round(PRESETTLE_S / model.opt.timestep)
        walls, total_steps = [], []
        for length in lengths:
            trajectory = back_and_forth(length)
            play_s, bare_s, play_cpu, bare_cpu = [], [], [], []
            for _ in range(repeats):
                start, cpu = time.perf_counter(), time.process_time()
                playback = play_arm(model, trajectory, task="scaling")
                play_s.append(time.perf_counter() - start)
                play_cpu.append(time.process_time() - cpu)
                steps = playback.log.steps + hold
                start, cpu = time.perf_counter(), time.process_time()
                bare_steps(plain, steps)
                bare_s.append(time.perf_counter() - start)
                bare_cpu.append(time.process_time() - cpu)
            wall, bare = min(play_s), min(bare_s)
            cpu_ratio = min(bare_cpu) / min(play_cpu)
            report = playback.report
            clearance = report.min_clearance_m
            clr = "-" if clearance is None else f"{clearance * 1e3:.1f}"
            hit = "-" if report.obstacle is None else str(report.obstacle.steps_in_contact)
            print(
                f"{n:>4} {length:>5} {steps:>6} {wall / steps * 1e6:>10.1f} "
                f"{bare / steps * 1e6:>10.1f} {bare / wall:>11.3f} {cpu_ratio:>9.3f} "
                f"{wall * 1e3:>8.1f} "
                f"{clr:>10} {hit:>13}"
            )
            walls.append(wall)
            total_steps.append(steps)
        slope, fixed = np.polyfit(total_steps, walls, 1)
        fits[n] = (slope, fixed)
    print("\nline through the lengths: wall = fixed + per_step * steps")
    base = fits[OBSTACLE_COUNTS[0]][0]
    for n, (slope, fixed) in fits.items():
        print(
            f"  {n:>2} obstacles: fixed {fixed * 1e3:6.1f} ms, per step {slope * 1e6:6.1f} us "
            f"({slope / base:.2f}x of 0 obstacles)"
        )


def collision_loop(model: mujoco.MjModel, q: np.ndarray) -> None:
    """``mj_kinematics`` + ``mj_collision`` per vector, in Python."""
    data = mujoco.MjData(model)
    adr = arm_binding(model).qpos_adr
    for row in q:
        data.qpos[adr] = row
        mujoco.mj_kinematics(model, data)
        mujoco.mj_collision(model, data)


def checker_table(all_scenes: dict[int, Scene], repeats: int) -> None:
    """(b) The collision checker per joint vector by obstacle count."""
    rng = np.random.default_rng(SEED)
    q = rng.uniform(LYNX_ARM.q_min, LYNX_ARM.q_max, size=(CHECK_VECTORS, 5))
    print(f"\n(b) CollisionChecker, {CHECK_VECTORS} random joint vectors in one call, best of")
    print(
        f"    {repeats}; baseline: mj_kinematics + mj_collision per vector (Python loop), "
        "same model"
    )
    print(
        f"{'obst':>4} {'check us':>9} {'min_clr us':>10} {'kin+coll us':>11} "
        f"{'check/base':>10} {'min_clr/base':>12} {'check/0 obst':>12} {'% hit':>6}"
    )
    first = None
    for n, scene in all_scenes.items():
        model = load_arm_scene(scene)
        checker = arm_checker(model)
        check = best(lambda c=checker: c.check(q), repeats) / len(q)
        clear = best(lambda c=checker: c.min_clearance(q), repeats) / len(q)
        base = best(lambda m=model: collision_loop(m, q), repeats) / len(q)
        first = check if first is None else first
        hit = checker.check(q).in_collision.mean() * 100
        print(
            f"{n:>4} {check * 1e6:>9.1f} {clear * 1e6:>10.1f} {base * 1e6:>11.1f} "
            f"{check / base:>10.2f} {clear / base:>12.2f} {check / first:>12.2f} {hit:>6.1f}"
        )


def draw(
    renderer: SceneRenderer,
    model: mujoco.MjModel,
    data: mujoco.MjData,
    adr: np.ndarray,
    grid: np.ndarray,
    image: np.ndarray,
) -> None:
    """Pose the arm at every row of ``grid`` and render it into ``image``."""
    for row in grid:
        data.qpos[adr] = row
        mujoco.mj_kinematics(model, data)
        mujoco.mj_camlight(model, data)
        renderer.render(data, out=image)


def render_table(all_scenes: dict[int, Scene], repeats: int) -> None:
    """(c) Fast-preset frames per second by obstacle count."""
    settings = RenderSettings(quality=Quality.FAST)
    q = back_and_forth(1)
    grid = q.sample(np.linspace(0.0, q.duration, FRAMES)).q
    print(f"\n(c) SceneRenderer, fast preset, {settings.width}x{settings.height}, {FRAMES} frames,")
    print(f"    best of {repeats}; baseline: the scene without obstacle")
    print(f"{'obst':>4} {'frames/s':>9} {'ms/frame':>9} {'vs 0 obst':>9}")
    first = None
    for n, scene in all_scenes.items():
        model = load_arm_scene(scene)
        data = mujoco.MjData(model)
        adr = arm_binding(model).qpos_adr
        image = np.empty((settings.height, settings.width, 3), dtype=np.uint8)
        with SceneRenderer(model, settings) as renderer:
            run = partial(draw, renderer, model, data, adr, grid, image)
            run()  # warm up the context
            per_frame = best(run, repeats) / FRAMES
        first = per_frame if first is None else first
        print(f"{n:>4} {1 / per_frame:>9.1f} {per_frame * 1e3:>9.1f} {first / per_frame:>9.2f}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--lengths-s", type=int, nargs="+", default=[1, 4, 16])
    parser.add_argument("--no-video", action="store_true", help="skip (c)")
    args = parser.parse_args()
    print(
        f"machine: {platform.machine()}, {os.cpu_count()} cpus; mujoco {mujoco.__version__}, "
        f"numpy {np.__version__}, MUJOCO_GL={os.environ.get('MUJOCO_GL')}"
    )
    all_scenes = scenes()
    for o in all_scenes[OBSTACLE_COUNTS[-1]].obstacles:
        print(f"  {o.name}: {o.shape} at ({', '.join(f'{v:+.3f}' for v in o.position)}) m")
    playback_table(all_scenes, args.lengths_s, args.repeats)
    checker_table(all_scenes, args.repeats)
    if not args.no_video:
        render_table(all_scenes, args.repeats)


if __name__ == "__main__":
    main()
