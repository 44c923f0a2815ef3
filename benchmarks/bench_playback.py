"""Playback speed and render + encode speed, each beside its raw cost.

Run: ``python benchmarks/bench_playback.py``.

* Playback real-time factor (simulated s per wall s) of the quintic
  pick-and-place without rendering (contacts, clearance and logging every step),
  beside ``mj_step`` alone for the same number of steps.
* Frames per second of render + H.264 encode at 640x480, beside
  ``Renderer.render`` alone, for both quality presets.
"""

from __future__ import annotations

import os
import tempfile
import time
from pathlib import Path

os.environ.setdefault("MUJOCO_GL", "egl")  # MuJoCo reads it once, when first imported

import mujoco
import numpy as np

from lynxsim.arm.task import build_trajectory
from lynxsim.sim.arm.model import load_arm_scene
from lynxsim.sim.arm.playback import play_arm
from lynxsim.sim.render import Quality, RenderSettings, SceneRenderer
from lynxsim.sim.video import mp4_writer
from lynxsim.tasks import load_task
from lynxsim.traj import TrajectoryKind

ROOT = Path(__file__).resolve().parents[1]
FRAMES = 60


def playback_rtf() -> None:
    task = load_task(ROOT / "tasks" / "pick_and_place.toml")
    trajectory = build_trajectory(task, TrajectoryKind.QUINTIC)
    for obstacle_label, model in (
        ("with obstacle", load_arm_scene()),
        ("no obstacle", load_arm_scene(obstacle=None)),
    ):
        start = time.perf_counter()
        playback = play_arm(model, trajectory, task=task.name)
        wall = time.perf_counter() - start
        steps = len(playback.log.time_s)
        simulated = steps * model.opt.timestep

        data = mujoco.MjData(model)
        start = time.perf_counter()
        for _ in range(steps):
            mujoco.mj_step(model, data)
        raw = time.perf_counter() - start
        print(
            f"playback ({obstacle_label:13s}): {simulated / wall:6.1f}x real time; "
            f"mj_step alone {simulated / raw:6.1f}x; playback overhead {wall / raw:4.2f}x "
            f"({steps} steps)"
        )


def render_fps() -> None:
    model = load_arm_scene()
    data = mujoco.MjData(model)
    mujoco.mj_resetDataKeyframe(model, data, 0)
    mujoco.mj_forward(model, data)
    for quality in Quality:
        settings = RenderSettings(quality=quality)
        with SceneRenderer(model, settings) as renderer:
            renderer.render(data)
            start = time.perf_counter()
            for _ in range(FRAMES):
                renderer.render(data)
            raw = (time.perf_counter() - start) / FRAMES
            with tempfile.TemporaryDirectory() as tmp, mp4_writer(Path(tmp) / "b.mp4", 30) as sink:
                start = time.perf_counter()
                for _ in range(FRAMES):
                    sink.append_data(renderer.render(data))
                both = (time.perf_counter() - start) / FRAMES
        print(
            f"render {quality.value:7s} 640x480: render+encode {1 / both:5.1f} frames/s, "
            f"Renderer.render alone {1 / raw:5.1f} frames/s (encode share {1 - raw / both:.0%})"
        )


def main() -> None:
    print(
        f"MUJOCO_GL={os.environ.get('MUJOCO_GL')}, mujoco {mujoco.__version__}, "
        f"numpy {np.__version__}"
    )
    playback_rtf()
    render_fps()


if __name__ == "__main__":
    main()
