"""Error context for the command line: errors that arise from a task file name the file."""

from __future__ import annotations

import contextlib
import os
from collections.abc import Iterator

from lynxsim.errors import LynxsimError, TaskFileError

__all__ = ["TaskRunError", "about_task"]


class TaskRunError(LynxsimError):
    """A task file loaded, but building or running it failed; the message names the file.

    Attributes:
        path: The task file.
        cause: The original error (also the ``__cause__``).
    """

    def __init__(self, path: str, cause: LynxsimError) -> None:
        super().__init__(f"{path}: {cause}")
        self.path = path
        self.cause = cause


@contextlib.contextmanager
def about_task(path: str | os.PathLike[str]) -> Iterator[None]:
    """Prefix any :class:`LynxsimError` raised inside with the task file's path.

    :class:`TaskFileError` already names its file and passes unchanged.
    """
    try:
        yield
    except TaskFileError:
        raise
    except LynxsimError as exc:
        raise TaskRunError(os.fspath(path), exc) from exc
