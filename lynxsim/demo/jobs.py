"""The demo's independent pieces of work, run in this process or in a pool of processes.

A :class:`Job` is a picklable call (a module-level function with its
arguments) that writes its own files and returns what the summary needs.
:func:`run_jobs` starts the costliest first, so that a pool is not left waiting
on one long job at the end.
"""

from __future__ import annotations

import multiprocessing
from collections.abc import Callable, Sequence
from concurrent.futures import Future, ProcessPoolExecutor, as_completed
from dataclasses import dataclass
from typing import Generic, TypeVar

from lynxsim.processes import pool_initializer

__all__ = ["Job", "JobProgress", "job_progress", "run_jobs"]

T_co = TypeVar("T_co", covariant=True)

JobProgress = Callable[[int, float], None]
"""Called as ``progress(k, fraction)``: ``k + fraction`` jobs done so far."""


@dataclass(frozen=True)
class Job(Generic[T_co]):
    """One independent piece of the demo.

    Attributes:
        name: What it makes, for messages.
        cost: Its expected cost, relative to the other jobs (about the frames it
            renders); jobs start in decreasing order of cost.
        work: Called as ``work(progress)`` with ``progress(fraction)`` or None;
            must be picklable (a module-level function or a partial of one).
    """

    name: str
    cost: float
    work: Callable[[Callable[[float], None] | None], T_co]


def run_jobs(
    jobs: Sequence[Job[T_co]],
    progress: JobProgress | None = None,
    *,
    workers: int = 1,
) -> list[T_co]:
    """Run every job; return their results in the order of ``jobs``.

    Args:
        jobs: The jobs.
        progress: Called as jobs advance: in this process within each job, in a
            pool each time a job ends (``progress(k, 1.0)``).
        workers: Processes running jobs at the same time (1: in this process,
            one after the other). Workers are spawned, never forked: no MuJoCo
            or GL state is shared; they end when this process dies.

    Returns:
        The result of each job.

    Raises:
        Exception: The first error of a job; the jobs not yet started are
            cancelled and the running ones are waited for (each leaves complete
            files or none).
    """
    order = sorted(range(len(jobs)), key=lambda i: -jobs[i].cost)
    results: dict[int, T_co] = {}
    if workers <= 1:
        for done, i in enumerate(order):
            results[i] = jobs[i].work(job_progress(progress, done))
        return [results[i] for i in range(len(jobs))]
    context = multiprocessing.get_context("spawn")
    initializer, initargs = pool_initializer()  # the workers die with this process
    pool = ProcessPoolExecutor(
        max_workers=workers, mp_context=context, initializer=initializer, initargs=initargs
    )
    try:
        futures: dict[Future[T_co], int] = {pool.submit(jobs[i].work, None): i for i in order}
        for done, future in enumerate(as_completed(futures)):
            results[futures[future]] = future.result()
            if progress is not None:
                progress(done, 1.0)
    finally:
        pool.shutdown(wait=True, cancel_futures=True)
    return [results[i] for i in range(len(jobs))]


def job_progress(progress: JobProgress | None, k: int) -> Callable[[float], None] | None:
    """The progress callback of job ``k``: ``fraction`` of it done is ``progress(k, fraction)``."""
    if progress is None:
        return None
    report = progress

    def update(fraction: float) -> None:
        report(k, fraction)

    return update
