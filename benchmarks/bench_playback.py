"""Playback speed beside the physics alone.

Run: ``python benchmarks/bench_playback.py``.

* Playback time per physics step of quintic runs without rendering (contacts,
  clearance to every obstacle and logging every step, the report included;
  wall time, and the CPU time of both threads where a helper thread steps),
  beside the physics alone in the same run, on the same scene compiled without
  the recording sensors (:mod:`lynxsim.sim.stepping.sensors`): the same controls stepped
  natively (``mujoco.rollout``, no Python per step: the bare physics), and set
  and stepped in a Python loop (``data.ctrl`` + ``mj_step``); the ratios of
  speeds are printed.

Video speed (overlays, encoding, a whole recording) is in ``bench_video.py``.
"""

from __future__ import annotations

import os
import time
from pathlib import Path

os.environ.setdefault("MUJOCO_GL", "egl")  # MuJoCo reads it once, when first imported

import mujoco
import numpy as np
from mujoco import rollout

from lynxsim.robots.arm import build_trajectory
from lynxsim.sim.arm.model import load_arm_scene, load_arm_spec
from lynxsim.sim.arm.playback import arm_binding, play_arm
from lynxsim.sim.stepping.commands import physics_grid
from lynxsim.tasks import load_task
from lynxsim.traj import TrajectoryKind

ROOT = Path(__file__).resolve().parents[1]
REPEATS = 3
PRESETTLE_S = 0.5
"""The hold before a playback's record (``rollout``'s default)."""


def _physics_alone(
    model: mujoco.MjModel, q_cmd: np.ndarray, steps: int
) -> tuple[float, float, float]:
    """Time of the same physics without the playback's records: loop, native, native CPU [s].

    The run's own commands (the hold before it, the trajectory and the
    settling), from the same rest state. Loop: set as the playback's Python
    path sets them, then ``mj_step``, step by step. Native: one
    ``mujoco.rollout`` call over the same controls.
    """
    binding = arm_binding(model)
    data = mujoco.MjData(model)
    data.qpos[binding.qpos_adr] = q_cmd[0]
    data.ctrl[binding.actuator_ids] = q_cmd[0]
    mujoco.mj_forward(model, data)
    spec = mujoco.mjtState.mjSTATE_FULLPHYSICS
    state = np.empty(mujoco.mj_stateSize(model, spec))
    mujoco.mj_getState(model, data, state, spec)
    hold = round(PRESETTLE_S / model.opt.timestep)
    ctrl = np.concatenate([np.repeat(q_cmd[:1], hold, axis=0), q_cmd])
    ctrl = np.concatenate([ctrl, np.repeat(q_cmd[-1:], hold + steps - len(ctrl), axis=0)])
    controls = np.repeat(np.array(data.ctrl)[None], len(ctrl), axis=0)
    controls[:, binding.actuator_ids] = ctrl
    adr = binding.actuator_ids
    start = time.perf_counter()
    for row in ctrl:
        data.ctrl[adr] = row
        mujoco.mj_step(model, data)
    loop = time.perf_counter() - start
    start, cpu = time.perf_counter(), time.process_time()
    rollout.rollout(model, data, state, controls[None], control_spec=mujoco.mjtState.mjSTATE_CTRL)
    return loop, time.perf_counter() - start, time.process_time() - cpu


def playback_rtf() -> None:
    """Playback against the physics alone, best of REPEATS each, in this run."""
    for label, path, scene in (
        ("pick_and_place, cylinder", "pick_and_place.toml", None),
        ("pick_and_place, no obstacle", "pick_and_place.toml", "none"),
        ("three_obstacles", "three_obstacles.toml", None),
    ):
        task = load_task(ROOT / "tasks" / path)
        trajectory = build_trajectory(task, TrajectoryKind.QUINTIC)
        built = task.scene if scene is None else task.scene.without_obstacles()
        model = load_arm_scene(built)
        plain = load_arm_spec(built).compile()  # the same scene without the recording sensors
        q_cmd = trajectory.sample(physics_grid(trajectory.duration, model.opt.timestep)).q
        walls, cpus, loops, natives, native_cpus = [], [], [], [], []
        for _ in range(REPEATS):
            start, cpu = time.perf_counter(), time.process_time()
            playback = play_arm(model, trajectory, task=task.name)
            walls.append(time.perf_counter() - start)
            cpus.append(time.process_time() - cpu)
            loop, native, native_cpu = _physics_alone(plain, q_cmd, playback.log.steps)
            loops.append(loop)
            natives.append(native)
            native_cpus.append(native_cpu)
        steps = playback.log.steps + round(PRESETTLE_S / model.opt.timestep)
        wall, cpu, loop, native = min(walls), min(cpus), min(loops), min(natives)
        native_cpu = min(native_cpus)
        print(
            f"playback ({label:27s}): {wall / steps * 1e6:5.1f} us/step "
            f"(CPU {cpu / steps * 1e6:5.1f}, all threads); physics alone "
            f"{native / steps * 1e6:5.1f} us/step native, {loop / steps * 1e6:5.1f} us/step "
            f"in a Python loop; speed ratio {native / wall:.2f} of native, "
            f"{loop / wall:.2f} of the loop; CPU ratio {native_cpu / cpu:.2f} of native "
            f"({steps} steps)"
        )


def main() -> None:
    print(
        f"MUJOCO_GL={os.environ.get('MUJOCO_GL')}, mujoco {mujoco.__version__}, "
        f"numpy {np.__version__}; load average {os.getloadavg()[0]:.2f}"
    )
    playback_rtf()


if __name__ == "__main__":
    main()
