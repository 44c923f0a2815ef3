"""The ``lynxsim`` command line: parses arguments and calls the library.

Each sub-command lives in its own module exposing ``register(subparsers)``;
the handler it sets returns the process exit code. Errors the user can cause
(any :class:`~lynxsim.errors.LynxsimError`, bad files) print one line on
stderr and exit non-zero, never a traceback.
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence
from typing import Any, NoReturn

from lynxsim.cli import arm, demo, env, play, rrr, traj
from lynxsim.errors import LynxsimError

__all__ = ["build_parser", "main"]

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


def build_parser() -> argparse.ArgumentParser:
    """The full argument parser with every sub-command."""
    parser = _OneLineParser(
        prog="lynxsim",
        description="Simulate the report's Lynxmotion arm and 3-RRR robot. "
        "Lengths are in mm and angles in degrees at the command line unless a flag says otherwise.",
    )
    sub = parser.add_subparsers(required=True, parser_class=_OneLineParser)
    for module in (arm, traj, play, rrr, demo, env):
        module.register(sub)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; returns the exit code."""
    args = build_parser().parse_args(argv)
    try:
        code: int = args.handler(args)
    except (LynxsimError, OSError) as exc:
        print(f"lynxsim: error: {exc}", file=sys.stderr)
        return EXIT_ERROR
    except KeyboardInterrupt:
        print("lynxsim: interrupted", file=sys.stderr)
        return 130
    return code
