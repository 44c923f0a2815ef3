"""``lynxsim dataset``: a summary and the load command, one-line errors, nothing partial left."""

from __future__ import annotations

import os
import random
import shlex
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from lynxsim.cli import main

FUZZ_EXAMPLES = 40
"""Hypothesis examples of the fuzzed command lines (most fail in parsing; a run takes ~0.1 s)."""

_ID = "lynxsim/pick-and-place-v1/expert-v0"


def _tree(root: Path) -> list[str]:
    return sorted(str(p.relative_to(root)) for p in root.rglob("*"))


def test_dataset_command_writes_npz_and_says_how_to_load_it(cli, tmp_path):
    result = cli("dataset", "--episodes", "2", "--seed", "4", "--out-dir", str(tmp_path), "--quiet")
    assert result.code == 0, result.err
    assert result.err == ""
    lines = result.out.splitlines()
    assert lines[0] == f"{tmp_path / _ID} (npz, dataset id {_ID})"
    assert lines[1] == (
        "  2 episodes of LynxPickAndPlace-v1, 400 steps, seeds 4..5, "
        "action noise 0.1 x the action range"
    )
    assert lines[2].startswith("  expert success   ")
    assert lines[3].startswith("  load with        python -c ")
    load = shlex.split(lines[3].removeprefix("  load with        "))
    code = f"{load[2]}; print(len(episodes), episodes[1].seed)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout == "2 5\n"


def test_the_printed_minari_command_loads_the_dataset(cli, tmp_path):
    pytest.importorskip("minari")
    result = cli("dataset", "--episodes", "1", "--format", "minari", "--out-dir", str(tmp_path))
    assert result.code == 0, result.err
    assert "1/1" in result.err  # the progress bar
    line = result.out.splitlines()[3]
    assert line.startswith(f"  load with        MINARI_DATASETS_PATH={tmp_path} python -c ")
    env_var, _, _, code = shlex.split(line.removeprefix("  load with        "))
    check = f"{code}; print(ds.total_episodes, ds.recover_environment().spec.id)"
    out = subprocess.run(
        [sys.executable, "-c", check],
        capture_output=True,
        text=True,
        check=True,
        env={**os.environ, env_var.split("=", 1)[0]: env_var.split("=", 1)[1]},
    )
    assert out.stdout == "1 LynxPickAndPlace-v1\n"


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["--episodes", "0"], "argument --episodes: must be between 1 and 1,000,000, got 0"),
        (["--noise", "2"], "argument --noise: must be between 0 and 1, got 2"),
        (["--noise", "nan"], "argument --noise: must be a finite number, got 'nan'"),
        (["--format", "hdf5"], "argument --format: invalid choice: 'hdf5'"),
        (["--seed", "-1"], "argument --seed: must be between 0 and"),
        (["--dataset-id", "../up-v0"], "argument --dataset-id: dataset id must look like"),
        (["--env", "CartPole-v1"], "argument --env: invalid choice: 'CartPole-v1'"),
    ],
    ids=lambda v: v[0] if isinstance(v, list) else None,
)
def test_bad_arguments_are_one_line_usage_errors(cli, tmp_path, argv, message):
    result = cli("dataset", "--out-dir", str(tmp_path), *argv)
    assert result.code == 2
    assert result.err.startswith(f"lynxsim dataset: error: {message}"), result.err
    assert result.err.count("\n") == 1
    assert _tree(tmp_path) == []


def test_out_is_required(cli):
    result = cli("dataset")
    assert result.code == 2
    assert result.err == "lynxsim dataset: error: the following arguments are required: --out-dir\n"


def test_errors_found_by_the_library_are_one_line(cli, tmp_path):
    argv = ["dataset", "--out-dir", str(tmp_path), "--episodes", "1"]
    assert cli(*argv, "--quiet").code == 0
    again = cli(*argv)  # no progress bar before the error, even without --quiet
    assert again.code == 1
    assert again.err == (
        f"lynxsim: error: will not replace {tmp_path / _ID}: it exists "
        "(remove it, or choose another root or dataset id)\n"
    )
    last = cli(*argv[:-1], "2", "--seed", str(2**63 - 1), "--dataset-id", "x-v0")
    assert last.code == 1
    assert last.err.startswith("lynxsim: error: the last episode's seed, seed + episodes - 1")
    assert last.err.count("\n") == 1


@pytest.mark.parametrize("fmt", ["npz", "minari"])
def test_sigterm_leaves_no_dataset(tmp_path, fmt):
    if fmt == "minari":
        pytest.importorskip("minari")
    argv = [
        "dataset",
        "--episodes",
        "100000",
        "--format",
        fmt,
        "--out-dir",
        str(tmp_path),
        "--quiet",
    ]
    proc = subprocess.Popen(
        [sys.executable, "-m", "lynxsim", *argv],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        env={**os.environ, "MUJOCO_GL": "egl"},
    )
    folder = tmp_path / "lynxsim" / "pick-and-place-v1"
    deadline = time.monotonic() + 120
    while not [p for p in folder.glob(".expert-v0.*.tmp/**/*") if p.stat().st_size > 100_000]:
        assert proc.poll() is None, proc.communicate()  # episodes are being written
        assert time.monotonic() < deadline
        time.sleep(0.05)
    proc.send_signal(signal.SIGTERM)
    _, err = proc.communicate(timeout=60)
    assert proc.returncode == 143
    assert err == "lynxsim: terminated\n"
    assert _tree(tmp_path) == []  # nor the folders it made for the dataset


_TOKENS = [
    "--env", "LynxReach-v1", "LynxPickAndPlace-v1", "--episodes", "1", "0", "-1", "2.5", "x",
    "--noise", "0", "0.1", "1", "1.5", "nan", "-inf", "1e-300", "--format", "npz", "minari",
    "--seed", "0", "9223372036854775807", "1" + "0" * 40, "--dataset-id", "a-v0", "../a-v0",
    "a/b-v1", "-v0", "--quiet", "--help", "",
]  # fmt: skip
"""Tokens of fuzzed ``dataset`` command lines: flags, good and bad values (``--out-dir`` comes
last, inside the test's folder: a drawn one could write into the working folder)."""


@settings(
    max_examples=FUZZ_EXAMPLES,
    deadline=None,
    suppress_health_check=[HealthCheck.function_scoped_fixture],
)
@given(seed=st.integers(0, 2**32 - 1))
def test_fuzzed_command_lines_write_a_whole_dataset_or_fail_in_one_line(
    tmp_path_factory, capsys, seed
):
    rng = random.Random(seed)
    root = tmp_path_factory.mktemp("fuzz")
    argv = ["dataset", *(rng.choice(_TOKENS) for _ in range(rng.randint(0, 8)))]
    argv += ["--out-dir", str(root / "out")] if rng.random() < 0.9 else []
    if "--episodes" not in argv:
        argv += ["--episodes", "1"]  # the default, 100, takes seconds
    try:
        code = main(argv)
    except SystemExit as exc:  # argparse: 0 after --help, 2 on a usage error
        code = exc.code
    err = capsys.readouterr().err
    assert code in (0, 1, 2), (argv, code)
    if code:
        assert err.count("\n") == 1, (argv, err)
        assert "Traceback" not in err
    elif "--help" not in argv:
        assert [p.name for p in (root / "out").rglob("episodes.npz")] or [
            p for p in (root / "out").rglob("main_data.hdf5")
        ], argv
    assert not [p for p in root.rglob(".*")], argv  # no temporary folder left


def test_an_out_dir_that_is_a_file_is_refused_before_any_work(cli, tmp_path):
    file = tmp_path / "file"
    file.write_text("x")
    result = cli("dataset", "--out-dir", str(file), "--episodes", "1")
    assert result.code == 1
    assert result.err == f"lynxsim: error: cannot write {file / _ID}: {file} is not a folder\n"
