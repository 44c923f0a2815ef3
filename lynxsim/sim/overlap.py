"""Native stepping on a second thread while this one does the Python work of what it gave.

``mujoco.rollout`` and ``mujoco.batch`` release the GIL while they step, so a
producer that steps natively in a background thread overlaps with a consumer
that classifies contacts and computes clearances (Python and short MuJoCo
calls) in the caller's thread: on two cores a run then costs about the larger
of the two instead of their sum. :func:`overlapped` runs such a pair;
:func:`spare_cpu` says whether there is a second CPU to run it on.
"""

from __future__ import annotations

import contextlib
import os
import queue
import threading
from collections.abc import Callable, Iterator
from typing import TypeVar

__all__ = ["cpu_count", "overlapped", "spare_cpu"]

T = TypeVar("T")

_AHEAD = 2
"""Items the producer may run ahead of the consumer (bounds the memory in flight)."""


def cpu_count() -> int:
    """How many CPUs this process may run on."""
    if hasattr(os, "sched_getaffinity"):
        return len(os.sched_getaffinity(0))
    return os.cpu_count() or 1


def spare_cpu() -> bool:
    """Whether this process may run on more than one CPU."""
    return cpu_count() > 1


class _Done:
    """End of the items (with the producer's exception, if it raised)."""

    def __init__(self, error: BaseException | None = None) -> None:
        self.error = error


def overlapped(
    produce: Callable[[], Iterator[T]], consume: Callable[[T], None], *, background: bool
) -> None:
    """Feed every item ``produce()`` yields to ``consume``, in order.

    With ``background`` the items are produced in a daemon thread, at most
    ``_AHEAD`` ahead of the consumer, and consumed in the caller's thread; an
    exception in either stops both and is raised here (the producer's first).
    Without it, one thread does both in turn (the same calls, the same order).

    Args:
        produce: Makes the iterator of items (called in the thread that produces).
        consume: Called with each item, in the caller's thread.
        background: Whether to produce in a second thread.
    """
    if not background:
        for item in produce():
            consume(item)
        return
    items: queue.Queue[T | _Done] = queue.Queue(maxsize=_AHEAD)
    stop = threading.Event()

    def run() -> None:
        try:
            for item in produce():
                if stop.is_set():
                    break
                items.put(item)
        except BaseException as error:  # handed to the caller's thread
            items.put(_Done(error))
            return
        items.put(_Done())

    worker = threading.Thread(target=run, name="lynxsim-stepper", daemon=True)
    worker.start()
    try:
        while True:
            got = items.get()
            if isinstance(got, _Done):
                break
            consume(got)
    except BaseException:
        stop.set()
        while worker.is_alive():  # let a producer blocked on a full queue finish
            with contextlib.suppress(queue.Empty):
                items.get(timeout=0.05)
        raise
    finally:
        worker.join()
    if got.error is not None:
        raise got.error
