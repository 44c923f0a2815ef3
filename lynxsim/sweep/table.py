"""The result table of a sweep: one row per run, columns in SI units, CSV and NPZ on disk.

Columns (:data:`COLUMNS`), every length in metres and time in seconds:

========================  =======  =====================================================
column                    dtype    meaning
========================  =======  =====================================================
task                      str      task name
type                      str      trajectory type
planner_seed              int64    the planner's seed (planned runs), -1 for other types
cube_x_m, _y_m, _z_m      float    the cube's start
obstacle_x_m, _y_m        float    the swept obstacle's centre (NaN without one)
obstacle_radius_m         float    its radius (NaN for a box or without one)
verdict                   str      clear, collided, start_overlap, invalid or no_motion
collided                  bool     an obstacle was touched (start_overlap included)
first_contact_s           float    time of the first obstacle contact, NaN if none
                                   (and for start_overlap: before the motion)
first_obstacle            str      which obstacle was touched first ("" if none)
min_clearance_m           float    smallest robot-obstacle distance over the run
min_clearance_time_s      float    when
tool_max_error_m          float    tracking: largest tool-point error
tool_rms_error_m          float    tracking: RMS tool-point error
tool_final_error_m        float    distance to the final target after settling
max_torque_ratio          float    largest |servo torque| / stall torque
healthy                   int8     1 no MuJoCo warning or NaN, 0 not, -1 not determined
method                    str      recorded (judged on a recorded run), physics (a run
                                   of its own) or none
========================  =======  =====================================================

Rows judged on a recorded run (:mod:`lynxsim.sim.recorded`) whose obstacle
was touched leave the clearance, tracking and health NaN / -1: after the first
contact the real run differs from the recorded one, and only a run of its own
would tell (its verdict and first contact time are exact).
"""

from __future__ import annotations

import csv
import math
import os
import struct
import zipfile
import zlib
from collections.abc import Mapping, Sequence
from pathlib import Path

import numpy as np
import numpy.typing as npt

from lynxsim.errors import InvalidInputError
from lynxsim.fileio import atomic_path
from lynxsim.verdicts import Verdict

__all__ = [
    "COLUMNS",
    "NPZ_READ_ERRORS",
    "VERDICTS",
    "Table",
    "concat",
    "empty",
    "finish",
    "read_npz",
    "write_csv",
    "write_npz",
]

NPZ_READ_ERRORS: tuple[type[Exception], ...] = (
    OSError,
    ValueError,
    EOFError,
    KeyError,
    RuntimeError,
    NotImplementedError,
    OverflowError,
    struct.error,
    zipfile.BadZipFile,
    zlib.error,
)
"""What reading a damaged NPZ file can raise (NumPy, :mod:`zipfile`, :mod:`zlib`)."""

Table = dict[str, npt.NDArray[np.generic]]
"""Column name to column, every column of the same length."""

COLUMNS: dict[str, str] = {
    "task": "U",
    "type": "U",
    "planner_seed": "i8",
    "cube_x_m": "f8",
    "cube_y_m": "f8",
    "cube_z_m": "f8",
    "obstacle_x_m": "f8",
    "obstacle_y_m": "f8",
    "obstacle_radius_m": "f8",
    "verdict": "U",
    "collided": "?",
    "first_contact_s": "f8",
    "first_obstacle": "U",
    "min_clearance_m": "f8",
    "min_clearance_time_s": "f8",
    "tool_max_error_m": "f8",
    "tool_rms_error_m": "f8",
    "tool_final_error_m": "f8",
    "max_torque_ratio": "f8",
    "healthy": "i1",
    "method": "U",
}
"""Every column and its NumPy kind, in table order."""

VERDICTS = Verdict.labels()
"""The values of the ``verdict`` column (:class:`lynxsim.verdicts.Verdict`)."""


def empty(rows: int) -> Table:
    """A table of ``rows`` rows: NaN floats, -1 integers, False, empty strings."""
    out: Table = {}
    for name, kind in COLUMNS.items():
        if kind == "f8":
            out[name] = np.full(rows, np.nan)
        elif kind in ("i8", "i1"):
            out[name] = np.full(rows, -1, dtype=kind)
        elif kind == "?":
            out[name] = np.zeros(rows, dtype=bool)
        else:
            out[name] = np.full(rows, "", dtype=object)
    return out


def finish(table: Mapping[str, npt.NDArray[np.generic]]) -> Table:
    """Columns in table order, strings as fixed-width Unicode (no pickled objects).

    Raises:
        InvalidInputError: A column is missing, not one-dimensional, of another
            length than the others or not of its kind.
    """
    missing = [name for name in COLUMNS if name not in table]
    if missing:
        raise InvalidInputError(f"table lacks columns: {', '.join(missing)}")
    columns = {name: np.asarray(table[name]) for name in COLUMNS}
    flat = [name for name, column in columns.items() if column.ndim != 1]
    if flat:
        raise InvalidInputError(f"table columns not one-dimensional: {', '.join(flat)}")
    lengths = {len(column) for column in columns.values()}
    if len(lengths) > 1:
        raise InvalidInputError(f"table columns differ in length: {sorted(lengths)}")
    out: Table = {}
    for name, kind in COLUMNS.items():
        column = columns[name]
        if kind != "U" and column.dtype.kind in "USO":
            raise InvalidInputError(f"table column {name} holds text, not {kind} numbers")
        try:
            out[name] = column.astype(str) if kind == "U" else column.astype(kind)
        except (ValueError, TypeError) as exc:
            raise InvalidInputError(f"table column {name}: {exc}") from None
    return out


def concat(tables: Sequence[Mapping[str, npt.NDArray[np.generic]]]) -> Table:
    """Rows of several tables, in order."""
    if not tables:
        return finish(empty(0))
    finished = [finish(t) for t in tables]
    return {name: np.concatenate([t[name] for t in finished]) for name in COLUMNS}


def write_npz(dest: str | os.PathLike[str], table: Mapping[str, npt.NDArray[np.generic]]) -> Path:
    """Write the table as NPZ (one array per column), atomically."""
    done = finish(table)
    with atomic_path(dest) as tmp:
        np.savez_compressed(tmp, **done)  # type: ignore[arg-type]
    return Path(dest)


def read_npz(path: str | os.PathLike[str]) -> Table:
    """Read a table written by :func:`write_npz`.

    Raises:
        InvalidInputError: The file is not such a table.
        OSError: It cannot be read.
    """
    try:
        with np.load(path, allow_pickle=False) as data:
            table = {name: data[name] for name in data.files}
    except OSError:
        raise
    except NPZ_READ_ERRORS as exc:
        raise InvalidInputError(f"{path}: not a sweep table ({type(exc).__name__})") from None
    try:
        return finish(table)
    except InvalidInputError as exc:
        raise InvalidInputError(f"{path}: not a sweep table ({exc})") from None


def _cell(value: object, kind: str) -> str:
    if kind == "f8":
        number = float(value)  # type: ignore[arg-type]
        return "" if math.isnan(number) else repr(number)
    if kind == "?":
        return "true" if value else "false"
    if kind == "i1":
        return "" if int(value) < 0 else str(int(value))  # type: ignore[call-overload]
    return str(value)


def write_csv(dest: str | os.PathLike[str], table: Mapping[str, npt.NDArray[np.generic]]) -> Path:
    """Write the table as CSV with a header, atomically.

    Floats are written exactly (``repr``: they read back bit for bit); NaN and
    an undetermined ``healthy`` are empty cells.
    """
    done = finish(table)
    rows = len(done["task"])
    columns = [(name, kind, done[name].tolist()) for name, kind in COLUMNS.items()]
    with atomic_path(dest) as tmp, tmp.open("w", newline="", encoding="utf-8") as handle:
        writer = csv.writer(handle)
        writer.writerow(list(COLUMNS))
        for i in range(rows):
            writer.writerow([_cell(values[i], kind) for _, kind, values in columns])
    return Path(dest)
