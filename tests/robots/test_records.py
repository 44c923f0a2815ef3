"""The robot rows and records: every row resolves to a typed record, and only they name a robot."""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

from lynxsim.errors import InvalidInputError
from lynxsim.registry import info, names
from lynxsim.robots import Robot, get, motion, simulation
from lynxsim.sim.adapter import SimAdapter
from lynxsim.sim.render import camera_names
from lynxsim.tasks import load_task

TASKS = Path(__file__).resolve().parents[2] / "tasks"
PACKAGE = Path(__file__).resolve().parents[2] / "lynxsim"


@pytest.mark.parametrize("path", sorted(TASKS.glob("*.toml")), ids=lambda p: p.stem)
def test_every_shipped_task_builds_through_its_record(path: Path) -> None:
    task = load_task(path)
    robot = get(task.robot)
    built = motion(robot, task)
    assert built.label.startswith(task.trajectory.value)  # "quintic-spline" for pass_through
    assert robot.motion(task, task.trajectory).label == built.label
    assert built.waypoint_names == tuple(p.name for p in task.poses)


@pytest.mark.parametrize("path", sorted(TASKS.glob("*.toml")), ids=lambda p: p.stem)
def test_each_record_names_its_models_cameras_default_first(path: Path) -> None:
    task = load_task(path)
    robot = get(task.robot)
    assert camera_names(simulation(robot).model(task.scene)) == robot.cameras


def test_each_row_names_importable_parts() -> None:
    for name in names():
        record = get(name)
        assert isinstance(record, Robot)
        assert record.info == info(name)
        assert isinstance(simulation(record), SimAdapter)


def test_unknown_robot_lists_the_known_ones() -> None:
    with pytest.raises(InvalidInputError, match="expected one of: arm, rrr"):
        get("scara")
    with pytest.raises(InvalidInputError, match="unknown robot 'scara'; expected one of: arm, rrr"):
        info("scara")


def test_no_module_compares_a_robot_name() -> None:
    """A module that tests ``x == "arm"`` would need editing for every new robot."""
    robot_names = set(names())
    offenders = []
    for source in PACKAGE.rglob("*.py"):
        for node in ast.walk(ast.parse(source.read_text())):
            if isinstance(node, ast.Compare):
                for side in [node.left, *node.comparators]:
                    if isinstance(side, ast.Constant) and side.value in robot_names:
                        offenders.append(f"{source.relative_to(PACKAGE)}:{node.lineno}")
    assert offenders == []


INTERFACE = (
    *sorted((PACKAGE / "robots").glob("*.py")),
    PACKAGE / "sim" / "adapter.py",
    PACKAGE / "sim" / "joint_sim.py",
    PACKAGE / "run_options.py",
    PACKAGE / "traj" / "motion.py",
    PACKAGE / "traj" / "kinematics.py",
    PACKAGE / "plan" / "request.py",
)
"""The modules of the robot interface: its types, records, lookups and adapters' protocol."""


@pytest.mark.parametrize("source", INTERFACE, ids=lambda p: str(p.relative_to(PACKAGE)))
def test_the_robot_interface_names_no_any(source: Path) -> None:
    """No ``typing.Any`` at the seam: strict mypy checks every adapter against it."""
    offenders = [
        node.lineno
        for node in ast.walk(ast.parse(source.read_text()))
        if (isinstance(node, ast.Name) and node.id == "Any")
        or (isinstance(node, ast.Attribute) and node.attr == "Any")
        or (isinstance(node, ast.alias) and node.name == "Any")
    ]
    assert offenders == []
