"""Playback through the position actuators: tracking, the obstacle verdict, refusals."""

from __future__ import annotations

import json
import math
from pathlib import Path

import mujoco
import numpy as np
import pytest

from lynxsim.arm import tool_pose
from lynxsim.arm.motion import ArmPose, generate
from lynxsim.errors import InvalidInputError, LimitViolationError, NonFiniteInputError
from lynxsim.robots.arm import build_trajectory
from lynxsim.scene import REPORT_CYLINDER, REPORT_SCENE
from lynxsim.sim.arm.model import load_arm_scene
from lynxsim.sim.arm.playback import arm_binding, play_arm
from lynxsim.sim.arm.task import run_arm_trajectory
from lynxsim.sim.collision import CLEARANCE_CAP_M, classify_contacts
from lynxsim.sim.stepping.commands import physics_grid
from lynxsim.sim.stepping.rollout import rollout
from lynxsim.tasks import load_task
from lynxsim.traj import WAYPOINT_KINDS, TrajectoryKind

ROOT = Path(__file__).resolve().parents[2]
PICK_AND_PLACE = ROOT / "tasks" / "pick_and_place.toml"
VIA_POINTS = ROOT / "tasks" / "obstacle_avoidance.toml"

MAX_TOOL_ERROR_M = 5e-3
"""Issue 4, item 4: the tool's largest tracking error on the quintic pick-and-place."""
FINAL_TOOL_ERROR_M = 1e-3
"""Issue 4, item 4: the tool's error after 0.5 s of settling."""
NO_OBSTACLE = REPORT_SCENE.without_obstacles()
"""Table and cube, no obstacle."""
NO_CUBE = REPORT_SCENE.without_cube()
"""Table and the report's cylinder, no cube."""


@pytest.fixture(scope="module")
def pick_and_place():
    return load_task(PICK_AND_PLACE)


def test_quintic_pick_and_place_tracks_within_bounds(pick_and_place):
    trajectory = build_trajectory(pick_and_place, TrajectoryKind.QUINTIC)
    assert trajectory.segment_durations.tolist() == [1.0, 1.0, 1.0, 1.0]
    report = run_arm_trajectory(trajectory, task="pick_and_place", scene=NO_OBSTACLE).report
    assert report.tool_max_error_m <= MAX_TOOL_ERROR_M
    assert report.tool_final_error_m <= FINAL_TOOL_ERROR_M
    assert report.settle_s == pytest.approx(0.5)
    # No servo saturates: every peak torque stays below its datasheet stall torque.
    assert max(report.max_torque_ratio) < 1.0
    assert report.healthy
    assert report.obstacle is None


@pytest.mark.parametrize("kind", WAYPOINT_KINDS, ids=[k.value for k in WAYPOINT_KINDS])
def test_plain_task_hits_the_obstacle_between_p2_and_p3(pick_and_place, kind):
    trajectory = build_trajectory(pick_and_place, kind)
    report = play_arm(load_arm_scene(NO_CUBE), trajectory, task="pick_and_place").report
    assert report.collided
    t_p2, t_p3 = trajectory.waypoint_times[1:3]
    assert t_p2 < report.obstacle.first_time_s < t_p3
    robot_geom, obstacle_geom = report.obstacle.first_pair
    assert obstacle_geom == REPORT_CYLINDER.name
    assert report.obstacle.first_obstacle == REPORT_CYLINDER.name
    assert robot_geom.endswith("_collision")
    assert report.obstacle.max_penetration_m > 0.0
    assert report.min_clearance_m < 0.0
    assert report.healthy


@pytest.mark.parametrize("cube", [False, True], ids=["arm", "arm_and_cube"])
def test_via_points_with_straight_lines_clear_the_obstacle(cube):
    trajectory = build_trajectory(load_task(VIA_POINTS), TrajectoryKind.LINE)
    scene = REPORT_SCENE if cube else NO_CUBE
    report = run_arm_trajectory(trajectory, task="via", scene=scene).report
    assert not report.collided
    assert report.obstacle.steps_in_contact == 0
    # The report's via points pass the cylinder closely but clear it.
    assert 0.005 < report.min_clearance_m < 0.05
    assert report.healthy


def test_carried_cube_hitting_the_obstacle_is_a_collision(pick_and_place):
    # On the straight line from P2 to P3 the gripped cube reaches the cylinder
    # before any part of the arm does.
    trajectory = build_trajectory(pick_and_place, TrajectoryKind.LINE)
    with_cube = run_arm_trajectory(trajectory, task="p", scene=REPORT_SCENE).report
    arm_only = run_arm_trajectory(trajectory, task="p", scene=NO_CUBE).report
    assert with_cube.obstacle.first_pair == ("cube", REPORT_CYLINDER.name)
    assert with_cube.obstacle.first_time_s < arm_only.obstacle.first_time_s
    assert "cube" not in {p.geom1 for p in with_cube.floor_contacts + with_cube.self_collisions}


def test_contacts_and_clearance_describe_the_same_instant(pick_and_place):
    playback = play_arm(
        load_arm_scene(NO_CUBE), build_trajectory(pick_and_place, "quintic"), task="p"
    )
    first_negative = playback.log.time_s[np.argmax(playback.log.clearance_m < 0.0)]
    assert playback.report.obstacle.first_time_s == pytest.approx(first_negative)


def test_path_far_from_the_obstacle_does_not_touch_it():
    poses = [
        ArmPose((0.0, -0.25, 0.3), 0.0),
        ArmPose((0.0, -0.3, 0.0), -math.pi / 2),
    ]
    trajectory = generate("quintic", poses, 1.0)
    report = play_arm(load_arm_scene(NO_CUBE), trajectory, task="far").report
    assert not report.collided
    assert report.min_clearance_m > 0.1


def test_scene_without_obstacle_never_reports_one(pick_and_place):
    trajectory = build_trajectory(pick_and_place, TrajectoryKind.QUINTIC)
    report = play_arm(load_arm_scene(NO_OBSTACLE.without_cube()), trajectory, task="p").report
    assert report.obstacle is None
    assert report.obstacles == ()
    assert not report.collided
    assert report.min_clearance_m is None


def test_commands_outside_the_joint_ranges_are_refused_before_playback():
    model = load_arm_scene(NO_CUBE)
    data = mujoco.MjData(model)
    q_cmd = np.zeros((100, 5))
    q_cmd[60:, 2] = 0.2  # elbow range is [-145, 0] deg
    with pytest.raises(
        LimitViolationError, match=r"joint 3 \(elbow\) by 11\.459 deg at t = 0\.122"
    ):
        rollout(
            model, data, arm_binding(model), q_cmd, np.zeros((100, 3)), task="t", trajectory="t"
        )
    assert data.time == 0.0  # nothing was simulated


def _refused(model, **kwargs):
    """Play 100 resting steps with ``kwargs``; what was refused must leave the data unstepped."""
    data = mujoco.MjData(model)
    try:
        rollout(
            model,
            data,
            arm_binding(model),
            np.zeros((100, 5)) + np.radians([0, 45, -90, 0, 0]),
            np.zeros((100, 3)),
            task="t",
            trajectory="t",
            **kwargs,
        )
    finally:
        assert data.time == 0.0  # nothing was simulated


@pytest.mark.parametrize(
    ("kwargs", "error", "message"),
    [
        ({"settle_s": math.nan}, NonFiniteInputError, "settle_s must be finite"),
        ({"settle_s": math.inf}, NonFiniteInputError, "settle_s must be finite"),
        ({"settle_s": -0.5}, InvalidInputError, "settle_s must be between 0 and 3600 s"),
        ({"settle_s": 1e30}, InvalidInputError, "settle_s must be between"),
        ({"settle_s": "0.5"}, InvalidInputError, "settle_s must be a number"),
        ({"settle_s": None}, InvalidInputError, "settle_s must be a number"),
        ({"settle_s": True}, InvalidInputError, "settle_s must be a number"),
        ({"presettle_s": -1.0}, InvalidInputError, "presettle_s must be between"),
        ({"gripper_cmd": 0.02}, InvalidInputError, "gripper_cmd must be a function"),
        ({"gripper_cmd": lambda t: math.nan}, NonFiniteInputError, "gripper_cmd must be finite"),
        ({"gripper_cmd": lambda t: None}, InvalidInputError, "openings must be real numbers"),
        ({"gripper_cmd": lambda t: "x"}, InvalidInputError, "openings must be real numbers"),
        ({"gripper_cmd": lambda t: np.zeros(2)}, InvalidInputError, "one number per time"),
        (
            {"gripper_cmd": lambda t: 0.05},
            LimitViolationError,
            r"gripper opening 0\.05 m at t = -0\.500 s leaves its range \[0, 0\.03\] m",
        ),
        ({"gripper_cmd": lambda t: -1.0 if t > 0.1 else 0.0}, LimitViolationError, "t = 0.102 s"),
    ],
)
def test_bad_hold_times_and_gripper_openings_are_refused_before_playback(kwargs, error, message):
    with pytest.raises(error, match=message):
        _refused(load_arm_scene(REPORT_SCENE), **kwargs)


@pytest.mark.parametrize(
    ("duration", "dt", "error", "message"),
    [
        (-1.0, 0.002, InvalidInputError, "duration_s must be positive"),
        (1.0, 0.0, InvalidInputError, "dt must be positive"),
        (math.nan, 0.002, NonFiniteInputError, "duration_s must be finite"),
        ("1", 0.002, InvalidInputError, "duration_s must be a number"),
        (1e9, 0.002, InvalidInputError, "over 100,000,000 steps"),
    ],
)
def test_physics_grid_refuses_what_is_no_duration(duration, dt, error, message):
    with pytest.raises(error, match=message):
        physics_grid(duration, dt)


@pytest.mark.parametrize("name", ["task", "trajectory"])
def test_run_names_must_be_text(name):
    kwargs = {"task": "t", "trajectory": "t", name: None}
    model = load_arm_scene(NO_CUBE)
    with pytest.raises(InvalidInputError, match=f"{name} must be of type str"):
        rollout(
            model,
            mujoco.MjData(model),
            arm_binding(model),
            np.zeros((10, 5)),
            np.zeros((10, 3)),
            **kwargs,
        )


def test_data_of_another_model_is_refused_before_playback():
    model = load_arm_scene(REPORT_SCENE)
    other = mujoco.MjData(load_arm_scene(NO_OBSTACLE.without_cube()))
    trajectory = generate(
        "quintic", [ArmPose((0.0, 0.25, 0.3), 0.0), ArmPose((0.1, 0.25, 0.3), 0.0)], 2.0
    )
    with pytest.raises(InvalidInputError, match="data was made for another model: its qpos has"):
        play_arm(model, trajectory, task="t", data=other)
    assert other.time == 0.0
    with pytest.raises(InvalidInputError, match=r"data must be a mujoco\.MjData, got 'x'"):
        play_arm(model, trajectory, task="t", data="x")


def test_report_round_trips_through_json(tmp_path, pick_and_place):
    trajectory = build_trajectory(pick_and_place, TrajectoryKind.QUINTIC)
    report = play_arm(load_arm_scene(NO_CUBE), trajectory, task="p").report
    data = json.loads(report.write_json(tmp_path / "r.json").read_text())
    assert data["collided"] is True
    assert data["obstacle"]["first_pair"][1] == REPORT_CYLINDER.name
    assert data["obstacle"]["first_obstacle"] == REPORT_CYLINDER.name
    assert [o["name"] for o in data["obstacles"]] == [REPORT_CYLINDER.name]
    assert data["obstacles"][0]["collided"] is True
    assert len(data["joint_max_error_rad"]) == 5
    assert set(data) >= {
        "tool_max_error_m",
        "tool_rms_error_m",
        "tool_final_error_m",
        "min_clearance_m",
        "self_collisions",
        "floor_contacts",
        "healthy",
    }


# ------------------ records of each instant, taken without posing twice (issue 12)

THREE_OBSTACLES = ROOT / "tasks" / "three_obstacles.toml"
RECORDED_RUNS = (
    (PICK_AND_PLACE, TrajectoryKind.QUINTIC),  # stalls against the cylinder
    (PICK_AND_PLACE, TrajectoryKind.LINE),  # the carried cube hits it
    (VIA_POINTS, TrajectoryKind.LINE),  # passes it 13 mm apart
    (THREE_OBSTACLES, TrajectoryKind.RUCKIG),  # a cylinder, a box and a sphere
)


def _command(path: Path, kind: TrajectoryKind):
    task = load_task(path)
    model = load_arm_scene(task.scene)
    trajectory = build_trajectory(task, kind)
    q_cmd = trajectory.sample(physics_grid(trajectory.duration, model.opt.timestep)).q
    return model, q_cmd


def _play(model, q_cmd, **kwargs):
    return rollout(
        model,
        mujoco.MjData(model),
        arm_binding(model),
        q_cmd,
        tool_pose(q_cmd).position,
        task="t",
        trajectory="t",
        **kwargs,
    )


def _assert_same_log(a, b):
    for name in (
        "time_s", "qpos", "q_cmd", "q", "tool_ref", "tool", "force", "clearance_m",
        "contact_step", "contact_geoms", "contact_dist",
    ):  # fmt: skip
        np.testing.assert_array_equal(getattr(a, name), getattr(b, name), err_msg=name)
    assert (a.warnings, a.diverged_at_s, a.trajectory_steps) == (
        b.warnings,
        b.diverged_at_s,
        b.trajectory_steps,
    )


@pytest.mark.parametrize(
    ("path", "kind"), RECORDED_RUNS, ids=[f"{p.stem}-{k.value}" for p, k in RECORDED_RUNS]
)
def test_every_record_describes_its_own_state(path, kind):
    """Tool, contacts and clearances of each step equal those of its logged state posed alone.

    Contacts are logged one row per touching pair and step (its deepest), in
    pair order, whether MuJoCo listed them or the recording sensors sensed them.

    The reference poses each logged ``qpos`` (``mj_kinematics`` + ``mj_collision``)
    and measures every carried geom against every obstacle with
    ``mj_geomDistance``, no bound involved.
    """
    model, q_cmd = _command(path, kind)
    log = _play(model, q_cmd)
    groups = log.meta.groups
    carried = np.flatnonzero(groups.carried).tolist()
    data, fromto = mujoco.MjData(model), np.zeros(6)
    counted = classify_contacts(groups, log.contact_geoms, log.contact_dist)
    assert counted.obstacle.any() or path == VIA_POINTS
    for k in range(log.steps):
        data.qpos[:] = log.qpos[k]
        mujoco.mj_kinematics(model, data)
        mujoco.mj_collision(model, data)
        assert np.array_equal(data.site_xpos[arm_binding(model).tool_site_id], log.tool[k])
        n = data.ncon
        geoms, dist = np.array(data.contact.geom[:n]), np.array(data.contact.dist[:n])
        c = classify_contacts(groups, geoms, dist)
        keep = c.obstacle | c.self_hit | c.support
        deepest: dict[tuple[int, int], float] = {}  # one row per pair: its deepest contact
        for (g1, g2), d in zip(geoms[keep].tolist(), dist[keep].tolist(), strict=True):
            pair = (min(g1, g2), max(g1, g2))
            deepest[pair] = min(d, deepest.get(pair, np.inf))
        rows = log.contact_step == k
        assert log.contact_geoms[rows].tolist() == [list(p) for p in sorted(deepest)]
        assert log.contact_dist[rows].tolist() == [deepest[p] for p in sorted(deepest)]
        for j, obstacle in enumerate(groups.obstacle_geoms.tolist()):
            exact = min(
                mujoco.mj_geomDistance(model, data, g, obstacle, CLEARANCE_CAP_M, fromto)
                for g in carried
            )
            assert log.clearance_m[k, j] == min(exact, CLEARANCE_CAP_M), (k, j)


def test_physics_is_the_same_as_stepping_alone(pick_and_place):
    """The records never touch the physics: the states equal a bare ctrl + mj_step loop."""
    model, q_cmd = _command(PICK_AND_PLACE, TrajectoryKind.QUINTIC)
    log = _play(model, q_cmd, settle_s=0.1)
    binding = arm_binding(model)
    data = mujoco.MjData(model)
    data.qpos[binding.qpos_adr] = q_cmd[0]
    data.ctrl[binding.actuator_ids] = q_cmd[0]
    mujoco.mj_forward(model, data)
    for _ in range(round(0.5 / model.opt.timestep)):
        mujoco.mj_step(model, data)
    for k in range(log.steps):
        data.ctrl[binding.actuator_ids] = q_cmd[min(k, len(q_cmd) - 1)]
        mujoco.mj_step(model, data)
        assert np.array_equal(data.qpos, log.qpos[k]), k


def test_a_step_hook_sees_each_state_posed_and_changes_nothing():
    model, q_cmd = _command(PICK_AND_PLACE, TrajectoryKind.QUINTIC)
    seen = []
    site = arm_binding(model).tool_site_id
    with_hook = _play(model, q_cmd, on_step=lambda k, d: seen.append(d.site_xpos[site].copy()))
    _assert_same_log(with_hook, _play(model, q_cmd))
    np.testing.assert_array_equal(np.array(seen), with_hook.tool)


def test_a_run_that_mujoco_resets_ends_where_it_diverged():
    """Servos far too stiff: MuJoCo finds bad accelerations and resets the state in mj_step.

    The log ends before the step that MuJoCo reset (what follows a reset is
    the model's rest pose, not the run), says when it diverged, and its
    records describe each logged state (the lagged records are replaced by a
    replay that poses every state), as with a step hook.
    """
    model, q_cmd = _command(PICK_AND_PLACE, TrajectoryKind.QUINTIC)
    model.actuator_gainprm[:5, 0] *= 1e9
    model.actuator_biasprm[:5, 1] *= 1e9
    model.actuator_forcerange[:5] *= 1e9
    messages: list[str] = []
    previous = mujoco.get_mju_user_warning()
    mujoco.set_mju_user_warning(messages.append)  # not into MUJOCO_LOG.TXT
    try:
        log = _play(model, q_cmd[:300], settle_s=0.0)
        hooked = _play(model, q_cmd[:300], settle_s=0.0, on_step=lambda k, d: None)
    finally:
        mujoco.set_mju_user_warning(previous)
    assert log.warnings["badqacc"]
    assert any("QACC" in m for m in messages)
    dt = model.opt.timestep
    assert 0 < log.steps < 300
    np.testing.assert_array_equal(log.time_s, np.cumsum(np.full(log.steps, dt)))
    assert log.diverged_at_s == pytest.approx((log.steps + 1) * dt, abs=1e-12)
    _assert_same_log(log, hooked)
    assert hooked.diverged_at_s == log.diverged_at_s
    data = mujoco.MjData(model)
    for k in range(log.steps):
        data.qpos[:] = log.qpos[k]
        mujoco.mj_kinematics(model, data)
        assert np.array_equal(data.site_xpos[arm_binding(model).tool_site_id], log.tool[k])
