"""``lynxsim rrr``: handlers called through the real parser, so their exceptions show."""

from __future__ import annotations

import json

import pytest

from lynxsim.cli import build_parser
from lynxsim.errors import UnreachablePlatformPoseError


@pytest.fixture
def run(capsys):
    parser = build_parser()

    def _run(*argv):
        args = parser.parse_args(["rrr", *argv])
        code = args.handler(args)
        return code, capsys.readouterr().out

    return _run


def test_ik_prints_every_working_mode(run):
    code, out = run("ik", "200", "150", "0")
    assert code == 0
    lines = out.splitlines()
    assert lines[0].startswith("leg spans |P_i - B_i| [mm]: 121.93  207.88  163.22")
    rows = [line.split() for line in lines[2:]]
    assert [r[0] for r in rows] == [str(m) for m in range(8)]
    assert rows[0][1:5] == ["+++", "-5.41", "117.24", "-154.13"]
    assert rows[7][1:5] == ["---", "93.80", "-165.51", "-62.39"]


def test_ik_accepts_negative_angles_and_si(run):
    code, out = run("ik", "0.2", "0.15", "-0.2", "--si", "--json")
    data = json.loads(out)
    assert code == 0
    assert data["units"] == {"length": "m", "angle": "rad"}
    assert len(data["modes"]) == 8
    assert data["modes"][5]["elbow_signs"] == "-+-"


def test_unreachable_pose_names_the_leg_in_one_line(run):
    with pytest.raises(UnreachablePlatformPoseError, match="leg 1 cannot stretch") as info:
        run("ik", "300", "250", "-40")
    assert info.value.legs == (1,)
    assert "\n" not in str(info.value)


def test_non_finite_pose_is_a_usage_error(run, capsys):
    with pytest.raises(SystemExit) as info:
        run("ik", "nan", "150", "0")
    assert info.value.code == 2
    assert "argument X: must be a finite number, got 'nan'" in capsys.readouterr().err


def test_fk_lists_assembly_modes(run):
    code, out = run("fk", "93.80", "-165.51", "-62.39")
    assert code == 0
    assert out.startswith("2 assembly modes:")
    assert "200.0" in out
    assert "7 (---)" in out


def test_fk_without_solution_says_so(run):
    code, out = run("fk", "180", "0", "90")
    assert code == 0
    assert "no platform pose" in out


def test_workspace_writes_a_png(run, tmp_path):
    dest = tmp_path / "ws.png"
    code, out = run(
        "workspace",
        "--alpha",
        "0",
        "-20",
        "--resolution-mm",
        "8",
        "--out",
        str(dest),
        "--mode",
        "2",
    )
    assert code == 0
    assert dest.read_bytes()[:4] == b"\x89PNG"
    assert "alpha   +0.00 deg: reachable area" in out
    assert "alpha  -20.00 deg" in out


def test_workspace_rejects_a_bad_resolution(run, tmp_path, capsys):
    with pytest.raises(SystemExit) as info:
        run("workspace", "--resolution-mm", "0", "--out", str(tmp_path / "x.png"))
    assert info.value.code == 2
    assert "--resolution-mm: must be between 0.1 and 100 mm, got 0" in capsys.readouterr().err


def test_bad_mode_is_a_usage_error(run):
    with pytest.raises(SystemExit) as info:
        run("workspace", "--mode", "9")
    assert info.value.code == 2


def test_poses_prints_the_figure20_table(run, tmp_path):
    dest = tmp_path / "poses.png"
    code, out = run("poses", "--out", str(dest))
    assert code == 0
    assert "leg 1 fails" in out
    assert "-81.61 to +81.61 deg" in out
    assert dest.exists()
