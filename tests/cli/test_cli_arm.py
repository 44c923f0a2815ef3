"""The arm's command line: the report's numbers, JSON output and one-line errors."""

from __future__ import annotations

import json
import subprocess
import sys

import numpy as np
import pytest

from lynxsim.cli import main
from tests.helpers import assert_close


def test_ik_prints_report_joints(capsys):
    assert main(["ik", "142.83", "-16.56", "-62.05", "-47.80"]) == 0
    values = [float(v) for v in capsys.readouterr().out.split(":")[1].split()]
    assert_close(values[:4], [-6.61, 38.19, -144.24, 58.24], atol=0.02)


def test_fk_prints_report_pose(capsys):
    assert main(["fk", "-25.27", "100.5", "-41.19", "-13.62", "154.6"]) == 0
    first = capsys.readouterr().out.splitlines()[0].split()
    assert_close([float(first[i]) for i in (2, 4, 6)], [107.31, -50.66, 415.13], atol=0.005)
    assert float(first[9]) == pytest.approx(45.69, abs=0.005)


def test_fk_json_is_labelled_and_si_on_request(capsys):
    assert main(["fk", "0", "90", "0", "0", "0", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["units"] == {"length": "mm", "angle": "deg"}
    assert_close(out["tool_position"], [0.0, 0.0, 63 + 153 + 153 + 98], atol=1e-6)
    assert main(["fk", "0", str(np.pi / 2), "0", "0", "0", "--json", "--si"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["units"] == {"length": "m", "angle": "rad"}
    assert_close(out["tool_position"], [0.0, 0.0, 0.467], atol=1e-9)


def test_ik_json_lists_candidates(capsys):
    assert main(["ik", "0", "300", "0", "-90", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert len(out["candidates"]) == 4
    assert sum(c["valid"] for c in out["candidates"]) == 1
    assert_close(out["q"][:4], [90.0, 15.89, -18.47, -87.42], atol=0.01)


@pytest.mark.parametrize(
    ("argv", "code", "message"),
    [
        (["ik", "600", "0", "0", "0"], 1, "out of the arm's reach"),
        (["ik", "100", "0", "50", "90"], 1, "joint 4 out of range"),
        (["ik", "1", "2", "nan", "3"], 2, "argument Z: must be a finite number, got 'nan'"),
        (["fk", "0", "0", "inf", "0", "0"], 2, "argument Q3: must be a finite number"),
        (["ik", "1", "2"], 2, "required: Z, PITCH"),
        (["ik", "1", "2", "x", "3"], 2, "invalid float value: 'x'"),
        (["workspace", "--samples", "0"], 2, "must be between 1 and 10,000,000, got 0"),
    ],
    ids=["out-of-reach", "joint-range", "nan", "inf", "missing", "not-a-number", "no-samples"],
)
def test_bad_input_gives_one_line_and_nonzero_exit(cli, argv, code, message):
    result = cli(*argv)
    assert result.code == code
    assert result.err.count("\n") == 1, result.err
    assert message in result.err
    assert result.out == ""


def test_bad_input_from_the_shell_has_no_traceback():
    proc = subprocess.run(
        [sys.executable, "-m", "lynxsim", "fk", "1", "2"],
        capture_output=True,
        text=True,
        check=False,
    )
    assert proc.returncode == 2
    assert proc.stderr == "lynxsim fk: error: the following arguments are required: Q3, Q4, Q5\n"


def test_workspace_writes_png(tmp_path, capsys):
    dest = tmp_path / "ws.png"
    assert main(["workspace", "--out", str(dest), "--samples", "20000", "--quiet"]) == 0
    assert dest.read_bytes()[:4] == b"\x89PNG"
    assert "behind the base plane" in capsys.readouterr().out


@pytest.mark.parametrize("command", ["workspace", "rrr"])
@pytest.mark.parametrize("name", ["ws.jpg", "ws.PDF", "ws"])
def test_workspace_out_must_name_a_png_file(tmp_path, capsys, command, name):
    dest = tmp_path / name
    argv = ["workspace", "--out", str(dest)] if command == "workspace" else ["rrr", "workspace"]
    if command == "rrr":
        argv += ["--out", str(dest)]
    assert main(argv) == 1
    err = capsys.readouterr().err
    assert err == f"lynxsim: error: --out must name a .png file (the figure is PNG), got {dest}\n"
    assert list(tmp_path.iterdir()) == []
