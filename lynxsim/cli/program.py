"""The command line's parser and :func:`main`: every sub-command, errors as one line.

Imported by :func:`lynxsim.cli.run` once its signal handlers are installed
(see :mod:`lynxsim.cli`).
"""

from __future__ import annotations

import argparse
import contextlib
import signal
import sys
import threading
from collections.abc import Iterator, Sequence
from typing import Any, NoReturn

from lynxsim.cli import Terminated, interruption, on_sigterm
from lynxsim.errors import LynxsimError

__all__ = ["EXIT_ERROR", "EXIT_USAGE", "build_parser", "main"]

EXIT_USAGE = 2
EXIT_ERROR = 1


def _is_float_literal(text: str) -> bool:
    """Whether ``float()`` reads ``text`` (``-9e1``, ``-.5``, ``-1.5E+2``, ``-inf``, ``nan``)."""
    try:
        float(text)
    except ValueError:
        return False
    return True


class _OneLineParser(argparse.ArgumentParser):
    """Argument parser whose errors are one line, not usage plus message.

    Any negative float literal is read as a value, never as an option: plain
    argparse takes ``-90`` and ``-.5`` for numbers but ``-9e1`` or ``-inf`` for
    unknown options. Sub-parsers are of this class too (``parser_class``).
    """

    def error(self, message: str) -> NoReturn:
        self.exit(EXIT_USAGE, f"{self.prog}: error: {message}\n")

    def _parse_optional(self, arg_string: str) -> Any:
        if (
            arg_string.startswith("-")
            and arg_string not in self._option_string_actions
            and _is_float_literal(arg_string)
        ):
            return None  # a positional value
        return super()._parse_optional(arg_string)


@contextlib.contextmanager
def _signals_deferred() -> Iterator[None]:
    """Hold Ctrl-C and SIGTERM back until the block ends (then they arrive as usual).

    The sub-commands import native extensions (MuJoCo, OMPL, Ruckig); a Python
    exception raised by a signal inside such a module's C++ initialisation cannot
    unwind through it and aborts the process (exit -6 with a C++ traceback). Blocked
    at the OS level, the signal waits and is raised right after the imports.
    """
    deferred = {signal.SIGINT, signal.SIGTERM}
    signal.pthread_sigmask(signal.SIG_BLOCK, deferred)
    try:
        yield
    finally:
        signal.pthread_sigmask(signal.SIG_UNBLOCK, deferred)


def build_parser() -> argparse.ArgumentParser:
    """The full argument parser with every sub-command."""
    with _signals_deferred():
        from lynxsim.cli import arm, dataset, demo, env, plan, play, real, rrr, sweep, traj, view

    parser = _OneLineParser(
        prog="lynxsim",
        description="Simulate the report's Lynxmotion arm and 3-RRR robot. "
        "Lengths are in mm and angles in degrees at the command line unless a flag says otherwise.",
    )
    sub = parser.add_subparsers(required=True, parser_class=_OneLineParser)
    for module in (arm, traj, plan, play, view, rrr, demo, env, dataset, sweep, real):
        module.register(sub)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; returns the exit code.

    Ctrl-C exits 130 and SIGTERM 143, each after removing the partial outputs of
    the run (temporary files of :func:`lynxsim.fileio.atomic_path`).
    """
    in_main_thread = threading.current_thread() is threading.main_thread()
    previous = signal.signal(signal.SIGTERM, on_sigterm) if in_main_thread else None
    try:
        args = build_parser().parse_args(argv)
        code: int = args.handler(args)
    except (LynxsimError, OSError) as exc:
        print(f"lynxsim: error: {_one_line(exc)}", file=sys.stderr)
        return EXIT_ERROR
    except KeyboardInterrupt:
        print("lynxsim: interrupted", file=sys.stderr)
        return 130
    except Terminated:
        print("lynxsim: terminated", file=sys.stderr)
        return 128 + signal.SIGTERM
    except ImportError as exc:  # a signal while a native module initialised (MuJoCo's)
        found = interruption(exc)
        if found is None:
            raise
        if isinstance(found, Terminated):
            print("lynxsim: terminated", file=sys.stderr)
            return 128 + signal.SIGTERM
        print("lynxsim: interrupted", file=sys.stderr)
        return 130
    finally:
        if in_main_thread:
            signal.signal(signal.SIGTERM, previous)
    return code


def _one_line(exc: BaseException) -> str:
    """An error's message on one line (multi-line messages joined with ' | ')."""
    return " | ".join(line.strip() for line in str(exc).splitlines() if line.strip())
