"""Where and how a dataset is stored: its format, its id (a folder inside a root), atomically.

A dataset id is Minari's ``namespace/name-vN`` (e.g. ``lynxsim/pick-and-place-v1/expert-v0``)
and doubles as the dataset's path inside the root folder, for every format; a
Minari root is what ``MINARI_DATASETS_PATH`` points to. Datasets are written with
:func:`lynxsim.fileio.atomic_folder`: a killed run leaves no folder under the
dataset's name (only, after ``kill -9``, a hidden ``.NAME.*.tmp``).
"""

from __future__ import annotations

import enum
import os
import re
from pathlib import Path

from lynxsim.errors import InvalidInputError, short

__all__ = [
    "MAX_ID_LENGTH",
    "NEW_FOLDER_HINT",
    "DatasetFormat",
    "check_dataset_id",
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
    LEROBOT: LeRobot's ``LeRobotDataset`` v3.0: parquet, JSON and MP4 (extra
        ``lynxsim[datasets]``; :mod:`lynxsim.datasets.lerobot_writer`).
    """

    NPZ = "npz"
    MINARI = "minari"
    LEROBOT = "lerobot"


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


NEW_FOLDER_HINT = "remove it, or choose another root or dataset id"
"""What an existing dataset folder's error suggests."""
