"""Fixtures of the robot-interface tests: the outside robot registered, the CLI in-process.

The ``cli`` fixture is the command-line tests' (:mod:`tests.cli.conftest`).

The planar arm (``examples/planar_arm``) lives outside lynxsim: the fixture puts
``examples/`` on ``sys.path`` (worker processes inherit it), imports the robot's
module (which registers it) and unregisters it afterwards, so that the rest of
the suite sees the built-in robots only.
"""

from __future__ import annotations

import os

os.environ.setdefault("MUJOCO_GL", "egl")

import importlib
import sys
from collections.abc import Iterator
from pathlib import Path

import pytest

from lynxsim.robots import Robot, register, unregister
from tests.cli.conftest import CliResult, cli  # noqa: F401 - the fixture, shared

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"
PLANAR = EXAMPLES / "planar_arm"
PLANAR_TASKS = PLANAR / "tasks"
REACH_TASK = PLANAR_TASKS / "planar_reach.toml"
POST_TASK = PLANAR_TASKS / "planar_post.toml"
POST_SWEEP = PLANAR / "sweeps" / "planar_post_map.toml"

__all__ = ["CliResult"]


@pytest.fixture(scope="module")
def planar_arm() -> Iterator[Robot]:
    """The planar arm, registered through the public API for the tests of one module."""
    sys.path.insert(0, str(EXAMPLES))
    try:
        module = importlib.import_module("planar_arm.robot")
        robot: Robot = register(module.ROBOT)  # importing registered it; again is a no-op
        yield robot
    finally:
        unregister("planar_arm")
        sys.path.remove(str(EXAMPLES))
