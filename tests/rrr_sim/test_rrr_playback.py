"""Playing 3-RRR paths in MuJoCo: loop closure, tracking, link interference, video, CLI, demo."""

from __future__ import annotations

import dataclasses
import json
import math
from pathlib import Path

import imageio.v2 as imageio
import numpy as np
import pytest

from lynxsim.demo.rrr import FIGURE20_FILE, run_rrr_demo
from lynxsim.errors import InvalidInputError
from lynxsim.robots.rrr import path_from_task
from lynxsim.rrr.path import platform_path
from lynxsim.sim.render import Quality, RenderSettings
from lynxsim.sim.rrr.model import HOME_POSE, load_rrr_scene
from lynxsim.sim.rrr.playback import RRRMetrics, play_rrr
from lynxsim.sim.rrr.task import run_rrr_path
from lynxsim.tasks import load_task
from tests.helpers import short_rrr_task
from tests.rrr_sim.conftest import FIGURE20_A, FIGURE20_F

ROOT = Path(__file__).resolve().parents[2]
TASKS = {
    "tour": ROOT / "tasks" / "rrr_figure20_tour.toml",
    "closed_curve": ROOT / "tasks" / "rrr_closed_curve.toml",
}

PLAYBACK_LOOP_TOL_M = 0.5e-3
"""Acceptance: loop closure during a playback, 0.5 mm [m]."""
REST_LOOP_TOL_M = 1e-4
"""Acceptance: loop closure at rest, 0.1 mm [m]."""
TRACKING_TOL_M = 1e-3
"""Platform centre against the commanded path during the task playbacks [m]."""
TRACKING_TOL_RAD = math.radians(0.2)
"""Platform orientation against the commanded path [rad]."""
FINAL_TOL_M = 0.5e-3
FINAL_TOL_RAD = math.radians(0.1)
RRR_METRIC_NAMES = (
    "working_mode",
    "loop_closure_max_m",
    "loop_closure_final_m",
    "platform_position_max_error_m",
    "platform_position_rms_error_m",
    "platform_position_final_error_m",
    "platform_orientation_max_error_rad",
    "platform_orientation_rms_error_rad",
    "platform_orientation_final_error_rad",
    "link_min_clearance_m",
    "path_min_abs_parallel",
    "path_min_serial",
    "base_speed_max_rad_s",
)
"""The 3-RRR figures of a run report, in order (:class:`RRRMetrics`)."""
SMALL_RENDER = RenderSettings(width=160, height=128, camera="top", quality=Quality.FAST, fps=20)

SHORT_RRR_TASK = short_rrr_task()


@pytest.fixture(scope="module", params=TASKS.values(), ids=TASKS.keys())
def task_report(request):
    task = load_task(request.param)
    return run_rrr_path(path_from_task(task), task=task.name).report


def test_task_playback_keeps_loops_closed_and_tracks_the_path(task_report):
    r = task_report
    assert r.healthy
    assert not r.warnings
    assert r.diverged_at_s is None
    m = r.metrics
    assert isinstance(m, RRRMetrics)
    assert tuple(f.name for f in dataclasses.fields(m)) == RRR_METRIC_NAMES
    assert m.working_mode == 7
    assert m.loop_closure_max_m <= PLAYBACK_LOOP_TOL_M
    assert m.loop_closure_final_m <= REST_LOOP_TOL_M
    assert m.platform_position_max_error_m <= TRACKING_TOL_M
    assert m.platform_orientation_max_error_rad <= TRACKING_TOL_RAD
    assert m.platform_position_final_error_m <= FINAL_TOL_M
    assert m.platform_orientation_final_error_rad <= FINAL_TOL_RAD
    assert r.self_collisions == ()
    assert m.link_min_clearance_m > 0.02
    assert r.obstacle is None
    assert r.obstacles == ()
    assert max(r.max_torque_ratio) < 1.0, "the servos never saturate"
    json.loads(json.dumps(r.to_dict()))


def test_link_interference_during_a_playback_is_a_self_collision():
    # a -> f in working mode 7: proximal link 3 runs into the platform edge P2-P3.
    path = platform_path(np.array([FIGURE20_A, FIGURE20_F]), 1.5, stretch=True)
    r = play_rrr(path, 7, task="into_interference", settle_s=0.2).report
    pairs = {(p.geom1, p.geom2) for p in r.self_collisions}
    assert ("leg3_proximal_collision", "platform_collision23") in pairs
    assert r.metrics.link_min_clearance_m < 0.0
    assert r.metrics.platform_position_final_error_m > FINAL_TOL_M, "the links block the motion"
    assert r.healthy


def test_model_must_be_assembled_at_the_path_start():
    path = platform_path(np.array([FIGURE20_A, HOME_POSE]), 1.0)
    with pytest.raises(InvalidInputError, match=r"not assembled at the path's first pose"):
        play_rrr(path, 7, task="x", model=load_rrr_scene())
    assert play_rrr(path, 7, task="x", model=load_rrr_scene(FIGURE20_A, 7)).report.healthy


def test_video_is_recorded_at_the_video_rate_of_simulated_time(tmp_path):
    path = platform_path(np.array([HOME_POSE, FIGURE20_A]), 0.6, stretch=True)
    video = tmp_path / "short.mp4"
    done = []
    r = run_rrr_path(
        path, task="short", video=video, render=SMALL_RENDER, settle_s=0.1, progress=done.append
    ).report
    assert r.healthy
    assert done[-1] == 1.0
    frames = imageio.mimread(video)
    assert len(frames) == pytest.approx((0.6 + 0.1) * SMALL_RENDER.fps, abs=2)
    assert frames[-1].shape == (128, 160, 3)


def test_demo_writes_videos_reports_plots_and_figure20_verdicts(tmp_path):
    tasks = tmp_path / "tasks"
    tasks.mkdir()
    (tasks / "short_rrr.toml").write_text(SHORT_RRR_TASK)
    (tasks / "arm.toml").write_text((ROOT / "tasks" / "pick_and_place.toml").read_text())
    out = tmp_path / "out"
    seen = []
    reports = run_rrr_demo(out, SMALL_RENDER, lambda i, f: seen.append((i, f)), tasks=tasks)
    assert [r.task for r in reports] == ["short_rrr"]
    assert (out / "short_rrr_quintic.mp4").is_file()
    assert json.loads((out / "short_rrr_quintic.json").read_text())["healthy"] is True
    assert (out / "plots" / "short_rrr_quintic.png").is_file()
    verdicts = (out / FIGURE20_FILE).read_text()
    assert "simulation says UNREACHABLE" in verdicts
    assert seen[-1] == (0, 1.0)
