"""The arm's scene: obstacle variants, contacts with the obstacle, the cube, cameras."""

from __future__ import annotations

import math

import mujoco
import numpy as np
import pytest

from lynxsim.arm import ik_one
from lynxsim.errors import InvalidInputError
from lynxsim.reproduce.arm_tables import TABLE4
from lynxsim.resources import model_path
from lynxsim.scene import REPORT_CYLINDER, REPORT_SCENE, TABLE, Box, Cylinder, Scene, Sphere
from lynxsim.sim.arm.model import (
    COLLISION_GROUP,
    CUBE_BODY,
    CUBE_GEOM,
    GRIPPER_ACTUATOR,
    HOME_KEY,
    SCENE_XML,
    TABLE_GEOM,
    VISUAL_GROUP,
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


def _cylinder_geom(model: mujoco.MjModel, ids: SceneIds) -> int:
    """The geom of the report's cylinder: the scene's only obstacle, named after it."""
    g = mujoco.mj_name2id(model, int(mujoco.mjtObj.mjOBJ_GEOM), REPORT_CYLINDER.name)
    assert g >= 0
    assert ids.obstacle_geoms == (g,)
    return int(g)


def _obstacle_clearance(model: mujoco.MjModel, data: mujoco.MjData, ids: SceneIds) -> float:
    """Least signed distance between the arm's collision geoms and the obstacle [m]."""
    obstacle = _cylinder_geom(model, ids)
    fromto = np.zeros(6)
    return min(
        mujoco.mj_geomDistance(model, data, g, obstacle, DISTMAX_M, fromto)
        for g in ids.arm_collision_geoms
    )


def _contact_pairs(model: mujoco.MjModel, data: mujoco.MjData) -> set[tuple[int, int]]:
    return {(int(c.geom1), int(c.geom2)) for c in data.contact[: data.ncon]}


def _via_joints() -> list[np.ndarray]:
    return [ik_one(np.asarray(p[:3]) * 1e-3, math.radians(p[3])) for p in VIA_POINTS_MM_DEG]


def test_default_scene_is_the_shipped_file():
    # The shipped file holds no obstacle (they are built from the scene); its
    # table and cube are the default scene's, so building them changes nothing.
    shipped = mujoco.MjModel.from_xml_path(str(model_path(SCENE_XML)))
    built = load_arm_scene()
    assert SceneIds.from_model(shipped).obstacle_geoms == ()
    assert [built.geom(g).name for g in SceneIds.from_model(built).obstacle_geoms] == [
        REPORT_CYLINDER.name
    ]
    geom, body = int(mujoco.mjtObj.mjOBJ_GEOM), int(mujoco.mjtObj.mjOBJ_BODY)
    for name in (TABLE_GEOM, CUBE_GEOM):
        g_shipped = mujoco.mj_name2id(shipped, geom, name)
        g_built = mujoco.mj_name2id(built, geom, name)
        assert_close(built.geom_size[g_built], shipped.geom_size[g_shipped], atol=SPEC_TOL_M)
        assert_close(built.geom_pos[g_built], shipped.geom_pos[g_shipped], atol=SPEC_TOL_M)
    b_shipped = mujoco.mj_name2id(shipped, body, CUBE_BODY)
    b_built = mujoco.mj_name2id(built, body, CUBE_BODY)
    assert_close(built.body_pos[b_built], shipped.body_pos[b_shipped], atol=SPEC_TOL_M)
    assert_close(built.body_quat[b_built], shipped.body_quat[b_shipped], atol=SPEC_TOL_M)


def test_report_obstacle_stands_on_the_table_up_to_400_mm(scene_model, scene_ids):
    expected = Cylinder("cylinder", (0.15, 0.15, TABLE.top_z), 0.04, 0.4 - TABLE.top_z)
    assert expected == REPORT_CYLINDER
    assert REPORT_SCENE.obstacles == (REPORT_CYLINDER,)
    g = _cylinder_geom(scene_model, scene_ids)
    assert scene_model.geom_type[g] == int(mujoco.mjtGeom.mjGEOM_CYLINDER)
    radius, half_height = scene_model.geom_size[g, :2]
    x, y, z = scene_model.geom_pos[g]
    assert_close([x, y, radius], [0.15, 0.15, 0.04], atol=SPEC_TOL_M)
    assert_close(z + half_height, 0.4, atol=SPEC_TOL_M)
    assert_close(z - half_height, table_top_z(load_arm_spec()), atol=SPEC_TOL_M)


def test_obstacle_can_be_moved_resized_or_removed():
    moved = Cylinder("cylinder", (0.2, -0.1, TABLE.top_z), 0.03, 0.25 - TABLE.top_z)
    model = load_arm_scene(Scene((moved,)))
    g = _cylinder_geom(model, SceneIds.from_model(model))
    radius, half_height = model.geom_size[g, :2]
    assert_close([radius, *model.geom_pos[g, :2]], [0.03, 0.2, -0.1], atol=SPEC_TOL_M)
    assert_close(model.geom_pos[g, 2] + half_height, 0.25, atol=SPEC_TOL_M)
    assert_close(model.geom_pos[g, 2] - half_height, TABLE.top_z, atol=SPEC_TOL_M)
    no_obstacle = load_arm_scene(REPORT_SCENE.without_obstacles())
    assert SceneIds.from_model(no_obstacle).obstacle_geoms == ()
    assert SceneIds.from_model(load_arm_scene(REPORT_SCENE.without_cube())).cube_geom is None


_BOTTOM = (0.1, 0.1, TABLE.top_z)
"""Bottom-face centre of the obstacles of the rejection tests [m]."""


@pytest.mark.parametrize(
    ("make", "message"),
    [
        (lambda: Cylinder("c", _BOTTOM, 0.0, 0.4), "radius must lie within"),
        (lambda: Cylinder("c", _BOTTOM, -0.04, 0.4), "radius must lie within"),
        (lambda: Cylinder("c", _BOTTOM, 0.04, 0.0), "height must lie within"),
        (lambda: Cylinder("c", _BOTTOM, 0.04, -0.1), "height must lie within"),
        (lambda: Cylinder("c", (0.1, math.nan, TABLE.top_z), 0.04, 0.4), "finite"),
        (lambda: Cylinder("c", (0.1, 0.1), 0.04, 0.4), "tuple of 3 numbers"),
        (lambda: Cylinder("c", _BOTTOM, math.inf, 0.4), "finite"),
        (lambda: Cylinder("", _BOTTOM, 0.04, 0.4), "non-empty printable"),
        (lambda: Box("b", _BOTTOM, (0.1, 0.0, 0.1)), r"size\[1\] must lie within"),
        (lambda: Box("b", _BOTTOM, (0.1, 0.1, 0.1), yaw=math.nan), "yaw must be finite"),
        (lambda: Sphere("s", _BOTTOM, -0.02), "radius must lie within"),
        (lambda: Sphere("s", (math.nan, 0.1, 0.1), 0.02), "finite"),
    ],
    ids=[
        "zero_radius",
        "negative_radius",
        "flat",
        "negative_height",
        "nan_centre",
        "two_coordinates",
        "infinite_radius",
        "empty_name",
        "flat_box",
        "nan_yaw",
        "negative_sphere",
        "nan_sphere",
    ],
)
def test_invalid_obstacle_is_rejected(make, message):
    with pytest.raises(InvalidInputError, match=message):
        make()


def test_scene_rejects_duplicate_names_and_obstacles_over_the_base_or_the_cube():
    twin = Sphere("cylinder", (0.3, -0.2, 0.2), 0.02)
    with pytest.raises(InvalidInputError, match="two obstacles are named 'cylinder'"):
        Scene((REPORT_CYLINDER, twin))
    with pytest.raises(InvalidInputError, match="encloses the robot's base"):
        Scene((Sphere("s", (0.0, 0.0, 0.05), 0.06),))
    with pytest.raises(InvalidInputError, match="encloses the cube's start"):
        Scene((Box("b", (0.0, 0.3, TABLE.top_z), (0.1, 0.1, 0.1)),))
    # Without the cube, the same box is fine.
    assert Scene((Box("b", (0.0, 0.3, TABLE.top_z), (0.1, 0.1, 0.1)),), cube=None).cube is None


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
    assert len(scene_ids.obstacle_geoms) == 1
    for other in (*scene_ids.obstacle_geoms, scene_ids.table_geom, scene_ids.cube_geom):
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
    obstacle = _cylinder_geom(scene_model, scene_ids)
    assert not any(obstacle in pair for pair in pairs)
    assert _obstacle_clearance(scene_model, scene_data, scene_ids) > VIA_CLEARANCE_MIN_M


def test_plain_task_p2_to_p3_passes_through_the_obstacle(scene_model, scene_ids, scene_data):
    q2, q3 = (np.radians([*TABLE4[i].q_deg, 0.0]) for i in (1, 2))
    _pose(scene_model, scene_data, scene_ids, 0.5 * (q2 + q3))
    arm = set(scene_ids.arm_collision_geoms)
    obstacle = _cylinder_geom(scene_model, scene_ids)
    hits = {
        pair
        for pair in _contact_pairs(scene_model, scene_data)
        if obstacle in pair and (arm & set(pair))
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
