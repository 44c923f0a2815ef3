"""Boxes and spheres swept too: judged placements equal their own runs (three_obstacles)."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pytest

from lynxsim.robots import motion
from lynxsim.robots.arm import ROBOT as ARM
from lynxsim.scene import Scene
from lynxsim.sim.arm.recorded import arm_scene_model, record_run
from lynxsim.sim.arm.task import run_arm_trajectory
from lynxsim.sim.sweep_judge import PlacementJudge
from lynxsim.tasks import load_task
from lynxsim.verdicts import Verdict

TASKS = Path(__file__).resolve().parents[2] / "tasks"


@pytest.mark.slow
@pytest.mark.parametrize("name", ["box", "sphere"])
def test_judged_box_and_sphere_placements_equal_their_own_runs(name):
    task = load_task(TASKS / "three_obstacles.toml")
    trajectory = motion(ARM, task, "line")
    obstacle = task.scene.obstacle(name)
    others = tuple(o for o in task.scene.obstacles if o.name != name)
    run = record_run(
        trajectory, task=task.name, scene=Scene(others, task.scene.table, task.scene.cube)
    )
    gx, gy = np.meshgrid(np.arange(-250, 451, 50) / 1000.0, np.arange(-500, 501, 50) / 1000.0)
    x, y = gx.reshape(-1), gy.reshape(-1)
    judged = PlacementJudge(run, obstacle, arm_scene_model).judge(x, y)
    rng = np.random.default_rng(0)
    for code in (Verdict.CLEAR, Verdict.COLLIDED):
        rows = np.flatnonzero(judged.verdict == code)
        assert len(rows) >= 3
        for j in rng.choice(rows, size=3, replace=False).tolist():
            moved = dataclasses.replace(obstacle, position=(x[j], y[j], obstacle.position[2]))
            scene = Scene((*others, moved), task.scene.table, task.scene.cube)
            report = run_arm_trajectory(trajectory, task=task.name, scene=scene).report
            own = next(o for o in report.obstacles if o.name == name)
            assert own.collided == (code == Verdict.COLLIDED)
            if code == Verdict.CLEAR:
                assert own.min_clearance_m == judged.min_clearance_m[j]
                assert own.min_clearance_time_s == judged.min_clearance_time_s[j]
            else:
                assert own.first_contact_s == judged.first_contact_s[j]
