"""The demo's arm runs in worker processes give the same reports and files as in one process."""

from __future__ import annotations

import pytest

from lynxsim.demo.arm import arm_runs, run_arm_demo
from lynxsim.sim.render import Quality, RenderSettings
from lynxsim.tasks import load_task
from lynxsim.traj import TrajectoryKind
from tests.helpers import short_arm_task

SMALL = RenderSettings(width=160, height=128, quality=Quality.FAST, fps=10)


@pytest.mark.slow
def test_parallel_runs_match_sequential_runs(tmp_path):
    path = tmp_path / "short.toml"
    path.write_text(short_arm_task())
    runs = [r for r in arm_runs([load_task(path)], lambda m: None)
            if r.trajectory.kind in (TrajectoryKind.QUINTIC, TrajectoryKind.CUBIC)]  # fmt: skip
    one = run_arm_demo(runs, tmp_path / "one", SMALL, jobs=1)
    done = []
    two = run_arm_demo(runs, tmp_path / "two", SMALL, lambda k, f: done.append(k + f), jobs=2)
    assert [r.to_dict() for r in one] == [r.to_dict() for r in two]
    assert done == [1.0, 2.0]
    names = sorted(p.name for p in (tmp_path / "one").rglob("*") if p.is_file())
    assert names == sorted(p.name for p in (tmp_path / "two").rglob("*") if p.is_file())
    assert "short_quintic.mp4" in names
