"""Running sweeps: shards saved and skipped, rows in order, every kind of row, no Ray imported."""

from __future__ import annotations

import dataclasses
import itertools
import subprocess
import sys

import numpy as np
import pytest

from lynxsim.errors import InvalidInputError
from lynxsim.robots import motion
from lynxsim.robots.arm import ROBOT as ARM
from lynxsim.sim.arm.task import run_arm_trajectory
from lynxsim.sweep.maps import write_maps
from lynxsim.sweep.runner import LocalBackend, compute_shard, groups, run_sweep, shards
from lynxsim.sweep.spec import load_sweep
from lynxsim.sweep.table import COLUMNS, VERDICTS, read_npz
from lynxsim.tasks import load_task
from lynxsim.traj import TrajectoryKind
from tests.sweep.conftest import ROOT, TASKS, grid_spec

LINE = (TrajectoryKind.LINE,)


def _small():
    return grid_spec(60.0, LINE, x_mm=(-60.0, 180.0), y_mm=(-120.0, 240.0), rows_per_shard=10)


def test_shards_cover_the_rows_in_order():
    spec = _small()
    every = shards(spec)
    assert [s.index for s in every] == list(range(len(every)))
    rows = [(s.group.first_row + s.start, s.rows) for s in every]
    assert rows[0][0] == 0
    for (start, count), (after, _) in itertools.pairwise(rows):
        assert start + count == after
    assert sum(g.rows for g in groups(spec)) == sum(count for _, count in rows) == 2 * 35


def test_a_rerun_reuses_saved_shards_and_recomputes_a_damaged_one(tmp_path):
    spec = _small()
    first = run_sweep(spec, tmp_path)
    assert (first.computed, first.reused) == (8, 0)
    files = sorted(tmp_path.glob("*.shards/*/shard_*.npz"))
    assert len(files) == 8
    files[2].write_bytes(b"not a table")
    (files[0].parent / ".shard_000005.abc.tmp.npz").write_bytes(b"partial")  # a killed writer's
    again = run_sweep(spec, tmp_path)
    assert (again.computed, again.reused) == (1, 7)
    for name in COLUMNS:
        assert np.array_equal(
            first.table[name], again.table[name], equal_nan=name.endswith(("_m", "_s", "ratio"))
        )
    assert np.array_equal(
        read_npz(first.npz)["min_clearance_m"], first.table["min_clearance_m"], equal_nan=True
    )
    header = first.csv.read_text().splitlines()[0]
    assert header == ",".join(COLUMNS)


def test_the_local_pool_gives_the_same_table(tmp_path):
    spec = _small()
    one = run_sweep(spec, tmp_path / "one").table
    two = run_sweep(spec, tmp_path / "two", backend=LocalBackend(2)).table
    for name in COLUMNS:
        assert np.array_equal(one[name], two[name], equal_nan=one[name].dtype.kind == "f")


def test_rows_of_every_verdict_are_consistent(tmp_path):
    table = run_sweep(
        grid_spec(30.0, LINE, x_mm=(-60.0, 240.0), y_mm=(-60.0, 330.0)), tmp_path
    ).table
    verdict = table["verdict"]
    assert set(verdict.tolist()) <= set(VERDICTS)
    assert {"clear", "collided", "start_overlap", "invalid"} <= set(verdict.tolist())
    clear = verdict == "clear"
    assert np.isfinite(table["min_clearance_m"][clear]).all()
    assert np.isnan(table["first_contact_s"][clear]).all()
    assert (table["healthy"][clear] == 1).all()
    hit = verdict == "collided"
    assert table["collided"][hit].all()
    assert np.isfinite(table["first_contact_s"][hit]).all()
    assert np.isnan(
        table["min_clearance_m"][hit]
    ).all()  # after a contact only a run of its own tells
    assert (table["first_obstacle"][hit] == "cylinder").all()
    assert table["collided"][verdict == "start_overlap"].all()
    assert (table["method"][verdict != "invalid"] == "recorded").all()


def test_planned_rows_and_sweeps_without_an_obstacle_are_played_row_by_row(tmp_path):
    path = tmp_path / "s.toml"
    path.write_text(
        f'tasks = ["{TASKS / "obstacle_avoidance.toml"}"]\n'
        'types = ["line"]\n'
        "[cube]\npositions_mm = [[0.0, 300.0, 0.0], [0.0, 290.0, 0.0]]\n"
    )
    table = run_sweep(load_sweep(path), tmp_path / "out").table
    assert table["verdict"].tolist() == ["clear", "clear"]
    assert table["method"].tolist() == ["physics", "physics"]
    assert table["cube_y_m"].tolist() == [0.3, 0.29]
    task = load_task(TASKS / "obstacle_avoidance.toml")
    own = run_arm_trajectory(motion(ARM, task, "line"), task=task.name, scene=task.scene)
    assert table["min_clearance_m"][0] == own.report.min_clearance_m


@pytest.mark.slow
def test_planned_rows_are_planned_around_each_placement(tmp_path):
    spec = grid_spec(
        100.0,
        (TrajectoryKind.PLANNED,),
        tasks=("obstacle_avoidance.toml",),
        x_mm=(150.0, 250.0),
        y_mm=(150.0, 150.0),
    )
    shard = shards(spec)[0]
    rows = compute_shard(spec, shard)
    assert rows["method"].tolist() == ["physics", "physics"]
    assert rows["verdict"].tolist() == ["clear", "clear"]
    assert (rows["planner_seed"] == 0).all()


def test_the_core_never_imports_ray(tmp_path):
    code = (
        "import sys\n"
        "from lynxsim.sweep import load_sweep, run_sweep\n"
        "import lynxsim.cli.sweep, lynxsim.sweep.maps\n"
        f"spec = load_sweep({str(ROOT / 'sweeps' / 'report_obstacle_map_coarse.toml')!r})\n"
        "assert 'ray' not in sys.modules, 'ray imported'\n"
    )
    subprocess.run([sys.executable, "-c", code], check=True, cwd=tmp_path)


@pytest.mark.parametrize("jobs", [0, 257, 2.5, "2", None, True])
def test_a_local_backend_needs_a_whole_number_of_workers(jobs):
    with pytest.raises(InvalidInputError, match="jobs must be"):
        LocalBackend(jobs)


def test_maps_of_names_that_clean_alike_do_not_overwrite_each_other(tmp_path):
    """Two tasks named ``arm/one`` and ``arm_one`` give two maps, not one written twice."""
    base = grid_spec(
        200.0, LINE, tasks=("obstacle_avoidance.toml",) * 2, x_mm=(0.0, 200.0), y_mm=(0.0, 0.0)
    )
    tasks = tuple(
        dataclasses.replace(t, name=n)
        for t, n in zip(base.tasks, ("arm/one", "arm_one"), strict=True)
    )
    spec = dataclasses.replace(base, tasks=tasks)
    table = run_sweep(spec, tmp_path / "sweep").table
    maps = write_maps(spec, table, tmp_path / "maps")
    assert len(maps) == 2
    assert len(set(maps)) == 2
    assert all(m.is_file() for m in maps)
    assert [m.name for m in maps] == [
        f"{spec.name}_arm_one_line.png",
        f"{spec.name}_arm_one_line_2.png",
    ]
