"""Planned motions judged by the physics: clear when played, bit for bit the same per seed."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import mujoco
import numpy as np
import pytest

from lynxsim.arm import LYNX_ARM
from lynxsim.arm.motion import arm_lipschitz, joint_radii
from lynxsim.plan import StartInCollisionError
from lynxsim.robots import motion, plan
from lynxsim.robots.arm import ROBOT as ARM
from lynxsim.scene import Cylinder
from lynxsim.sim.arm.model import SceneIds, load_arm_scene
from lynxsim.sim.arm.playback import arm_checker
from lynxsim.sim.arm.task import run_arm_trajectory
from lynxsim.sim.planning import DEFAULT_MARGIN_M, PLANNING_CAP_M, CheckerOracle
from lynxsim.tasks import load_task
from lynxsim.traj import TrajectoryKind
from tests.helpers import assert_close

TASKS = Path(__file__).resolve().parents[2] / "tasks"

TRACKING_ALLOWANCE_M = 0.005
"""Clearance the physics run may lose against the plan's margin: the servos' tracking
error (the README's tool errors stay under 2 mm) and the fingers closing on the cube."""


@pytest.mark.parametrize("name", ["pick_and_place", "obstacle_avoidance", "three_obstacles"])
def test_planned_motion_is_clear_in_the_physics_run(name):
    task = load_task(TASKS / f"{name}.toml")
    trajectory = motion(ARM, task, TrajectoryKind.PLANNED)
    assert trajectory.kind is TrajectoryKind.PLANNED
    report = run_arm_trajectory(trajectory, task=name, scene=task.scene).report
    assert not report.collided
    assert report.self_collisions == ()
    assert report.min_clearance_m >= DEFAULT_MARGIN_M - TRACKING_ALLOWANCE_M
    assert len(report.obstacles) == len(task.scene.obstacles)
    assert report.tool_final_error_m < 0.002
    assert report.healthy


def test_three_obstacles_block_quintic_and_not_planned():
    task = load_task(TASKS / "three_obstacles.toml")
    quintic = motion(ARM, task, TrajectoryKind.QUINTIC)
    checker = arm_checker(load_arm_scene(task.scene))
    commanded = checker.check(
        quintic.sample(np.arange(0.0, quintic.duration, 0.002)).q, grasped=True
    )
    assert (commanded.clearance_m.min(axis=0) < 0.0).all()  # its path runs through all three
    played = run_arm_trajectory(quintic, task="q", scene=task.scene).report
    assert played.collided
    planned = run_arm_trajectory(
        motion(ARM, task, TrajectoryKind.PLANNED), task="p", scene=task.scene
    ).report
    assert not planned.collided
    assert (
        min(o.min_clearance_m for o in planned.obstacles) >= DEFAULT_MARGIN_M - TRACKING_ALLOWANCE_M
    )


def test_same_task_and_seed_give_the_same_trajectory_bit_for_bit():
    task = load_task(TASKS / "obstacle_avoidance.toml")
    a, b = (plan(ARM, task, seed=3).trajectory for _ in range(2))
    t = np.linspace(0.0, a.duration, 2001)
    assert a.duration == b.duration
    for x, y in zip(a.sample(t), b.sample(t)):
        assert np.array_equal(x, y)


def test_every_timed_sample_keeps_half_the_margin_by_the_checker():
    task = load_task(TASKS / "three_obstacles.toml")
    planned = plan(ARM, task, seed=1)
    oracle = CheckerOracle(arm_checker(load_arm_scene(task.scene)))
    t = np.arange(0.0, planned.trajectory.duration, 0.002)
    clearance = oracle.clearance(planned.trajectory.sample(t).q, grasped=True)
    assert clearance.min() >= DEFAULT_MARGIN_M / 2


@pytest.mark.parametrize("grasped", [False, True], ids=["free", "grasped"])
def test_the_oracle_reads_hits_as_minus_infinity_and_agrees_with_the_checker(grasped):
    task = load_task(TASKS / "three_obstacles.toml")
    checker = arm_checker(load_arm_scene(task.scene))
    oracle = CheckerOracle(checker)
    rng = np.random.default_rng(0)
    q = rng.uniform(LYNX_ARM.q_min, LYNX_ARM.q_max, size=(400, 5))
    check = checker.check(q, grasped=grasped)
    clearance = oracle.clearance(q, grasped=grasped)
    hit = check.in_collision | check.support
    assert hit.any()
    assert (~hit).any()
    assert np.all(clearance[hit] == -np.inf)
    expected = np.minimum(check.min_clearance_m[~hit], PLANNING_CAP_M)
    assert (expected < PLANNING_CAP_M).sum() > 50  # exact values, not only the cap
    assert_close(clearance[~hit], expected, atol=1e-12)


def test_lipschitz_bound_holds_for_every_collision_geom_corner():
    """No corner of a robot collision box moves more than L * |dq| (the planner's premise)."""
    model = load_arm_scene()
    data = mujoco.MjData(model)
    ids = SceneIds.from_model(model)
    robot = np.flatnonzero(ids.collision_groups(model).robot)
    signs = np.array(np.meshgrid([-1, 1], [-1, 1], [-1, 1])).reshape(3, -1).T  # (8, 3)
    aabb = np.asarray(model.geom_aabb)[robot]  # centre, half sizes, geom frame

    def corners(q: np.ndarray) -> np.ndarray:
        data.qpos[np.asarray(ids.arm_qpos)] = q
        mujoco.mj_kinematics(model, data)
        local = aabb[:, None, :3] + signs[None] * aabb[:, None, 3:]  # (G, 8, 3)
        rot = data.geom_xmat[robot].reshape(-1, 3, 3)
        return data.geom_xpos[robot][:, None] + np.einsum("gij,gkj->gki", rot, local)

    lipschitz, radii = arm_lipschitz(), joint_radii()
    rng = np.random.default_rng(1)
    worst, worst_joint = 0.0, np.zeros(5)
    for k in range(1000):
        q0 = rng.uniform(LYNX_ARM.q_min, LYNX_ARM.q_max)
        step = rng.normal(scale=0.05, size=5)
        if k % 2:  # one joint alone: its own radius bounds the motion
            j = k // 2 % 5
            step = np.eye(5)[j] * step[j]
        q1 = np.clip(q0 + step, LYNX_ARM.q_min, LYNX_ARM.q_max)
        dq = np.linalg.norm(q1 - q0)
        if dq == 0.0:
            continue
        moved = np.linalg.norm(corners(q1) - corners(q0), axis=-1).max()
        worst = max(worst, moved / (lipschitz * dq))
        if k % 2:
            worst_joint[j] = max(worst_joint[j], moved / (radii[j] * dq))
    assert 0.3 < worst <= 1.0, worst  # tight enough to matter, never exceeded
    assert (worst_joint <= 1.0).all(), worst_joint


def test_a_start_inside_the_margin_names_the_segment():
    task = load_task(TASKS / "obstacle_avoidance.toml")
    near_p1 = Cylinder("post", position=(0.0, 0.33, -0.0125), radius=0.01, height=0.4)
    crowded = dataclasses.replace(task, scene=dataclasses.replace(task.scene, obstacles=(near_p1,)))
    with pytest.raises(
        StartInCollisionError, match=r"^segment 'P1 -> V1': the start .* has clearance"
    ):
        plan(ARM, crowded)
