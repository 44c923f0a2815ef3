"""``lynxsim env`` and the recording helper: summary lines, MP4 output, one-line errors."""

from __future__ import annotations

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
    assert "LynxPickAndPlace-v0, expert policy, 2 episodes (seeds 3..4)" in out
    assert "success rate     100.0%" in out
    assert "collisions       0 episodes, 0 steps" in out
    reader = imageio.get_reader(video)
    assert reader.get_meta_data()["fps"] == 25
    frames = [f for _, f in zip(range(3), reader)]
    assert frames[0].shape == (480, 640, 3)
    assert frames[-1].std() > RENDER_STD_MIN


def test_env_command_runs_a_random_policy_on_reach(capsys):
    argv = ["env", "--policy", "random", "--env", "LynxReach-v0", "--episodes", "2", "--quiet"]
    assert main(argv) == 0
    assert "LynxReach-v0, random policy, 2 episodes" in capsys.readouterr().out


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
