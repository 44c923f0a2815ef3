"""Fixtures of the command-line tests.

``MUJOCO_GL`` defaults to ``egl`` before any test module imports ``mujoco`` (MuJoCo
reads it once, at import), so that ``play``, ``demo`` and ``env`` render headless.
"""

from __future__ import annotations

import os

os.environ.setdefault("MUJOCO_GL", "egl")

from collections.abc import Callable
from typing import NamedTuple

import pytest

from lynxsim.cli import main


class CliResult(NamedTuple):
    """What one in-process run of ``lynxsim`` gave: exit code, stdout, stderr."""

    code: int
    out: str
    err: str


@pytest.fixture
def cli(capsys: pytest.CaptureFixture[str]) -> Callable[..., CliResult]:
    """Run ``lynxsim ARGV...`` in-process; argparse's exits become exit codes."""

    def run(*argv: str) -> CliResult:
        try:
            code = main(list(argv))
        except SystemExit as exc:  # argparse: 0 after --help, 2 on a usage error
            code = exc.code if isinstance(exc.code, int) else -1
        captured = capsys.readouterr()
        return CliResult(code, captured.out, captured.err)

    return run
