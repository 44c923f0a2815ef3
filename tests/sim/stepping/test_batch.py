"""Batch rollouts: every log and report bit-identical to single playbacks of the same commands."""

from __future__ import annotations

import dataclasses
import threading
from pathlib import Path
from typing import Any

import mujoco
import numpy as np
import pytest

from lynxsim.errors import InvalidInputError, LimitViolationError
from lynxsim.robots.arm import build_trajectory
from lynxsim.sim.arm.batch import play_arm_batch
from lynxsim.sim.arm.model import load_arm_scene
from lynxsim.sim.arm.playback import arm_binding, play_arm
from lynxsim.sim.arm.task import pick_and_place_gripper
from lynxsim.sim.stepping.batch import BatchRun, batch_rollout
from lynxsim.sim.stepping.native import chunk_bounds
from lynxsim.sim.summary import Playback
from lynxsim.tasks import load_task
from lynxsim.traj import TrajectoryKind

ROOT = Path(__file__).resolve().parents[3]
ARM_TASKS = sorted(p for p in (ROOT / "tasks").glob("*.toml") if load_task(p).robot == "arm")
"""The shipped arm tasks."""
KINDS = (TrajectoryKind.CUBIC, TrajectoryKind.LSPB, TrajectoryKind.LINE, TrajectoryKind.RUCKIG)
"""Trajectory types played in one batch per task (their durations differ)."""


def assert_identical(a: Any, b: Any, where: str = "log") -> None:
    """Equal bit for bit: arrays in dtype, shape and every value; dataclasses field by field."""
    if isinstance(a, np.ndarray):
        assert a.dtype == b.dtype, where
        assert a.shape == b.shape, where
        assert np.array_equal(a, b), where  # NaN nowhere: a NaN would fail here
    elif dataclasses.is_dataclass(a) and not isinstance(a, type):
        for f in dataclasses.fields(a):
            assert_identical(getattr(a, f.name), getattr(b, f.name), f"{where}.{f.name}")
    elif isinstance(a, dict):
        assert a.keys() == b.keys(), where
        for k in a:
            assert_identical(a[k], b[k], f"{where}[{k!r}]")
    else:
        assert a == b, where


def assert_same_playback(batch: Playback, single: Playback) -> None:
    assert_identical(batch.log, single.log)
    assert batch.report == single.report


@pytest.mark.parametrize("path", ARM_TASKS, ids=[p.stem for p in ARM_TASKS])
@pytest.mark.parametrize("nthread", [1, 2], ids=["1thread", "2threads"])
def test_batch_of_a_task_equals_single_playbacks(path, nthread):
    task = load_task(path)
    model = load_arm_scene(task.scene)
    trajectories = [build_trajectory(task, kind) for kind in KINDS]
    # The gripper schedule of a run with the cube, and none: both reproduced.
    grippers = [pick_and_place_gripper(t.duration) for t in trajectories[:-1]] + [None]
    assert len({t.duration for t in trajectories}) > 1  # runs of different lengths
    batch = play_arm_batch(
        model, trajectories, task=task.name, gripper_cmds=grippers, nthread=nthread
    )
    assert len(batch) == len(trajectories)
    for trajectory, gripper, played in zip(trajectories, grippers, batch, strict=True):
        single = play_arm(model, trajectory, task=task.name, gripper_cmd=gripper)
        assert_same_playback(played, single)
        assert played.report.healthy


def test_batch_keeps_verdicts_first_contacts_and_clearances():
    # The plain pick-and-place hits the cylinder; the via points clear it.
    hit = load_task(ROOT / "tasks" / "pick_and_place.toml")
    model = load_arm_scene(hit.scene.without_cube())
    trajectories = [build_trajectory(hit, kind) for kind in (TrajectoryKind.QUINTIC, "line")]
    batch = play_arm_batch(model, trajectories, task=hit.name, nthread=2)
    for trajectory, played in zip(trajectories, batch, strict=True):
        single = play_arm(model, trajectory, task=hit.name)
        assert played.report.collided
        assert played.report.obstacle == single.report.obstacle
        assert played.report.obstacles == single.report.obstacles
        assert_identical(played.log.clearance_m, single.log.clearance_m)


@pytest.mark.parametrize("nthread", [1, 2], ids=["1thread", "2threads"])
def test_batch_progress_rises_to_one_and_changes_nothing(nthread):
    """A progress bar over a batch: heard once per stepped chunk of a group, the same logs."""
    task = load_task(ROOT / "tasks" / "three_obstacles.toml")
    model = load_arm_scene(task.scene)
    trajectories = [build_trajectory(task, kind) for kind in KINDS[:3]]
    heard: list[float] = []
    with_bar = play_arm_batch(
        model, trajectories, task=task.name, nthread=nthread, progress=heard.append
    )
    without = play_arm_batch(model, trajectories, task=task.name, nthread=nthread)
    longest = max(p.log.steps for p in with_bar)
    groups = min(nthread, len(trajectories))
    assert len(heard) >= len(chunk_bounds(longest))  # every group's chunks are heard
    assert len(heard) <= groups * len(chunk_bounds(longest))
    assert heard == sorted(heard)
    assert 0.0 < heard[0] < 1.0
    assert heard[-1] == 1.0
    for a, b in zip(with_bar, without, strict=True):
        assert_same_playback(a, b)


def test_run_where_mujoco_warns_is_logged_as_rollout_logs_it():
    # Servos far too stiff: MuJoCo finds bad accelerations and resets the state.
    task = load_task(ROOT / "tasks" / "pick_and_place.toml")
    model = load_arm_scene(task.scene)
    model.actuator_gainprm[:5, 0] *= 1e9
    model.actuator_biasprm[:5, 1] *= 1e9
    model.actuator_forcerange[:5] *= 1e9
    trajectory = build_trajectory(task, TrajectoryKind.QUINTIC)
    messages: list[str] = []
    previous = mujoco.get_mju_user_warning()
    mujoco.set_mju_user_warning(messages.append)  # not into MUJOCO_LOG.TXT
    try:
        warned = play_arm_batch(model, [trajectory, trajectory], task="t", nthread=2)
        single = play_arm(model, trajectory, task="t")
    finally:
        mujoco.set_mju_user_warning(previous)
    assert single.log.warnings["badqacc"]
    assert any("QACC" in m for m in messages)
    for played in warned:
        assert_same_playback(played, single)


def test_commands_outside_the_joint_ranges_are_refused_before_stepping():
    model = load_arm_scene()
    q_cmd = np.zeros((100, 5))
    q_cmd[60:, 2] = 0.2  # elbow range is [-145, 0] deg
    good = BatchRun(np.zeros((100, 5)), np.zeros((100, 3)), task="t", trajectory="t")
    bad = dataclasses.replace(good, q_cmd=q_cmd)
    with pytest.raises(LimitViolationError, match=r"joint 3 \(elbow\) by 11\.459 deg"):
        batch_rollout(model, arm_binding(model), [good, bad])


@pytest.mark.parametrize(
    ("nthread", "message"),
    [
        (0, "between 1 and 1,024, got 0"),
        (-1, "between 1 and 1,024, got -1"),
        (2000, "between 1 and 1,024, got 2,000"),
        (2.5, "an integer, got 2.5"),
        ("2", "an integer, got '2'"),
        (True, "an integer, got True"),
    ],
)
def test_thread_counts_that_are_not_whole_numbers_in_range_are_refused(nthread, message):
    model = load_arm_scene()
    with pytest.raises(InvalidInputError, match=f"nthread must be {message}"):
        batch_rollout(model, arm_binding(model), [], nthread=nthread)


def test_a_batch_uses_no_more_threads_than_runs_and_takes_any_iterable():
    """Many threads asked for two runs: two are used (no idle helper is started)."""
    model = load_arm_scene()
    run = BatchRun(np.zeros((50, 5)), np.zeros((50, 3)), task="t", trajectory="t")
    seen: set[str] = set()

    def watch(fraction: float) -> None:
        seen.update(t.name for t in threading.enumerate() if t.name.startswith("lynxsim-"))

    logs = batch_rollout(model, arm_binding(model), iter([run, run]), nthread=64, progress=watch)
    assert len(logs) == 2
    assert seen <= {"lynxsim-stepper-0"}


def test_gripper_schedules_must_match_the_trajectories():
    task = load_task(ROOT / "tasks" / "pick_and_place.toml")
    model = load_arm_scene(task.scene)
    trajectory = build_trajectory(task, TrajectoryKind.QUINTIC)
    with pytest.raises(InvalidInputError, match="1 gripper schedules for 2 trajectories"):
        play_arm_batch(model, [trajectory, trajectory], task="t", gripper_cmds=[None])


def test_empty_batch_plays_nothing():
    model = load_arm_scene()
    assert batch_rollout(model, arm_binding(model), []) == []
