"""The recording sensors say what posing a state says: positions, forces and contacts.

The reference for each state is MuJoCo's own ``MjData`` after ``mj_forward``
(site and geom poses, actuator forces, the contact list classified by
:func:`lynxsim.sim.collision.classify_contacts`); the sensors' records of the
same state must equal it bit for bit, and the contact gate must flag exactly
the states with a contact that counts (obstacle, self or table hit).
"""

from __future__ import annotations

import dataclasses
from pathlib import Path

import mujoco
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from lynxsim.robots.arm import build_trajectory
from lynxsim.sim.arm.model import load_arm_scene, load_arm_spec
from lynxsim.sim.arm.playback import arm_binding, play_arm
from lynxsim.sim.arm.task import pick_and_place_gripper
from lynxsim.sim.collision import classify_contacts
from lynxsim.sim.stepping.commands import physics_grid
from lynxsim.sim.stepping.sensors import PREFIX, RecordingLayout, add_recording_sensors
from lynxsim.tasks import load_task
from lynxsim.traj import TrajectoryKind

ROOT = Path(__file__).resolve().parents[3]
THREE_OBSTACLES = load_task(ROOT / "tasks" / "three_obstacles.toml")


@pytest.fixture(scope="module")
def scene():
    model = load_arm_scene(THREE_OBSTACLES.scene)
    binding = arm_binding(model)
    layout = RecordingLayout.of(model, binding)
    assert layout is not None
    return model, binding, layout


@settings(max_examples=60, deadline=None)
@given(
    fractions=st.lists(st.floats(0.0, 1.0), min_size=5, max_size=5),
    opening=st.floats(0.0, 1.0),
)
def test_sensors_record_what_posing_the_state_gives(scene, fractions, opening):
    """Random joint vectors over the whole range (the arm in the table, itself, the obstacles)."""
    model, binding, layout = scene
    data = mujoco.MjData(model)
    lo, hi = np.asarray(model.jnt_range)[
        [model.actuator_trnid[a, 0] for a in binding.actuator_ids]
    ].T
    data.qpos[binding.qpos_adr] = lo + np.asarray(fractions) * (hi - lo)
    data.ctrl[binding.actuator_ids] = data.qpos[binding.qpos_adr]
    data.ctrl[binding.gripper_actuator_id] = 0.03 * opening
    mujoco.mj_forward(model, data)
    sensed = layout.split(np.array(data.sensordata)[None], np.array(data.sensordata))

    groups = binding.groups
    carried = np.flatnonzero(groups.carried)
    assert np.array_equal(sensed.tool[0], data.site_xpos[binding.tool_site_id])
    assert np.array_equal(sensed.geom_xpos[0], data.geom_xpos[carried])
    assert np.array_equal(sensed.geom_xmat[0], data.geom_xmat[carried])
    assert np.array_equal(sensed.force[0], data.actuator_force)

    n = data.ncon
    geoms, dist = np.array(data.contact.geom[:n]), np.array(data.contact.dist[:n])
    c = classify_contacts(groups, geoms, dist)
    assert sensed.gate[0] == bool((c.obstacle | c.self_hit | c.support).any())


def test_a_scene_without_the_sensors_logs_the_same_run():
    """Native stepping with sensors and the Python loop without them: the same log, bit for bit."""
    task = THREE_OBSTACLES
    trajectory = build_trajectory(task, TrajectoryKind.QUINTIC)
    gripper = pick_and_place_gripper(trajectory.duration)
    plain = load_arm_spec(task.scene).compile()
    assert not any(plain.sensor(s).name.startswith(PREFIX) for s in range(plain.nsensor))
    sensed = play_arm(load_arm_scene(task.scene), trajectory, task=task.name, gripper_cmd=gripper)
    looped = play_arm(plain, trajectory, task=task.name, gripper_cmd=gripper)
    assert sensed.report == looped.report
    assert sensed.report.obstacle is not None
    assert sensed.report.obstacle.collided
    for name in (
        "time_s", "qpos", "q_cmd", "q", "tool_ref", "tool", "force", "clearance_m",
        "contact_step", "contact_geoms", "contact_dist",
    ):  # fmt: skip
        np.testing.assert_array_equal(
            getattr(sensed.log, name), getattr(looped.log, name), err_msg=name
        )
    assert len(sensed.log.time_s) == len(
        physics_grid(trajectory.duration, plain.opt.timestep)
    ) + round(0.5 / plain.opt.timestep)


def test_a_scene_whose_parts_have_no_names_gets_no_sensors():
    """Sensors name what they measure; an unnamed carried geom leaves the model as it was."""
    spec = load_arm_spec(THREE_OBSTACLES.scene)
    model = spec.compile()
    spec.geom("forearm_collision").name = ""
    unnamed = spec.compile()
    out = add_recording_sensors(spec, unnamed, arm_binding(unnamed))
    assert out is unnamed
    assert RecordingLayout.of(out, arm_binding(out)) is None
    assert RecordingLayout.of(model, arm_binding(model)) is None  # compiled before any sensor


def test_a_robot_subtree_holding_a_colliding_geom_of_no_group_gets_no_sensors():
    """The gate counts contacts per robot subtree: a foreign colliding geom there would pass."""
    spec = load_arm_spec(THREE_OBSTACLES.scene)
    plain = spec.compile()
    forearm = plain.body(int(plain.geom("forearm_collision").bodyid[0])).name
    extra = spec.body(forearm).add_geom()
    extra.name, extra.type, extra.size = "lamp", mujoco.mjtGeom.mjGEOM_SPHERE, [0.01, 0, 0]
    extra.group, extra.contype, extra.conaffinity = 0, 1, 1  # colliding, not in the robot's group
    model = spec.compile()
    binding = arm_binding(model)
    assert not binding.groups.carried[model.geom("lamp").id]
    assert add_recording_sensors(spec, model, binding) is model
    extra.contype = extra.conaffinity = 0  # a visual geom: the subtree is the robot's again
    model = spec.compile()
    assert (
        RecordingLayout.of(
            add_recording_sensors(spec, model, arm_binding(model)), arm_binding(model)
        )
        is not None
    )


def test_a_scene_without_obstacles_records_no_geom_poses_and_the_same_log():
    """Geom poses serve the clearance bounds only: none are sensed where nothing is to clear."""
    task = THREE_OBSTACLES
    bare_scene = dataclasses.replace(task.scene, obstacles=())
    model = load_arm_scene(bare_scene)
    layout = RecordingLayout.of(model, arm_binding(model))
    assert layout is not None
    assert layout.geom_pos.size == 0
    assert layout.geom_mat.size == 0
    trajectory = build_trajectory(task, TrajectoryKind.QUINTIC)
    sensed = play_arm(model, trajectory, task=task.name)
    looped = play_arm(load_arm_spec(bare_scene).compile(), trajectory, task=task.name)
    assert sensed.report == looped.report
    assert sensed.log.clearance_m.shape == (len(sensed.log.time_s), 0)
    for name in ("qpos", "tool", "force", "contact_step", "contact_geoms", "contact_dist"):
        np.testing.assert_array_equal(getattr(sensed.log, name), getattr(looped.log, name))
