"""A full disk under a dataset: one line, exit 1, nothing left behind (no empty folder)."""

from __future__ import annotations

import os
import subprocess
import sys

import pytest

from tests.datasets.conftest import FORMATS
from tests.helpers import full_disk

LATEST = "LynxPickAndPlace-v2"
"""The env's latest version (an older one adds Gymnasium's deprecation warning on stderr)."""


@pytest.mark.parametrize("limit_bytes", [2_000, 200_000], ids=["at-once", "midway"])
@pytest.mark.parametrize("fmt", FORMATS)
def test_a_full_disk_is_one_line_and_leaves_no_partial_dataset(tmp_path, fmt, limit_bytes):
    out = tmp_path / "datasets"
    proc = subprocess.run(
        [
            sys.executable, "-m", "lynxsim", "dataset", "--format", fmt, "--episodes", "3",
            "--out-dir", str(out), "--quiet", "--env", LATEST,
        ],
        capture_output=True,
        text=True,
        preexec_fn=full_disk(limit_bytes),
        timeout=300,
        env={**os.environ, "MUJOCO_GL": "egl"},
    )  # fmt: skip
    assert proc.returncode == 1, proc.stderr
    (line,) = proc.stderr.splitlines()
    assert line.startswith("lynxsim: error: "), line
    assert "Traceback" not in proc.stderr
    assert not out.exists()  # no partial file, and no folder made for it left empty
