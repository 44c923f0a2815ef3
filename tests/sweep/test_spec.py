"""Sweep files: the shipped ones load; every mistake names the file and the field."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from lynxsim.sweep.spec import SweepFileError, load_sweep, table_extent_mm
from lynxsim.traj import WAYPOINT_KINDS, TrajectoryKind
from tests.sweep.conftest import ROOT, TASKS

SWEEPS = sorted((ROOT / "sweeps").glob("*.toml"))

GOOD = f"""
name = "t"
tasks = ["{TASKS / "obstacle_avoidance.toml"}"]
types = ["line", "planned"]
planner_seeds = [0, 3]
[obstacle]
name = "cylinder"
radius_mm = [30.0, 40.0]
[obstacle.grid]
step_mm = 50.0
x_mm = [0.0, 100.0]
y_mm = [-50.0, 50.0]
[cube]
positions_mm = [[0.0, 300.0, 0.0], [10.0, 300.0, 0.0]]
"""


@pytest.mark.parametrize("path", SWEEPS, ids=[p.stem for p in SWEEPS])
def test_shipped_sweeps_load(path):
    spec = load_sweep(path)
    assert spec.kinds == WAYPOINT_KINDS
    assert [t.name for t in spec.tasks] == ["pick_and_place", "obstacle_avoidance"]
    assert spec.obstacle is not None
    assert spec.obstacle.grid_shape is not None
    (x0, _), (_, y1) = table_extent_mm()
    assert spec.obstacle.x_mm.min() == x0
    assert spec.obstacle.y_mm.max() == y1


def test_the_report_map_has_a_5_mm_grid_holding_the_report_placement():
    spec = load_sweep(ROOT / "sweeps" / "report_obstacle_map.toml")
    assert spec.obstacle is not None
    assert np.diff(np.unique(spec.obstacle.x_mm)).tolist() == [5.0] * 140
    hit = (spec.obstacle.x_mm / 1000.0 == 0.15) & (spec.obstacle.y_mm / 1000.0 == 0.15)
    assert hit.sum() == 1  # the report's (150, 150) mm, in metres as the task loader has it


def test_a_full_sweep_file_reads_every_field(tmp_path):
    path = tmp_path / "t.toml"
    path.write_text(GOOD)
    spec = load_sweep(path)
    assert spec.kinds == (TrajectoryKind.LINE, TrajectoryKind.PLANNED)
    assert spec.planner_seeds == (0, 3)
    assert spec.obstacle is not None
    assert spec.obstacle.radii_mm == (30.0, 40.0)
    assert spec.obstacle.x_mm.tolist() == [0.0, 50.0, 100.0] * 3
    assert spec.cube_positions == ((0.0, 0.3, 0.0), (0.01, 0.3, 0.0))
    assert spec.placements == 9
    assert len(spec.digest) == 64


@pytest.mark.parametrize(
    ("old", "new", "field", "problem"),
    [
        ('types = ["line", "planned"]', 'types = ["line", "spline"]', "types[1]", "unknown type"),
        ('types = ["line", "planned"]', 'types = "some"', "types", "unknown group"),
        ('name = "cylinder"', 'name = "tower"', "obstacle.name", "has no obstacle 'tower'"),
        ("step_mm = 50.0", "step_mm = 0.0", "obstacle.grid.step_mm", "must be positive"),
        ("step_mm = 50.0", "step_mm = 0.001", "obstacle.grid.step_mm", "must lie within"),
        ("x_mm = [0.0, 100.0]", "x_mm = [100.0, 0.0]", "obstacle.grid.x_mm", "above high"),
        ("planner_seeds = [0, 3]", "planner_seeds = [-1]", "planner_seeds[0]", "between"),
        ("[obstacle.grid]", "[obstacle.random]", "obstacle.random.step_mm", "unknown key"),
        ("radius_mm = [30.0, 40.0]", "radius_mm = []", "obstacle.radius_mm", "non-empty"),
        ("[[0.0, 300.0, 0.0],", "[[0.0, 300.0],", "cube.positions_mm[0]", "3 numbers"),
        ('name = "t"', 'name = "t"\nspeed = 3', "speed", "unknown key"),
        (
            "radius_mm = [30.0, 40.0]",
            "radius_mm = [30.0, 30.0000001]",
            "obstacle.radius_mm[1]",
            "repeats 30 mm",
        ),
        (
            "[[0.0, 300.0, 0.0],",
            "[[0.0, 300.0, -100.0],",
            "cube.positions_mm[0]",
            "cube centred at z = -100 mm would reach into the table",
        ),
    ],
    ids=lambda v: str(v)[:20],
)
def test_errors_name_the_file_and_the_field(tmp_path, old, new, field, problem):
    path = tmp_path / "bad.toml"
    assert old in GOOD
    path.write_text(GOOD.replace(old, new, 1))
    with pytest.raises(SweepFileError, match=problem) as info:
        load_sweep(path)
    assert info.value.field == field
    assert str(info.value).startswith(f"{path}: {field}: ")
    assert "\n" not in str(info.value)


def test_a_bad_task_file_is_named_with_the_sweep_field(tmp_path):
    task = tmp_path / "task.toml"
    task.write_text('robot = "arm"\n')
    path = tmp_path / "s.toml"
    path.write_text(GOOD.replace(str(TASKS / "obstacle_avoidance.toml"), "task.toml"))
    with pytest.raises(SweepFileError, match=r"tasks\[0\]: .*task\.toml: trajectory: missing"):
        load_sweep(path)


def test_task_paths_are_relative_to_the_sweep_file(tmp_path):
    (tmp_path / "sub").mkdir()
    path = tmp_path / "sub" / "s.toml"
    relative = Path("..") / ".." / Path(*Path(TASKS).parts[-1:])
    text = GOOD.replace(str(TASKS / "obstacle_avoidance.toml"), "missing.toml")
    path.write_text(text)
    with pytest.raises(SweepFileError, match=r"tasks\[0\]: cannot read .*sub/missing\.toml"):
        load_sweep(path)
    assert relative.name == "tasks"


def test_too_many_runs_are_refused(tmp_path):
    path = tmp_path / "big.toml"
    path.write_text(
        GOOD.replace("step_mm = 50.0", "step_mm = 0.1").replace(
            "x_mm = [0.0, 100.0]", "x_mm = [-300.0, 300.0]"
        )
    )
    with pytest.raises(SweepFileError, match="at most"):
        load_sweep(path)


def test_a_radius_that_sinks_the_swept_sphere_into_the_table_is_refused(tmp_path):
    path = tmp_path / "ball.toml"
    path.write_text(
        f"""
name = "ball"
tasks = ["{TASKS / "three_obstacles.toml"}"]
types = ["quintic"]
[obstacle]
name = "sphere"
radius_mm = [30.0, 350.0]
[obstacle.grid]
step_mm = 50.0
x_mm = [300.0, 400.0]
y_mm = [0.0, 0.0]
"""
    )
    with pytest.raises(
        SweepFileError, match=r"radius 350 mm at 'sphere'\S* height would reach"
    ) as info:
        load_sweep(path)
    assert info.value.field == "obstacle.radius_mm[1]"
