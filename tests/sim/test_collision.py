"""Scenes of several obstacles, and the batch collision checker against playback.

The checker (:class:`lynxsim.sim.collision.CollisionChecker`) and playback
(:func:`lynxsim.sim.stepping.rollout.rollout`) share one collision definition, so the
checker's verdict and clearance for a logged state must be the log's, exactly.
"""

from __future__ import annotations

import math
import pickle
import threading
from pathlib import Path

import mujoco
import numpy as np
import pytest

from lynxsim.arm import ik_one
from lynxsim.errors import InvalidInputError, NonFiniteInputError
from lynxsim.reproduce.arm_tables import TABLE4
from lynxsim.robots.arm import build_trajectory
from lynxsim.scene import REPORT_CYLINDER, REPORT_SCENE, TABLE, Box, Cylinder, Scene, Sphere
from lynxsim.sim.arm.model import SceneIds, load_arm_scene
from lynxsim.sim.arm.playback import arm_checker, play_arm
from lynxsim.sim.arm.task import run_arm_trajectory
from lynxsim.sim.collision import (
    CLEARANCE_CAP_M,
    ClearanceGeometry,
    CollisionCheck,
    CollisionChecker,
    classify_contacts,
)
from lynxsim.sim.collision.clearance import _bounds
from lynxsim.sim.stepping.log import PlaybackLog
from lynxsim.tasks import load_task
from lynxsim.traj import TrajectoryKind
from tests.helpers import assert_close

ROOT = Path(__file__).resolve().parents[2]
PICK_AND_PLACE = ROOT / "tasks" / "pick_and_place.toml"
OBSTACLE_AVOIDANCE = ROOT / "tasks" / "obstacle_avoidance.toml"

SPEC_TOL_M = 1e-12
"""Agreement of the built geoms with the scene's values [m]."""
CLEARANCE_TOL_M = 1e-12
"""Agreement of the checker's clearance with the playback's [m]."""
MIN_CHECKED_STATES = 1000
"""Logged states checked against the checker over the shipped tasks."""
SAMPLES_PER_RUN = 400
"""Evenly spaced logged states taken from each run (besides every obstacle hit)."""

THREE_OBSTACLES = Scene(
    (
        Cylinder("pillar", (0.15, 0.15, TABLE.top_z), 0.04, 0.3),
        Box("crate", (0.25, -0.15, TABLE.top_z), (0.08, 0.05, 0.12), yaw=0.6),
        Sphere("ball", (-0.2, 0.2, 0.25), 0.05),
    )
)
"""One obstacle of each shape, none in the shipped files."""
FAR_SPHERE = Sphere("far_ball", (-0.3, 0.0, 0.3), 0.03)
"""Behind the arm: the pick-and-place never comes near it."""
BALL_ON_THE_WAY = Sphere("ball", (0.0, 0.32, 0.15), 0.02)
"""On the tool's path from P1 to P2 of the pick-and-place (half way, t = 0.5 s)."""
OUT_OF_REACH = Sphere("far_away", (2.0, 2.0, 0.5), 0.1)
"""More than the clearance cap from every configuration of the arm."""


def _sampled_steps(log: PlaybackLog) -> np.ndarray:
    """Evenly spaced steps of a log, and every step with an obstacle hit."""
    even = np.linspace(0, log.steps - 1, SAMPLES_PER_RUN).round().astype(np.intp)
    return np.union1d(even, np.flatnonzero(log.obstacle_hits()))


def _q_mid_p2_p3() -> np.ndarray:
    """Half way from P2 to P3 in joint space (straight interpolation): inside the cylinder."""
    q2, q3 = (np.radians([*TABLE4[i].q_deg, 0.0]) for i in (1, 2))
    return 0.5 * (q2 + q3)


# ------------------------------------------------------------ (a) the scene


def test_three_obstacles_build_into_named_geoms_of_their_shape_size_and_pose():
    model = load_arm_scene(THREE_OBSTACLES)
    ids = SceneIds.from_model(model)
    data = mujoco.MjData(model)
    mujoco.mj_kinematics(model, data)
    cylinder, box, sphere = THREE_OBSTACLES.obstacles
    names = tuple(o.name for o in THREE_OBSTACLES.obstacles)
    assert tuple(model.geom(g).name for g in ids.obstacle_geoms) == names
    assert ids.collision_groups(model).obstacle_names == names
    assert arm_checker(model).check(np.zeros(5)).obstacle_names == names
    g_cyl, g_box, g_sph = ids.obstacle_geoms
    geom_type = mujoco.mjtGeom

    assert model.geom_type[g_cyl] == int(geom_type.mjGEOM_CYLINDER)
    assert_close(model.geom_size[g_cyl, :2], [0.04, 0.15], atol=SPEC_TOL_M)
    x, y, z = cylinder.position
    assert_close(data.geom_xpos[g_cyl], [x, y, z + 0.5 * cylinder.height], atol=SPEC_TOL_M)
    assert_close(data.geom_xmat[g_cyl], np.eye(3).ravel(), atol=SPEC_TOL_M)

    assert model.geom_type[g_box] == int(geom_type.mjGEOM_BOX)
    assert_close(model.geom_size[g_box], 0.5 * np.asarray(box.size), atol=SPEC_TOL_M)
    x, y, z = box.position
    assert_close(data.geom_xpos[g_box], [x, y, z + 0.5 * box.size[2]], atol=SPEC_TOL_M)
    c, s = math.cos(box.yaw), math.sin(box.yaw)
    yaw = [[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]]
    assert_close(data.geom_xmat[g_box].reshape(3, 3), yaw, atol=SPEC_TOL_M)

    assert model.geom_type[g_sph] == int(geom_type.mjGEOM_SPHERE)
    assert_close(model.geom_size[g_sph, 0], sphere.radius, atol=SPEC_TOL_M)
    assert_close(data.geom_xpos[g_sph], sphere.position, atol=SPEC_TOL_M)

    for g in ids.obstacle_geoms:  # fixed to the world, colliding with the arm
        assert model.geom_bodyid[g] == 0
        assert model.geom_contype[g] & 1
        assert model.geom_conaffinity[g] & 1


@pytest.mark.parametrize("name", ["cube", "table", "floor", "base_link", "gripper_servo_collision"])
def test_obstacle_named_like_a_part_of_the_scene_is_refused(name):
    scene = Scene((Sphere(name, (-0.2, 0.2, 0.25), 0.05),))
    with pytest.raises(InvalidInputError, match=f"obstacle name '{name}' is taken"):
        load_arm_scene(scene)


# ------------------------------------- (b) the checker agrees with playback


@pytest.fixture(scope="module")
def shipped_runs():
    """The shipped tasks played in their scenes: (label, scene, log) of each run."""
    runs = []
    for path, kinds in (
        (PICK_AND_PLACE, (TrajectoryKind.QUINTIC, TrajectoryKind.LINE)),
        (OBSTACLE_AVOIDANCE, (None,)),
    ):
        task = load_task(path)
        scene = task.scene
        for kind in kinds:
            trajectory = build_trajectory(task, kind)
            playback = run_arm_trajectory(trajectory, task=task.name, scene=scene)
            runs.append((f"{task.name} {trajectory.kind.value}", scene, playback.log))
    return runs


def test_checker_gives_the_playback_verdict_and_clearance_of_logged_states(shipped_runs):
    checked = hits = 0
    for label, scene, log in shipped_runs:
        steps = _sampled_steps(log)
        result = arm_checker(load_arm_scene(scene)).check_states(log.qpos[steps])
        logged_hits = log.obstacle_hits()[steps]
        np.testing.assert_array_equal(result.obstacle, logged_hits, err_msg=label)
        assert result.clearance_m.shape == log.clearance_m[steps].shape
        assert_close(
            result.clearance_m, log.clearance_m[steps], atol=CLEARANCE_TOL_M, err_msg=label
        )
        # Self and table contacts agree too (the same definition decides them).
        c = classify_contacts(log.meta.groups, log.contact_geoms, log.contact_dist)
        for flags, kind in ((result.self_hit, c.self_hit), (result.support, c.support)):
            logged = np.zeros(log.steps, dtype=bool)
            logged[log.contact_step[kind]] = True
            np.testing.assert_array_equal(flags, logged[steps], err_msg=label)
        checked += len(steps)
        hits += int(logged_hits.sum())
    assert checked >= MIN_CHECKED_STATES
    assert 0 < hits < checked  # both verdicts occur among the checked states


# ------------------------------------ (c) joint vectors, and the held cube


def test_joint_vectors_without_cube_agree_with_a_playback_without_cube():
    scene = REPORT_SCENE.without_cube()
    model = load_arm_scene(scene)
    trajectory = build_trajectory(load_task(PICK_AND_PLACE), TrajectoryKind.QUINTIC)
    log = play_arm(model, trajectory, task="pick_and_place").log
    steps = _sampled_steps(log)
    result = arm_checker(load_arm_scene(scene)).check(log.q[steps])
    logged_hits = log.obstacle_hits()[steps]
    assert logged_hits.any()
    assert not logged_hits.all()
    np.testing.assert_array_equal(result.obstacle, logged_hits)
    assert_close(result.clearance_m, log.clearance_m[steps], atol=CLEARANCE_TOL_M)


def test_grasped_puts_the_cube_at_the_tool_site():
    model = load_arm_scene(REPORT_SCENE)
    ids = SceneIds.from_model(model)
    assert ids.cube_qpos is not None
    checker = arm_checker(model)
    data = mujoco.MjData(model)
    adr = ids.cube_qpos
    rng = np.random.default_rng(7)
    q2, q3 = (np.radians([*TABLE4[i].q_deg, 0.0]) for i in (1, 2))
    configurations = [q2, _q_mid_p2_p3(), *(q2 + (q3 - q2) * rng.uniform(0, 1, (4, 1)))]
    for q in configurations:
        held = checker.check(q, grasped=True)
        # Where the checker put the cube: its own data, posed at q.
        posed = checker._data
        assert_close(posed.qpos[adr : adr + 3], posed.site_xpos[ids.tool_site], atol=0.0)
        # The same tool site in a data of our own.
        data.qpos[:] = model.qpos0
        data.qpos[list(ids.arm_qpos)] = q
        mujoco.mj_kinematics(model, data)
        tool = data.site_xpos[ids.tool_site].copy()
        assert_close(posed.qpos[adr : adr + 3], tool, atol=0.0)
        assert_close(posed.xpos[model.geom_bodyid[ids.cube_geom]], tool, atol=SPEC_TOL_M)
        # The whole state with the cube at the tool site gives the same verdict.
        quat = np.empty(4)
        mujoco.mju_mat2Quat(quat, data.site_xmat[ids.tool_site])
        state = data.qpos.copy()
        state[adr : adr + 3] = tool
        state[adr + 3 : adr + 7] = quat
        as_state = checker.check_states(state[None])
        assert held.obstacle == as_state.obstacle
        assert_close(held.clearance_m, as_state.clearance_m, atol=0.0)
    # On the straight tool line from P2 to P3 the carried cube is nearer the
    # cylinder than any part of the arm: held, it sets the clearance.
    p2, p3 = (np.asarray(TABLE4[i].position_mm) * 1e-3 for i in (1, 2))
    entering = ik_one(p2 + 0.35 * (p3 - p2), 0.0)
    held, left = checker.check(entering, grasped=True), checker.check(entering)
    assert 0.0 < held.clearance_m[0, 0] < left.clearance_m[0, 0] - 1e-3


# --------------------------------------------- (d) refusals, cap, contact


def test_checker_refuses_bad_shapes_and_non_finite_values():
    model = load_arm_scene(REPORT_SCENE)
    checker = arm_checker(model)
    for q in (np.zeros(4), np.zeros((3, 6)), np.zeros((2, 3, 5)), 0.0):
        with pytest.raises(InvalidInputError, match=r"q must have shape \(N, 5\) or \(5,\)"):
            checker.check(q)
    for states in (np.zeros(model.nq), np.zeros((2, model.nq + 1))):
        with pytest.raises(InvalidInputError, match=rf"qpos must have shape \(N, {model.nq}\)"):
            checker.check_states(states)
    for bad in (math.nan, math.inf, -math.inf):
        with pytest.raises(NonFiniteInputError, match="joint vectors must be finite"):
            checker.check([0.0, 0.5, bad, 0.0, 0.0])
        states = np.tile(model.qpos0, (3, 1))
        states[1, 2] = bad
        with pytest.raises(NonFiniteInputError, match="states must be finite"):
            checker.check_states(states)
    with pytest.raises(InvalidInputError, match="base_qpos must have shape"):
        CollisionChecker(model, checker.groups, [0, 1], base_qpos=np.zeros(model.nq - 1))
    with pytest.raises(NonFiniteInputError, match="base_qpos must be finite"):
        CollisionChecker(model, checker.groups, [0, 1], base_qpos=np.full(model.nq, math.nan))
    for cap, error in (
        (-1.0, InvalidInputError),
        (0.0, InvalidInputError),
        (math.nan, NonFiniteInputError),
        ("1", InvalidInputError),
        (True, InvalidInputError),
    ):
        with pytest.raises(error, match="cap must"):
            CollisionChecker(model, checker.groups, [0, 1], cap=cap)
        with pytest.raises(error, match="cap must"):
            checker.min_clearance(np.zeros(5), cap=cap)
    for q in (np.zeros(5, dtype=complex), np.zeros(5, dtype=bool), "abc", None):
        with pytest.raises(InvalidInputError, match="q must be real numbers"):
            checker.check(q)
        with pytest.raises(InvalidInputError, match="q must be real numbers"):
            checker.min_clearance(q)
    without_cube = arm_checker(load_arm_scene(REPORT_SCENE.without_cube()))
    with pytest.raises(InvalidInputError, match="grasped=True needs a payload"):
        without_cube.check(np.zeros(5), grasped=True)


def test_checker_of_no_vectors_answers_empty():
    checker = arm_checker(load_arm_scene(REPORT_SCENE))
    none = np.zeros((0, 5))
    assert checker.min_clearance(none).shape == (0,)
    assert checker.check(none).clearance_m.shape == (0, 1)


def test_one_checker_serves_threads_and_pickles():
    """Calls from several threads take turns on the checker's data: the answers of one thread."""
    checker = arm_checker(load_arm_scene(THREE_OBSTACLES))
    q = np.random.default_rng(2).uniform(-0.5, 0.5, (200, 5))
    expected = checker.check(q)
    smallest = checker.min_clearance(q)
    answers: list[tuple[CollisionCheck, np.ndarray]] = []

    def ask() -> None:
        for _ in range(5):
            answers.append((checker.check(q), checker.min_clearance(q)))

    threads = [threading.Thread(target=ask) for _ in range(2)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    assert len(answers) == 10
    for check, clearance in answers:
        for field in ("obstacle", "self_hit", "support", "clearance_m"):
            np.testing.assert_array_equal(getattr(check, field), getattr(expected, field))
        np.testing.assert_array_equal(clearance, smallest)
    copy = pickle.loads(pickle.dumps(checker))
    np.testing.assert_array_equal(copy.min_clearance(q), smallest)


def test_clearance_far_from_every_obstacle_reads_as_the_cap():
    q = np.vstack([np.zeros(5), _q_mid_p2_p3(), np.radians([-90.0, 60.0, -90.0, 0.0, 0.0])])
    far = arm_checker(load_arm_scene(Scene((OUT_OF_REACH,)))).check(q)
    assert not far.obstacle.any()
    assert (far.clearance_m == CLEARANCE_CAP_M).all()
    assert (far.min_clearance_m == CLEARANCE_CAP_M).all()
    # No obstacle at all: no clearance column, the cap as the smallest.
    none = arm_checker(load_arm_scene(REPORT_SCENE.without_obstacles())).check(q)
    assert none.clearance_m.shape == (3, 0)
    assert (none.min_clearance_m == CLEARANCE_CAP_M).all()
    # A smaller cap: the arm turned away from the cylinder reads as that cap.
    model = load_arm_scene(REPORT_SCENE)
    ids = SceneIds.from_model(model)
    exact = arm_checker(model).check(q[2])
    assert 0.05 < exact.clearance_m[0, 0] < CLEARANCE_CAP_M
    capped = CollisionChecker(model, ids.collision_groups(model), ids.arm_qpos, cap=0.05)
    assert capped.check(q[2]).clearance_m[0, 0] == 0.05


def test_configuration_inside_the_cylinder_collides_with_negative_clearance():
    model = load_arm_scene(REPORT_SCENE)
    q = np.vstack([_q_mid_p2_p3(), np.radians([*TABLE4[1].q_deg, 0.0])])
    result = arm_checker(model).check(q)
    assert result.obstacle_names == (REPORT_CYLINDER.name,)
    assert result.obstacle.tolist() == [True, False]
    assert result.in_collision.tolist() == [True, False]
    assert result.clearance_m[0, 0] < 0.0 < result.clearance_m[1, 0]
    assert_close(result.min_clearance_m, result.clearance_m[:, 0], atol=0.0)
    assert not result.self_hit.any()
    single = arm_checker(model).check(q[0])  # one vector: a batch of one
    assert single.obstacle.shape == (1,)
    assert single.obstacle[0]
    assert single.clearance_m[0, 0] == result.clearance_m[0, 0]


# -------------------------------------------- (e) one report per obstacle


@pytest.mark.parametrize(
    ("sphere", "first"),
    [(FAR_SPHERE, REPORT_CYLINDER.name), (BALL_ON_THE_WAY, BALL_ON_THE_WAY.name)],
    ids=["far_sphere", "sphere_on_the_way"],
)
def test_report_names_the_obstacle_hit_first_and_reports_each_obstacle(sphere, first):
    scene = Scene((REPORT_CYLINDER, sphere), cube=None)
    trajectory = build_trajectory(load_task(PICK_AND_PLACE), TrajectoryKind.QUINTIC)
    report, log = play_arm(load_arm_scene(scene), trajectory, task="pick_and_place")
    verdict = report.obstacle
    assert verdict is not None
    assert verdict.collided
    assert verdict.first_obstacle == first
    assert verdict.first_pair[1] == first
    assert [o.name for o in report.obstacles] == [REPORT_CYLINDER.name, sphere.name]
    cylinder, ball = report.obstacles
    assert_close(
        [o.min_clearance_m for o in report.obstacles], log.clearance_m.min(axis=0), atol=0.0
    )
    assert report.min_clearance_m == min(cylinder.min_clearance_m, ball.min_clearance_m)
    assert cylinder.collided
    assert cylinder.min_clearance_m < 0.0
    if sphere is FAR_SPHERE:
        assert not ball.collided
        assert ball.first_contact_s is None
        assert ball.min_clearance_m > 0.0
        assert ball.min_clearance_m > cylinder.min_clearance_m
        assert cylinder.first_contact_s == verdict.first_time_s
        assert report.min_clearance_m == cylinder.min_clearance_m
    else:
        assert ball.collided
        assert ball.min_clearance_m < 0.0
        assert ball.first_contact_s == verdict.first_time_s < cylinder.first_contact_s
        t_p1, t_p2 = trajectory.waypoint_times[:2]
        assert t_p1 < ball.first_contact_s < t_p2


# -------------------- (f) the model's obstacles as they are now, and exact clearances


def test_checker_sees_an_obstacle_moved_in_the_model():
    """Environments move obstacle geoms at reset; the checker must not keep the old place."""
    model = load_arm_scene(REPORT_SCENE.without_cube())
    checker = arm_checker(model)
    q = np.radians([45.0, 90.0, -60.0, -30.0, 0.0])  # reaches towards the cylinder
    before = checker.check(q)
    near = checker.min_clearance(q, cap=CLEARANCE_CAP_M)
    g = int(checker.groups.obstacle_geoms[0])
    model.geom_pos[g, :2] = (-0.3, -0.3)  # behind the arm
    after = checker.check(q)
    assert after.clearance_m[0, 0] > before.clearance_m[0, 0] + 0.1
    fresh = arm_checker(model).check(q)  # a checker made after the move
    np.testing.assert_array_equal(after.clearance_m, fresh.clearance_m)
    np.testing.assert_array_equal(after.obstacle, fresh.obstacle)
    assert checker.min_clearance(q, cap=CLEARANCE_CAP_M)[0] == fresh.min_clearance_m[0] > near[0]


def test_a_held_cube_touching_an_obstacle_is_a_hit():
    """The held cube collides where it is held: its body, not only its geoms, is moved there.

    Against ``mj_kinematics`` + ``mj_collision`` with the cube's free joint put
    at the tool site, over random joint vectors in a scene of three obstacles
    (MuJoCo's broadphase places a body by its inertial frame: a cube whose
    geoms alone were moved kept its contacts where it stood on the table).
    """
    model = load_arm_scene(Scene(THREE_OBSTACLES.obstacles, cube=REPORT_SCENE.cube))
    checker = arm_checker(model)
    groups = checker.groups
    rng = np.random.default_rng(11)
    q = rng.uniform(
        np.radians([-90, 0, -145, -90, 0]), np.radians([90, 135, 0, 90, 360]), (3000, 5)
    )
    result = checker.check(q, grasped=True)
    smallest = checker.min_clearance(q, grasped=True)
    ids = SceneIds.from_model(model)
    data = mujoco.MjData(model)
    pairs = groups.obstacle_pairs()
    hits = 0
    for k in range(len(q)):
        data.qpos[:] = model.qpos0
        data.qpos[list(ids.arm_qpos)] = q[k]
        mujoco.mj_kinematics(model, data)
        adr = ids.cube_qpos
        data.qpos[adr : adr + 3] = data.site_xpos[ids.tool_site]
        mujoco.mju_mat2Quat(data.qpos[adr + 3 : adr + 7], data.site_xmat[ids.tool_site])
        mujoco.mj_kinematics(model, data)
        mujoco.mj_collision(model, data)
        touching = {
            (int(a), int(b))
            for (a, b), dist in zip(data.contact.geom, data.contact.dist, strict=True)
            if dist <= 0.0
        }
        expected = bool(touching & pairs)
        assert result.obstacle[k] == expected, k
        if expected:
            hits += 1
            assert smallest[k] == -np.inf
    assert hits > 50


def test_a_clearance_in_penetration_is_no_shallower_than_any_pair_its_bounds_admit():
    """In penetration every pair whose bound is below the clearance is measured exactly.

    ``mj_geomDistance`` of a capsule and a box given a negative ``distmax``
    may return ``distmax`` instead of a deeper depth, so a second pair must be
    measured with a cap of at least zero. Random joint vectors among a box, a
    cylinder and a sphere; each pair that the bounds do not rule out
    (bound < clearance) is measured alone and must not be deeper.
    """
    model = load_arm_scene(Scene(THREE_OBSTACLES.obstacles))
    checker = arm_checker(model)
    groups = checker.groups
    rng = np.random.default_rng(5)
    q = rng.uniform(np.radians([-90, 0, -145, -90, 0]), np.radians([90, 135, 0, 90, 360]), (600, 5))
    result = checker.check(q)
    ids = SceneIds.from_model(model)
    data = mujoco.MjData(model)
    carried = np.flatnonzero(groups.carried)
    checked = 0
    for k in np.flatnonzero((result.clearance_m < 0.0).any(axis=1)).tolist():
        data.qpos[:] = model.qpos0
        data.qpos[list(ids.arm_qpos)] = q[k]
        mujoco.mj_kinematics(model, data)
        geometry = ClearanceGeometry.of(model, data, groups)
        bounds = _bounds(geometry, data.geom_xpos[carried][None], data.geom_xmat[carried][None])[0]
        for j, obstacle in enumerate(groups.obstacle_geoms.tolist()):
            clearance = result.clearance_m[k, j]
            for i in np.flatnonzero(bounds[:, j] < clearance).tolist():
                alone = mujoco.mj_geomDistance(
                    model, data, int(carried[i]), obstacle, CLEARANCE_CAP_M, None
                )
                assert alone >= clearance, (k, model.geom(int(carried[i])).name, alone, clearance)
                checked += 1
    assert checked > 100


@pytest.mark.parametrize("grasped", [False, True], ids=["cube_on_table", "cube_held"])
def test_positive_clearances_are_the_smallest_distance_of_any_pair(grasped):
    """The bounds only skip pairs that cannot be nearest: every positive clearance is exact.

    Against ``mj_geomDistance`` of every carried geom and obstacle, one of each
    shape, over random joint vectors (the cube's geoms placed without a second
    kinematics when held).
    """
    model = load_arm_scene(Scene(THREE_OBSTACLES.obstacles, cube=REPORT_SCENE.cube))
    checker = arm_checker(model)
    rng = np.random.default_rng(3)
    q = rng.uniform(np.radians([-90, 0, -145, -90, 0]), np.radians([90, 135, 0, 90, 360]), (400, 5))
    result = checker.check(q, grasped=grasped)
    smallest = checker.min_clearance(q, grasped=grasped)
    groups = checker.groups
    carried = np.flatnonzero(groups.carried).tolist()
    ids = SceneIds.from_model(model)
    data, fromto = mujoco.MjData(model), np.zeros(6)
    positive = 0
    for k in range(len(q)):
        data.qpos[:] = model.qpos0
        data.qpos[list(ids.arm_qpos)] = q[k]
        mujoco.mj_kinematics(model, data)
        if grasped:  # the reference: the cube's free joint at the tool site, posed again
            adr = ids.cube_qpos
            data.qpos[adr : adr + 3] = data.site_xpos[ids.tool_site]
            mujoco.mju_mat2Quat(data.qpos[adr + 3 : adr + 7], data.site_xmat[ids.tool_site])
            mujoco.mj_kinematics(model, data)
        for j, obstacle in enumerate(groups.obstacle_geoms.tolist()):
            exact = min(
                mujoco.mj_geomDistance(model, data, g, obstacle, CLEARANCE_CAP_M, fromto)
                for g in carried
            )
            if exact > 0.0:
                positive += 1
                assert_close(result.clearance_m[k, j], exact, atol=CLEARANCE_TOL_M)
        if not result.in_collision[k] and not result.support[k]:
            assert smallest[k] == result.min_clearance_m[k]
    assert positive > 600  # most pairs are apart, some touch
