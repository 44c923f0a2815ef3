"""Playback speed beside the physics alone.

Run: ``python benchmarks/bench_playback.py``.

* Playback time per physics step of quintic runs without rendering (contacts,
  clearance to every obstacle and logging every step, the report included),
  beside the physics alone in the same run: the same commands set and stepped,
  and ``mj_step`` alone on a fresh data; the ratio of speeds is printed.

Video speed (overlays, encoding, a whole recording) is in ``bench_video.py``.
"""

from __future__ import annotations

import os
import time
from pathlib import Path

os.environ.setdefault("MUJOCO_GL", "egl")  # MuJoCo reads it once, when first imported

import mujoco
import numpy as np

from lynxsim.arm.task import build_trajectory
from lynxsim.sim.arm.model import load_arm_scene
from lynxsim.sim.arm.playback import arm_binding, physics_grid, play_arm
from lynxsim.tasks import load_task
from lynxsim.traj import TrajectoryKind

ROOT = Path(__file__).resolve().parents[1]
REPEATS = 3
PRESETTLE_S = 0.5
"""The hold before a playback's record (``rollout``'s default)."""


def _physics_alone(model: mujoco.MjModel, q_cmd: np.ndarray, steps: int) -> tuple[float, float]:
    """Wall time of the same physics without the playback's records: (commanded, bare) [s].

    Commanded: the run's own commands (the hold before it, the trajectory and the
    settling), set as the playback sets them, then ``mj_step``. Bare: ``mj_step``
    alone on a fresh data for as many steps (the arm uncommanded).
    """
    binding = arm_binding(model)
    data = mujoco.MjData(model)
    data.qpos[binding.qpos_adr] = q_cmd[0]
    mujoco.mj_forward(model, data)
    hold = round(PRESETTLE_S / model.opt.timestep)
    ctrl = np.concatenate([np.repeat(q_cmd[:1], hold, axis=0), q_cmd])
    ctrl = np.concatenate([ctrl, np.repeat(q_cmd[-1:], hold + steps - len(ctrl), axis=0)])
    adr = binding.actuator_ids
    start = time.perf_counter()
    for row in ctrl:
        data.ctrl[adr] = row
        mujoco.mj_step(model, data)
    commanded = time.perf_counter() - start
    data = mujoco.MjData(model)
    start = time.perf_counter()
    for _ in range(len(ctrl)):
        mujoco.mj_step(model, data)
    return commanded, time.perf_counter() - start


def playback_rtf() -> None:
    """Playback against the physics alone, best of REPEATS each, in this run."""
    for label, path, scene in (
        ("pick_and_place, cylinder", "pick_and_place.toml", None),
        ("pick_and_place, no obstacle", "pick_and_place.toml", "none"),
        ("three_obstacles", "three_obstacles.toml", None),
    ):
        task = load_task(ROOT / "tasks" / path)
        trajectory = build_trajectory(task, TrajectoryKind.QUINTIC)
        model = load_arm_scene(task.scene if scene is None else task.scene.without_obstacles())
        q_cmd = trajectory.sample(physics_grid(trajectory.duration, model.opt.timestep)).q
        walls, commanded, bare = [], [], []
        for _ in range(REPEATS):
            start = time.perf_counter()
            playback = play_arm(model, trajectory, task=task.name)
            walls.append(time.perf_counter() - start)
            c, b = _physics_alone(model, q_cmd, playback.log.steps)
            commanded.append(c)
            bare.append(b)
        steps = playback.log.steps + round(PRESETTLE_S / model.opt.timestep)
        wall, c, b = min(walls), min(commanded), min(bare)
        print(
            f"playback ({label:27s}): {wall / steps * 1e6:5.1f} us/step; physics alone "
            f"{c / steps * 1e6:5.1f} us/step (commanded), {b / steps * 1e6:5.1f} us/step "
            f"(bare mj_step); speed ratio {c / wall:.2f} of commanded, {b / wall:.2f} of bare "
            f"({steps} steps)"
        )


def main() -> None:
    print(
        f"MUJOCO_GL={os.environ.get('MUJOCO_GL')}, mujoco {mujoco.__version__}, "
        f"numpy {np.__version__}"
    )
    playback_rtf()


if __name__ == "__main__":
    main()
