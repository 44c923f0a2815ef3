"""The arm's scene: obstacle variants, contacts with the obstacle, the cube, cameras."""

from __future__ import annotations

import math

import mujoco
import numpy as np
import pytest

from lynxsim.arm import ik_one
from lynxsim.errors import InvalidInputError
from lynxsim.reference import TABLE4
from lynxsim.resources import model_path
from lynxsim.sim import (
    COLLISION_GROUP,
    GRIPPER_ACTUATOR,
    HOME_KEY,
    OBSTACLE_GEOM,
    REPORT_OBSTACLE,
    SCENE_XML,
    VISUAL_GROUP,
    ObstacleSpec,
    SceneIds,
    load_arm_scene,
    load_arm_spec,
    table_top_z,
)
from tests.helpers import assert_close

VIA_POINTS_MM_DEG = (
    (0.0, 300.0, 0.0, -90.0),
    (80.0, 250.0, 300.0, 0.0),
    (80.0, 0.0, 300.0, 0.0),
    (250.0, 0.0, 300.0, 0.0),
    (90.0, -250.0, 300.0, 0.0),
    (0.0, -300.0, 0.0, -90.0),
)
"""The report's obstacle-avoidance via points (x, y, z [mm], pitch [deg]), SPEC section 1."""
VIA_CLEARANCE_MIN_M = 0.02
"""Least distance between the arm's collision geoms and the obstacle at a via point [m]."""
CUBE_HALF_M = 0.0125
"""Half the edge of the cube [m]."""
SPEC_TOL_M = 1e-12
"""Agreement of geom placement with what the spec was given [m]."""
DISTMAX_M = 0.5
"""Search radius of ``mj_geomDistance`` [m]."""
LIFT_MIN_M = 0.2
"""How far the grasped cube must rise with the tool from P1 to P2 [m]."""
RENDER_STD_MIN = 5.0
"""Pixel standard deviation below which a rendered frame counts as blank [0-255]."""


def _pose(model: mujoco.MjModel, data: mujoco.MjData, ids: SceneIds, q: np.ndarray) -> None:
    """Put the arm at ``q`` [rad] with the gripper open and run ``mj_forward``."""
    mujoco.mj_resetDataKeyframe(
        model, data, mujoco.mj_name2id(model, int(mujoco.mjtObj.mjOBJ_KEY), HOME_KEY)
    )
    data.qpos[list(ids.arm_qpos)] = q
    mujoco.mj_forward(model, data)


def _obstacle_clearance(model: mujoco.MjModel, data: mujoco.MjData, ids: SceneIds) -> float:
    """Least signed distance between the arm's collision geoms and the obstacle [m]."""
    assert ids.obstacle_geom is not None
    fromto = np.zeros(6)
    return min(
        mujoco.mj_geomDistance(model, data, g, ids.obstacle_geom, DISTMAX_M, fromto)
        for g in ids.arm_collision_geoms
    )


def _contact_pairs(model: mujoco.MjModel, data: mujoco.MjData) -> set[tuple[int, int]]:
    return {(int(c.geom1), int(c.geom2)) for c in data.contact[: data.ncon]}


def _via_joints() -> list[np.ndarray]:
    return [ik_one(np.asarray(p[:3]) * 1e-3, math.radians(p[3])) for p in VIA_POINTS_MM_DEG]


def test_default_scene_is_the_shipped_file():
    shipped = mujoco.MjModel.from_xml_path(str(model_path(SCENE_XML)))
    built = load_arm_scene()
    g_shipped = mujoco.mj_name2id(shipped, int(mujoco.mjtObj.mjOBJ_GEOM), OBSTACLE_GEOM)
    g_built = mujoco.mj_name2id(built, int(mujoco.mjtObj.mjOBJ_GEOM), OBSTACLE_GEOM)
    assert_close(built.geom_size[g_built], shipped.geom_size[g_shipped], atol=SPEC_TOL_M)
    assert_close(built.geom_pos[g_built], shipped.geom_pos[g_shipped], atol=SPEC_TOL_M)


def test_report_obstacle_stands_on_the_table_up_to_400_mm(scene_model, scene_ids):
    assert ObstacleSpec(center=(0.15, 0.15), radius=0.04, top_z=0.4) == REPORT_OBSTACLE
    g = scene_ids.obstacle_geom
    assert g is not None
    assert scene_model.geom_type[g] == int(mujoco.mjtGeom.mjGEOM_CYLINDER)
    radius, half_height = scene_model.geom_size[g, :2]
    x, y, z = scene_model.geom_pos[g]
    assert_close([x, y, radius], [0.15, 0.15, 0.04], atol=SPEC_TOL_M)
    assert_close(z + half_height, 0.4, atol=SPEC_TOL_M)
    assert_close(z - half_height, table_top_z(load_arm_spec()), atol=SPEC_TOL_M)


def test_obstacle_can_be_moved_resized_or_removed():
    spec = ObstacleSpec(center=(0.2, -0.1), radius=0.03, top_z=0.25)
    model = load_arm_scene(spec)
    g = SceneIds.from_model(model).obstacle_geom
    assert g is not None
    radius, half_height = model.geom_size[g, :2]
    assert_close([radius, *model.geom_pos[g, :2]], [0.03, 0.2, -0.1], atol=SPEC_TOL_M)
    assert_close(model.geom_pos[g, 2] + half_height, 0.25, atol=SPEC_TOL_M)
    assert SceneIds.from_model(load_arm_scene(None)).obstacle_geom is None
    assert SceneIds.from_model(load_arm_scene(cube=False)).cube_geom is None


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"center": (0.1, 0.1), "radius": 0.0, "top_z": 0.4}, "radius must be positive"),
        ({"center": (0.1, 0.1), "radius": -0.04, "top_z": 0.4}, "radius must be positive"),
        ({"center": (0.1, 0.1), "radius": 0.04, "top_z": 0.0}, "top_z must be above"),
        ({"center": (0.1, math.nan), "radius": 0.04, "top_z": 0.4}, "finite"),
        ({"center": (0.1, 0.1, 0.0), "radius": 0.04, "top_z": 0.4}, "finite"),
    ],
    ids=["zero_radius", "negative_radius", "flat", "nan_centre", "three_coordinates"],
)
def test_invalid_obstacle_is_rejected(kwargs, message):
    with pytest.raises(InvalidInputError, match=message):
        ObstacleSpec(**kwargs)


def test_geom_groups_and_contact_bits(scene_model, scene_ids):
    arm = set(scene_ids.arm_collision_geoms)
    assert arm
    for g in range(scene_model.ngeom):
        collides = bool(scene_model.geom_contype[g] or scene_model.geom_conaffinity[g])
        if g in arm:
            assert scene_model.geom_contype[g] == scene_model.geom_conaffinity[g] == 1
        elif scene_model.geom_group[g] == COLLISION_GROUP:
            pytest.fail(f"collision geom {scene_model.geom(g).name} is not part of the arm")
        if scene_model.geom_group[g] == VISUAL_GROUP:
            assert not collides, scene_model.geom(g).name
    for other in (scene_ids.obstacle_geom, scene_ids.table_geom, scene_ids.cube_geom):
        assert other is not None
        assert scene_model.geom_conaffinity[other] & 1
        assert scene_model.geom_contype[other] & 1
    # Every moving body of the arm has collision geometry.
    bodies = {int(scene_model.geom_bodyid[g]) for g in arm}
    for name in ("turntable", "upper_arm", "forearm", "wrist", "hand", "left_finger"):
        assert mujoco.mj_name2id(scene_model, int(mujoco.mjtObj.mjOBJ_BODY), name) in bodies


def test_cube_sits_on_the_table_with_its_centre_at_p1(scene_model, scene_ids, scene_data):
    assert table_top_z(load_arm_spec()) == pytest.approx(-CUBE_HALF_M)
    cube = scene_model.geom_bodyid[scene_ids.cube_geom]
    p1 = np.asarray(TABLE4[0].position_mm) * 1e-3
    assert_close(scene_data.xpos[cube], p1, atol=SPEC_TOL_M)
    mujoco.mj_step(scene_model, scene_data, nstep=500)
    assert_close(scene_data.xpos[cube], p1, atol=1e-3)


@pytest.mark.parametrize("index", range(len(VIA_POINTS_MM_DEG)), ids=lambda i: f"via{i}")
def test_via_points_clear_the_obstacle(scene_model, scene_ids, scene_data, index):
    _pose(scene_model, scene_data, scene_ids, _via_joints()[index])
    pairs = _contact_pairs(scene_model, scene_data)
    assert not any(scene_ids.obstacle_geom in pair for pair in pairs)
    assert _obstacle_clearance(scene_model, scene_data, scene_ids) > VIA_CLEARANCE_MIN_M


def test_plain_task_p2_to_p3_passes_through_the_obstacle(scene_model, scene_ids, scene_data):
    q2, q3 = (np.radians([*TABLE4[i].q_deg, 0.0]) for i in (1, 2))
    _pose(scene_model, scene_data, scene_ids, 0.5 * (q2 + q3))
    arm = set(scene_ids.arm_collision_geoms)
    hits = {
        pair
        for pair in _contact_pairs(scene_model, scene_data)
        if scene_ids.obstacle_geom in pair and (arm & set(pair))
    }
    assert hits
    assert _obstacle_clearance(scene_model, scene_data, scene_ids) < 0.0


def test_task_and_via_poses_have_no_self_contacts(scene_model, scene_ids, scene_data):
    arm = set(scene_ids.arm_collision_geoms)
    poses = [np.radians([*row.q_deg, 0.0]) for row in TABLE4] + _via_joints()
    for q in poses:
        _pose(scene_model, scene_data, scene_ids, q)
        pairs = _contact_pairs(scene_model, scene_data)
        assert not [p for p in pairs if p[0] in arm and p[1] in arm], np.degrees(q)


def test_gripper_grasps_the_cube_at_p1_and_lifts_it_to_p2(scene_model, scene_ids, scene_data):
    p1, p2 = (np.radians([*TABLE4[i].q_deg, 0.0]) for i in (0, 1))
    _pose(scene_model, scene_data, scene_ids, p1)
    scene_data.ctrl[list(scene_ids.arm_actuators)] = p1
    mujoco.mj_step(scene_model, scene_data, nstep=250)
    scene_data.ctrl[scene_ids.gripper_actuator] = 0.0
    mujoco.mj_step(scene_model, scene_data, nstep=250)
    cube = scene_model.geom_bodyid[scene_ids.cube_geom]
    z0 = float(scene_data.xpos[cube, 2])
    steps = 500
    for k in range(steps):
        s = (k + 1) / steps
        blend = 10 * s**3 - 15 * s**4 + 6 * s**5
        scene_data.ctrl[list(scene_ids.arm_actuators)] = p1 + (p2 - p1) * blend
        mujoco.mj_step(scene_model, scene_data)
    mujoco.mj_step(scene_model, scene_data, nstep=250)
    assert scene_data.xpos[cube, 2] - z0 > LIFT_MIN_M
    assert np.linalg.norm(scene_data.xpos[cube] - scene_data.site_xpos[scene_ids.tool_site]) < 0.01
    assert scene_model.actuator(GRIPPER_ACTUATOR).id == scene_ids.gripper_actuator


@pytest.mark.parametrize("camera", ["front", "top"])
def test_named_camera_renders_a_non_blank_frame(scene_model, scene_data, camera):
    try:
        renderer = mujoco.Renderer(scene_model, height=120, width=160)
    except Exception as exc:  # no usable GL backend on this machine
        pytest.skip(f"off-screen rendering unavailable: {exc}")
    with renderer:
        renderer.update_scene(scene_data, camera=camera)
        frame = renderer.render()
    assert frame.shape == (120, 160, 3)
    assert frame.std() > RENDER_STD_MIN
