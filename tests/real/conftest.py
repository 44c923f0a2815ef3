"""Fixtures of the real-arm tests: an emulated board on a pseudo-terminal, the CLI in-process."""

from __future__ import annotations

import os

os.environ.setdefault("MUJOCO_GL", "egl")

from collections.abc import Callable, Iterator

import pytest

from lynxsim.real.pty_server import PtyEmulator
from tests.cli.conftest import CliResult, cli  # noqa: F401 - the fixture, shared

__all__ = ["CliResult"]


@pytest.fixture
def emulator() -> Iterator[PtyEmulator]:
    """An emulated SSC-32U served on a pseudo-terminal."""
    with PtyEmulator() as emu:
        yield emu


@pytest.fixture
def short_task(tmp_path) -> Callable[[str], str]:
    """Writes a short arm task (1 s quintic, no obstacle) and returns its path."""
    from tests.helpers import short_arm_task

    def write(name: str = "short") -> str:
        path = tmp_path / f"{name}.toml"
        path.write_text(short_arm_task(name))
        return str(path)

    return write
