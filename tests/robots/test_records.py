"""The robot rows and records: every row resolves, and only they name a robot."""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

from lynxsim.errors import InvalidInputError
from lynxsim.registry import info, names
from lynxsim.robots import motion_builder, robot, sim_adapter
from lynxsim.tasks import load_task

TASKS = Path(__file__).resolve().parents[2] / "tasks"
PACKAGE = Path(__file__).resolve().parents[2] / "lynxsim"


@pytest.mark.parametrize("path", sorted(TASKS.glob("*.toml")), ids=lambda p: p.stem)
def test_every_shipped_task_builds_and_prepares_through_its_row(path: Path) -> None:
    task = load_task(path)
    motion = motion_builder(task.robot)(task, None)
    prepared = sim_adapter(task.robot).prepare(task, None)
    assert prepared.label.startswith(task.trajectory.value)  # "quintic-spline" for pass_through
    label = motion.label if hasattr(motion, "label") else motion.kind.value
    assert label == prepared.label


def test_each_row_names_importable_parts() -> None:
    for name in names():
        assert info(name).name == name
        assert (PACKAGE / "models" / robot(name).model).is_file()
        assert callable(motion_builder(name))
        assert sim_adapter(name).default_camera


def test_unknown_robot_lists_the_known_ones() -> None:
    with pytest.raises(InvalidInputError, match="expected one of: arm, rrr"):
        robot("scara")
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
