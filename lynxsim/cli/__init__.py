"""The ``lynxsim`` command line: parses arguments and calls the library.

Each sub-command lives in its own module exposing ``register(subparsers)``;
the handler it sets returns the process exit code. Errors the user can cause
(any :class:`~lynxsim.errors.LynxsimError`, bad files) print one line on
stderr and exit non-zero, never a traceback.

This module imports nothing but :mod:`os`, :mod:`signal` and :mod:`sys`
(loaded with the interpreter): :func:`run`, the entry point, handles Ctrl-C
and SIGTERM from its first instruction, before the parser and the
sub-commands (:mod:`lynxsim.cli.program`) are imported.
"""

from __future__ import annotations

import os
import signal
import sys
from typing import TYPE_CHECKING, NoReturn

if TYPE_CHECKING:
    import argparse
    from collections.abc import Sequence
    from types import FrameType

__all__ = ["Terminated", "build_parser", "interruption", "main", "on_sigterm", "run"]

_EXIT_INTERRUPTED = 130
_EXIT_TERMINATED = 128 + signal.SIGTERM


class Terminated(BaseException):
    """SIGTERM arrived: unwinds like Ctrl-C, so that every partial output is removed."""


def on_sigterm(signum: int, frame: FrameType | None) -> NoReturn:
    """The SIGTERM handler: raises :class:`Terminated`."""
    raise Terminated


def interruption(exc: BaseException) -> KeyboardInterrupt | Terminated | None:
    """The Ctrl-C or SIGTERM behind ``exc``, if any.

    A signal that arrives while a native extension initialises (MuJoCo's) comes
    back as ``ImportError: initialization failed`` caused by it.
    """
    seen: BaseException | None = exc
    while seen is not None:
        if isinstance(seen, KeyboardInterrupt | Terminated):
            return seen
        seen = seen.__cause__ or seen.__context__
    return None


def build_parser() -> argparse.ArgumentParser:
    """The full argument parser with every sub-command (:mod:`lynxsim.cli.program`)."""
    from lynxsim.cli.program import build_parser as build

    return build()


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; returns the exit code (:func:`lynxsim.cli.program.main`).

    Ctrl-C exits 130 and SIGTERM 143, each after removing the partial outputs of
    the run (temporary files of :func:`lynxsim.fileio.atomic_path`).
    """
    from lynxsim.cli.program import main as program_main

    return program_main(argv)


def run() -> NoReturn:
    """The ``lynxsim`` program: :func:`main`, then exit with its code.

    Ctrl-C and SIGTERM are handled from its first instruction on, the import of
    the sub-commands included: one line on stderr, exit 130 or 143.

    After Ctrl-C or SIGTERM (the partial outputs already removed) the process
    ends at once, skipping the interpreter's shutdown: objects of a native
    library interrupted mid-call (an OMPL search) would otherwise be reported
    as leaked on stderr, breaking the one-line rule.
    """
    signal.signal(signal.SIGTERM, on_sigterm)  # first: a signal from here on is one line
    try:
        try:
            code = main()
        except ImportError as exc:  # a signal while a native module initialised
            found = interruption(exc)
            if found is None:
                raise
            raise found from None
    except KeyboardInterrupt:  # before main's own handling began
        code = _EXIT_INTERRUPTED
        print("lynxsim: interrupted", file=sys.stderr)
    except Terminated:
        code = _EXIT_TERMINATED
        print("lynxsim: terminated", file=sys.stderr)
    for signum in (signal.SIGINT, signal.SIGTERM):  # the command has ended: its code stands
        signal.signal(signum, signal.SIG_IGN)
    if code in (_EXIT_INTERRUPTED, _EXIT_TERMINATED):
        sys.stdout.flush()
        sys.stderr.flush()
        os._exit(code)
    sys.exit(code)
