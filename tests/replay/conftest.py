"""Fixtures of the replay tests: real runs with their replay files, and a real headless Chromium.

Runs are played once per session through the functions ``lynxsim play`` uses
(:func:`run_arm_trajectory`, :func:`run_rrr_path` with ``replay=``), and the
model of each is rebuilt the same way for checks against MuJoCo. The browser
is the system's Chromium (``apt-get install chromium``), driven by
Playwright; nothing is downloaded, and a page's requests other than
``file:`` ones are refused and recorded.
"""

from __future__ import annotations

import os

os.environ.setdefault("MUJOCO_GL", "egl")

from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path

import mujoco
import numpy as np
import pytest

from lynxsim.robots import motion
from lynxsim.robots.arm import ROBOT as ARM
from lynxsim.robots.rrr import path_from_task
from lynxsim.sim.arm.model import load_arm_scene
from lynxsim.sim.arm.task import run_arm_trajectory
from lynxsim.sim.render import RenderSettings
from lynxsim.sim.rrr.playback import start_model
from lynxsim.sim.rrr.task import DEFAULT_RRR_RENDER, run_rrr_path
from lynxsim.sim.stepping.log import PlaybackLog
from lynxsim.sim.summary import Playback
from lynxsim.tasks import load_task
from lynxsim.web.page import page_from_file
from lynxsim.web.replay_data import ReplayData
from lynxsim.web.replay_file import REPLAY_SUFFIX, read_replay_file

ROOT = Path(__file__).resolve().parents[2]
TASKS = ROOT / "tasks"
CHROMIUM = Path("/usr/bin/chromium")
CHROMIUM_FLAGS = [
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
]
"""The closed network refuses Chromium's background connections: they are switched off."""


@dataclass(frozen=True)
class ReplayRun:
    """A run played with its replay saved: model, report and log, replay data and page."""

    model: mujoco.MjModel
    playback: Playback
    replay_file: Path
    page: Path
    camera: str

    @property
    def log(self) -> PlaybackLog:
        return self.playback.log

    @property
    def data(self) -> ReplayData:
        return read_replay_file(self.replay_file)


def _arm_run(folder: Path, task_file: str, kind: str) -> ReplayRun:
    task = load_task(TASKS / task_file)
    trajectory = motion(ARM, task, kind)
    replay = folder / f"{task.name}_{kind}{REPLAY_SUFFIX}"
    playback = run_arm_trajectory(trajectory, task=task.name, scene=task.scene, replay=replay)
    page = page_from_file(replay, folder / f"{task.name}_{kind}.html")
    camera = RenderSettings().camera
    return ReplayRun(load_arm_scene(task.scene), playback, replay, page, camera)


@pytest.fixture(scope="session")
def planned_run(tmp_path_factory: pytest.TempPathFactory) -> ReplayRun:
    """The acceptance run: three obstacles, the planned motion (clear of them)."""
    return _arm_run(tmp_path_factory.mktemp("planned"), "three_obstacles.toml", "planned")


@pytest.fixture(scope="session")
def colliding_run(tmp_path_factory: pytest.TempPathFactory) -> ReplayRun:
    """The report's plain task: the hand hits the cylinder and stalls against it."""
    return _arm_run(tmp_path_factory.mktemp("colliding"), "pick_and_place.toml", "quintic")


@pytest.fixture(scope="session")
def rrr_run(tmp_path_factory: pytest.TempPathFactory) -> ReplayRun:
    """A 3-RRR run (closed loops, a free platform): 6 s of the report's closed curve."""
    folder = tmp_path_factory.mktemp("rrr")
    task = load_task(TASKS / "rrr_closed_curve.toml")
    path = path_from_task(task)
    replay = folder / f"{task.name}{REPLAY_SUFFIX}"
    playback = run_rrr_path(path, task=task.name, replay=replay)
    page = page_from_file(replay, folder / f"{task.name}.html")
    model, _ = start_model(path, 7)
    return ReplayRun(model, playback, replay, page, DEFAULT_RRR_RENDER.camera)


def true_body_poses(
    model: mujoco.MjModel, qpos: np.ndarray, names: tuple[str, ...]
) -> tuple[np.ndarray, np.ndarray]:
    """World positions (B, 3) [m] and quaternions (B, 4) of named bodies in state ``qpos``."""
    data = mujoco.MjData(model)
    data.qpos[:] = qpos
    mujoco.mj_kinematics(model, data)
    ids = [model.body(n).id for n in names]
    return np.array(data.xpos[ids]), np.array(data.xquat[ids])


# ---- the browser -------------------------------------------------------------------------


@dataclass
class PageLog:
    """What a page must not do: console errors, uncaught errors, failed or refused requests."""

    errors: list[str] = field(default_factory=list)
    failed: list[str] = field(default_factory=list)
    refused: list[str] = field(default_factory=list)

    def assert_clean(self) -> None:
        assert not self.errors, self.errors
        assert not self.failed, self.failed
        assert not self.refused, self.refused


class Browser:
    """Opens pages in one headless Chromium context, each with its :class:`PageLog`."""

    def __init__(self, context) -> None:
        self._context = context

    def open(self, url: str, width: int = 1300, height: int = 1000):
        page = self._context.new_page()
        page.set_viewport_size({"width": width, "height": height})
        log = PageLog()
        page.on("console", lambda m: log.errors.append(m.text) if m.type == "error" else None)
        page.on("pageerror", lambda e: log.errors.append(str(e)))
        page.on("requestfailed", lambda r: log.failed.append(f"{r.url}: {r.failure}"))

        def only_files(route) -> None:
            if route.request.url.startswith("file:"):
                route.continue_()
            else:
                log.refused.append(route.request.url)
                route.abort()

        page.route("**/*", only_files)
        page.goto(url, wait_until="load")
        return page, log


@pytest.fixture(scope="session")
def browser(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Browser]:
    """The system's headless Chromium, a fresh profile, no network but files."""
    if not CHROMIUM.is_file():
        pytest.fail(f"{CHROMIUM} is missing: apt-get install chromium (CI installs it)")
    from playwright.sync_api import sync_playwright

    with sync_playwright() as p:
        context = p.chromium.launch_persistent_context(
            str(tmp_path_factory.mktemp("chromium-profile")),
            executable_path=str(CHROMIUM),
            headless=True,
            args=CHROMIUM_FLAGS,
        )
        try:
            yield Browser(context)
        finally:
            context.close()
