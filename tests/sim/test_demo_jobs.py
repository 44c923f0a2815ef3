"""The demo's jobs in worker processes give the same reports and files as in one process."""

from __future__ import annotations

import functools

import pytest

from lynxsim.demo.jobs import Job, run_jobs
from lynxsim.demo.runs import demo_jobs, demo_runs, run_demo
from lynxsim.sim.render import Quality, RenderSettings
from lynxsim.tasks import load_task
from tests.helpers import short_arm_task

SMALL = RenderSettings(width=160, height=128, quality=Quality.FAST, fps=10)


def _square(x: int, started: list[int], progress) -> int:
    started.append(x)
    if progress is not None:
        progress(0.5)
        progress(1.0)
    return x * x


def _fail(progress) -> None:
    raise ValueError("job failed")


def test_jobs_start_costliest_first_and_results_keep_the_given_order():
    started: list[int] = []
    costs = {1: 1.0, 2: 5.0, 3: 3.0}
    jobs = [Job(f"j{x}", c, functools.partial(_square, x, started)) for x, c in costs.items()]
    seen = []
    assert run_jobs(jobs, lambda k, f: seen.append((k, f))) == [1, 4, 9]
    assert started == [2, 3, 1]
    assert seen == [(0, 0.5), (0, 1.0), (1, 0.5), (1, 1.0), (2, 0.5), (2, 1.0)]


@pytest.mark.slow
def test_a_failing_job_raises_its_error_from_the_pool():
    jobs = [Job("ok", 1.0, functools.partial(_square, 2, [])), Job("bad", 2.0, _fail)]
    with pytest.raises(ValueError, match="job failed"):
        run_jobs(jobs, workers=2)


def test_arm_jobs_are_the_runs_then_one_path_comparison_per_task(tmp_path):
    path = tmp_path / "short.toml"
    path.write_text(short_arm_task())
    runs = list(demo_runs([load_task(path)], lambda m: None))
    jobs = demo_jobs(runs, tmp_path, SMALL)
    assert [j.name for j in jobs] == [r.stem for r in runs] + ["short_paths"]
    assert all(j.cost > jobs[-1].cost for j in jobs[:-1])  # runs render, the comparison draws


@pytest.mark.slow
def test_parallel_runs_match_sequential_runs(tmp_path):
    path = tmp_path / "short.toml"
    path.write_text(short_arm_task())
    runs = [r for r in demo_runs([load_task(path)], lambda m: None)
            if r.motion.label in ("quintic", "cubic")]  # fmt: skip
    one = run_demo(runs, tmp_path / "one", SMALL, jobs=1)
    done = []
    two = run_demo(runs, tmp_path / "two", SMALL, lambda k, f: done.append(k + f), jobs=2)
    assert [r.to_dict() for r in one] == [r.to_dict() for r in two]
    assert done == [1.0, 2.0, 3.0]  # two runs and the path comparison
    names = sorted(p.name for p in (tmp_path / "one").rglob("*") if p.is_file())
    assert names == sorted(p.name for p in (tmp_path / "two").rglob("*") if p.is_file())
    assert "short_quintic.mp4" in names
    assert "short_paths.png" in names
