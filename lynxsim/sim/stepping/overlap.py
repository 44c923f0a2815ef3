"""Native stepping shared between helper threads and this one, the Python work done here.

``mujoco.rollout`` and ``mujoco.batch`` release the GIL while they step, so
helper threads stepping natively overlap with the caller's thread, which turns
what they stepped into records (contacts, clearances: Python and short MuJoCo
calls that hold the GIL). :func:`share_stepping` runs such work: each *source*
is an iterator whose ``next()`` steps one chunk natively; a helper thread
steps whatever source is free, and the caller's thread consumes each stepped
chunk and, when none is waiting, steps a free source itself, so that neither
CPU idles while there is stepping left. :func:`cpu_count` says how many CPUs
there are to share.
"""

from __future__ import annotations

import os
import queue
import threading
from collections.abc import Callable, Iterator, Sequence
from enum import Enum
from typing import TypeVar

__all__ = ["cpu_count", "share_stepping"]

T = TypeVar("T")


def cpu_count() -> int:
    """How many CPUs this process may run on."""
    if hasattr(os, "sched_getaffinity"):
        return len(os.sched_getaffinity(0))
    return os.cpu_count() or 1


class _State(Enum):
    READY = 1  # free to step
    STEPPING = 2  # a thread is stepping it
    PARKED = 3  # as many chunks as allowed wait to be consumed
    DONE = 4  # exhausted (or failed)


class _End:
    """A source is exhausted (with the exception it raised, if it failed)."""

    def __init__(self, error: BaseException | None = None) -> None:
        self.error = error


def share_stepping(
    sources: Sequence[Iterator[T]],
    consume: Callable[[T], None],
    *,
    helpers: int,
    ahead: int = 2,
) -> None:
    """Exhaust every source, feeding each item to ``consume`` in the caller's thread.

    Items of one source are consumed in the order it yields them; a source is
    never advanced by two threads at once, nor more than ``ahead`` items ahead
    of what was consumed of it. With ``helpers`` 0 one thread does everything:
    one item of each live source in turn, each consumed as soon as it is made.

    Args:
        sources: The iterators (each ``next()`` typically steps a chunk natively).
        consume: Called with each item, in the caller's thread.
        helpers: Helper threads that advance sources (0: none).
        ahead: Most items of one source made but not yet consumed.

    Raises:
        Whatever a source or ``consume`` raised (the helpers are stopped first).
    """
    if helpers <= 0:
        live = list(sources)
        while live:
            for source in list(live):
                made = next(source, _End())
                if isinstance(made, _End):
                    live.remove(source)
                else:
                    consume(made)
        return
    lock = threading.Condition()
    state = [_State.READY] * len(sources)
    pending = [0] * len(sources)  # items made, not yet consumed
    count = [0] * len(sources)  # items made
    results: queue.Queue[tuple[int, T | _End]] = queue.Queue()
    stopping = False
    idle = 0  # helpers waiting for a source to step

    def take() -> int | None:
        """The ready source least advanced, now marked as stepping (call with the lock held).

        Keeping the sources abreast lets them end together, in parallel.
        """
        ready = [g for g, s in enumerate(state) if s is _State.READY]
        if not ready:
            return None
        g = min(ready, key=count.__getitem__)
        state[g] = _State.STEPPING
        return g

    def advance(g: int) -> None:
        """Step source g once (without the lock) and hand over what it made."""
        try:
            item: T | _End = next(sources[g], _End())
        except BaseException as error:  # handed to the caller's thread
            item = _End(error)
        with lock:
            if isinstance(item, _End):
                state[g] = _State.DONE
            else:
                pending[g] += 1
                count[g] += 1
                state[g] = _State.READY if pending[g] < ahead else _State.PARKED
                lock.notify_all()
            results.put((g, item))  # under the lock: before another thread steps g again

    def help_out() -> None:
        nonlocal idle
        while True:
            with lock:
                g = take()
                while g is None and not stopping:
                    idle += 1
                    lock.wait()
                    idle -= 1
                    g = take()
                if stopping:
                    if g is not None:
                        state[g] = _State.DONE
                    return
            assert g is not None
            advance(g)

    threads: list[threading.Thread] = []
    try:
        for i in range(helpers):  # a helper that cannot start stops those that did
            thread = threading.Thread(target=help_out, name=f"lynxsim-stepper-{i}", daemon=True)
            thread.start()
            threads.append(thread)
        ended = 0
        while ended < len(sources):
            try:
                g, item = results.get_nowait()
            except queue.Empty:
                with lock:
                    mine = None if idle else take()
                if mine is not None:  # nothing to consume, no helper free: step here
                    advance(mine)
                    continue
                g, item = results.get()
            if isinstance(item, _End):
                if item.error is not None:
                    raise item.error
                ended += 1
                continue
            consume(item)
            with lock:
                pending[g] -= 1
                if state[g] is _State.PARKED:
                    state[g] = _State.READY
                    lock.notify_all()
    finally:
        with lock:
            stopping = True
            lock.notify_all()
        for thread in threads:
            thread.join()
