"""Video speed: overlays, encoding and a whole recording, each beside ``Renderer.render`` alone.

Run: ``python benchmarks/bench_video.py [--quality fast medium default] [--rounds 3]``.

One model, one log (the quintic pick-and-place, played once), its frames at
640x480 and 30 frames/s, all in one run. Each figure is the median of
``--rounds`` rounds taken in turn, so that a busy machine slows them alike;
beside frames per wall second, the CPU time of a frame (this process's threads,
Mesa's included, and the ffmpeg processes), which a busy machine changes less:

* ``render alone``: :class:`~lynxsim.sim.render.SceneRenderer` without overlay
  (``mujoco.Renderer.render`` and the scene update), the baseline;
* ``+ overlays``: the trace, targets and contact colouring as ``render_log``
  draws them (the trace through the points 0.5 mm needs);
* ``+ overlays, every step traced``: the trace through every recorded step
  (at most 600 segments), what ``render_log`` drew before;
* ``render + encode``: no overlay, into :func:`~lynxsim.sim.video.mp4_writer`,
  the final decode check included;
* ``render_log``: the log to a finished, checked MP4 (what ``lynxsim play``
  spends after the physics);
* ``play end to end``: :func:`~lynxsim.sim.arm.task.run_arm_trajectory`,
  physics and video, as frames written per wall second.
"""

from __future__ import annotations

import argparse
import os
import statistics
import tempfile
import time
from collections.abc import Callable, Iterator
from pathlib import Path

os.environ.setdefault("MUJOCO_GL", "egl")  # MuJoCo reads it once, when first imported

import mujoco
import numpy as np

from lynxsim.arm.motion import tool_poses
from lynxsim.robots import motion
from lynxsim.robots.arm import ROBOT as ARM
from lynxsim.sim.arm.model import load_arm_scene
from lynxsim.sim.arm.playback import play_arm
from lynxsim.sim.arm.task import run_arm_trajectory
from lynxsim.sim.recording import frame_steps, render_log
from lynxsim.sim.render import Overlay, PathTrace, Quality, RenderSettings, SceneRenderer
from lynxsim.sim.video import mp4_writer
from lynxsim.tasks import load_task
from lynxsim.traj import TrajectoryKind

ROOT = Path(__file__).resolve().parents[1]


def bench(quality: Quality, rounds: int) -> None:
    task = load_task(ROOT / "tasks" / "pick_and_place.toml")
    trajectory = motion(ARM, task, TrajectoryKind.QUINTIC)
    model = load_arm_scene(task.scene)
    log = play_arm(model, trajectory, task=task.name).log
    settings = RenderSettings(quality=quality)
    steps = frame_steps(log.time_s, settings.fps).tolist()
    targets = np.array([p.position for p in tool_poses(trajectory.waypoints)])
    trace = PathTrace.of(log.tool)
    data = mujoco.MjData(model)
    image = np.empty((settings.height, settings.width, 3), dtype=np.uint8)

    def poses() -> Iterator[int]:
        for k in steps:
            data.qpos[:] = log.qpos[k]
            mujoco.mj_kinematics(model, data)
            mujoco.mj_camlight(model, data)
            yield k

    def render_alone() -> int:
        with SceneRenderer(model, settings) as renderer:
            for _ in poses():
                renderer.render(data, out=image)
        return len(steps)

    def overlays(path_until: Callable[[int], np.ndarray]) -> Callable[[], int]:
        def run() -> int:
            with SceneRenderer(model, settings) as renderer:
                for k in poses():
                    overlay = Overlay(path=path_until(k), targets=targets)
                    renderer.render(data, overlay, out=image)
            return len(steps)

        return run

    def render_encode() -> int:
        with (
            tempfile.TemporaryDirectory() as tmp,
            SceneRenderer(model, settings) as renderer,
            mp4_writer(Path(tmp) / "b.mp4", settings.fps) as sink,
        ):
            for _ in poses():
                sink.append_data(renderer.render(data, out=image))
        return len(steps)

    def whole_log() -> int:
        with tempfile.TemporaryDirectory() as tmp:
            return render_log(model, log, Path(tmp) / "c.mp4", settings, targets)

    def play() -> int:
        with tempfile.TemporaryDirectory() as tmp:
            run_arm_trajectory(
                trajectory, task=task.name, scene=task.scene, video=Path(tmp) / "d.mp4",
                render=settings,
            )  # fmt: skip
        return len(steps)

    cases: dict[str, Callable[[], int]] = {
        "render alone": render_alone,
        "+ overlays": overlays(trace.until),
        "+ overlays, every step traced": overlays(lambda k: log.tool[: k + 1]),
        "render + encode": render_encode,
        "render_log (log to checked MP4)": whole_log,
        "play end to end (physics + video)": play,
    }
    fps: dict[str, list[float]] = {name: [] for name in cases}
    cpu_ms: dict[str, list[float]] = {name: [] for name in cases}
    render_alone()  # warm up: GL context, shaders, page cache
    for _ in range(rounds):
        for name, case in cases.items():
            start, cpu = time.perf_counter(), _cpu_s()
            frames = case()
            fps[name].append(frames / (time.perf_counter() - start))
            cpu_ms[name].append((_cpu_s() - cpu) / frames * 1e3)
    base = statistics.median(fps["render alone"])
    print(
        f"{quality.value} preset, {settings.width}x{settings.height}, {len(steps)} frames, "
        f"median of {rounds} rounds"
    )
    for name, values in fps.items():
        median = statistics.median(values)
        print(
            f"  {name:36s} {median:6.1f} frames/s  {median / base:5.2f}x render alone  "
            f"CPU {statistics.median(cpu_ms[name]):5.1f} ms/frame"
        )


def _cpu_s() -> float:
    """CPU time of this process and its waited-for children so far [s]."""
    t = os.times()
    return t.user + t.system + t.children_user + t.children_system


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument(
        "--quality", nargs="+", choices=[q.value for q in Quality], default=["fast"]
    )
    parser.add_argument("--rounds", type=int, default=3)
    args = parser.parse_args()
    print(
        f"MUJOCO_GL={os.environ.get('MUJOCO_GL')}, mujoco {mujoco.__version__}, "
        f"numpy {np.__version__}, {os.cpu_count()} CPUs"
    )
    for quality in args.quality:
        bench(Quality(quality), args.rounds)


if __name__ == "__main__":
    main()
