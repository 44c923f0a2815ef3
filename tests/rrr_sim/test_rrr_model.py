"""The 3-RRR MJCF model against lynxsim.rrr: geometry, loops, servos, names, stepping."""

from __future__ import annotations

import math

import mujoco
import numpy as np
import pytest

from lynxsim.errors import InvalidInputError, UnreachablePlatformPoseError
from lynxsim.rrr import RRR_ROBOT, ik, leg_points, platform_joints
from lynxsim.rrr.modes import HOME_MODE
from lynxsim.rrr.path import actuated_window, wrap_to_window
from lynxsim.sim.rrr.model import (
    HOME_POSE,
    LEG_BASE_JOINTS,
    LEG_ELBOW_JOINTS,
    assembly_qpos,
    load_rrr_model,
    load_rrr_scene,
    load_rrr_spec,
    loop_closure_errors,
    platform_pose,
)
from lynxsim.sim.rrr.verify import interference_at, settled_mode
from tests.helpers import assert_close
from tests.model_checks import (
    assert_every_element_named,
    step_random_controls,
    warnings_fired,
)
from tests.rrr_sim.conftest import FIGURE20_A, FIGURE20_E, FIGURE20_F

GEOMETRY_TOL_M = 1e-9
"""Agreement of MuJoCo's site and body positions with lynxsim.rrr [m]."""
ASSEMBLED_LOOP_TOL_M = 1e-12
"""Loop-closure error of an exact assembly before any step [m]."""
REST_LOOP_TOL_M = 1e-4
"""Acceptance: loop-closure error at rest [m] (0.1 mm)."""
N_RANDOM_ASSEMBLIES = 300
SIM_DURATION_S = 1.0
CONTROL_PERIOD_S = 0.05
"""How often the random controls change while stepping the scene [s]."""
HS805BB_STALL_TORQUE_NM = 2.42
"""HS-805BB stall torque at 6 V, 24.7 kg·cm (lynxsim/models/lynx_arm/README.md) [N·m]."""
HS805BB_KP = 555.0
"""kp = stall torque / 0.25 deg, as the arm's servos [N·m/rad]."""

OBJ = mujoco.mjtObj

MODELS = {
    "scene": load_rrr_scene,
    "robot": load_rrr_model,
    "scene_at_figure20_a_mode_0": lambda: load_rrr_scene(FIGURE20_A, 0),
}


@pytest.mark.parametrize("factory", MODELS.values(), ids=MODELS.keys())
def test_every_element_is_named_uniquely(factory):
    model = factory()
    assert_every_element_named(model)


def test_compiler_reads_radians_and_options_are_the_house_defaults(rrr_scene):
    assert not load_rrr_spec().compiler.degree
    assert rrr_scene.opt.timestep == pytest.approx(0.002)
    assert int(rrr_scene.opt.integrator) == int(mujoco.mjtIntegrator.mjINT_IMPLICITFAST)


def test_scene_has_top_and_front_cameras_and_lights(rrr_scene):
    top = mujoco.mj_name2id(rrr_scene, int(OBJ.mjOBJ_CAMERA), "top")
    assert top >= 0
    assert mujoco.mj_name2id(rrr_scene, int(OBJ.mjOBJ_CAMERA), "front") >= 0
    assert int(rrr_scene.cam_projection[top]) == int(mujoco.mjtProjection.mjPROJ_ORTHOGRAPHIC)
    # Looking straight down: the camera's -z axis is world -z.
    assert_close(rrr_scene.cam_mat0[top].reshape(3, 3)[:, 2], [0.0, 0.0, 1.0], atol=1e-12)
    assert rrr_scene.nlight >= 2


def test_geometry_is_rrr_robot(rrr_model):
    model = rrr_model
    for i in range(3):
        proximal = model.body(f"leg{i + 1}_proximal")
        distal = model.body(f"leg{i + 1}_distal")
        assert_close(proximal.pos[:2], RRR_ROBOT.base[i], atol=GEOMETRY_TOL_M)
        assert_close(distal.pos, [RRR_ROBOT.proximal, 0.0, 0.0], atol=GEOMETRY_TOL_M)
        assert_close(model.site(f"leg{i + 1}_tip").pos, [RRR_ROBOT.distal, 0, 0], atol=1e-15)
        assert_close(
            model.site(f"platform_joint{i + 1}").pos[:2], RRR_ROBOT.platform[i], atol=1e-15
        )
    heights = [model.body(f"leg{i}_proximal").pos[2] for i in (1, 2, 3)]
    assert heights == [model.body("platform").pos[2]] * 3, "the mechanism is not in one plane"


def test_sites_equal_leg_points_for_random_assemblies(rrr_scene, rrr_ids):
    rng = np.random.default_rng(20241122)
    data = mujoco.MjData(rrr_scene)
    cx, cy = RRR_ROBOT.base_centre
    checked = 0
    while checked < N_RANDOM_ASSEMBLIES:
        pose = np.array(
            [rng.uniform(cx - 0.2, cx + 0.2), rng.uniform(cy - 0.2, cy + 0.2), rng.uniform(-1, 1)]
        )
        if not ik(pose).ok:
            continue
        mode = int(rng.integers(8))
        data.qpos[:] = assembly_qpos(rrr_scene, pose, mode, ids=rrr_ids)
        mujoco.mj_kinematics(rrr_scene, data)
        points = leg_points(pose, mode)
        elbows = data.xpos[[rrr_scene.body(f"leg{i}_distal").id for i in (1, 2, 3)]]
        assert_close(elbows[:, :2], points[:, 1], atol=GEOMETRY_TOL_M)
        assert_close(data.site_xpos[rrr_ids.tip_sites][:, :2], points[:, 2], atol=GEOMETRY_TOL_M)
        assert_close(
            data.site_xpos[rrr_ids.joint_sites][:, :2], platform_joints(pose), atol=GEOMETRY_TOL_M
        )
        assert_close(platform_pose(data, rrr_ids), pose, atol=1e-12)
        assert loop_closure_errors(data, rrr_ids).max() < ASSEMBLED_LOOP_TOL_M
        assert settled_mode(data, rrr_ids) == mode
        checked += 1


def test_home_keyframe_is_qpos0_and_closes_every_loop(rrr_scene, rrr_ids, rrr_data):
    assert_close(rrr_scene.key_qpos[rrr_ids.home_key], rrr_scene.qpos0, atol=1e-15)
    assert_close(rrr_data.qpos, assembly_qpos(rrr_scene, HOME_POSE, HOME_MODE), atol=1e-15)
    assert loop_closure_errors(rrr_data, rrr_ids).max() < ASSEMBLED_LOOP_TOL_M
    assert_close(platform_pose(rrr_data, rrr_ids), HOME_POSE, atol=1e-15)
    assert_close(rrr_data.ctrl, rrr_data.qpos[rrr_ids.base_qpos], atol=1e-15)
    assert settled_mode(rrr_data, rrr_ids) == HOME_MODE


def test_loops_stay_closed_at_rest(rrr_scene, rrr_ids, rrr_data):
    worst = 0.0
    for _ in range(round(SIM_DURATION_S / rrr_scene.opt.timestep)):
        mujoco.mj_step(rrr_scene, rrr_data)
        worst = max(worst, float(loop_closure_errors(rrr_data, rrr_ids).max()))
    assert worst < REST_LOOP_TOL_M
    assert_close(platform_pose(rrr_data, rrr_ids), HOME_POSE, atol=1e-9)
    assert not warnings_fired(rrr_data)


def test_loops_are_connect_equalities_between_leg_tips_and_platform_joints(rrr_scene, rrr_ids):
    for k, eq in enumerate(rrr_ids.loops):
        assert int(rrr_scene.eq_type[eq]) == int(mujoco.mjtEq.mjEQ_CONNECT)
        assert int(rrr_scene.eq_objtype[eq]) == int(OBJ.mjOBJ_SITE)
        assert rrr_scene.eq_obj1id[eq] == rrr_ids.tip_sites[k]
        assert rrr_scene.eq_obj2id[eq] == rrr_ids.joint_sites[k]
        assert rrr_scene.eq_solref[eq][0] == pytest.approx(2 * rrr_scene.opt.timestep)


def test_only_the_base_joints_carry_position_servos(rrr_scene):
    model = rrr_scene
    actuated = {model.joint(int(j)).name for j in model.actuator_trnid[:, 0]}
    assert actuated == set(LEG_BASE_JOINTS)
    assert not actuated & set(LEG_ELBOW_JOINTS)
    assert model.nu == 3
    for name in LEG_BASE_JOINTS:
        act = model.actuator(name)
        assert int(act.trntype[0]) == int(mujoco.mjtTrn.mjTRN_JOINT)
        assert model.joint(int(act.trnid[0])).name == name
        assert act.gainprm[0] == pytest.approx(HS805BB_KP)
        assert act.biasprm[1] == pytest.approx(-HS805BB_KP)
        assert act.biasprm[2] < 0.0, "the servo is damped"
        assert_close(act.forcerange, [-HS805BB_STALL_TORQUE_NM, HS805BB_STALL_TORQUE_NM], atol=0)
    centre = actuated_window()
    assert_close(
        model.actuator_ctrlrange, np.column_stack([centre - math.pi, centre + math.pi]), atol=1e-12
    )


def test_every_joint_turns_about_z_and_only_the_platform_is_free(rrr_scene):
    types = [int(t) for t in rrr_scene.jnt_type]
    assert types.count(int(mujoco.mjtJoint.mjJNT_HINGE)) == 6
    assert types.count(int(mujoco.mjtJoint.mjJNT_FREE)) == 1
    for j in range(rrr_scene.njnt):
        if types[j] == int(mujoco.mjtJoint.mjJNT_HINGE):
            assert_close(rrr_scene.jnt_axis[j], [0.0, 0.0, 1.0], atol=0)
            assert not rrr_scene.jnt_limited[j]


def test_scene_steps_one_second_of_random_controls_without_warnings(rrr_scene, rrr_ids, rrr_data):
    step_random_controls(rrr_scene, rrr_data, SIM_DURATION_S, CONTROL_PERIOD_S)
    assert not warnings_fired(rrr_data)
    assert np.isfinite(rrr_data.qpos).all()
    assert rrr_data.time == pytest.approx(SIM_DURATION_S)


def test_variant_is_written_at_its_assembly(rrr_ids):
    model = load_rrr_scene(FIGURE20_A, 0)
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    assert loop_closure_errors(data, rrr_ids).max() < ASSEMBLED_LOOP_TOL_M
    assert_close(platform_pose(data, rrr_ids), FIGURE20_A, atol=1e-15)
    assert_close(data.qpos[rrr_ids.base_qpos], wrap_to_window(ik(FIGURE20_A).theta[0]), atol=1e-12)
    assert settled_mode(data, rrr_ids) == 0
    # Hinge qpos stay absolute angles: the home keyframe still closes every loop.
    mujoco.mj_resetDataKeyframe(model, data, rrr_ids.home_key)
    mujoco.mj_forward(model, data)
    assert_close(platform_pose(data, rrr_ids), HOME_POSE, atol=1e-12)
    assert loop_closure_errors(data, rrr_ids).max() < ASSEMBLED_LOOP_TOL_M


def test_unreachable_assembly_is_a_clear_error():
    with pytest.raises(UnreachablePlatformPoseError, match=r"leg 1 cannot stretch") as err:
        load_rrr_spec(FIGURE20_E, HOME_MODE)
    assert err.value.legs == (1,)
    with pytest.raises(InvalidInputError, match=r"working mode must be an integer in 0\.\.7"):
        load_rrr_spec(FIGURE20_A, 8)


def test_crossing_links_are_self_collisions_joined_links_are_not(rrr_scene, rrr_ids):
    data = mujoco.MjData(rrr_scene)
    crossing = interference_at(rrr_scene, data, assembly_qpos(rrr_scene, FIGURE20_F, 7), rrr_ids)
    assert {(p.geom1, p.geom2) for p in crossing} == {
        ("leg3_proximal_collision", "platform_collision23")
    }
    assert crossing[0].max_penetration_m > 0.01
    # The same pose in mode 0, and home: distal links overlap the platform only at their pins.
    assert not interference_at(rrr_scene, data, assembly_qpos(rrr_scene, FIGURE20_F, 0), rrr_ids)
    assert not interference_at(rrr_scene, data, rrr_scene.qpos0, rrr_ids)
    assert len(rrr_ids.link_geoms) == 9
