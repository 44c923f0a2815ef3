"""The arm's MJCF model against lynxsim.arm: kinematics, limits, servos, names, stepping."""

from __future__ import annotations

import math

import mujoco
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from lynxsim.arm import LYNX_ARM, fk, frame_transforms
from lynxsim.reproduce.arm_tables import TABLE4
from lynxsim.scene import REPORT_SCENE, TABLE, Cylinder, Scene
from lynxsim.sim.arm.model import (
    ARM_JOINTS,
    FINGER_JOINTS,
    FRAME_SITES,
    GRIPPER_TENDON,
    HOME_KEY,
    SceneIds,
    load_arm_model,
    load_arm_scene,
)
from tests.helpers import assert_close
from tests.model_checks import (
    assert_every_element_named,
    step_random_controls,
    warnings_fired,
)

POSITION_TOL_M = 1e-12
"""Agreement of MuJoCo's site positions with the DH chain [m]."""
ROTATION_TOL = 1e-12
"""Agreement of MuJoCo's site orientations with the DH chain (matrix entries) [-]."""
REPORT_POINT_TOL_M = 5e-5
"""Agreement with the report's task points; its joint angles are rounded to 0.01 deg [m]."""
REPORT_AXIS_TOL = 1e-3
"""Agreement of the tool axis with the report's pitch, rounded inputs [-]."""
HOME_SAG_TOL_M = 1e-3
"""Tool sag at ``home`` after 1 s under gravity: the settled-error bound of issue 4 [m]."""
N_RANDOM_JOINTS = 1000
"""Random joint vectors drawn for the FK comparison."""
SIM_DURATION_S = 1.0
CONTROL_PERIOD_S = 0.05
"""How often the random controls change while stepping a scene [s]."""

KGF_CM = 0.0980665
"""One kgf·cm in N·m (Hitec datasheets give torques in kg·cm)."""
STALL_TORQUE_6V_KGF_CM = {
    "base": 6.0,  # HS-485HB
    "shoulder": 24.7,  # HS-805BB
    "elbow": 13.2,  # HS-755HB
    "wrist_pitch": 9.6,  # HS-645MG
    "wrist_roll": 4.8,  # HS-225MG
}
"""Stall torques at 6.0 V from the Hitec datasheets (lynxsim/models/lynx_arm/README.md)."""
GRIPPER_STALL_TORQUE_6V_KGF_CM = 4.1
"""HS-422 stall torque at 6.0 V [kg·cm]."""
GRIPPER_OPENING_M = 0.03
"""Full opening of the Lynxmotion gripper [m]."""
GRIPPER_SERVO_TRAVEL_RAD = math.pi / 2
"""Servo turn that opens the gripper fully (README): force = torque * travel / opening."""
FORCE_RANGE_RTOL = 5e-3
"""The model rounds datasheet torques to 3 significant digits."""

OBJ = mujoco.mjtObj

SCENE_VARIANTS = {
    "robot": load_arm_model,
    "scene": load_arm_scene,
    "no_obstacle": lambda: load_arm_scene(REPORT_SCENE.without_obstacles()),
    "moved_obstacle": lambda: load_arm_scene(
        Scene((Cylinder("cylinder", (0.2, -0.1, TABLE.top_z), 0.03, 0.25 - TABLE.top_z),))
    ),
    "no_cube": lambda: load_arm_scene(REPORT_SCENE.without_cube()),
}


def _id(model: mujoco.MjModel, kind: mujoco.mjtObj, name: str) -> int:
    index = int(mujoco.mj_name2id(model, int(kind), name))
    assert index >= 0, f"no {kind.name} named {name!r}"
    return index


def _site_frames(model: mujoco.MjModel, data: mujoco.MjData) -> tuple[np.ndarray, np.ndarray]:
    """Positions (7, 3) [m] and rotations (7, 3, 3) of the DH frame sites."""
    sites = [_id(model, OBJ.mjOBJ_SITE, name) for name in FRAME_SITES]
    return data.site_xpos[sites].copy(), data.site_xmat[sites].reshape(-1, 3, 3).copy()


def _arm_qpos(model: mujoco.MjModel) -> list[int]:
    return [int(model.jnt_qposadr[_id(model, OBJ.mjOBJ_JOINT, n)]) for n in ARM_JOINTS]


def test_frame_sites_equal_dh_frames_for_random_joints(arm_model):
    rng = np.random.default_rng(20240501)
    q = rng.uniform(LYNX_ARM.lower, LYNX_ARM.upper, size=(N_RANDOM_JOINTS, 5))
    expected = frame_transforms(q)
    data = mujoco.MjData(arm_model)
    adr = _arm_qpos(arm_model)
    positions = np.empty((N_RANDOM_JOINTS, 7, 3))
    rotations = np.empty((N_RANDOM_JOINTS, 7, 3, 3))
    for k in range(N_RANDOM_JOINTS):
        data.qpos[adr] = q[k]
        mujoco.mj_kinematics(arm_model, data)
        positions[k], rotations[k] = _site_frames(arm_model, data)
    assert_close(positions, expected[..., :3, 3], atol=POSITION_TOL_M)
    assert_close(rotations, expected[..., :3, :3], atol=ROTATION_TOL)


@settings(max_examples=200, deadline=None)
@given(
    q=st.tuples(
        *(st.floats(float(lo), float(hi)) for lo, hi in zip(LYNX_ARM.lower, LYNX_ARM.upper))
    )
)
def test_tool_site_is_the_fk_tool_frame(arm_model, q):
    data = mujoco.MjData(arm_model)
    data.qpos[_arm_qpos(arm_model)] = q
    mujoco.mj_kinematics(arm_model, data)
    tool = _id(arm_model, OBJ.mjOBJ_SITE, "tool")
    expected = fk(np.asarray(q))
    assert_close(data.site_xpos[tool], expected[:3, 3], atol=POSITION_TOL_M)
    z_axis = data.site_xmat[tool].reshape(3, 3)[:, 2]
    assert_close(z_axis, expected[:3, 2], atol=ROTATION_TOL)


def test_joint_zero_is_dh_zero(arm_model):
    assert_close(arm_model.qpos0[_arm_qpos(arm_model)], np.zeros(5), atol=0.0)
    data = mujoco.MjData(arm_model)
    mujoco.mj_kinematics(arm_model, data)
    positions, rotations = _site_frames(arm_model, data)
    expected = frame_transforms(np.zeros(5))
    assert_close(positions, expected[:, :3, 3], atol=POSITION_TOL_M)
    assert_close(rotations, expected[:, :3, :3], atol=ROTATION_TOL)
    # Joint 4's -90 deg DH offset is the wrist body's orientation, not a joint offset.
    wrist = _id(arm_model, OBJ.mjOBJ_BODY, "wrist")
    half = -math.pi / 4
    assert_close(arm_model.body_quat[wrist], [math.cos(half), 0, 0, math.sin(half)], atol=1e-6)


def test_arm_joints_are_hinges_about_body_z_with_the_geometry_ranges(arm_model):
    joints = [_id(arm_model, OBJ.mjOBJ_JOINT, n) for n in ARM_JOINTS]
    assert all(arm_model.jnt_type[j] == int(mujoco.mjtJoint.mjJNT_HINGE) for j in joints)
    assert all(arm_model.jnt_limited[j] for j in joints)
    assert_close(arm_model.jnt_axis[joints], np.tile([0.0, 0.0, 1.0], (5, 1)), atol=0.0)
    assert_close(arm_model.jnt_range[joints, 0], LYNX_ARM.lower, atol=1e-12)
    assert_close(arm_model.jnt_range[joints, 1], LYNX_ARM.upper, atol=1e-12)


def test_simulation_options(arm_model):
    assert arm_model.opt.timestep == pytest.approx(0.002)
    assert int(arm_model.opt.integrator) == int(mujoco.mjtIntegrator.mjINT_IMPLICITFAST)


@pytest.mark.parametrize("name", ARM_JOINTS)
def test_joint_actuator_is_a_position_servo_limited_to_stall_torque(arm_model, name):
    act = _id(arm_model, OBJ.mjOBJ_ACTUATOR, name)
    joint = _id(arm_model, OBJ.mjOBJ_JOINT, name)
    assert arm_model.actuator_trntype[act] == int(mujoco.mjtTrn.mjTRN_JOINT)
    assert arm_model.actuator_trnid[act, 0] == joint
    kp = arm_model.actuator_gainprm[act, 0]
    assert kp > 0.0
    assert arm_model.actuator_biasprm[act, 1] == pytest.approx(-kp)
    assert arm_model.actuator_ctrllimited[act]
    assert_close(arm_model.actuator_ctrlrange[act], arm_model.jnt_range[joint], atol=0.0)
    stall = STALL_TORQUE_6V_KGF_CM[name] * KGF_CM
    assert arm_model.actuator_forcelimited[act]
    assert_close(arm_model.actuator_forcerange[act], [-stall, stall], atol=0, rtol=FORCE_RANGE_RTOL)
    dof = arm_model.jnt_dofadr[joint]
    assert arm_model.dof_armature[dof] > 0.0
    assert arm_model.dof_damping[dof] > 0.0


def test_gripper_actuator_drives_the_opening_in_metres(arm_model):
    act = _id(arm_model, OBJ.mjOBJ_ACTUATOR, "gripper")
    tendon = _id(arm_model, OBJ.mjOBJ_TENDON, GRIPPER_TENDON)
    assert arm_model.actuator_trntype[act] == int(mujoco.mjtTrn.mjTRN_TENDON)
    assert arm_model.actuator_trnid[act, 0] == tendon
    assert_close(arm_model.actuator_ctrlrange[act], [0.0, GRIPPER_OPENING_M], atol=0.0)
    force = GRIPPER_STALL_TORQUE_6V_KGF_CM * KGF_CM * GRIPPER_SERVO_TRAVEL_RAD / GRIPPER_OPENING_M
    assert_close(arm_model.actuator_forcerange[act], [-force, force], atol=0, rtol=FORCE_RANGE_RTOL)
    fingers = [_id(arm_model, OBJ.mjOBJ_JOINT, n) for n in FINGER_JOINTS]
    assert all(arm_model.jnt_type[j] == int(mujoco.mjtJoint.mjJNT_SLIDE) for j in fingers)
    assert_close(arm_model.jnt_range[fingers], [[0.0, 0.015]] * 2, atol=0.0)
    # The tendon's length is the sum of the finger travels: the opening.
    adr = arm_model.tendon_adr[tendon]
    assert arm_model.tendon_num[tendon] == 2
    assert sorted(arm_model.wrap_objid[adr : adr + 2]) == sorted(fingers)
    assert_close(arm_model.wrap_prm[adr : adr + 2], [1.0, 1.0], atol=0.0)
    eq = _id(arm_model, OBJ.mjOBJ_EQUALITY, "finger_coupling")
    assert arm_model.eq_type[eq] == int(mujoco.mjtEq.mjEQ_JOINT)
    assert {int(arm_model.eq_obj1id[eq]), int(arm_model.eq_obj2id[eq])} == set(fingers)


def test_gripper_opens_and_closes_symmetrically(arm_model):
    data = mujoco.MjData(arm_model)
    key = _id(arm_model, OBJ.mjOBJ_KEY, HOME_KEY)
    fingers = [arm_model.jnt_qposadr[_id(arm_model, OBJ.mjOBJ_JOINT, n)] for n in FINGER_JOINTS]
    for opening in (0.0, 0.02, GRIPPER_OPENING_M):
        mujoco.mj_resetDataKeyframe(arm_model, data, key)
        data.ctrl[_id(arm_model, OBJ.mjOBJ_ACTUATOR, "gripper")] = opening
        mujoco.mj_step(arm_model, data, nstep=int(SIM_DURATION_S / arm_model.opt.timestep))
        left, right = data.qpos[fingers]
        assert left + right == pytest.approx(opening, abs=1e-3)
        assert left == pytest.approx(right, abs=2e-4)


def test_moving_bodies_carry_servo_and_bracket_masses(arm_model):
    moving = [
        _id(arm_model, OBJ.mjOBJ_BODY, n)
        for n in ("turntable", "upper_arm", "forearm", "wrist", "hand")
    ]
    assert all(arm_model.body_mass[b] > 0.03 for b in moving)
    assert (arm_model.body_inertia[moving] > 0.0).all()
    total = float(arm_model.body_mass[moving].sum())
    assert 0.45 < total < 0.75, f"moving mass {total} kg"


@pytest.mark.parametrize("model_factory", SCENE_VARIANTS.values(), ids=SCENE_VARIANTS.keys())
def test_every_element_is_named_uniquely(model_factory):
    model = model_factory()
    assert_every_element_named(model)


def test_scene_has_named_cameras_and_lights(scene_model):
    for camera in ("front", "top"):
        _id(scene_model, OBJ.mjOBJ_CAMERA, camera)
    assert scene_model.nlight >= 2


@pytest.mark.parametrize("model_factory", SCENE_VARIANTS.values(), ids=SCENE_VARIANTS.keys())
def test_every_scene_steps_one_second_of_random_controls_without_warnings(model_factory):
    model = model_factory()
    data = mujoco.MjData(model)
    mujoco.mj_resetDataKeyframe(model, data, _id(model, OBJ.mjOBJ_KEY, HOME_KEY))
    step_random_controls(model, data, SIM_DURATION_S, CONTROL_PERIOD_S)
    assert not warnings_fired(data)
    assert np.isfinite(data.qpos).all()
    assert data.time == pytest.approx(SIM_DURATION_S)


def test_home_keyframe_is_in_range(scene_model):
    key = _id(scene_model, OBJ.mjOBJ_KEY, HOME_KEY)
    qpos = scene_model.key_qpos[key]
    for j in range(scene_model.njnt):
        if scene_model.jnt_limited[j]:
            low, high = scene_model.jnt_range[j]
            assert low <= qpos[scene_model.jnt_qposadr[j]] <= high, scene_model.joint(j).name
    low, high = scene_model.actuator_ctrlrange.T
    ctrl = scene_model.key_ctrl[key]
    assert ((low <= ctrl) & (ctrl <= high)).all()
    # Each joint's servo is commanded to where the joint starts.
    ids = SceneIds.from_model(scene_model)
    assert_close(ctrl[list(ids.arm_actuators)], qpos[list(ids.arm_qpos)], atol=0.0)


def test_home_tool_site_is_fk_and_holds_under_gravity(scene_model, scene_ids, scene_data):
    q_home = scene_data.qpos[list(scene_ids.arm_qpos)].copy()
    target = fk(q_home)[:3, 3]
    assert_close(scene_data.site_xpos[scene_ids.tool_site], target, atol=POSITION_TOL_M)
    mujoco.mj_step(scene_model, scene_data, nstep=int(SIM_DURATION_S / scene_model.opt.timestep))
    sag = np.linalg.norm(scene_data.site_xpos[scene_ids.tool_site] - target)
    assert sag < HOME_SAG_TOL_M


@pytest.mark.parametrize("row", TABLE4, ids=[row.name for row in TABLE4])
def test_report_task_joints_put_the_tool_site_on_the_task_point(
    scene_model, scene_ids, scene_data, row
):
    q = np.radians([*row.q_deg, 0.0])
    scene_data.qpos[list(scene_ids.arm_qpos)] = q
    mujoco.mj_forward(scene_model, scene_data)
    tool = scene_data.site_xpos[scene_ids.tool_site]
    assert_close(tool, fk(q)[:3, 3], atol=POSITION_TOL_M)
    assert_close(tool, np.asarray(row.position_mm) * 1e-3, atol=REPORT_POINT_TOL_M)
    pitch, heading = math.radians(row.pitch_deg), q[0]
    axis = [
        math.cos(pitch) * math.cos(heading),
        math.cos(pitch) * math.sin(heading),
        math.sin(pitch),
    ]
    z_axis = scene_data.site_xmat[scene_ids.tool_site].reshape(3, 3)[:, 2]
    assert_close(z_axis, axis, atol=REPORT_AXIS_TOL)
