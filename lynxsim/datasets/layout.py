"""Where and how a dataset is stored: its format, its id (a folder inside a root), atomically.

A dataset id is Minari's ``namespace/name-vN`` (e.g. ``lynxsim/pick-and-place-v1/expert-v0``)
and doubles as the dataset's path inside the root folder, for both formats; a
Minari root is what ``MINARI_DATASETS_PATH`` points to. :func:`atomic_folder`
writes into a hidden temporary folder beside the destination and renames it only
when the writer has finished and checked its output: a killed run leaves no
folder under the dataset's name (only, after ``kill -9``, a hidden ``.NAME.*.tmp``).
"""

from __future__ import annotations

import contextlib
import enum
import os
import re
import shutil
import tempfile
from collections.abc import Iterator
from pathlib import Path

from lynxsim.errors import InvalidInputError, OutputPathError, short
from lynxsim.fileio import check_destination

__all__ = [
    "MAX_ID_LENGTH",
    "DatasetFormat",
    "atomic_folder",
    "check_dataset_id",
    "check_new_folder",
    "dataset_folder",
    "default_dataset_id",
]

MAX_ID_LENGTH = 200
"""Longest dataset id (characters)."""

_ID = re.compile(r"[A-Za-z0-9][A-Za-z0-9_-]*(/[A-Za-z0-9][A-Za-z0-9_-]*)*-v[0-9]+")


class DatasetFormat(enum.Enum):
    """How a dataset is stored.

    NPZ: ``episodes.npz`` and ``metadata.json`` (NumPy only; :mod:`lynxsim.datasets.npz`).
    MINARI: Minari's standard format, HDF5 storage (extra ``lynxsim[datasets]``;
        :mod:`lynxsim.datasets.minari_writer`).
    """

    NPZ = "npz"
    MINARI = "minari"


def default_dataset_id(env_id: str) -> str:
    """``lynxsim/<env in kebab case>/expert-v0``, e.g. ``lynxsim/pick-and-place-v1/expert-v0``."""
    name = env_id.removeprefix("Lynx")
    kebab = re.sub(r"(?<=[a-z0-9])(?=[A-Z])", "-", name).lower()
    return f"lynxsim/{kebab}/expert-v0"


def check_dataset_id(dataset_id: str) -> str:
    """``dataset_id`` if it is a Minari id that is also a safe relative path, else raise.

    Valid: ``name-vN`` or ``namespace/.../name-vN``; every part ASCII letters,
    digits, ``_`` and ``-``, starting with a letter or digit (no ``..``, no hidden
    or absolute paths); a version number at the end.

    Raises:
        InvalidInputError: Anything else (the message shows the form).
    """
    if not isinstance(dataset_id, str):
        raise InvalidInputError(f"dataset_id must be a string, got {short(dataset_id)}")
    if len(dataset_id) > MAX_ID_LENGTH or not _ID.fullmatch(dataset_id):
        raise InvalidInputError(
            f"dataset id must look like 'namespace/name-v0' (letters, digits, '_', '-'; "
            f"at most {MAX_ID_LENGTH} characters), got {short(dataset_id)}"
        )
    return dataset_id


def dataset_folder(root: str | os.PathLike[str], dataset_id: str) -> Path:
    """The folder of a dataset: ``root / dataset_id``.

    Raises:
        InvalidInputError: See :func:`check_dataset_id`.
    """
    return Path(root) / check_dataset_id(dataset_id)


def check_new_folder(dest: str | os.PathLike[str]) -> Path:
    """Refuse a destination that exists (of any kind), or whose parent cannot be a folder.

    Raises:
        OutputPathError: ``dest`` exists, or a part of its path is not a folder.
    """
    dest = Path(dest)
    if os.path.lexists(dest):
        raise OutputPathError(
            f"will not replace {dest}: it exists (remove it, or choose another root or dataset id)"
        )
    return check_destination(dest)


@contextlib.contextmanager
def atomic_folder(dest: str | os.PathLike[str]) -> Iterator[Path]:
    """Yield a new temporary folder beside ``dest``; rename it to ``dest`` on success.

    On any exception (``KeyboardInterrupt`` and the CLI's SIGTERM included) the
    temporary folder and everything in it are removed, and ``dest`` never appears.

    Raises:
        OutputPathError: ``dest`` exists (checked before and again just before
            the rename), or a part of its path is not a folder.
    """
    dest = check_new_folder(dest)
    dest.parent.mkdir(parents=True, exist_ok=True)
    tmp = Path(tempfile.mkdtemp(prefix=f".{dest.name}.", suffix=".tmp", dir=dest.parent))
    try:
        yield tmp
        # mkdtemp creates the folder private (0700); give it the usual permissions.
        umask = os.umask(0)
        os.umask(umask)
        tmp.chmod(0o777 & ~umask)
        # dest may have appeared while we wrote, and a rename replaces an empty folder.
        check_new_folder(dest)
        os.rename(tmp, dest)
    except BaseException:
        shutil.rmtree(tmp, ignore_errors=True)
        raise
