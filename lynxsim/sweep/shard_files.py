"""A sweep's saved shards: each file says which sweep and shard it holds, and is checked.

A shard file is the shard's rows as a table NPZ (:mod:`lynxsim.sweep.table`)
with three more arrays: ``_sweep`` (the sweep's digest,
:attr:`lynxsim.sweep.spec.SweepSpec.digest`), ``_shard`` (its index) and
``_checksum`` (SHA-256 of every column's dtype, shape and bytes). A file is
used only when it reads whole, names this sweep and this shard, holds the
shard's number of rows and its checksum matches; anything else (truncated,
bit-flipped, another shard's file, an edited value) is a :class:`ShardFileError`
saying why, and the runner computes the shard again.
"""

from __future__ import annotations

import hashlib
import os
from collections.abc import Callable, Mapping
from pathlib import Path

import numpy as np
import numpy.typing as npt

from lynxsim.errors import InvalidInputError
from lynxsim.fileio import atomic_path, safe_stem
from lynxsim.sweep.spec import SweepSpec
from lynxsim.sweep.table import COLUMNS, NPZ_READ_ERRORS, Table, finish

__all__ = [
    "Notice",
    "ShardFileError",
    "checksum",
    "read_shard",
    "saved_shard",
    "shard_folder",
    "shard_path",
    "write_shard",
]

_KEYS = ("_sweep", "_shard", "_checksum")

Notice = Callable[[str], None]
"""Called with one line for the user (a saved shard that is computed again, and why)."""


class ShardFileError(InvalidInputError):
    """A saved shard that cannot be used: unreadable, of another sweep or shard, or altered."""


def checksum(table: Mapping[str, npt.NDArray[np.generic]]) -> str:
    """SHA-256 (hex) of a finished table's columns: names, dtypes, shapes and bytes, in order."""
    h = hashlib.sha256()
    for name in COLUMNS:
        column = np.ascontiguousarray(table[name])
        h.update(f"\0{name}\0{column.dtype.str}\0{column.shape}\0".encode())
        h.update(column.tobytes())
    return h.hexdigest()


def write_shard(
    dest: str | os.PathLike[str],
    table: Mapping[str, npt.NDArray[np.generic]],
    *,
    sweep: str,
    index: int,
) -> Path:
    """Save a shard's rows with what identifies them, atomically.

    Args:
        dest: The file (``.npz``).
        table: The shard's rows.
        sweep: The sweep's digest.
        index: The shard's index.
    """
    done = finish(table)
    marks = {
        "_sweep": np.array(sweep),
        "_shard": np.array(index, dtype=np.int64),
        "_checksum": np.array(checksum(done)),
    }
    with atomic_path(dest) as tmp:
        np.savez_compressed(tmp, **done, **marks)  # type: ignore[arg-type]
    return Path(dest)


def read_shard(path: str | os.PathLike[str], *, sweep: str, index: int, rows: int) -> Table:
    """A saved shard, verified: it must be shard ``index`` of sweep ``sweep``, whole.

    Args:
        path: The file.
        sweep: The sweep's digest.
        index: The shard's index.
        rows: Its number of rows.

    Returns:
        Its rows.

    Raises:
        ShardFileError: Why it cannot be used.
    """
    try:
        with np.load(path, allow_pickle=False) as data:
            arrays = {name: data[name] for name in data.files}
    except NPZ_READ_ERRORS as exc:
        raise ShardFileError(f"unreadable ({type(exc).__name__})") from None
    if not isinstance(arrays, dict) or any(k not in arrays for k in _KEYS):
        raise ShardFileError("carries no sweep, shard or checksum")
    marks = {k: arrays.pop(k) for k in _KEYS}
    if any(m.shape != () for m in marks.values()):
        raise ShardFileError("malformed sweep, shard or checksum")
    if marks["_sweep"].dtype.kind != "U" or str(marks["_sweep"]) != sweep:
        raise ShardFileError("belongs to another sweep")
    if marks["_shard"].dtype.kind != "i" or int(marks["_shard"]) != index:
        raise ShardFileError("belongs to another shard")
    try:
        table = finish(arrays)
    except InvalidInputError as exc:
        raise ShardFileError(str(exc)) from None
    if any(column.shape != (rows,) for column in table.values()):
        raise ShardFileError(f"does not hold the shard's {rows} rows")
    if marks["_checksum"].dtype.kind != "U" or str(marks["_checksum"]) != checksum(table):
        raise ShardFileError("altered (checksum mismatch)")
    return table


def shard_folder(spec: SweepSpec, out: Path) -> Path:
    """Where a sweep's shards are saved: ``out/STEM.shards/DIGEST``."""
    return out / f"{safe_stem(spec.name, 'sweep')}.shards" / spec.digest[:16]


def shard_path(folder: Path, index: int) -> Path:
    """Shard ``index``'s file in :func:`shard_folder`."""
    return folder / f"shard_{index:06d}.npz"


def saved_shard(
    path: Path, sweep: str, index: int, rows: int, notice: Notice | None
) -> Table | None:
    """A saved shard, verified (:func:`read_shard`); None where it must be computed.

    A missing file is computed without a word; one that cannot be used
    (unreadable, another sweep's or shard's, altered) is computed again with
    one line to ``notice`` saying which and why.
    """
    if not path.is_file():
        return None
    try:
        return read_shard(path, sweep=sweep, index=index, rows=rows)
    except ShardFileError as exc:
        reason = str(exc)
    if notice is not None:
        notice(f"shard {index} ({path.name}) {reason}: computed again")
    return None
