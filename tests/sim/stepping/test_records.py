"""A natively stepped run's records do not depend on how it is cut, nor on a helper thread.

:class:`lynxsim.sim.stepping.records.SensedRecorder` makes a run's records chunk by
chunk (each state's sensors sit in the next step's row, across chunk
boundaries); :func:`lynxsim.sim.stepping.native.chunk_bounds` says how a run is cut;
``rollout`` steps on a helper thread where a second CPU is free. Any cut, and
either way of stepping, must give the same records and log, bit for bit.
"""

from __future__ import annotations

import itertools
from pathlib import Path

import mujoco
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from mujoco import rollout as native

import lynxsim.sim.stepping.native as native_module
from lynxsim.arm import tool_pose
from lynxsim.robots.arm import build_trajectory
from lynxsim.sim.arm.model import load_arm_scene
from lynxsim.sim.arm.playback import arm_binding, play_arm
from lynxsim.sim.arm.task import pick_and_place_gripper
from lynxsim.sim.stepping.commands import physics_grid, plan_commands, rest_at_start
from lynxsim.sim.stepping.native import chunk_bounds
from lynxsim.sim.stepping.records import SensedChunk, SensedRecorder, StepRecords
from lynxsim.sim.stepping.sensors import RecordingLayout
from lynxsim.tasks import load_task
from lynxsim.traj import TrajectoryKind

ROOT = Path(__file__).resolve().parents[3]
THREE_OBSTACLES = load_task(ROOT / "tasks" / "three_obstacles.toml")


@pytest.fixture(scope="module")
def stepped():
    """The three-obstacle task's quintic run stepped natively in one go (it rubs an obstacle)."""
    model = load_arm_scene(THREE_OBSTACLES.scene)
    binding = arm_binding(model)
    trajectory = build_trajectory(THREE_OBSTACLES, TrajectoryKind.QUINTIC)
    q = trajectory.sample(physics_grid(trajectory.duration, model.opt.timestep)).q
    commands = plan_commands(
        model, binding, q, tool_pose(q).position, settle_s=0.5, presettle_s=0.5, gripper_cmd=None
    )
    data = mujoco.MjData(model)
    rest_at_start(model, data, binding, q[0])
    full = mujoco.mjtState.mjSTATE_FULLPHYSICS
    state = np.empty(mujoco.mj_stateSize(model, full))
    controls = np.repeat(np.array(data.ctrl)[None], len(commands.ctrl), axis=0)
    controls[:, commands.ctrl_adr] = commands.ctrl
    mujoco.mj_getState(model, data, state, full)
    states, sensordata = native.rollout(
        model, data, state, controls[None], control_spec=mujoco.mjtState.mjSTATE_CTRL
    )
    mujoco.mj_forward(model, data)
    layout = RecordingLayout.of(model, binding)
    assert layout is not None
    run = (states[0, :, 0], states[0, :, 1 : 1 + model.nq], sensordata[0])
    return model, binding, layout, run, np.array(data.sensordata)


def _records(stepped, cuts: list[int]) -> StepRecords:
    model, binding, layout, (time, qpos, sensordata), final = stepped
    recorder = SensedRecorder(model, binding.groups, layout, len(time))
    ends = [*cuts, len(time)]
    for a, b in zip([0, *cuts], ends, strict=True):
        last = b == len(time)
        recorder.add(SensedChunk(time[a:b], qpos[a:b], sensordata[a:b], final if last else None))
    return recorder.finish()


@settings(max_examples=8, deadline=None)
@given(data=st.data())
def test_records_do_not_depend_on_how_the_run_is_cut(stepped, data):
    steps = len(stepped[3][0])
    cuts = sorted(set(data.draw(st.lists(st.integers(1, steps - 1), max_size=12))))
    whole, cut = _records(stepped, []), _records(stepped, cuts)
    for name in ("time", "qpos", "force", "tool"):
        np.testing.assert_array_equal(getattr(cut, name), getattr(whole, name), err_msg=name)
    # each obstacle's minimum and its step (the clearance of every step is computed
    # from the states when a log's are read)
    assert cut.minima is not None
    assert whole.minima is not None
    np.testing.assert_array_equal(cut.minima.value, whole.minima.value)
    np.testing.assert_array_equal(cut.minima.step, whole.minima.step)
    groups = stepped[1].groups
    for a, b in zip(cut.contacts(groups, steps), whole.contacts(groups, steps), strict=True):
        np.testing.assert_array_equal(a, b)
    assert len(whole.contacts(groups, steps)[0]) > 0  # the run touches: contacts are compared


def test_a_run_without_a_helper_thread_logs_the_same(monkeypatch):
    """One CPU (no helper: stepping and records in turn) and the default give the same log."""
    task = THREE_OBSTACLES
    trajectory = build_trajectory(task, TrajectoryKind.QUINTIC)
    gripper = pick_and_place_gripper(trajectory.duration)
    model = load_arm_scene(task.scene)
    shared = play_arm(model, trajectory, task=task.name, gripper_cmd=gripper)
    monkeypatch.setattr(native_module, "cpu_count", lambda: 1)
    alone = play_arm(model, trajectory, task=task.name, gripper_cmd=gripper)
    assert alone.report == shared.report
    for name in ("time_s", "qpos", "force", "tool", "clearance_m", "contact_step", "contact_geoms"):
        np.testing.assert_array_equal(getattr(alone.log, name), getattr(shared.log, name))


def test_no_steps_make_no_chunks():
    assert chunk_bounds(0) == []


@given(steps=st.integers(1, 20_000))
def test_chunks_cover_the_run_in_order_short_at_either_end(steps):
    bounds = chunk_bounds(steps)
    assert bounds[0][0] == 0
    assert bounds[-1][1] == steps
    assert all(a < b for a, b in bounds)
    assert all(b == c for (_, b), (c, _) in itertools.pairwise(bounds))
    sizes = [b - a for a, b in bounds]
    assert max(sizes) <= native_module._CHUNK_MOST
    assert sizes[0] <= native_module._CHUNK_FIRST
    if steps >= 4 * native_module._CHUNK_MOST:
        assert sizes[-1] == native_module._CHUNK_LAST
        # no short chunk in the middle: the stepping may run only so many chunks ahead
        middle = [s for s in sizes if s > native_module._CHUNK_MOST // 2]
        assert max(middle) - min(middle) <= 1


def test_progress_is_heard_per_native_chunk_and_changes_nothing():
    """A progress bar keeps the native path: one report per chunk, the same log."""
    task = THREE_OBSTACLES
    trajectory = build_trajectory(task, TrajectoryKind.QUINTIC)
    model = load_arm_scene(task.scene)
    heard: list[float] = []
    with_bar = play_arm(model, trajectory, task=task.name, progress=heard.append)
    without = play_arm(model, trajectory, task=task.name)
    assert len(heard) == len(chunk_bounds(with_bar.log.steps))
    assert heard == sorted(heard)
    assert heard[-1] == 1.0
    assert with_bar.report == without.report
    np.testing.assert_array_equal(with_bar.log.qpos, without.log.qpos)
    np.testing.assert_array_equal(with_bar.log.clearance_m, without.log.clearance_m)


def test_a_python_loop_run_reports_progress_too():
    """A step hook sends the run through the Python loop; its progress still comes, rising."""
    task = THREE_OBSTACLES
    trajectory = build_trajectory(task, TrajectoryKind.QUINTIC)
    heard: list[float] = []
    play_arm(
        load_arm_scene(task.scene),
        trajectory,
        task=task.name,
        on_step=lambda k, data: None,
        progress=heard.append,
    )
    assert 15 <= len(heard) <= 25  # about every 5 %
    assert heard == sorted(heard)
    assert heard[0] == 0.0
    assert heard[-1] == 1.0  # the end is heard, as on the native path
