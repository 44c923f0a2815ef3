"""Off-screen rendering and MP4 output, checked by decoding the files."""

from __future__ import annotations

import math
import threading

import imageio.v2 as imageio
import mujoco
import numpy as np
import pytest

from lynxsim.arm.motion import ArmPose, generate
from lynxsim.errors import InvalidInputError
from lynxsim.sim.arm.model import VISUAL_GROUP, load_arm_scene
from lynxsim.sim.arm.task import run_arm_trajectory
from lynxsim.sim.render import (
    TRACE_TOLERANCE_M,
    Overlay,
    PathTrace,
    Quality,
    RenderSettings,
    SceneRenderer,
    simplify_polyline,
)
from lynxsim.sim.video import decoded_frames, mp4_writer

FAST = RenderSettings(quality=Quality.FAST)
CHANGED_PX = 30
"""A pixel differs when its RGB values differ by more than this in sum."""


def _distance_to_polyline(points, polyline):
    """Distance of each point (N, 3) to the nearest segment of a polyline (K, 3) [m]."""
    a, b = polyline[:-1], polyline[1:]
    ab = b - a
    rel = points[:, None, :] - a[None]
    length2 = np.maximum((ab * ab).sum(-1), 1e-30)
    t = np.clip((rel * ab[None]).sum(-1) / length2, 0.0, 1.0)
    return np.linalg.norm(rel - t[..., None] * ab[None], axis=-1).min(axis=1)


@pytest.mark.parametrize("seed", range(5), ids=lambda s: f"seed{s}")
def test_simplified_polyline_stays_within_tolerance_and_keeps_its_ends(seed):
    rng = np.random.default_rng(seed)
    points = np.cumsum(rng.normal(scale=1e-3, size=(2000, 3)), axis=0)  # a random walk [m]
    kept = simplify_polyline(points, TRACE_TOLERANCE_M)
    assert kept[0] == 0
    assert kept[-1] == len(points) - 1
    assert (np.diff(kept) > 0).all()
    assert len(kept) < len(points)
    assert _distance_to_polyline(points, points[kept]).max() <= TRACE_TOLERANCE_M


def test_a_straight_path_needs_its_two_ends_only():
    line = np.linspace([0.0, 0.0, 0.0], [0.3, 0.1, 0.2], 500)
    assert simplify_polyline(line, TRACE_TOLERANCE_M).tolist() == [0, 499]
    assert simplify_polyline(line[:1], TRACE_TOLERANCE_M).tolist() == [0]
    assert simplify_polyline(np.zeros((0, 3)), TRACE_TOLERANCE_M).tolist() == []


@pytest.mark.parametrize("tolerance", [-1e-3, math.nan, math.inf], ids=["negative", "nan", "inf"])
def test_simplify_refuses_a_bad_tolerance(tolerance):
    with pytest.raises(InvalidInputError, match="tolerance_m must be finite and >= 0, got"):
        simplify_polyline(np.zeros((3, 3)), tolerance)


def test_trace_ends_at_the_current_step():
    t = np.linspace(0.0, 2.0 * np.pi, 1000)
    trace = PathTrace.of(np.stack([0.2 * np.cos(t), 0.2 * np.sin(t), 0.1 + 0 * t], axis=1))
    for step in (0, 1, 137, 999):
        drawn = trace.until(step)
        np.testing.assert_array_equal(drawn[0], trace.points[0])
        np.testing.assert_array_equal(drawn[-1], trace.points[step])
        if step > 0:
            gap = _distance_to_polyline(trace.points[: step + 1], drawn)
            assert gap.max() <= 2 * TRACE_TOLERANCE_M


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


def test_render_into_a_given_buffer_returns_it_with_the_same_frame():
    model = load_arm_scene()
    data = mujoco.MjData(model)
    mujoco.mj_resetDataKeyframe(model, data, 0)
    mujoco.mj_forward(model, data)
    buffer = np.zeros((FAST.height, FAST.width, 3), dtype=np.uint8)
    with SceneRenderer(model, FAST) as renderer:
        renderer.render(data)  # the first frame of a context differs by a level or two
        fresh = renderer.render(data)
        assert renderer.render(data, out=buffer) is buffer
    np.testing.assert_array_equal(buffer, fresh)


def test_the_trace_looks_like_the_path_through_every_step():
    model = load_arm_scene()
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    t = np.linspace(0.0, 1.5 * np.pi, 600)  # every step drawn (no more than the cap)
    path = np.stack([0.15 + 0.1 * np.cos(t), 0.1 * np.sin(t), 0.25 + 0.05 * t], axis=1)
    trace = PathTrace.of(path)
    assert len(trace.kept) < 100
    with SceneRenderer(model, FAST) as renderer:
        renderer.render(data)  # the first frame of a context differs by a level or two
        plain = renderer.render(data).astype(int)
        every = renderer.render(data, Overlay(path=path)).astype(int)
        traced = renderer.render(data, Overlay(path=trace.until(len(path) - 1))).astype(int)
    drawn = (np.abs(every - plain).sum(axis=-1) > CHANGED_PX).sum()
    differ = (np.abs(traced - every).sum(axis=-1) > CHANGED_PX).sum()
    assert drawn > 500
    assert differ < 0.1 * drawn  # line ends and joins


@pytest.mark.parametrize(
    ("quality", "multisampling", "shadows"),
    [
        (Quality.LEAN, False, False),
        (Quality.FAST, False, False),
        (Quality.MEDIUM, False, True),
        (Quality.DEFAULT, True, True),
    ],
    ids=lambda v: getattr(v, "value", str(v)),
)
def test_quality_presets_choose_shadows_and_multisampling(quality, multisampling, shadows):
    model = load_arm_scene()
    samples = int(model.vis.quality.offsamples)
    with SceneRenderer(model, RenderSettings(width=64, height=48, quality=quality)) as renderer:
        flags = renderer._renderer.scene.flags
        assert bool(flags[int(mujoco.mjtRndFlag.mjRND_SHADOW)]) is shadows
        assert not flags[int(mujoco.mjtRndFlag.mjRND_REFLECTION)]
        lean = quality is Quality.LEAN
        assert bool(flags[int(mujoco.mjtRndFlag.mjRND_SKYBOX)]) is not lean
        context = renderer._renderer._mjr_context
        assert int(context.offSamples) == (samples if multisampling else 0)
    assert int(model.vis.quality.offsamples) == samples  # the model's, put back
    assert int(model.vis.quality.numslices) == 28  # the model's, put back after the context


@pytest.mark.parametrize("quality", [Quality.LEAN, Quality.FAST], ids=lambda q: q.value)
def test_only_the_lean_preset_leaves_the_floor_undrawn(quality):
    model = load_arm_scene()
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    with SceneRenderer(model, RenderSettings(width=84, height=84, quality=quality)) as renderer:
        frame = renderer.render(data)
        scene = renderer._renderer.scene
        planes = [g for g in scene.geoms[: scene.ngeom] if g.type == mujoco.mjtGeom.mjGEOM_PLANE]
    assert len(planes) == (quality is not Quality.LEAN)
    assert frame.std() > 20.0  # the table and the arm are drawn either way


def test_a_fast_renderer_leaves_the_models_multisampling_to_later_renderers():
    model = load_arm_scene()
    samples = int(model.vis.quality.offsamples)
    assert samples > 0
    size = {"width": 64, "height": 48}
    with SceneRenderer(model, RenderSettings(quality=Quality.FAST, **size)):
        pass
    with SceneRenderer(model, RenderSettings(quality=Quality.DEFAULT, **size)) as renderer:
        assert int(renderer._renderer._mjr_context.offSamples) == samples


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


def test_frames_of_any_size_are_encoded_to_whole_macroblocks(tmp_path):
    dest = tmp_path / "odd.mp4"
    frames = np.random.default_rng(1).integers(0, 255, size=(5, 70, 100, 3), dtype=np.uint8)
    with mp4_writer(dest, 10.0) as sink:
        for frame in frames:
            sink.append_data(frame)
    assert decoded_frames(dest) == 5
    assert imageio.get_reader(dest).get_data(0).shape == (80, 112, 3)


@pytest.mark.parametrize(
    ("second", "message"),
    [
        (np.zeros((48, 64, 3), dtype=np.uint8), r"one size: \(64, 96, 3\), then \(48, 64, 3\)"),
        (np.zeros((64, 96, 3)), r"must be \(height, width, 3\) uint8, got \(64, 96, 3\) float64"),
        (np.zeros((64, 96), dtype=np.uint8), r"must be \(height, width, 3\) uint8, got \(64, 96\)"),
    ],
    ids=["size", "dtype", "channels"],
)
def test_a_bad_frame_is_refused_and_leaves_no_file(tmp_path, second, message):
    with pytest.raises(InvalidInputError, match=message):
        _write(tmp_path / "a.mp4", [np.zeros((64, 96, 3), dtype=np.uint8), second])
    assert list(tmp_path.iterdir()) == []


def _write(dest, frames, then=None):
    with mp4_writer(dest, 30.0) as sink:
        for frame in frames:
            sink.append_data(frame)
        if then is not None:
            raise then


def test_an_interrupt_stops_the_encoder_and_leaves_no_file(tmp_path):
    frames = [np.zeros((480, 640, 3), dtype=np.uint8)] * 20
    with pytest.raises(KeyboardInterrupt):
        _write(tmp_path / "a.mp4", frames, then=KeyboardInterrupt())
    assert list(tmp_path.iterdir()) == []
    assert "mp4-writer" not in [t.name for t in threading.enumerate()]


def test_frames_are_copied_so_the_caller_may_reuse_its_buffer(tmp_path):
    dest = tmp_path / "a.mp4"
    buffer = np.zeros((64, 96, 3), dtype=np.uint8)
    with mp4_writer(dest, 10.0) as sink:
        for value in (0, 255):
            buffer[:] = value
            sink.append_data(buffer)
    first, second = (f.astype(int).mean() for f in imageio.get_reader(dest))
    assert first < 5
    assert second > 250
