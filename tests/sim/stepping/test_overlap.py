"""Stepping shared between helper threads and the caller's: every item, in order, once.

:func:`lynxsim.sim.stepping.overlap.share_stepping` drives real playbacks and batches
(``tests/sim/stepping/test_batch.py``, ``tests/sim/stepping/test_records.py``); here its
contract is checked on plain iterators, whose ``next()`` may sleep (as a
native step releases the GIL) or raise, with zero, one and two helpers.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Iterator

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from lynxsim.sim.stepping.overlap import share_stepping


class Source:
    """Yields (name, k) for k < length; checks it is never advanced by two threads at once."""

    def __init__(self, name: int, length: int, pause_s: float, log: list[str]) -> None:
        self.name, self.length, self.pause_s, self.log = name, length, pause_s, log
        self.busy = threading.Lock()
        self.made = 0

    def __iter__(self) -> Iterator[tuple[int, int]]:
        return self

    def __next__(self) -> tuple[int, int]:
        if not self.busy.acquire(blocking=False):
            raise AssertionError(f"source {self.name} advanced by two threads at once")
        try:
            if self.made == self.length:
                raise StopIteration
            time.sleep(self.pause_s)  # releases the GIL, as a native step does
            self.made += 1
            self.log.append(f"made {self.name}")
            return self.name, self.made - 1
        finally:
            self.busy.release()


def _helpers_alive() -> list[threading.Thread]:
    return [t for t in threading.enumerate() if t.name.startswith("lynxsim-stepper")]


@settings(max_examples=40, deadline=None)
@given(
    lengths=st.lists(st.integers(0, 12), min_size=1, max_size=5),
    helpers=st.integers(0, 2),
    ahead=st.integers(1, 3),
    pause_s=st.sampled_from([0.0, 0.0005]),
)
def test_every_item_is_consumed_once_in_its_sources_order(lengths, helpers, ahead, pause_s):
    log: list[str] = []
    sources = [Source(i, n, pause_s, log) for i, n in enumerate(lengths)]
    got: dict[int, list[int]] = {i: [] for i in range(len(lengths))}
    consumer = threading.current_thread()

    def consume(item: tuple[int, int]) -> None:
        assert threading.current_thread() is consumer
        name, k = item
        # never more than `ahead` items of a source made and not yet consumed
        assert sources[name].made - len(got[name]) <= ahead
        got[name].append(k)
        log.append(f"used {name}")

    share_stepping(sources, consume, helpers=helpers, ahead=ahead)
    assert got == {i: list(range(n)) for i, n in enumerate(lengths)}
    assert not _helpers_alive()


def test_without_helpers_each_item_is_consumed_before_the_next_is_made():
    log: list[str] = []
    sources = [Source(0, 3, 0.0, log), Source(1, 2, 0.0, log)]
    share_stepping(sources, lambda item: log.append(f"used {item[0]}"), helpers=0)
    assert log == [
        "made 0", "used 0", "made 1", "used 1",
        "made 0", "used 0", "made 1", "used 1",
        "made 0", "used 0",
    ]  # fmt: skip


def test_a_helper_steps_while_the_caller_consumes():
    """Items made on a helper thread while the caller was consuming another (both sleep)."""
    spans: list[tuple[str, float, float]] = []

    class Timed(Source):
        def __next__(self) -> tuple[int, int]:
            start = time.perf_counter()
            item = super().__next__()
            spans.append((threading.current_thread().name, start, time.perf_counter()))
            return item

    def consume(item: tuple[int, int]) -> None:
        start = time.perf_counter()
        time.sleep(0.01)
        spans.append(("consume", start, time.perf_counter()))

    share_stepping([Timed(i, 4, 0.01, []) for i in range(2)], consume, helpers=1)
    made = [(a, b) for name, a, b in spans if name.startswith("lynxsim-stepper")]
    used = [(a, b) for name, a, b in spans if name == "consume"]
    assert made
    assert any(a < d and c < b for a, b in made for c, d in used)


def test_a_helper_that_cannot_start_stops_the_others(monkeypatch):
    """Out of threads after one helper started: that one is stopped, the error raised."""
    started = 0
    start = threading.Thread.start

    def start_twice(thread: threading.Thread) -> None:
        nonlocal started
        started += 1
        if started > 1:
            raise RuntimeError("can't start new thread")
        start(thread)

    monkeypatch.setattr(threading.Thread, "start", start_twice)
    with pytest.raises(RuntimeError, match="can't start new thread"):
        share_stepping([Source(0, 20, 0.001, [])], lambda item: None, helpers=3)
    monkeypatch.undo()
    assert not _helpers_alive()


@pytest.mark.parametrize("helpers", [0, 1, 2])
def test_a_failing_source_stops_everything_and_raises(helpers):
    def failing() -> Iterator[int]:
        yield 1
        raise ValueError("stepping failed")

    with pytest.raises(ValueError, match="stepping failed"):
        share_stepping([Source(0, 50, 0.001, []), failing()], lambda item: None, helpers=helpers)
    assert not _helpers_alive()


@pytest.mark.parametrize("helpers", [0, 1, 2])
def test_a_failing_consumer_stops_the_helpers_and_raises(helpers):
    def consume(item: tuple[int, int]) -> None:
        if item == (1, 2):
            raise RuntimeError("recording failed")

    sources = [Source(0, 50, 0.001, []), Source(1, 50, 0.001, [])]
    with pytest.raises(RuntimeError, match="recording failed"):
        share_stepping(sources, consume, helpers=helpers)
    assert not _helpers_alive()
    assert sources[0].made < 50  # stopped early, not run to the end
