"""Measured joint angles of a real run against the simulated run its log carries.

Hitec analog servos report nothing (``QP`` returns the commanded pulse), so
what the arm really did comes from a sensor the user has (a camera, an IMU,
potentiometer taps) as a CSV file: a ``time_s`` column on the log's clock
(seconds from the first line sent) and one ``<joint>_deg`` column per joint
measured (any subset). The log's header holds the digital twin's simulated
joints on the same clock; they are interpolated at the measured times.
"""

from __future__ import annotations

import csv
import io
import math
import os
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from lynxsim.errors import DataFileError, InvalidInputError
from lynxsim.real.log import RunLog

__all__ = ["JointComparison", "compare_measured", "read_measured"]

_MAX_BYTES = 64 << 20
_MAX_ROWS = 1_000_000


@dataclass(frozen=True)
class JointComparison:
    """One measured joint against the simulated run.

    Attributes:
        joint: Its name.
        samples: Measured samples inside the simulated run's time span.
        max_error_rad: Largest |measured - simulated| [rad].
        max_error_time_s: When, on the log's clock [s].
        rms_error_rad: RMS of the same [rad].
    """

    joint: str
    samples: int
    max_error_rad: float
    max_error_time_s: float
    rms_error_rad: float


def read_measured(
    path: str | os.PathLike[str], joint_names: tuple[str, ...]
) -> tuple[np.ndarray, dict[str, np.ndarray]]:
    """Read a measured-angles CSV: times [s] and, per joint present, angles [rad].

    Raises:
        DataFileError: Not UTF-8 CSV, no ``time_s`` column, an unknown column, a
            value that is not a finite number (names the row and column), or times
            that do not increase.
        OSError: The file cannot be read.
    """
    p = Path(path)
    if p.exists() and not p.is_file():
        raise DataFileError(str(p), None, "not a regular file")
    with p.open("rb") as f:
        raw = f.read(_MAX_BYTES + 1)
    if len(raw) > _MAX_BYTES:
        raise DataFileError(str(p), None, f"larger than {_MAX_BYTES} bytes")
    try:
        text = raw.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        raise DataFileError(str(p), None, f"not UTF-8 text ({exc.reason})") from None
    try:
        rows = list(csv.reader(io.StringIO(text)))
    except csv.Error as exc:
        raise DataFileError(str(p), None, f"not CSV: {exc}") from None
    if not rows:
        raise DataFileError(str(p), None, "empty")
    header = [h.strip() for h in rows[0]]
    allowed = ["time_s", *(f"{n}_deg" for n in joint_names)]
    for h in header:
        if h not in allowed:
            shown = h if h.isprintable() and len(h) < 60 else repr(h)[:60]
            raise DataFileError(
                str(p), f"column {shown}", f"unknown; expected: {', '.join(allowed)}"
            )
    if "time_s" not in header or len(set(header)) != len(header) or len(header) < 2:
        raise DataFileError(
            str(p), "header", "needs time_s, at least one <joint>_deg column, no column twice"
        )
    body = rows[1:]
    if not body or len(body) > _MAX_ROWS:
        raise DataFileError(str(p), None, f"needs 1..{_MAX_ROWS} data rows, got {len(body)}")
    values = np.empty((len(body), len(header)))
    for i, row in enumerate(body, start=2):
        if len(row) != len(header):
            raise DataFileError(str(p), f"row {i}", f"{len(row)} values for {len(header)} columns")
        for j, cell in enumerate(row):
            try:
                v = float(cell)
            except ValueError:
                v = math.nan
            if not math.isfinite(v) or abs(v) > 1e7:
                raise DataFileError(
                    str(p), f"row {i}, {header[j]}", f"not a finite number: {cell!r}"[:120]
                )
            values[i - 2, j] = v
    t = values[:, header.index("time_s")]
    if (np.diff(t) <= 0).any():
        raise DataFileError(str(p), "time_s", "times must increase")
    joints = {
        n: np.radians(values[:, header.index(f"{n}_deg")])
        for n in joint_names
        if f"{n}_deg" in header
    }
    return t, joints


def compare_measured(
    log: RunLog, t: np.ndarray, measured: dict[str, np.ndarray]
) -> tuple[JointComparison, ...]:
    """Each measured joint against the log's simulated run, at the measured times in its span.

    Raises:
        InvalidInputError: No measured time inside the simulated run.
    """
    twin = log.header["twin"]
    names = tuple(log.header["joint_names"])
    t_sim = np.asarray(twin["time_s"], dtype=float)
    q_sim = np.radians(np.asarray(twin["q_deg"], dtype=float))
    inside = (t >= t_sim[0]) & (t <= t_sim[-1])
    if not inside.any():
        raise InvalidInputError(
            f"no measured time inside the simulated run's {t_sim[0]:.2f}..{t_sim[-1]:.2f} s "
            "(the log's clock: seconds from the first line sent)"
        )
    out = []
    for name, q in measured.items():
        sim = np.interp(t[inside], t_sim, q_sim[:, names.index(name)])
        err = np.abs(q[inside] - sim)
        k = int(np.argmax(err))
        out.append(
            JointComparison(
                name,
                int(inside.sum()),
                float(err[k]),
                float(t[inside][k]),
                float(np.sqrt(np.mean(err**2))),
            )
        )
    return tuple(out)
