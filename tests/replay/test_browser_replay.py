"""Replay pages in a real headless Chromium.

They load clean, show the log's poses, and the arm where MuJoCo's own renderer draws it.
"""

from __future__ import annotations

import dataclasses
import io
import json
import time

import mujoco
import numpy as np
import pytest
from imageio import v3 as iio

from lynxsim.sim.replay.scene import scene_parts
from lynxsim.web.page import write_replay_page
from lynxsim.web.poses import point_error_bound
from tests.replay.conftest import ReplayRun, true_body_poses

POSE_TOL_M = 1e-3
"""The issue's bound on a body pose read back from the page against the log's [m]."""
SILHOUETTE_IOU = 0.97
"""Least overlap (intersection over union) of the page's and MuJoCo's silhouettes of the
moving bodies from one camera (measured: 0.998 front, arm; the rest is the tessellation of
round primitives and rasterisation at the edges)."""
OTHER_STATE_IOU = 0.9
"""The page's silhouette must overlap MuJoCo's of another state less than this (the check
sees a pose that is off)."""
SIZE = (640, 480)


def _state(page) -> dict:
    return page.evaluate("window.lynxsimReplay.state()")


def _seek(page, t: float) -> dict:
    return page.evaluate(f"window.lynxsimReplay.seek({t!r})")


def _point_error(run: ReplayRun, state: dict, step: int) -> float:
    """Largest distance of a drawn point from the log's pose at ``step`` [m] (pose error bound)."""
    names = tuple(b["name"] for b in state["bodies"])
    pos_true, quat_true = true_body_poses(run.model, run.log.qpos[step], names)
    pos = np.array([b["pos"] for b in state["bodies"]])
    quat = np.array([b["quat"] for b in state["bodies"]])
    parts = scene_parts(run.model)
    assert parts.body_names == names
    return float(point_error_bound(pos_true, quat_true, pos, quat, parts.reach_m).max())


@pytest.mark.parametrize("which", ["planned_run", "rrr_run", "colliding_run"])
def test_page_loads_offline_with_no_console_error_and_no_request(browser, request, which):
    run = request.getfixturevalue(which)
    page, log = browser.open(run.page.as_uri())
    state = _state(page)
    assert state["draws"] >= 1
    assert page.locator("#view-error").inner_text() == ""
    assert page.locator("table.verdicts tr").count() >= 8
    log.assert_clean()
    page.close()


@pytest.mark.parametrize("which", ["planned_run", "rrr_run"])
def test_body_poses_read_back_from_the_page_equal_the_log(browser, request, which):
    run = request.getfixturevalue(which)
    page, log = browser.open(run.page.as_uri())
    steps = run.log.steps
    for step in (steps // 5, steps // 2 + 1, (4 * steps) // 5 + 3):  # on and between frames
        state = _seek(page, float(run.log.time_s[step]))
        assert state["time_s"] == pytest.approx(run.log.time_s[step], abs=1e-12)
        error = _point_error(run, state, step)
        assert error <= POSE_TOL_M
        assert error <= run.data.pose_error_m + 1e-9  # within what the page states
    log.assert_clean()
    page.close()


def _egl_mask(model: mujoco.MjModel, qpos: np.ndarray, camera: str) -> np.ndarray:
    """MuJoCo's silhouette of the bodies not welded to the world: (H, W) bool."""
    data = mujoco.MjData(model)
    data.qpos[:] = qpos
    mujoco.mj_forward(model, data)
    with mujoco.Renderer(model, SIZE[1], SIZE[0]) as renderer:
        renderer.enable_segmentation_rendering()
        renderer.update_scene(data, camera=camera)
        seg = renderer.render()
    objid, objtype = seg[..., 0], seg[..., 1]
    weld = np.asarray(model.body_weldid)
    out = np.zeros(objid.shape, dtype=bool)
    for kind, bodies in (
        (mujoco.mjtObj.mjOBJ_GEOM, model.geom_bodyid),
        (mujoco.mjtObj.mjOBJ_SITE, model.site_bodyid),
    ):
        mine = (objtype == int(kind)) & (objid >= 0)
        out[mine] = weld[np.asarray(bodies)[objid[mine]]] != 0
    return out


def _iou(a: np.ndarray, b: np.ndarray) -> float:
    return float((a & b).sum() / (a | b).sum())


@pytest.mark.parametrize("which", ["planned_run", "rrr_run"])
def test_a_frame_shows_the_moving_bodies_where_mujoco_draws_them(browser, request, which):
    run = request.getfixturevalue(which)
    step, other = run.log.steps // 3, (5 * run.log.steps) // 6
    t = float(run.log.time_s[step])
    url = f"{run.page.as_uri()}#camera={run.camera}&size={SIZE[0]}x{SIZE[1]}&mask=moving&t={t!r}"
    page, log = browser.open(url)
    png = page.screenshot(clip={"x": 0, "y": 0, "width": SIZE[0], "height": SIZE[1]})
    shot = iio.imread(io.BytesIO(png))[..., :3].mean(axis=2) > 127
    egl = _egl_mask(run.model, run.log.qpos[step], run.camera)
    assert egl.sum() > 500  # the robot is in the picture
    assert _iou(shot, egl) >= SILHOUETTE_IOU
    assert _iou(shot, _egl_mask(run.model, run.log.qpos[other], run.camera)) < OTHER_STATE_IOU
    log.assert_clean()
    page.close()


def test_the_slider_reaches_the_last_frame_and_play_stops_there(browser, planned_run):
    page, log = browser.open(planned_run.page.as_uri())
    data = planned_run.data
    slider = page.locator("#time")
    slider.focus()
    page.keyboard.press("End")
    state = _state(page)
    assert state["frame"] == data.frames - 1
    assert state["time_s"] == pytest.approx(float(data.time_s[-1]), abs=1e-12)
    assert f"frame {data.frames} of {data.frames}" in page.locator("#clock").inner_text()
    page.keyboard.press("Home")
    assert _state(page)["frame"] == 0
    _seek(page, float(data.time_s[-1]) - 0.2)
    page.select_option("#speed", "2")
    page.click("#play")
    deadline = time.monotonic() + 10.0  # 0.2 s at twice real time, on a slow machine
    while _state(page)["playing"]:
        assert time.monotonic() < deadline
        page.wait_for_timeout(50)  # the page's CSP refuses wait_for_function's eval
    assert _state(page)["frame"] == data.frames - 1
    log.assert_clean()
    page.close()


def test_contacts_are_painted_while_they_last(browser, colliding_run):
    data = colliding_run.data
    obstacle = data.contacts.kind == 0
    assert obstacle.any()
    first = float(data.contacts.start_s[obstacle].min())
    page, log = browser.open(colliding_run.page.as_uri())
    assert _seek(page, float(data.time_s[0]))["painted"] == []
    painted = _seek(page, first + 0.05)["painted"]
    assert "cylinder" in painted
    assert len(painted) >= 2  # the arm's geoms that touch it, too
    log.assert_clean()
    page.close()


def test_the_camera_turns_when_the_view_is_dragged(browser, planned_run):
    page, log = browser.open(planned_run.page.as_uri())
    box = page.locator("#view").bounding_box()
    before = page.locator("#view").screenshot()
    page.mouse.move(box["x"] + 200, box["y"] + 200)
    page.mouse.down()
    page.mouse.move(box["x"] + 320, box["y"] + 240, steps=5)
    page.mouse.up()
    assert _state(page)["camera"] == "orbit"
    assert page.locator("#view").screenshot() != before
    log.assert_clean()
    page.close()


HOSTILE = '</script><img src="x" onerror="console.error(1)"><!-- & "quotes"'


def test_hostile_names_show_as_text_and_load_nothing(browser, planned_run, tmp_path):
    data = planned_run.data
    names = (HOSTILE, *data.geoms.names[1:])
    geoms = dataclasses.replace(data.geoms, names=names)
    report = json.loads(data.report_json)
    report["task"] = HOSTILE
    hostile = dataclasses.replace(
        data,
        title=HOSTILE,
        geoms=geoms,
        report_json=json.dumps(report, sort_keys=True, separators=(",", ":")),
    )
    page_path = write_replay_page(hostile, tmp_path / "hostile.html")
    page, log = browser.open(page_path.as_uri())
    assert page.locator("h1").inner_text() == HOSTILE
    assert page.locator("img").count() == 0
    assert HOSTILE in page.locator("table.verdicts").inner_text()
    log.assert_clean()
    page.close()
