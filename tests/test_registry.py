"""The robot rows: validated, looked up by name, each name registered once."""

from __future__ import annotations

import pytest

from lynxsim.errors import InvalidInputError
from lynxsim.registry import RobotInfo, info, names, register_info


def test_rows_are_validated_and_a_name_is_registered_once() -> None:
    with pytest.raises(InvalidInputError, match="robot name must be lower-case letters"):
        RobotInfo("Arm", "x", "tool", True, "m:a")
    with pytest.raises(InvalidInputError, match="unknown pose schema 'dh'"):
        RobotInfo("scara", "x", "dh", True, "m:a")  # type: ignore[arg-type]
    with pytest.raises(InvalidInputError, match="entry must be 'module:attribute'"):
        RobotInfo("scara", "x", "tool", True, "lynxsim.robots.arm")
    register_info(info("arm"))  # the same row again: nothing changes
    assert names() == ("arm", "rrr")
    with pytest.raises(InvalidInputError, match="robot 'arm' is registered already"):
        register_info(RobotInfo("arm", "another arm", "tool", True, "m:a"))
