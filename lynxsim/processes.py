"""Worker processes that end when the process that started them dies.

A pool's workers outlive a parent killed with SIGKILL (an out-of-memory killer,
a batch system): adopted by init, they hold the caller's stdout and stderr open
and a caller waiting for end of file waits forever. :func:`die_with_parent`,
called first in each worker (a pool's ``initializer``), prevents that in two
ways: on Linux the kernel sends the worker SIGKILL when its parent ends
(``prctl(PR_SET_PDEATHSIG)``), and everywhere a daemon thread polls the parent's
id and ends the worker once it has changed (the parent died and the worker was
adopted). :func:`pool_initializer` wraps a pool's own initializer with it.
"""

from __future__ import annotations

import ctypes
import ctypes.util
import os
import signal
import sys
import threading
from collections.abc import Callable

__all__ = ["POLL_S", "die_with_parent", "pool_initializer"]

POLL_S = 0.5
"""How often the watchdog thread looks at the parent's id [s]."""

_PR_SET_PDEATHSIG = 1  # <linux/prctl.h>


def _kernel_signal() -> bool:
    """Ask Linux to send this process SIGKILL when its parent thread ends; whether it took."""
    if not sys.platform.startswith("linux"):
        return False
    try:
        libc = ctypes.CDLL(ctypes.util.find_library("c"), use_errno=True)
        return int(libc.prctl(_PR_SET_PDEATHSIG, int(signal.SIGKILL), 0, 0, 0)) == 0
    except (OSError, AttributeError):
        return False


def _end() -> None:
    os.kill(os.getpid(), signal.SIGKILL)


def _watch(parent: int) -> None:
    event = threading.Event()
    while not event.wait(POLL_S):
        if os.getppid() != parent:
            _end()


def die_with_parent(parent: int) -> None:
    """End this process (SIGKILL) as soon as the process ``parent`` is gone.

    Args:
        parent: The id of the process that started this one (``os.getpid()`` there).
    """
    _kernel_signal()
    if os.getppid() != parent:  # it died before the signal was asked for
        _end()
    threading.Thread(target=_watch, args=(parent,), name="parent-watchdog", daemon=True).start()


def _init_then(parent: int, initializer: Callable[..., object] | None, *args: object) -> None:
    die_with_parent(parent)
    if initializer is not None:
        initializer(*args)


def pool_initializer(
    initializer: Callable[..., object] | None = None, *args: object
) -> tuple[Callable[..., None], tuple[object, ...]]:
    """``(initializer, initargs)`` for a process pool whose workers die with this process.

    Args:
        initializer: The pool's own initializer, called after, or None.
        args: Its arguments.

    Returns:
        What to pass as the pool's ``initializer`` and ``initargs``.
    """
    return _init_then, (os.getpid(), initializer, *args)
