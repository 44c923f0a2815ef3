"""Talking to a real SSC-32U (or its emulator) over a serial port, and playing a stream on it.

:class:`Ssc32Link` is the serial link, on pyserial (the optional extra
``lynxsim[real]``; imported only when a link opens). :func:`play_stream` sends
a :class:`~lynxsim.real.stream.CommandStream` on schedule, logs every line and
answer, polls ``Q`` to know when moves end, reads the final pulses back with
``QP``, and on any error, Ctrl-C or SIGTERM (any exception) sends ``STOP`` to
every channel before it lets the exception go on.
"""

from __future__ import annotations

import contextlib
import time
from collections.abc import Callable
from dataclasses import dataclass
from types import TracebackType
from typing import Any

from lynxsim.errors import BoardTimeoutError, InvalidInputError, SerialLinkError
from lynxsim.real.calibration import BAUD_RATES
from lynxsim.real.log import EndKind, RunLogWriter
from lynxsim.real.protocol import (
    CR,
    QUERY_STATUS,
    QUERY_VERSION,
    decode_pulse_byte,
    format_query_pulses,
    format_stop,
)
from lynxsim.real.stream import CommandStream

__all__ = ["DEFAULT_TIMEOUT_S", "PlayResult", "Ssc32Link", "play_stream"]

DEFAULT_TIMEOUT_S = 0.5
"""How long a query waits for its answer [s] (the board answers within 5 ms)."""
_POLL_S = 0.01
"""Pause between two ``Q`` while waiting for a move to end [s]."""
_END_MARGIN_S = 1.0
"""How long after its expected end a move may still be running before that is an error [s]."""


class Ssc32Link:
    """An open serial link to an SSC-32U.

    Args:
        port: The serial device (``/dev/ttyUSB0``, ``COM3``, an emulator's ``/dev/pts/N``).
        baud: Baud rate, one of the board's (2400, 9600, 38400, 115200) [bit/s].
        timeout_s: How long a query waits for its answer [s].

    Raises:
        SerialLinkError: pyserial is missing, or the port cannot be opened.
        InvalidInputError: A baud rate the board does not have.
    """

    def __init__(self, port: str, baud: int, *, timeout_s: float = DEFAULT_TIMEOUT_S) -> None:
        if baud not in BAUD_RATES:
            raise InvalidInputError(f"baud {baud} is not one of {BAUD_RATES}")
        try:
            import serial
        except ImportError:
            raise SerialLinkError(
                "talking to a serial port needs pyserial: pip install 'lynxsim[real]'"
            ) from None
        self.port = port
        self.timeout_s = timeout_s
        self._serial_error: type[Exception] = serial.SerialException
        try:
            self._serial: Any = serial.Serial(
                port, baud, timeout=timeout_s, write_timeout=max(timeout_s, 1.0)
            )
        except (serial.SerialException, OSError, ValueError) as exc:
            raise SerialLinkError(f"cannot open {port}: {exc}") from None
        self._serial.reset_input_buffer()

    def _io(self, what: str, action: Callable[[], Any]) -> Any:
        try:
            return action()
        except (self._serial_error, OSError) as exc:
            raise SerialLinkError(
                f"{self.port} failed while {what} (did it vanish?): {exc}"
            ) from None

    def send(self, text: str) -> None:
        """Send one line (the CR is added)."""
        data = (text + CR).encode("ascii")
        self._io(f"sending {text!r}", lambda: self._serial.write(data))

    def _answer(self, query: str, size: int | None) -> bytes:
        self.send(query)
        if size is None:
            data: bytes = self._io(
                f"reading the answer to {query}", lambda: self._serial.read_until(b"\r")
            )
            complete = data.endswith(b"\r")
        else:
            data = self._io(f"reading the answer to {query}", lambda: self._serial.read(size))
            complete = len(data) == size
        if not complete:
            raise BoardTimeoutError(
                f"no answer to {query!r} from {self.port} within {self.timeout_s:g} s "
                f"(got {len(data)} bytes): is the board powered and set to this baud rate?"
            )
        return data

    def version(self) -> str:
        """The board's ``VER`` answer."""
        return self._answer(QUERY_VERSION, None).decode("ascii", "replace").strip()

    def moving(self) -> bool:
        """``Q``: whether the last move is still running."""
        answer = self._answer(QUERY_STATUS, 1)
        if answer not in (b".", b"+"):
            raise SerialLinkError(f"{self.port} answered {answer!r} to Q (expected '.' or '+')")
        return answer == b"+"

    def pulses_us(self, channels: tuple[int, ...]) -> tuple[int, ...]:
        """``QP``: the channels' present pulse widths [us], 10 us resolution."""
        answer = self._answer(format_query_pulses(channels), len(channels))
        return tuple(decode_pulse_byte(b) for b in answer)

    def stop(self, channels: tuple[int, ...]) -> None:
        """``STOP`` every channel, then wait until the bytes have left."""
        for channel in channels:
            self.send(format_stop(channel))
        self._io("flushing the stop", self._serial.flush)

    def close(self) -> None:
        """Close the port (never raises)."""
        with contextlib.suppress(Exception):
            self._serial.close()

    def __enter__(self) -> Ssc32Link:
        return self

    def __exit__(
        self,
        exc_type: type[BaseException] | None,
        exc: BaseException | None,
        tb: TracebackType | None,
    ) -> None:
        self.close()


@dataclass(frozen=True)
class PlayResult:
    """What a run on the board did.

    Attributes:
        lines_sent: How many lines went out.
        final_pulses_us: The joints' pulses read back at the end (``QP``, 10 us resolution).
        commanded_final_us: The stream's final joint targets [us].
        end_s: When the last move was seen done, from the first line [s].
        log: The log written.
    """

    lines_sent: int
    final_pulses_us: tuple[int, ...]
    commanded_final_us: tuple[int, ...]
    end_s: float
    log: str

    @property
    def agrees(self) -> bool:
        """Whether every read-back pulse is its commanded one, to the 10 us resolution of QP."""
        return all(
            q == 10 * (c // 10) for q, c in zip(self.final_pulses_us, self.commanded_final_us)
        )


def _wait_until_done(
    link: Ssc32Link,
    log: RunLogWriter,
    t0: float,
    deadline: float,
    clock: Callable[[], float],
    sleep: Callable[[float], None],
) -> None:
    while True:
        busy = link.moving()
        log.query(clock() - t0, QUERY_STATUS, "+" if busy else ".")
        if not busy:
            return
        if clock() > deadline:
            raise BoardTimeoutError(
                f"{link.port} still reports a move running {_END_MARGIN_S:g} s after it should "
                "have ended"
            )
        sleep(_POLL_S)


def play_stream(
    link: Ssc32Link,
    stream: CommandStream,
    log: RunLogWriter,
    *,
    clock: Callable[[], float] = time.monotonic,
    sleep: Callable[[float], None] = time.sleep,
    progress: Callable[[float], None] | None = None,
) -> PlayResult:
    """Send a stream on schedule and see it through; stop every channel if anything goes wrong.

    The log is finished (renamed to its destination) however the run ends.

    Args:
        link: The open link.
        stream: The lines to send.
        log: The run's log.
        clock: Monotonic clock [s].
        sleep: Waits [s].
        progress: Called with the fraction of the lines sent.

    Returns:
        The :class:`PlayResult`.

    Raises:
        SerialLinkError: The port vanished or failed (the stop was attempted).
        BoardTimeoutError: The board did not answer, or a move did not end.
        BaseException: Ctrl-C (KeyboardInterrupt) or the CLI's SIGTERM, after the stop.
    """
    channels = stream.channels + (
        () if stream.gripper_channel is None else (stream.gripper_channel,)
    )
    t0 = clock()
    sent = 0
    try:
        first_move = True
        for line in stream.lines:
            while (wait := t0 + line.at_s - clock()) > 0:
                sleep(min(wait, 0.05))
            if line.kind == "move" and (first_move or stream.options.mode == "waypoints"):
                _wait_until_done(link, log, t0, clock() + _END_MARGIN_S, clock, sleep)
                first_move = False
            link.send(line.text)
            log.sent(clock() - t0, line.text)
            sent += 1
            if progress is not None:
                progress(sent / len(stream.lines))
        end = t0 + stream.motion_start_s + stream.duration_s
        while (wait := end - clock()) > 0:
            sleep(min(wait, 0.05))
        _wait_until_done(link, log, t0, clock() + _END_MARGIN_S, clock, sleep)
        done_s = clock() - t0
        final = link.pulses_us(stream.channels)
        log.query(clock() - t0, format_query_pulses(stream.channels), " ".join(map(str, final)))
    except BaseException as exc:
        kind: EndKind = "error" if isinstance(exc, Exception) else "interrupted"
        message = f"{type(exc).__name__}: {exc}".strip()
        try:
            link.stop(channels)
            log.event(clock() - t0, "STOP sent to channels " + " ".join(map(str, channels)))
        except SerialLinkError as stop_exc:
            log.event(clock() - t0, f"STOP could not be sent: {stop_exc}")
            message += f" (STOP could not be sent: {stop_exc})"
        log.finish(clock() - t0, kind, None, message)
        raise
    path = log.finish(clock() - t0, "completed", list(final))
    return PlayResult(sent, final, stream.final_us, done_s, str(path))
