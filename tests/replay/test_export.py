"""The exporter against MuJoCo.

Every primitive, colours as MuJoCo draws them, the stated pose error a true bound at every
physics step, contacts and clearances kept.
"""

from __future__ import annotations

import mujoco
import numpy as np
import pytest

from lynxsim.errors import InvalidInputError
from lynxsim.sim.replay import FREE_CAMERA, export_replay
from lynxsim.sim.replay.scene import scene_parts
from lynxsim.web.page import replay_page
from lynxsim.web.poses import interpolate_poses
from lynxsim.web.replay_data import GEOM_KINDS

PAGE_LIMIT_BYTES = 3 * 2**20
"""The issue's bound on the replay page of a 6 s run [bytes]."""

_ALL_KINDS = """
<mujoco>
  <compiler angle="radian" autolimits="true"/>
  <asset>
    <material name="red" rgba="0.9 0.1 0.1 1"/>
    <mesh name="tetra" vertex="0 0 0  0.1 0 0  0 0.1 0  0 0 0.1"/>
  </asset>
  <worldbody>
    <camera name="fixed" pos="0 -1 0.5" xyaxes="1 0 0 0 0.5 1"/>
    <geom name="ground" type="plane" size="0 0 0.1" rgba="0.2 0.3 0.4 1"/>
    <geom name="wall" type="box" size="0.1 0.2 0.3" pos="1 0 0" material="red"/>
    <geom name="hidden" type="sphere" size="0.1" group="3"/>
    <geom name="clear" type="sphere" size="0.1" rgba="1 1 1 0"/>
    <geom name="tetra" type="mesh" mesh="tetra"/>
    <site name="mark" type="cylinder" size="0.02 0.001" pos="0 0.5 0" rgba="0 1 0 0.5"/>
    <body name="arm" pos="0 0 0.5">
      <joint name="hinge" axis="0 1 0"/>
      <geom name="ball" type="sphere" size="0.05" rgba="0 0 1 1"/>
      <geom name="rod" type="capsule" fromto="0 0 0 0.3 0 0" size="0.02" material="red"
        rgba="0.5 0.5 0.5 1"/>
      <geom name="egg" type="ellipsoid" size="0.03 0.02 0.01" pos="0.3 0 0"/>
      <geom name="drum" type="cylinder" size="0.04 0.01" pos="0 0 0.1" euler="0.3 0 0"/>
      <site name="tip" type="box" size="0.01 0.01 0.01" pos="0.35 0 0"/>
      <body name="fixed_child" pos="0.1 0 0">
        <geom name="plate" type="box" size="0.01 0.02 0.03"/>
      </body>
    </body>
  </worldbody>
</mujoco>
"""


def test_every_primitive_is_drawn_with_the_colour_and_pose_mujoco_gives_it():
    model = mujoco.MjModel.from_xml_string(_ALL_KINDS)
    parts = scene_parts(model)
    g = parts.geoms
    by_name = {n: i for i, n in enumerate(g.names)}
    assert set(by_name) == {"ground", "wall", "mark", "ball", "rod", "egg", "drum", "tip", "plate"}
    assert set(g.kind.tolist()) == set(
        GEOM_KINDS
    )  # plane, sphere, capsule, ellipsoid, cylinder, box
    assert parts.body_names == ("arm", "fixed_child")
    np.testing.assert_allclose(g.rgba[by_name["wall"]], [0.9, 0.1, 0.1, 1], atol=1e-6)  # material
    np.testing.assert_allclose(g.rgba[by_name["ball"]], [0, 0, 1, 1], atol=1e-6)
    np.testing.assert_allclose(
        g.rgba[by_name["rod"]], [0.9, 0.1, 0.1, 1], atol=1e-6
    )  # default rgba
    np.testing.assert_allclose(g.rgba[by_name["mark"]], [0, 1, 0, 0.5], atol=1e-6)
    assert g.body[by_name["wall"]] == -1
    assert g.body[by_name["plate"]] == 1
    np.testing.assert_allclose(g.pos[by_name["wall"]], [1, 0, 0])
    np.testing.assert_allclose(g.size[by_name["rod"]][:2], [0.02, 0.15], atol=1e-12)
    # a drawn point of the drum: pose in its body, as MuJoCo has it in the world
    data = mujoco.MjData(model)
    data.qpos[:] = 0.7
    mujoco.mj_kinematics(model, data)
    drum = model.geom("drum").id
    R_body = data.xmat[model.body("arm").id].reshape(3, 3)
    R_geom = np.empty(9)
    mujoco.mju_quat2Mat(R_geom, g.quat[by_name["drum"]])
    np.testing.assert_allclose(
        R_body @ g.pos[by_name["drum"]] + data.xpos[model.body("arm").id], data.geom_xpos[drum]
    )
    np.testing.assert_allclose(
        R_body @ R_geom.reshape(3, 3), data.geom_xmat[drum].reshape(3, 3), atol=1e-12
    )
    assert [c.name for c in parts.cameras] == ["fixed"]


def _drawn_points_true_and_shown(run, steps):
    """World positions of the centres and box corners of every moving primitive, (S, P, 3).

    As MuJoCo has them, and as the page draws them.
    """
    model, data, parts = run.model, mujoco.MjData(run.model), scene_parts(run.model)
    replay = run.data
    pos, quat = replay.body_poses(run.log.time_s[steps])
    moving = np.flatnonzero(parts.geoms.body >= 0)
    corners = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)], dtype=float)
    true, shown = [], []
    for i, k in enumerate(steps):
        data.qpos[:] = run.log.qpos[k]
        mujoco.mj_kinematics(model, data)
        t_pts, s_pts = [], []
        for gi in moving:
            b = parts.geoms.body[gi]
            Rg = np.empty(9)
            mujoco.mju_quat2Mat(Rg, parts.geoms.quat[gi])
            local = parts.geoms.pos[gi] + (corners * parts.geoms.size[gi]) @ Rg.reshape(3, 3).T
            Rb_true = data.xmat[parts.bodies[b]].reshape(3, 3)
            Rb = np.empty(9)
            mujoco.mju_quat2Mat(Rb, quat[i, b])
            t_pts.append(local @ Rb_true.T + data.xpos[parts.bodies[b]])
            s_pts.append(local @ Rb.reshape(3, 3).T + pos[i, b])
        true.append(np.concatenate(t_pts))
        shown.append(np.concatenate(s_pts))
    return np.array(true), np.array(shown)


@pytest.mark.parametrize("which", ["planned_run", "rrr_run", "colliding_run"])
def test_the_stated_pose_error_bounds_every_drawn_point_at_every_physics_step(request, which):
    run = request.getfixturevalue(which)
    steps = np.arange(0, run.log.steps, 3)
    true, shown = _drawn_points_true_and_shown(run, steps)
    error = np.linalg.norm(true - shown, axis=-1).max()
    stated = run.data.pose_error_m
    assert error <= stated * (1 + 1e-9) + 1e-12
    assert stated <= 1e-3  # under a millimetre at the default frame rate
    assert error > 0.1 * stated  # the bound is not vacuous


def test_a_slower_frame_rate_states_a_larger_error(planned_run):
    run = planned_run
    fine = export_replay(run.model, run.log, run.playback.report, fps=100.0)
    coarse = export_replay(run.model, run.log, run.playback.report, fps=20.0)
    assert coarse.frames < fine.frames
    assert coarse.pose_error_m > fine.pose_error_m
    np.testing.assert_array_equal(fine.poses.pos_q, run.data.poses.pos_q)  # the saved one


def test_frames_start_at_the_first_and_end_at_the_last_recorded_step(rrr_run):
    data, log = rrr_run.data, rrr_run.log
    assert data.time_s[0] == log.time_s[0]
    assert data.time_s[-1] == log.time_s[-1]
    # frame i shows the first step at or after i / fps (as the videos do): 0.002, 0.01, 0.02, ...
    np.testing.assert_allclose(data.time_s[1:-1], np.arange(1, data.frames - 1) * 0.01, atol=1e-9)


def test_clearance_curves_keep_the_run_minimum_of_each_obstacle(planned_run):
    data, log = planned_run.data, planned_run.log
    assert data.clearance.names == ("cylinder", "box", "sphere")
    np.testing.assert_array_equal(data.clearance.values_m.min(axis=0), log.clearance_m.min(axis=0))
    for o in planned_run.playback.report.obstacles:
        j = data.clearance.names.index(o.name)
        assert data.clearance.values_m[:, j].min() == o.min_clearance_m


def test_contact_spans_cover_exactly_the_steps_of_obstacle_hits(colliding_run):
    data, log = colliding_run.data, colliding_run.log
    hits = log.time_s[log.obstacle_hits()]
    cylinder = data.geoms.names.index("cylinder")
    mine = (data.contacts.geom == cylinder) & (data.contacts.kind == 0)
    inside = np.zeros(log.steps, dtype=bool)
    for a, b in zip(data.contacts.start_s[mine], data.contacts.end_s[mine]):
        inside |= (log.time_s >= a) & (log.time_s <= b)
    np.testing.assert_array_equal(log.time_s[inside], hits)
    first = colliding_run.playback.report.obstacle.first_time_s
    assert data.contacts.start_s[mine].min() == first
    painted = {data.geoms.names[g] for g in data.contacts.geom[data.contacts.kind == 0]}
    assert "cylinder" in painted
    assert len(painted) > 1


def test_pages_stay_under_three_megabytes_for_six_seconds(planned_run, rrr_run):
    for run in (planned_run, rrr_run):
        seconds = float(run.log.time_s[-1])
        assert 5.0 < seconds < 7.0
        assert len(replay_page(run.data).encode()) < PAGE_LIMIT_BYTES
        assert run.page.stat().st_size < PAGE_LIMIT_BYTES


def test_the_free_camera_is_offered_and_a_bad_camera_or_log_is_refused(planned_run):
    run = planned_run
    assert [c.name for c in run.data.cameras] == ["front", "top", FREE_CAMERA]
    assert run.data.default_camera == "front"
    with pytest.raises(
        InvalidInputError, match=r"no camera named 'side'; available: front, top, free"
    ):
        export_replay(run.model, run.log, run.playback.report, camera="side")
    other = mujoco.MjModel.from_xml_string(_ALL_KINDS)
    with pytest.raises(InvalidInputError, match="recorded with another model"):
        export_replay(other, run.log, run.playback.report)
    with pytest.raises(InvalidInputError, match="fps"):
        export_replay(run.model, run.log, run.playback.report, fps=0.0)


def test_interpolated_poses_at_frame_times_are_the_frames(planned_run):
    data = planned_run.data
    pos, quat = interpolate_poses(
        data.time_s, data.poses.positions(), data.poses.quaternions(), data.time_s
    )
    np.testing.assert_allclose(pos, data.poses.positions(), atol=1e-15)
    np.testing.assert_allclose(quat, data.poses.quaternions(), atol=1e-15)
