"""A natively stepped run finds each obstacle's minimum with few exact distances, the same values.

:class:`lynxsim.sim.collision.minima.ClearanceMinima` rules states out by the
compiled bounds; the log's clearances of every step are computed when read
(:class:`lynxsim.sim.stepping.clearance_log.LoggedClearance`). Both must be
what a Python-loop run (a step hook: every clearance computed, as before)
gives, bit for bit, and the report the same, on scenes of 1, 3 and 10 obstacles.
"""

from __future__ import annotations

import mujoco
import numpy as np
import pytest

from lynxsim.arm.motion import ArmPose, quintic
from lynxsim.random_scenes import random_obstacles
from lynxsim.scene import REPORT_CUBE, Scene, Sphere
from lynxsim.sim.arm.model import load_arm_scene
from lynxsim.sim.arm.playback import arm_binding, play_arm

P2 = ArmPose((0.0, 0.25, 0.3), pitch=0.0, name="P2")
P3 = ArmPose((0.25, 0.0, 0.3), pitch=0.0, name="P3")


def _scene(n: int, seed: int) -> Scene:
    drawn = random_obstacles(
        np.random.default_rng(seed),
        min(n, 8),
        keep_free=(P2.position, P3.position, REPORT_CUBE.position),
        gap_m=0.06,
    )
    behind = (
        Sphere("behind1", (-0.2, 0.25, 0.1), radius=0.03),
        Sphere("behind2", (-0.2, -0.25, 0.1), radius=0.03),
    )
    return Scene(obstacles=(drawn + behind)[:n])


def _hook(k: int, data: mujoco.MjData) -> None:
    """A step hook: the run then records in a Python loop, every clearance computed."""


@pytest.mark.parametrize(("n", "seed"), [(1, 12), (3, 12), (3, 4), (10, 12)])
def test_minima_and_logged_clearances_are_the_python_loops(n: int, seed: int) -> None:
    model = load_arm_scene(_scene(n, seed))
    motion = quintic([P2, P3], durations=1.0)
    native = play_arm(model, motion, task="t", settle_s=0.1)
    loop = play_arm(model, motion, task="t", settle_s=0.1, on_step=_hook)
    assert native.report == loop.report  # the minima found by bounds are the argmin's
    lowest = native.log.clearance.minimum.copy()
    np.testing.assert_array_equal(native.log.clearance_m, loop.log.clearance_m)
    values = native.log.clearance_m
    assert values.shape == (native.log.steps, n)
    np.testing.assert_array_equal(lowest, values.min(axis=0))
    np.testing.assert_array_equal(native.log.clearance.first_step, values.argmin(axis=0))


def test_a_model_changed_after_its_run_reads_the_runs_clearances() -> None:
    model = load_arm_scene(_scene(1, 12))
    motion = quintic([P2, P3], durations=1.0)
    want = play_arm(model, motion, task="t", settle_s=0.1, on_step=_hook).log.clearance_m
    native = play_arm(model, motion, task="t", settle_s=0.1)
    g = int(arm_binding(model).groups.obstacle_geoms[0])
    pos = np.array(model.geom_pos[g])
    model.geom_pos[g] = pos + 0.05  # the obstacle moved after the run
    np.testing.assert_array_equal(native.log.clearance_m, want)
    np.testing.assert_array_equal(model.geom_pos[g], pos + 0.05)  # and left where it was put
