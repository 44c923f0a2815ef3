"""The emulated SSC-32U on a pseudo-terminal: a serial device any client can open.

:class:`PtyEmulator` opens a pseudo-terminal pair, puts its device side in
raw mode and serves an :class:`~lynxsim.real.board.Ssc32Board` on the other
side from a helper thread, in real time (the board's clock is
``time.monotonic`` from the server's start). A pseudo-terminal has no baud
rate: bytes arrive as fast as the client writes them. ``close()`` makes the
device vanish under its client (reads and writes then fail), as an unplugged
USB cable does.
"""

from __future__ import annotations

import contextlib
import os
import select
import termios
import threading
import time
import tty
from types import TracebackType

from lynxsim.real.board import Ssc32Board

__all__ = ["PtyEmulator"]

_POLL_S = 0.005
"""How long the server waits for bytes before looking again whether it should stop [s]."""


class PtyEmulator:
    """An emulated board behind a pseudo-terminal, served from a helper thread.

    Args:
        answers: False: a board that never answers.

    Attributes:
        board: The emulated board (read it under :attr:`lock`).
        lock: Held while the server feeds the board.
        path: The device path a client opens (``/dev/pts/N``).
    """

    def __init__(self, *, answers: bool = True) -> None:
        self.board = Ssc32Board(answers=answers)
        self.lock = threading.Lock()
        self._master, self._slave = os.openpty()
        tty.setraw(self._slave, termios.TCSANOW)
        self.path = os.ttyname(self._slave)
        self._t0 = time.monotonic()
        self._stop = threading.Event()
        self._closed = False
        self._thread = threading.Thread(target=self._serve, name="ssc32-pty", daemon=True)
        self._thread.start()

    def now_s(self) -> float:
        """The board's clock: seconds since the server started [s]."""
        return time.monotonic() - self._t0

    def pulses_us(self, channels: tuple[int, ...]) -> tuple[int, ...]:
        """The pulses the board sends now on ``channels`` [us] (0: off)."""
        with self.lock:
            return self.board.pulses_us(channels, self.now_s())

    def _serve(self) -> None:
        while not self._stop.is_set():
            try:
                ready, _, _ = select.select([self._master], [], [], _POLL_S)
                if not ready:
                    continue
                data = os.read(self._master, 4096)
            except OSError:  # closed under us
                return
            with self.lock:
                answer = self.board.feed(data, self.now_s())
            if answer:
                try:
                    os.write(self._master, answer)
                except OSError:
                    return

    def close(self) -> None:
        """Stop serving and remove the device (its client's reads and writes then fail)."""
        if self._closed:
            return
        self._closed = True
        self._stop.set()
        self._thread.join(timeout=2.0)
        for fd in (self._master, self._slave):
            with contextlib.suppress(OSError):
                os.close(fd)

    def __enter__(self) -> PtyEmulator:
        return self

    def __exit__(
        self,
        exc_type: type[BaseException] | None,
        exc: BaseException | None,
        tb: TracebackType | None,
    ) -> None:
        self.close()
