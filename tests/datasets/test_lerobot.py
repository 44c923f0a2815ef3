"""LeRobot v3.0 datasets: LeRobot's documented layout, the env's data read back, refused inputs."""

from __future__ import annotations

import json
import os
import subprocess
import sys

import numpy as np
import pytest

from lynxsim.datasets import MissingExtraError, read_npz, write_dataset
from lynxsim.envs.registration import make_env
from lynxsim.errors import InvalidInputError, InvalidTypeError, LynxsimError
from tests.datasets.conftest import NOISE, SEED, record
from tests.helpers import full_disk

pytest.importorskip("pyarrow")  # the extra lynxsim[datasets] (CI installs it)

from lynxsim.datasets.lerobot_check import check_lerobot, read_lerobot
from tests.datasets.lerobot_schema import validate


def _tree(root):
    return sorted(str(p.relative_to(root)) for p in root.rglob("*"))


SCHEMA_EPISODES = 50
"""Episodes of the state-only dataset checked against the layout (the issue's acceptance size)."""
VIDEO_EPISODES = 4
"""Episodes of the dataset with videos (rendering costs ~10 ms a step here: 50 take ~100 s)."""
IMAGE_SIZE = 32
"""Side of its cameras' images [px]."""
VIDEO_PSNR_DB = 30.0
"""Least peak signal-to-noise ratio of a decoded video frame against the env's pixels."""


def _twins(factory: pytest.TempPathFactory, **kwargs: object):
    lerobot = record(factory.mktemp("lerobot"), "lerobot", **kwargs)
    npz = record(factory.mktemp("npz"), "npz", **kwargs)
    return lerobot, read_npz(npz.path)


@pytest.fixture(scope="module")
def fifty(tmp_path_factory: pytest.TempPathFactory):
    """50 pick-and-place episodes (state only) in LeRobot's format, and the same in NPZ."""
    return _twins(tmp_path_factory, episodes=SCHEMA_EPISODES)


@pytest.fixture(scope="module")
def clips(tmp_path_factory: pytest.TempPathFactory):
    """4 episodes with the front and top cameras as videos, and the same in NPZ."""
    images = {"images": ("front", "top"), "image_size": IMAGE_SIZE}
    return _twins(tmp_path_factory, episodes=VIDEO_EPISODES, **images)


@pytest.fixture(params=["fifty", "clips"])
def dataset(request: pytest.FixtureRequest):
    """Each of the two."""
    return request.getfixturevalue(request.param)


def test_a_fifty_episode_dataset_has_lerobots_documented_layout(fifty):
    summary, episodes = fifty
    dataset = validate(summary.path)
    assert dataset.info["total_episodes"] == SCHEMA_EPISODES == summary.episodes
    assert dataset.info["total_frames"] == sum(e.steps for e in episodes) == summary.steps
    assert dataset.info["fps"] == make_env("LynxPickAndPlace-v1").metadata["render_fps"]
    assert dataset.info["video_path"] is None
    assert sorted(p.name for p in (summary.path / "meta").iterdir()) == [
        "episodes",
        "info.json",
        "lynxsim.json",
        "stats.json",
        "tasks.parquet",
    ]


def test_a_dataset_with_videos_has_lerobots_documented_layout(clips):
    summary, episodes = clips
    dataset = validate(summary.path)
    assert dataset.info["total_frames"] == sum(e.steps for e in episodes)
    for camera in ("front", "top"):
        video = dataset.info["features"][f"observation.images.{camera}"]
        assert video["dtype"] == "video"
        assert video["shape"] == [IMAGE_SIZE, IMAGE_SIZE, 3]
        assert (
            summary.path / f"videos/observation.images.{camera}/chunk-000/file-000.mp4"
        ).is_file()


def test_the_frames_are_the_envs_steps(dataset):
    summary, episodes = dataset
    data = read_lerobot(summary.path)
    f = data.frames
    start = 0
    for i, e in enumerate(episodes):
        rows = slice(start, start + e.steps)
        start += e.steps
        obs = e.observations
        np.testing.assert_array_equal(
            f["observation.state"][rows], obs["observation"][:-1].astype(np.float32)
        )
        goals = np.concatenate([obs["achieved_goal"], obs["desired_goal"]], axis=1)[:-1]
        np.testing.assert_array_equal(
            f["observation.environment_state"][rows], goals.astype(np.float32)
        )
        np.testing.assert_array_equal(f["action"][rows], e.actions)
        np.testing.assert_array_equal(f["expert_action"][rows], e.infos["expert_action"][1:])
        np.testing.assert_array_equal(f["next.reward"][rows], e.rewards.astype(np.float32))
        np.testing.assert_array_equal(f["next.done"][rows], e.terminations | e.truncations)
        np.testing.assert_array_equal(f["next.terminated"][rows], e.terminations)
        np.testing.assert_array_equal(f["next.success"][rows], e.infos["is_success"][1:])
        np.testing.assert_array_equal(f["next.collision"][rows], e.infos["collision"][1:])
        assert (f["episode_index"][rows] == i).all()
    assert data.episodes["length"] == [e.steps for e in episodes]
    metadata = json.loads((summary.path / "meta/lynxsim.json").read_text())
    assert metadata["format"] == "lerobot"
    assert metadata["first_seed"] == SEED
    assert metadata["action_noise"] == NOISE
    assert metadata["total_episodes"] == len(episodes)


def _psnr_db(a: np.ndarray, b: np.ndarray) -> float:
    mse = np.mean((a.astype(np.float64) - b.astype(np.float64)) ** 2)
    return float(10 * np.log10(255.0**2 / mse)) if mse else np.inf


@pytest.mark.parametrize(("k", "camera"), [(0, "front"), (1, "top")])
def test_the_video_frames_are_the_envs_pixels_at_their_own_size(clips, k, camera):
    import imageio_ffmpeg

    summary, episodes = clips
    path = summary.path / f"videos/observation.images.{camera}/chunk-000/file-000.mp4"
    reader = imageio_ffmpeg.read_frames(str(path))
    assert tuple(next(reader)["size"]) == (IMAGE_SIZE, IMAGE_SIZE)
    pixels = np.concatenate(
        [e.observations["pixels"][:-1, :, :, 3 * k : 3 * k + 3] for e in episodes]
    )
    count = 0
    for expected, raw in zip(pixels, reader, strict=True):
        frame = np.frombuffer(raw, np.uint8).reshape(IMAGE_SIZE, IMAGE_SIZE, 3)
        assert _psnr_db(frame, expected) >= VIDEO_PSNR_DB
        count += 1
    assert count == sum(e.steps for e in episodes)


def test_regenerating_with_images_gives_byte_identical_files_without_videos_too(tmp_path):
    def files(root):
        return {
            str(p.relative_to(root)): p.read_bytes() for p in sorted(root.rglob("*")) if p.is_file()
        }

    kwargs = {"episodes": 2, "images": ("front", "top"), "image_size": 17, "videos": False}
    a = record(tmp_path / "a", "lerobot", **kwargs)
    b = record(tmp_path / "b", "lerobot", **kwargs)
    assert files(a.path) == files(b.path)
    assert not (a.path / "videos").exists()


def test_without_videos_the_images_are_the_envs_pixels_in_png(tmp_path):
    import imageio.v3 as iio

    kwargs = {"episodes": 2, "images": ("front", "top"), "image_size": 17, "videos": False}
    summary = record(tmp_path / "l", "lerobot", **kwargs)
    dataset = validate(summary.path)
    assert dataset.info["video_path"] is None
    (episode, _) = read_npz(record(tmp_path / "n", "npz", **kwargs).path)
    data = read_lerobot(summary.path)
    for k, camera in enumerate(("front", "top")):
        key = f"observation.images.{camera}"
        assert dataset.info["features"][key]["dtype"] == "image"
        decoded = np.stack([iio.imread(b, extension=".png") for b in data.frames[key]])
        expected = episode.observations["pixels"][:-1, :, :, 3 * k : 3 * k + 3]
        np.testing.assert_array_equal(decoded[: episode.steps], expected)


def test_a_reach_dataset_has_its_own_features(tmp_path):
    summary = write_dataset(tmp_path, 2, env_id="LynxReach-v1", format="lerobot")
    dataset = validate(summary.path)
    features = dataset.info["features"]
    assert features["action"]["shape"] == [4]
    assert dataset.info["video_path"] is None
    assert dataset.info["total_frames"] == 200


def test_images_of_an_odd_size_make_videos_of_their_size(tmp_path):
    summary = record(tmp_path, "lerobot", episodes=1, images=("front",), image_size=17)
    dataset = validate(summary.path)  # decodes the video: 17 x 17, every frame
    assert dataset.info["features"]["observation.images.front"]["shape"] == [17, 17, 3]
    assert dataset.info["features"]["observation.images.front"]["info"]["video.pix_fmt"] == (
        "yuv444p"
    )


@pytest.mark.parametrize("interrupt", [KeyboardInterrupt, RuntimeError], ids=["ctrl-c", "error"])
def test_an_interrupt_while_videos_are_encoded_leaves_no_dataset(tmp_path, interrupt):
    def stop_at_the_second(episode):
        if episode.seed == SEED + 1:
            raise interrupt

    with pytest.raises(interrupt):
        record(
            tmp_path, "lerobot", episodes=3, images=("front",), image_size=16,
            on_episode=stop_at_the_second,
        )  # fmt: skip
    assert _tree(tmp_path) == []  # no hidden .tmp, and no folder made for it, left


def test_videos_must_be_a_bool(tmp_path):
    with pytest.raises(InvalidTypeError, match=r"videos must be True or False, got 'no'"):
        record(tmp_path, "lerobot", episodes=1, videos="no")
    assert list(tmp_path.iterdir()) == []


def test_lerobot_without_pyarrow_is_a_clear_error_and_writes_nothing(tmp_path, monkeypatch):
    monkeypatch.setitem(sys.modules, "pyarrow", None)  # what an install without the extra gives
    with pytest.raises(MissingExtraError, match=r"LeRobot format .* pip install 'lynxsim\[datas"):
        record(tmp_path, "lerobot", episodes=1)
    assert list(tmp_path.iterdir()) == []


def test_reading_what_is_not_a_lerobot_dataset_is_a_typed_error(tmp_path):
    with pytest.raises(InvalidInputError, match=r"is not a LeRobot v3\.0 dataset"):
        read_lerobot(tmp_path)


def test_the_check_finds_a_truncated_video_and_a_missing_episode(tmp_path):
    summary = record(tmp_path, "lerobot", episodes=2, images=("front",), image_size=16)
    video = next(summary.path.rglob("*.mp4"))
    video.write_bytes(video.read_bytes()[: video.stat().st_size // 2])
    with pytest.raises(LynxsimError, match=r"does not decode|decodes to"):
        check_lerobot(summary.path)
    info_path = summary.path / "meta/info.json"
    info = json.loads(info_path.read_text())
    info["total_episodes"] = 3
    info_path.write_text(json.dumps(info))
    video.unlink()
    with pytest.raises(LynxsimError, match=r"against info\.json"):
        check_lerobot(summary.path)


@pytest.mark.parametrize(
    ("argv", "limit_bytes"),
    [  # state only: tests/datasets/test_full_disk.py
        (["--images", "--image-size", "32"], 20_000),  # the video (ffmpeg inherits the limit)
        (["--images", "--image-size", "32", "--no-videos"], 20_000),  # PNG in the data file
    ],
    ids=["video", "png"],
)
def test_a_full_disk_with_images_is_one_line_and_leaves_no_dataset(tmp_path, argv, limit_bytes):
    cmd = [sys.executable, "-m", "lynxsim", "dataset", "--format", "lerobot", "--episodes", "3"]
    proc = subprocess.run(
        [*cmd, *argv, "--out-dir", str(tmp_path), "--quiet"],
        capture_output=True,
        text=True,
        preexec_fn=full_disk(limit_bytes),
        timeout=300,
        env={**os.environ, "MUJOCO_GL": "egl"},
    )
    assert proc.returncode == 1, proc.stderr
    assert proc.stderr.count("\n") == 1, proc.stderr
    assert proc.stderr.startswith("lynxsim: error: "), proc.stderr
    assert _tree(tmp_path) == []  # no hidden .tmp, and no folder made for it, left


def test_the_printed_command_names_the_loading_script(tmp_path):
    cmd = [sys.executable, "-m", "lynxsim", "dataset", "--format", "lerobot", "--episodes", "1"]
    proc = subprocess.run(
        [*cmd, "--out-dir", str(tmp_path), "--quiet"],
        capture_output=True,
        text=True,
        check=True,
        env={**os.environ, "MUJOCO_GL": "egl"},
    )
    folder = tmp_path / "lynxsim/pick-and-place-v1/expert-v0"
    lines = proc.stdout.splitlines()
    assert lines[0] == f"{folder} (lerobot, dataset id lynxsim/pick-and-place-v1/expert-v0)"
    assert (
        lines[3] == f"  load with        python examples/load_lerobot.py {folder}  (needs lerobot)"
    )
    validate(folder)


@pytest.mark.parametrize(
    ("file_bytes", "raw_video_bytes", "files"),
    [
        (20_000, 10**9, [(0, 0), (0, 1), (1, 0), (1, 1), (2, 0)]),  # data files of one episode
        (10**9, 160_000, [(0, 0), (0, 0), (0, 1), (0, 1), (1, 0)]),  # videos of two
    ],
    ids=["data-limit", "video-limit"],
)
def test_files_and_chunks_roll_over_at_the_limits(tmp_path, file_bytes, raw_video_bytes, files):
    from dataclasses import replace

    from lynxsim.datasets import action_noise_std, noise_generator, record_episode
    from lynxsim.datasets.lerobot_meta import LeRobotLayout
    from lynxsim.datasets.lerobot_writer import LeRobotWriter
    from lynxsim.envs.evaluation import make_policy

    env = make_env("LynxReach-v1", pixels=("front",), pixel_width=16, pixel_height=16)
    layout = replace(
        LeRobotLayout.of_env(env, videos=True),
        chunks_size=2,
        file_bytes=file_bytes,
        raw_video_bytes=raw_video_bytes,
    )
    policy, std = make_policy("expert", env), action_noise_std(env.action_space, NOISE)
    folder = tmp_path / "dataset"
    folder.mkdir()
    with LeRobotWriter(folder, layout) as writer:
        for seed in range(SEED, SEED + len(files)):
            writer.add(record_episode(env, policy, seed, std, noise_generator(seed)))
        writer.finish({"first_seed": SEED})
    env.close()
    dataset = validate(folder)  # every file, index, video time and frame count
    e = {k: dataset.episodes.column(k).to_pylist() for k in dataset.episodes.column_names}
    key = "videos/observation.images.front"
    assert list(zip(e["data/chunk_index"], e["data/file_index"], strict=True)) == files
    assert list(zip(e[f"{key}/chunk_index"], e[f"{key}/file_index"], strict=True)) == files
    assert dataset.info["chunks_size"] == 2
    meta_files = sorted((folder / "meta/episodes").rglob("*.parquet"))
    assert (len(meta_files) > 1) == (file_bytes < 10**9)  # a row's stats take ~10 kB
