"""The log of a run on the board: what was sent and answered, when; written safely, checked.

A log is JSON lines. The first record is the header (format, version, task,
trajectory, stream options, channels, joint names, the calibration, the
commanded final pulses, and the digital twin's simulated joints on the stream's
clock); then one record per line sent (``{"t_s", "sent"}``), per query
(``{"t_s", "query", "answer"}``) and per event (``{"t_s", "event"}``); the last
record ends the run (``{"t_s", "end", "final_pulses_us", "message"}``, ``end``
being ``completed``, ``interrupted`` or ``error``). Times are seconds from the
moment the first line was sent.

The writer writes to a temporary name beside the destination and renames it
only once the end record is written, whatever ended the run (an interrupted
run's log is complete: it records the stop). The reader checks every record.
"""

from __future__ import annotations

import json
import os
import tempfile
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Literal

from lynxsim.errors import DataFileError
from lynxsim.fileio import check_destination

__all__ = ["LOG_FORMAT", "LOG_VERSION", "EndKind", "RunLog", "RunLogWriter", "read_log"]

LOG_FORMAT = "lynxsim-ssc32-log"
LOG_VERSION = 1
EndKind = Literal["completed", "interrupted", "error"]
"""How a run ended."""
_MAX_LOG_BYTES = 64 << 20
"""Largest log read back [bytes]."""


class RunLogWriter:
    """Writes a run's log record by record; :meth:`finish` makes it appear at its destination.

    Args:
        dest: The log's path (``.jsonl``).
        header: The header's fields (JSON-ready).

    Raises:
        OutputPathError: ``dest`` is not a regular file or its folder cannot be one.
    """

    def __init__(self, dest: str | os.PathLike[str], header: dict[str, Any]) -> None:
        self.dest = check_destination(dest)
        self.dest.parent.mkdir(parents=True, exist_ok=True)
        fd, name = tempfile.mkstemp(
            prefix=f".{self.dest.stem[:40]}.", suffix=".tmp", dir=self.dest.parent
        )
        self._tmp = Path(name)
        self._file = os.fdopen(fd, "w", encoding="utf-8")
        self._finished = False
        self._write({"format": LOG_FORMAT, "version": LOG_VERSION, **header})

    def _write(self, record: dict[str, Any]) -> None:
        self._file.write(json.dumps(record, separators=(",", ":")) + "\n")
        self._file.flush()

    def sent(self, t_s: float, text: str) -> None:
        """A line sent at ``t_s`` [s]."""
        self._write({"t_s": round(t_s, 6), "sent": text})

    def query(self, t_s: float, text: str, answer: str) -> None:
        """A query and its answer (text; ``QP`` answers as pulse widths)."""
        self._write({"t_s": round(t_s, 6), "query": text, "answer": answer})

    def event(self, t_s: float, text: str) -> None:
        """Something that happened (a stop sent, a timeout)."""
        self._write({"t_s": round(t_s, 6), "event": text})

    def finish(
        self, t_s: float, end: EndKind, final_pulses_us: list[int] | None, message: str = ""
    ) -> Path:
        """Write the end record, close and rename the log to its destination; returns it."""
        if self._finished:
            return self.dest
        self._write(
            {
                "t_s": round(t_s, 6),
                "end": end,
                "final_pulses_us": final_pulses_us,
                "message": message,
            }
        )
        self._file.close()
        self._finished = True
        umask = os.umask(0)
        os.umask(umask)
        self._tmp.chmod(0o666 & ~umask)
        check_destination(self.dest)
        os.replace(self._tmp, self.dest)
        return self.dest


@dataclass(frozen=True)
class RunLog:
    """A log read back.

    Attributes:
        header: The header record.
        sent: (time [s], line) of every line sent.
        queries: (time [s], query, answer).
        events: (time [s], event).
        end: How the run ended.
        end_s: When [s].
        final_pulses_us: The board's pulses read back at the end (10 us resolution), or None.
        message: The end record's message.
    """

    header: dict[str, Any]
    sent: tuple[tuple[float, str], ...]
    queries: tuple[tuple[float, str, str], ...]
    events: tuple[tuple[float, str], ...]
    end: EndKind
    end_s: float
    final_pulses_us: tuple[int, ...] | None
    message: str


def _fail(path: Path, field: str | None, problem: str) -> DataFileError:
    return DataFileError(str(path), field, problem)


def read_log(path: str | os.PathLike[str]) -> RunLog:
    """Read a run's log and check every record.

    Raises:
        DataFileError: Not a lynxsim log of this version, a record that breaks the
            format (names the line), or no end record (the file was cut).
        OSError: The file cannot be read.
    """
    p = Path(path)
    if p.exists() and not p.is_file():
        raise _fail(p, None, "not a regular file")
    with p.open("rb") as f:
        raw = f.read(_MAX_LOG_BYTES + 1)
    if len(raw) > _MAX_LOG_BYTES:
        raise _fail(p, None, f"larger than {_MAX_LOG_BYTES} bytes")
    try:
        rows = raw.decode("utf-8").splitlines()
    except UnicodeDecodeError as exc:
        raise _fail(p, None, f"not UTF-8 text ({exc.reason})") from None
    records = []
    for i, row in enumerate(rows, start=1):
        try:
            record = json.loads(row)
        except (json.JSONDecodeError, RecursionError):
            raise _fail(p, f"line {i}", "not a JSON record") from None
        if not isinstance(record, dict):
            raise _fail(p, f"line {i}", "not a JSON object")
        records.append(record)
    if not records:
        raise _fail(p, None, "empty")
    header = records[0]
    if header.get("format") != LOG_FORMAT or header.get("version") != LOG_VERSION:
        raise _fail(p, "line 1", f"not a {LOG_FORMAT} version {LOG_VERSION} header")
    sent, queries, events = [], [], []
    end = None
    for i, r in enumerate(records[1:], start=2):
        t = r.get("t_s")
        if isinstance(t, bool) or not isinstance(t, int | float) or not 0 <= t < 1e7:
            raise _fail(p, f"line {i}.t_s", f"must be a time in seconds, got {t!r}"[:120])
        if end is not None:
            raise _fail(p, f"line {i}", "a record after the end record")
        if set(r) == {"t_s", "sent"} and isinstance(r["sent"], str):
            sent.append((float(t), r["sent"]))
        elif set(r) == {"t_s", "query", "answer"} and all(
            isinstance(r[k], str) for k in ("query", "answer")
        ):
            queries.append((float(t), r["query"], r["answer"]))
        elif set(r) == {"t_s", "event"} and isinstance(r["event"], str):
            events.append((float(t), r["event"]))
        elif set(r) == {"t_s", "end", "final_pulses_us", "message"} and r["end"] in (
            "completed",
            "interrupted",
            "error",
        ):
            final = r["final_pulses_us"]
            if final is not None and not (
                isinstance(final, list)
                and all(isinstance(v, int) and not isinstance(v, bool) for v in final)
            ):
                raise _fail(p, f"line {i}.final_pulses_us", "must be a list of integers or null")
            end = (r["end"], float(t), None if final is None else tuple(final), str(r["message"]))
        else:
            raise _fail(p, f"line {i}", f"not a log record: {sorted(r)}"[:160])
    if end is None:
        raise _fail(p, None, "no end record: the log was cut")
    return RunLog(
        header, tuple(sent), tuple(queries), tuple(events), end[0], end[1], end[2], end[3]
    )
