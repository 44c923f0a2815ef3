"""``lynxsim play --html`` and ``lynxsim view``: the acceptance command, and bad input."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import numpy as np
import pytest

from lynxsim.cli import main
from lynxsim.web.replay_file import read_replay_file
from tests.replay.conftest import TASKS

PAGE_LIMIT_BYTES = 3 * 2**20
"""The issue's bound on a replay page of a 6 s run."""


def _cli(capsys, *argv: str) -> tuple[int, str, str]:
    try:
        code = main(list(argv))
    except SystemExit as exc:
        code = exc.code if isinstance(exc.code, int) else -1
    out = capsys.readouterr()
    return code, out.out, out.err


@pytest.fixture(scope="module")
def played(tmp_path_factory) -> Path:
    """``lynxsim play tasks/three_obstacles.toml --type planned --html`` (fast video)."""
    out = tmp_path_factory.mktemp("play") / "three_obstacles_planned.mp4"
    argv = ["play", str(TASKS / "three_obstacles.toml"), "--type", "planned", "--html"]
    code = main([*argv, "--out", str(out), "--quality", "fast", "--quiet"])
    assert code == 0
    return out


def test_play_html_writes_the_page_and_its_data_beside_the_video_and_report(played):
    names = sorted(p.name for p in played.parent.iterdir())
    stem = played.stem
    assert names == [f"{stem}.html", f"{stem}.json", f"{stem}.mp4", f"{stem}.replay.npz"]
    assert played.with_suffix(".html").stat().st_size < PAGE_LIMIT_BYTES
    data = read_replay_file(played.with_suffix(".replay.npz"))
    report = json.loads(played.with_suffix(".json").read_text())
    assert json.loads(data.report_json) == report


def test_the_acceptance_page_opens_offline_and_shows_the_same_run(browser, played, planned_run):
    page, log = browser.open(played.with_suffix(".html").as_uri())
    mine, theirs = planned_run.data, read_replay_file(played.with_suffix(".replay.npz"))
    np.testing.assert_array_equal(mine.poses.pos_q, theirs.poses.pos_q)  # the run is the same
    np.testing.assert_array_equal(mine.poses.quat_q, theirs.poses.quat_q)
    state = page.evaluate(f"window.lynxsimReplay.seek({float(mine.time_s[100])!r})")
    assert state["frame"] == 100
    expected = mine.poses.positions()[100]
    np.testing.assert_allclose([b["pos"] for b in state["bodies"]], expected, atol=1e-12)
    log.assert_clean()
    page.close()


def test_view_remakes_the_same_page_from_the_report(played, tmp_path, capsys):
    for suffix in (".json", ".replay.npz"):
        shutil.copy(played.with_suffix(suffix), tmp_path / f"run{suffix}")
    code, out, err = _cli(capsys, "view", str(tmp_path / "run.json"))
    assert (code, err) == (0, "")
    assert out == f"replay: {tmp_path / 'run.html'}\n"
    assert (tmp_path / "run.html").read_bytes() == played.with_suffix(".html").read_bytes()
    code, out, err = _cli(
        capsys, "view", str(tmp_path / "run.json"), "--out", str(tmp_path / "b.html"), "--quiet"
    )
    assert (code, out, err) == (0, "", "")
    assert (tmp_path / "b.html").read_bytes() == played.with_suffix(".html").read_bytes()


def _one_line_error(capsys, *argv: str) -> str:
    code, out, err = _cli(capsys, *argv)
    assert code == 1, err
    assert out == ""
    assert err.startswith("lynxsim: error: "), err
    assert err.count("\n") == 1, err
    return err


def test_view_refuses_a_report_whose_data_is_missing_altered_or_another_runs(
    played, tmp_path, capsys
):
    report = tmp_path / "run.json"
    shutil.copy(played.with_suffix(".json"), report)
    err = _one_line_error(capsys, "view", str(report))
    assert "no replay data beside it" in err
    shutil.copy(played.with_suffix(".replay.npz"), tmp_path / "run.replay.npz")
    edited = json.loads(report.read_text())
    edited["tool_max_error_m"] = 0.0
    report.write_text(json.dumps(edited))
    err = _one_line_error(capsys, "view", str(report))
    assert (
        f"{tmp_path / 'run.replay.npz'}: meta.report_json: written with another run report" in err
    )
    del edited["healthy"]
    report.write_text(json.dumps(edited))
    assert f"{report}: healthy: missing" in _one_line_error(capsys, "view", str(report))
    report.write_text("{not json")
    assert f"{report}: not JSON" in _one_line_error(capsys, "view", str(report))
    (tmp_path / "run.replay.npz").write_bytes(b"PK\x03\x04 broken")
    shutil.copy(played.with_suffix(".json"), report)
    err = _one_line_error(capsys, "view", str(report))
    assert f"{tmp_path / 'run.replay.npz'}: not a readable replay file" in err
    assert not list(tmp_path.glob("*.html"))  # nothing written on any error
    assert "must be a run report .json" in _one_line_error(capsys, "view", str(tmp_path / "x.npz"))
    err = _one_line_error(capsys, "view", str(report), "--out", str(tmp_path / "x.txt"))
    assert "--out must name an .html file" in err
    folder = tmp_path / "page.html"
    folder.mkdir()
    err = _one_line_error(capsys, "view", str(report), "--out", str(folder))
    assert err == f"lynxsim: error: will not replace {folder}: it is a folder\n"
