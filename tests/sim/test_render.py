"""Off-screen rendering and MP4 output, checked by decoding the files."""

from __future__ import annotations

import math

import imageio.v2 as imageio
import mujoco
import numpy as np
import pytest

from lynxsim.errors import InvalidInputError
from lynxsim.sim.arm.model import VISUAL_GROUP, load_arm_scene
from lynxsim.sim.arm.task import run_arm_trajectory
from lynxsim.sim.render import Overlay, Quality, RenderSettings, SceneRenderer
from lynxsim.sim.video import mp4_writer
from lynxsim.traj import ArmPose, generate

FAST = RenderSettings(quality=Quality.FAST)


@pytest.fixture(scope="module")
def short_trajectory():
    poses = [ArmPose((0.0, -0.25, 0.3), 0.0), ArmPose((0.0, -0.3, 0.0), -math.pi / 2)]
    return generate("quintic", poses, 1.0)


def test_mp4_decodes_to_expected_frames_and_size(tmp_path, short_trajectory):
    dest = tmp_path / "clip.mp4"
    playback = run_arm_trajectory(short_trajectory, task="t", video=dest, render=FAST, settle_s=0.5)
    t_last = float(playback.log.time_s[-1])
    expected = math.floor(t_last * FAST.fps + 1e-6) + 1
    reader = imageio.get_reader(dest)
    frames = [f for f in reader]
    assert reader.get_meta_data()["fps"] == pytest.approx(FAST.fps)
    assert len(frames) == expected
    assert frames[0].shape == (FAST.height, FAST.width, 3)
    assert [p.name for p in tmp_path.iterdir()] == ["clip.mp4"]  # no temporary left


def test_frame_shows_the_arm():
    model = load_arm_scene()
    data = mujoco.MjData(model)
    mujoco.mj_resetDataKeyframe(model, data, 0)
    mujoco.mj_forward(model, data)
    with SceneRenderer(model, FAST) as renderer:
        with_arm = renderer.render(data).astype(int)
        renderer._option.geomgroup[VISUAL_GROUP] = 0  # hide the arm's visual geoms
        without_arm = renderer.render(data).astype(int)
    changed = np.abs(with_arm - without_arm).sum(axis=-1) > 30
    assert with_arm.std() > 10.0  # not a blank image
    assert changed.mean() > 0.01  # the arm covers a visible part of the frame


def test_overlay_marks_targets_and_path():
    model = load_arm_scene()
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    with SceneRenderer(model, FAST) as renderer:
        plain = renderer.render(data).astype(int)
        path = np.stack([np.linspace(0.1, 0.3, 50), np.zeros(50), np.full(50, 0.2)], axis=1)
        marked = renderer.render(data, Overlay(path=path, targets=path[[0, -1]])).astype(int)
    assert (np.abs(marked - plain).sum(axis=-1) > 30).sum() > 50


def test_renderer_refuses_unknown_camera_and_oversized_frames():
    model = load_arm_scene()
    with pytest.raises(
        InvalidInputError, match=r"no camera named 'side'; available: \['front', 'top'\]"
    ):
        SceneRenderer(model, RenderSettings(camera="side"))
    with pytest.raises(InvalidInputError, match="exceeds the model's off-screen buffer 1280x720"):
        SceneRenderer(model, RenderSettings(width=1920, height=1080))


def _write_then_fail(dest):
    with mp4_writer(dest, 30.0) as sink:
        sink.append_data(np.zeros((480, 640, 3), dtype=np.uint8))
        raise RuntimeError("boom")


def test_failed_video_leaves_no_file(tmp_path):
    with pytest.raises(RuntimeError, match="boom"):
        _write_then_fail(tmp_path / "broken.mp4")
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize(
    ("dest", "fps", "message"),
    [
        ("a.avi", 30.0, "must end in .mp4"),
        ("a.mp4", 0.0, "fps must be between 1 and 240 frames/s, got 0"),
    ],
    ids=["suffix", "fps"],
)
def test_video_writer_validates_arguments(tmp_path, dest, fps, message):
    with pytest.raises(InvalidInputError, match=message), mp4_writer(tmp_path / dest, fps):
        pass
