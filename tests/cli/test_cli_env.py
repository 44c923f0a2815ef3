"""``lynxsim env`` and the recording helper: summary lines, MP4 output, one-line errors."""

from __future__ import annotations

import os
import subprocess
import sys

import imageio.v2 as imageio
import pytest

from lynxsim.cli import main
from lynxsim.envs import record_expert_episode

RENDER_STD_MIN = 5.0


@pytest.mark.slow
def test_env_command_reports_success_return_and_collisions(capsys, tmp_path):
    video = tmp_path / "expert.mp4"
    argv = ["env", "--policy", "expert", "--episodes", "2", "--seed", "3", "--quiet"]
    assert main([*argv, "--video", str(video)]) == 0
    out = capsys.readouterr().out
    assert "LynxPickAndPlace-v1, expert policy, 2 episodes (seeds 3..4)" in out
    assert "success rate     100.0%" in out
    assert "collisions       0 episodes, 0 steps" in out
    reader = imageio.get_reader(video)
    assert reader.get_meta_data()["fps"] == 25
    frames = [f for _, f in zip(range(3), reader)]
    assert frames[0].shape == (480, 640, 3)
    assert frames[-1].std() > RENDER_STD_MIN


def test_env_command_runs_a_random_policy_on_reach(capsys):
    argv = ["env", "--policy", "random", "--env", "LynxReach-v1", "--episodes", "2", "--quiet"]
    assert main(argv) == 0
    assert "LynxReach-v1, random policy, 2 episodes" in capsys.readouterr().out


def test_env_command_errors_are_one_line(capsys):
    with pytest.raises(SystemExit) as info:
        main(["env", "--episodes", "0", "--quiet"])
    assert info.value.code == 2
    assert capsys.readouterr().err.strip() == (
        "lynxsim env: error: argument --episodes: must be between 1 and 1,000,000, got 0"
    )


def test_record_expert_episode_writes_an_mp4_and_returns_its_stats(tmp_path):
    dest = tmp_path / "episode.mp4"
    stats = record_expert_episode(dest, seed=1, width=320, height=240)
    assert stats.success
    assert not stats.collided
    assert stats.steps == 200
    assert stats.frames == stats.steps + 1
    assert imageio.get_reader(dest).count_frames() == stats.frames


def test_env_command_with_random_obstacles_and_action_noise(capsys):
    argv = ["env", "--episodes", "3", "--seed", "5", "--quiet", "--random-obstacles", "1-3"]
    assert main([*argv, "--action-noise", "0.05"]) == 0
    out = capsys.readouterr().out
    assert (
        "LynxPickAndPlace-v1, expert policy, 3 episodes (seeds 5..7), "
        "1-3 random obstacles per episode, action noise 0.05"
    ) in out
    assert "collisions       0 episodes" in out


def test_randomize_obstacles_is_one_to_three_random_obstacles(capsys):
    argv = ["env", "--episodes", "2", "--seed", "3", "--quiet", "--action-noise", "0.1"]
    assert main([*argv, "--random-obstacles", "1-3"]) == 0
    spelled_out = capsys.readouterr().out
    assert main([*argv, "--randomize-obstacles"]) == 0
    assert capsys.readouterr().out == spelled_out
    assert "1-3 random obstacles per episode, action noise 0.1" in spelled_out


@pytest.mark.parametrize(
    ("flags", "message"),
    [
        (["--action-noise", "1.5"], "argument --action-noise: must be between 0 and 1, got 1.5"),
        (["--action-noise", "nan"], "argument --action-noise"),
        (["--random-obstacles", "5"], "argument --random-obstacles: must be between 0 and 4"),
        (["--random-obstacles=-1"], "argument --random-obstacles: must be between 0 and 4, got -1"),
        (["--random-obstacles", "3-1"], "must be N or LO-HI with LO <= HI, got 3-1"),
        (["--random-obstacles", "1-"], "argument --random-obstacles: must be an integer"),
        (["--random-obstacles", "2", "--no-obstacle"], "not allowed with argument"),
        (["--randomize-obstacles", "--no-obstacle"], "not allowed with argument"),
    ],
)
def test_env_scene_and_noise_flags_refuse_bad_values(capsys, flags, message):
    with pytest.raises(SystemExit) as info:
        main(["env", "--episodes", "1", "--quiet", *flags])
    assert info.value.code == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err
    assert message in err


@pytest.mark.parametrize("command", ["env", "dataset"])
def test_an_older_env_version_is_not_a_warning_on_stderr(tmp_path, command):
    # The commands default to the -v1 envs; Gymnasium's note that a -v2 exists is not for
    # the command line's stderr, whose errors are one line.
    argv = ["env", "--episodes", "1", "--quiet", "--video", str(tmp_path / "x.avi")]
    if command == "dataset":
        argv = ["dataset", "--episodes", "1", "--quiet", "--out-dir", str(tmp_path / "d")]
    proc = subprocess.run(
        [sys.executable, "-m", "lynxsim", *argv],
        capture_output=True,
        text=True,
        timeout=300,
        env={**os.environ, "MUJOCO_GL": "egl"},
    )
    assert "Warning" not in proc.stderr, proc.stderr
    assert len(proc.stderr.splitlines()) <= 1, proc.stderr
