"""A robot from outside lynxsim (examples/planar_arm) through every command, end to end.

The planar arm is registered through :func:`lynxsim.robots.register` only; no
file of ``lynxsim/`` names it. Each command runs in-process through
:func:`lynxsim.cli.main`: ``play`` (an MP4 decoded, the JSON report, the replay
page), ``traj`` (its joints, tool point and heading as columns), ``plan`` (the
planned path judged by physics: its playback is clear), ``sweep`` (a small map,
a placement checked against a run of its own, in worker processes) and the
demo's job list (in a process pool); its :class:`CollisionChecker` agrees with
the contacts of stepped physics, and its model's tool site with its FK.
"""

from __future__ import annotations

import csv
import dataclasses
import json
import subprocess
import sys
from pathlib import Path

import imageio.v2 as imageio
import mujoco
import numpy as np
import pytest

from lynxsim.demo.runs import demo_jobs, demo_runs, demo_tasks, run_demo
from lynxsim.robots import Robot, motion, plan, simulation
from lynxsim.scene import Scene
from lynxsim.sim.collision import classify_contacts
from lynxsim.sim.render import Quality, RenderSettings, camera_names
from lynxsim.tasks import load_task
from lynxsim.traj import Trajectory, TrajectoryKind
from tests.helpers import assert_close
from tests.robots.conftest import EXAMPLES, PLANAR_TASKS, POST_SWEEP, POST_TASK, REACH_TASK

SMALL = RenderSettings(width=160, height=120, quality=Quality.FAST, fps=10)
FK_TOL_M = 1e-12
"""The analytic FK against the model's tool site [m] (measured: 2e-16 m)."""
TRACKING_TOL_M = 0.01
"""The reach task's tool tracking error in physics [m] (kp 200, damping ratio 0.3)."""
CLEARANCE_TOL_M = 1e-12
"""The checker's clearance against the playback's [m] (the same MuJoCo distances)."""
SAMPLES = 300
"""Logged states checked against the checker."""

pytestmark = pytest.mark.usefixtures("planar_arm")


def test_its_model_has_the_records_cameras_and_its_tool_site_is_its_fk(planar_arm: Robot):
    task = load_task(REACH_TASK)
    model = simulation(planar_arm).model(task.scene)
    assert camera_names(model) == planar_arm.cameras
    assert planar_arm.kinematics is not None
    data = mujoco.MjData(model)
    site = model.site("tool").id
    rng = np.random.default_rng(0)
    bounds = planar_arm.kinematics.bounds
    q = rng.uniform(bounds.lower_array, bounds.upper_array, size=(200, 3))
    adr = [int(model.jnt_qposadr[model.joint(n).id]) for n in bounds.names]
    points = np.empty((len(q), 3))
    for i, qi in enumerate(q):
        data.qpos[adr] = qi
        mujoco.mj_kinematics(model, data)
        points[i] = data.site_xpos[site]
    assert_close(planar_arm.kinematics.tool_points(q), points, atol=FK_TOL_M)


def test_its_checker_agrees_with_the_contacts_of_stepped_physics(planar_arm: Robot):
    task = load_task(POST_TASK)
    adapter = simulation(planar_arm)
    log = adapter.play(task, motion(planar_arm, task)).log
    hits = log.obstacle_hits()
    assert hits.any()
    assert not hits.all()
    steps = np.union1d(
        np.linspace(0, log.steps - 1, SAMPLES).round().astype(np.intp), np.flatnonzero(hits)
    )
    result = adapter.checker(task.scene).check(log.q[steps])
    np.testing.assert_array_equal(result.obstacle, hits[steps])
    assert_close(result.clearance_m, log.clearance_m[steps], atol=CLEARANCE_TOL_M)
    c = classify_contacts(log.meta.groups, log.contact_geoms, log.contact_dist)
    for flags, kind in ((result.self_hit, c.self_hit), (result.support, c.support)):
        logged = np.zeros(log.steps, dtype=bool)
        logged[log.contact_step[kind]] = True
        np.testing.assert_array_equal(flags, logged[steps])


def test_play_writes_a_decodable_mp4_a_json_report_and_a_replay_page(cli, tmp_path: Path):
    out = tmp_path / "reach.mp4"
    result = cli(
        "play",
        str(REACH_TASK),
        "--out",
        str(out),
        "--json",
        "--html",
        "--quality",
        "fast",
        "--fps",
        "10",
    )
    assert result.code == 0, result.err
    report = json.loads(result.out)
    assert report == json.loads(out.with_suffix(".json").read_text())
    assert (report["task"], report["trajectory"], report["healthy"]) == (
        "planar_reach",
        "quintic",
        True,
    )
    assert report["tool_max_error_m"] < TRACKING_TOL_M
    assert report["self_collisions"] == []
    assert report["collided"] is False
    frames = imageio.get_reader(out).count_frames()
    assert frames == pytest.approx((report["duration_s"] + report["settle_s"]) * 10, abs=2)
    assert out.with_suffix(".html").read_text().startswith("<!DOCTYPE html>")
    assert out.with_suffix(".replay.npz").is_file()


def test_play_takes_its_run_option_and_camera_and_refuses_the_others(cli, tmp_path: Path):
    out = tmp_path / "post.mp4"
    result = cli("play", str(POST_TASK), "--no-obstacle", "--camera", "top", "--no-video", "--json",
                 "--out", str(out))  # fmt: skip
    assert result.code == 0, result.err
    assert json.loads(result.out)["obstacle"] is None  # the post left out
    for argv, message in (
        (["--mode", "3"], "--mode applies only to tasks of the planar 3-RRR parallel robot"),
        (["--camera", "wrist"], "--camera 'wrist': the planar three-link arm model has no such"),
        (["--controller", "ssc32"], "--controller ssc32 applies only to arm tasks"),
        (["--type", "line"], "'line' is not built for the planar arm"),
    ):
        result = cli("play", str(POST_TASK), "--no-video", "--out", str(out), *argv)
        assert (result.code, result.err.count("\n")) == (1, 1), result.err
        assert message in result.err


def test_traj_writes_its_joints_tool_point_and_heading(cli, tmp_path: Path):
    result = cli("traj", str(REACH_TASK), "--out-dir", str(tmp_path), "--rate-hz", "50")
    assert result.code == 0, result.err
    assert result.err == ""  # the comparison draws the types it builds: every one builds
    with (tmp_path / "planar_reach_quintic.csv").open() as f:
        rows = list(csv.DictReader(f))
    orders = (("q", "deg"), ("qd", "deg_s"), ("qdd", "deg_s2"), ("qddd", "deg_s3"))
    joints = [f"{name}{j}_{unit}" for name, unit in orders for j in (1, 2, 3)]
    assert list(rows[0]) == ["t_s", *joints, "x_mm", "y_mm", "z_mm", "heading_deg"]
    assert len(rows) == 101  # 2 s at 50 Hz, both ends
    last = rows[-1]
    assert float(last["q1_deg"]) == pytest.approx(90.0, abs=1e-9)
    assert float(last["heading_deg"]) == pytest.approx(80.0, abs=1e-9)  # 90 + 30 - 40
    assert float(last["z_mm"]) == pytest.approx(185.0, abs=1e-9)
    for name in ("planar_reach_quintic_joints.png", "planar_reach_paths.png"):
        assert (tmp_path / name).read_bytes().startswith(b"\x89PNG")


def test_plan_finds_a_path_around_the_post_that_physics_finds_clear(
    planar_arm: Robot, cli, tmp_path: Path
):
    result = cli("plan", str(POST_TASK), "--out-dir", str(tmp_path), "--json", "--seed", "1")
    assert result.code == 0, result.err
    report = json.loads(result.out)
    assert [s["segment"] for s in report["segments"]] == ["start -> goal"]
    assert report["segments"][0]["timed_min_clearance_m"] >= 0.01  # the margin kept
    assert (tmp_path / "planar_post_planned.csv").is_file()
    task = load_task(POST_TASK)
    planned = plan(planar_arm, task, seed=1).trajectory
    assert planned.duration == pytest.approx(report["duration_s"], rel=0, abs=0)  # bit for bit
    direct = simulation(planar_arm).play(task, motion(planar_arm, task, "quintic")).report
    physics = simulation(planar_arm).play(task, planned).report
    assert direct.collided  # the straight swing hits the post ...
    assert not physics.collided
    assert physics.healthy
    assert physics.min_clearance_m is not None
    assert physics.min_clearance_m > 0.0


def test_sweep_maps_the_post_and_a_clear_placement_is_its_own_run(
    planar_arm: Robot, cli, tmp_path: Path
):
    result = cli(
        "sweep", str(POST_SWEEP), "--out-dir", str(tmp_path), "--jobs", "2", "--json", "--quiet"
    )
    assert result.code == 0, result.err
    summary = json.loads(result.out)
    assert summary["shards_computed"] > 2  # in two worker processes
    assert [Path(m).name for m in summary["maps"]] == ["planar_post_map_planar_post_quintic.png"]
    with (tmp_path / "planar_post_map.csv").open() as f:
        rows = list(csv.DictReader(f))
    verdicts = {r["verdict"] for r in rows}
    assert {"clear", "collided"} <= verdicts, verdicts
    assert all(r["task"] == "planar_post" and r["type"] == "quintic" for r in rows)
    assert len(rows) == summary["runs"] > 50
    clear = next(r for r in rows if r["verdict"] == "clear")
    task = load_task(POST_TASK)
    post = task.scene.obstacle("post")
    x, y = float(clear["obstacle_x_m"]), float(clear["obstacle_y_m"])
    moved = dataclasses.replace(post, position=(x, y, post.position[2]))
    own = dataclasses.replace(task, scene=Scene((moved,), task.scene.table, task.scene.cube))
    report = simulation(planar_arm).play(own, motion(planar_arm, own)).report
    assert not report.collided
    assert report.min_clearance_m == float(clear["min_clearance_m"])  # exact, not close


def test_its_tasks_are_demo_jobs_and_run_in_a_process_pool(planar_arm: Robot, tmp_path: Path):
    tasks = demo_tasks(PLANAR_TASKS)
    assert [t.name for t in tasks] == ["planar_post", "planar_reach"]
    skipped: list[str] = []
    runs = list(demo_runs(tasks, skipped.append))
    assert {(r.task.name, r.motion.label) for r in runs} >= {
        ("planar_reach", k.value) for k in planar_arm.kinds
    }
    names = [j.name for j in demo_jobs(runs, tmp_path, SMALL)]
    assert names[-2:] == ["planar_post_paths", "planar_reach_paths"]
    chosen = [r for r in runs if r.task.name == "planar_reach" and r.motion.label in
              ("cubic", "ruckig")]  # fmt: skip
    reports = run_demo(chosen, tmp_path, SMALL, jobs=2)
    assert [(r.task, r.trajectory) for r in reports] == [
        ("planar_reach", "cubic"),
        ("planar_reach", "ruckig"),
    ]
    for stem in ("planar_reach_cubic", "planar_reach_ruckig"):
        assert imageio.get_reader(tmp_path / f"{stem}.mp4").count_frames() > 10
        assert json.loads((tmp_path / f"{stem}.json").read_text())["healthy"] is True
        assert (tmp_path / f"{stem}.html").is_file()
        assert (tmp_path / "plots" / f"{stem}.png").is_file()
    assert (tmp_path / "plots" / "planar_reach_paths.png").is_file()


def test_every_built_type_is_a_joint_trajectory_of_its_three_joints(planar_arm: Robot):
    task = load_task(REACH_TASK)
    for kind in planar_arm.kinds:
        if kind is TrajectoryKind.PLANNED:
            continue
        built = motion(planar_arm, task, kind)
        assert isinstance(built, Trajectory)
        assert built.n_joints == 3
        assert built.waypoint_names == ("A", "B", "C")
        assert_close(built.sample(built.waypoint_times).q, built.waypoints.q, atol=1e-9)


def test_an_installed_package_offers_it_through_an_entry_point(tmp_path: Path):
    dist = tmp_path / "planar_arm_robot-1.0.dist-info"
    dist.mkdir()
    (dist / "METADATA").write_text("Metadata-Version: 2.1\nName: planar-arm-robot\nVersion: 1.0\n")
    (dist / "entry_points.txt").write_text(
        "[lynxsim.robots]\nplanar_arm = planar_arm.robot:ROBOT\n"
    )
    code = (
        "import sys\n"
        "from lynxsim.tasks import load_task\n"
        "from lynxsim.robots import names, every\n"
        "assert 'planar_arm' not in names()\n"
        f"task = load_task({str(REACH_TASK)!r})\n"  # the unknown name found by its entry point
        "print(task.robot, [r.name for r in every()])\n"
    )
    run = subprocess.run(
        [sys.executable, "-c", code],
        capture_output=True,
        text=True,
        timeout=120,
        check=False,
        env={"PYTHONPATH": f"{tmp_path}:{EXAMPLES}", "PATH": "/usr/bin:/bin"},
    )
    assert run.returncode == 0, run.stderr[-2000:]
    assert run.stdout.strip() == "planar_arm ['arm', 'rrr', 'planar_arm']"
