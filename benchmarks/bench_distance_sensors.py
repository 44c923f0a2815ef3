"""What exact clearances would cost inside native stepping: MuJoCo ``geomdist`` sensors.

Run: ``python benchmarks/bench_distance_sensors.py [--steps 20000] [--repeats 3]``.

For the report's cylinder scene and the three-obstacle task's scene, one
``geomdist`` sensor per (carried geom, obstacle geom) pair (the pairs of the
collision definition, :mod:`lynxsim.sim.collision`: the arm's colliding geoms
and the cube against every obstacle) is compiled into the model with a given
``cutoff`` [m]: the sensor is the exact signed distance below the cutoff and
reads the cutoff above it. ``mj_step`` of the model with the sensors is timed
beside the same model without them, in the same run (the arm uncommanded, from
``qpos0``; best of ``--repeats``). The ratio says how far a playback whose
clearances came from the physics step itself (``mujoco.rollout``'s sensordata
in a batch) could stay from bare ``mj_step`` with each cap on the clearances.
"""

from __future__ import annotations

import argparse
import os
import time
from pathlib import Path

os.environ.setdefault("MUJOCO_GL", "egl")  # MuJoCo reads it once, when first imported

import mujoco
import numpy as np

from lynxsim.scene import REPORT_SCENE, Scene
from lynxsim.sim.arm.model import SceneIds, load_arm_spec
from lynxsim.tasks import load_task

ROOT = Path(__file__).resolve().parents[1]
CUTOFFS_M = (0.02, 0.05, 0.2, 1.0)
"""Sensor cutoffs tried [m] (1 m is today's clearance cap, ``CLEARANCE_CAP_M``)."""


def _model(scene: Scene, cutoff_m: float | None) -> tuple[mujoco.MjModel, int]:
    """The scene compiled with one ``geomdist`` sensor per carried–obstacle pair (None: none)."""
    spec = load_arm_spec(scene)
    plain = spec.compile()
    groups = SceneIds.from_model(plain).collision_groups(plain)
    pairs = [
        (plain.geom(int(c)).name, plain.geom(int(o)).name)
        for c in np.flatnonzero(groups.carried)
        for o in groups.obstacle_geoms
    ]
    if cutoff_m is None:
        return plain, len(pairs)
    for carried, obstacle in pairs:
        sensor = spec.add_sensor()
        sensor.type = mujoco.mjtSensor.mjSENS_GEOMDIST
        sensor.objtype = mujoco.mjtObj.mjOBJ_GEOM
        sensor.objname = carried
        sensor.reftype = mujoco.mjtObj.mjOBJ_GEOM
        sensor.refname = obstacle
        sensor.cutoff = cutoff_m
    return spec.compile(), len(pairs)


def _us_per_step(model: mujoco.MjModel, steps: int, repeats: int) -> float:
    """Best wall time of ``steps`` native steps from ``qpos0`` [us per step]."""
    data = mujoco.MjData(model)
    best = float("inf")
    for _ in range(repeats):
        mujoco.mj_resetData(model, data)
        start = time.perf_counter()
        mujoco.mj_step(model, data, nstep=steps)
        best = min(best, time.perf_counter() - start)
    return best / steps * 1e6


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n", 1)[0])
    parser.add_argument("--steps", type=int, default=20_000, help="physics steps per timing")
    parser.add_argument("--repeats", type=int, default=3, help="timings per figure (best kept)")
    args = parser.parse_args()
    print(f"mujoco {mujoco.__version__}, {args.steps} steps, best of {args.repeats}")
    three = load_task(ROOT / "tasks" / "three_obstacles.toml").scene
    for label, scene in (("report's cylinder", REPORT_SCENE), ("three_obstacles", three)):
        plain, pairs = _model(scene, None)
        bare = _us_per_step(plain, args.steps, args.repeats)
        print(f"{label}: {pairs} pairs; mj_step without sensors {bare:5.1f} us")
        for cutoff in CUTOFFS_M:
            with_sensors, _ = _model(scene, cutoff)
            t = _us_per_step(with_sensors, args.steps, args.repeats)
            print(f"  cutoff {cutoff * 1e3:6.0f} mm: {t:5.1f} us per step, {bare / t:.2f} of bare")


if __name__ == "__main__":
    main()
