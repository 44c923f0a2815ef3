"""The Ray backend on a local Ray instance: the local backend's table, bit for bit, and retries.

``ray.init(num_cpus=2)`` starts a real local Ray instance (no cluster needed).
A worker that kills itself midway through a shard (once: a marker file
remembers) loses only that shard: Ray runs it again, every finished shard is
already saved, and the table is still the local one.
"""

from __future__ import annotations

import os
import signal
from pathlib import Path

import numpy as np
import pytest

from lynxsim.sweep.runner import LocalBackend, run_sweep
from lynxsim.traj import TrajectoryKind
from tests.sweep.conftest import grid_spec

ray = pytest.importorskip("ray")

pytestmark = pytest.mark.slow


def _spec():  # 2 tasks x 2 types x 77 placements = 308 runs in 8 shards
    return grid_spec(
        40.0,
        (TrajectoryKind.LINE, TrajectoryKind.CUBIC),
        x_mm=(-90.0, 150.0),
        y_mm=(-190.0, 210.0),
        rows_per_shard=40,
    )


def _equal(a: dict, b: dict) -> None:
    assert list(a) == list(b)
    for name in a:
        assert a[name].dtype == b[name].dtype, name
        if a[name].dtype.kind == "f":
            assert np.array_equal(a[name], b[name], equal_nan=True), name
            assert np.array_equal(np.signbit(a[name]), np.signbit(b[name])), name
        else:
            assert np.array_equal(a[name], b[name]), name


class _KillOnce:
    """Kills the worker process computing shard ``shard`` the first time (a marker remembers)."""

    def __init__(self, marker: Path, shard: int) -> None:
        self.marker = marker
        self.shard = shard

    def __call__(self, index: int) -> None:
        if index == self.shard and not self.marker.exists():
            self.marker.write_text(str(os.getpid()))
            os.kill(os.getpid(), signal.SIGKILL)


@pytest.fixture(scope="module")
def local_ray():
    ray.init(num_cpus=2, include_dashboard=False, log_to_driver=False)
    ray.cloudpickle.register_pickle_by_value(__import__(__name__))
    yield ray
    ray.shutdown()


@pytest.fixture(scope="module")
def local_table(tmp_path_factory):
    return run_sweep(_spec(), tmp_path_factory.mktemp("local"), backend=LocalBackend(2)).table


def test_ray_table_equals_the_local_one(local_ray, local_table, tmp_path):
    from lynxsim.sweep.ray_backend import RayBackend

    outcome = run_sweep(_spec(), tmp_path, backend=RayBackend())
    assert len(outcome.table["task"]) == 308
    assert set(outcome.table["verdict"].tolist()) >= {"clear", "collided", "start_overlap"}
    _equal(outcome.table, local_table)


def test_a_killed_worker_loses_no_finished_shard(local_ray, local_table, tmp_path):
    from lynxsim.sweep.ray_backend import RayBackend

    marker = tmp_path / "killed"
    saved: list[int] = []
    outcome = run_sweep(
        _spec(),
        tmp_path / "out",
        backend=RayBackend(max_in_flight=1),
        hook=_KillOnce(marker, shard=3),
        progress=lambda done, total: saved.append(done),
    )
    assert marker.exists()  # the worker of shard 3 died once ...
    assert outcome.computed == 8  # ... and Ray ran it again
    shards = sorted((tmp_path / "out").glob("*.shards/*/shard_*.npz"))
    assert len(shards) == 8
    _equal(outcome.table, local_table)
    again = run_sweep(_spec(), tmp_path / "out", backend=RayBackend())
    assert (again.computed, again.reused) == (0, 8)
