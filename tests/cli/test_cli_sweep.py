"""``lynxsim sweep``: a table and maps from a sweep file; mistakes are one line and exit 1 or 2."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]

SMALL = """
name = "../escape/small"
tasks = ["{tasks}/obstacle_avoidance.toml"]
types = ["line"]
rows_per_shard = 20
[obstacle]
name = "cylinder"
[obstacle.grid]
step_mm = 60.0
x_mm = [0.0, 180.0]
y_mm = [0.0, 240.0]
"""


@pytest.fixture
def small(tmp_path: Path) -> Path:
    path = tmp_path / "small.toml"
    path.write_text(SMALL.format(tasks=ROOT / "tasks"))
    return path


def test_sweep_writes_table_and_maps_inside_the_folder(cli, small, tmp_path):
    out = tmp_path / "out"
    result = cli("sweep", str(small), "--out-dir", str(out), "--jobs", "1", "--json")
    assert result.code == 0, result.err
    summary = json.loads(result.out)
    assert summary["runs"] == 20
    assert summary["shards_computed"] == 1
    assert summary["csv"] == str(out / "escape_small.csv")  # the name never picks the folder
    maps = [Path(m) for m in summary["maps"]]
    assert [m.name for m in maps] == ["escape_small_obstacle_avoidance_line.png"]
    assert all(m.parent == out and m.stat().st_size > 10_000 for m in maps)
    assert not (tmp_path / "escape").exists()
    with np.load(out / "escape_small.npz") as data:
        assert len(data["verdict"]) == 20
    assert sum(summary["verdicts"]["obstacle_avoidance"]["line"].values()) == 20
    again = cli("sweep", str(small), "--out-dir", str(out), "--no-maps", "--quiet")
    assert again.code == 0, again.err
    assert "(0 shards computed, 1 reused)" in again.out
    assert "obstacle_avoidance   line" in again.out
    (shard,) = out.glob("escape_small.shards/*/shard_000000.npz")
    shard.write_bytes(shard.read_bytes()[:-40])  # truncated
    damaged = cli("sweep", str(small), "--out-dir", str(out), "--no-maps", "--quiet")
    assert damaged.code == 0, damaged.err
    assert "(1 shards computed, 0 reused)" in damaged.out
    (line,) = damaged.err.splitlines()
    assert line.startswith("lynxsim: shard 0 (shard_000000.npz) unreadable")
    assert line.endswith(": computed again")


@pytest.mark.parametrize(
    ("args", "code", "message"),
    [
        (["missing.toml"], 1, "No such file"),
        (["{small}", "--backend", "spark"], 2, "invalid choice"),
        (["{small}", "--jobs", "0"], 2, "must be between 1 and 256"),
        (["{small}", "--address", "auto"], 1, "--address and --verbose apply to --backend ray"),
        (
            ["{small}", "--backend", "ray", "--address", "nan"],
            1,
            "lynxsim: error: --address 'nan': expected HOST:PORT, ray://HOST:PORT or auto",
        ),
    ],
    ids=["missing", "backend", "jobs", "address", "address-form"],
)
def test_mistakes_are_one_line(cli, small, tmp_path, args, code, message):
    argv = [a.format(small=small) for a in args]
    result = cli("sweep", *argv, "--out-dir", str(tmp_path / "o"))
    assert result.code == code
    assert message in result.err
    assert len(result.err.strip().splitlines()) == 1


def test_a_bad_field_names_file_and_field(cli, small, tmp_path):
    small.write_text(small.read_text().replace('types = ["line"]', 'types = ["lines"]'))
    result = cli("sweep", str(small), "--out-dir", str(tmp_path / "o"))
    assert result.code == 1
    assert result.err.startswith(f"lynxsim: error: {small}: types[0]: unknown type 'lines'")


def test_ray_missing_is_one_line(small, tmp_path):
    code = (
        "import sys; sys.modules['ray'] = None\n"
        "from lynxsim.cli import main\n"
        f"argv = ['sweep', {str(small)!r}, '--backend', 'ray', '--out-dir', {str(tmp_path)!r}]\n"
        "sys.exit(main(argv))\n"
    )
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert result.returncode == 1
    assert result.stderr.strip().splitlines() == [
        "lynxsim: error: --backend ray needs Ray, which is not installed: "
        "pip install 'lynxsim[cluster]'"
    ]
