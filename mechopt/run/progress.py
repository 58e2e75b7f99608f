"""Progress on long runs: a bar on a terminal, plain lines in a pipe or CI.

Silent when the ``"mechopt"`` logger's own level is set above INFO (``mechopt
--quiet``, or ``logging.getLogger("mechopt").setLevel(logging.WARNING)`` from Python).
"""
from __future__ import annotations

import logging
import sys
import time

__all__ = ["Progress"]


class Progress:
    """``Progress(total, label)``; call ``update(done, info="")`` and ``close()``.

    On a TTY it redraws one line with a bar; otherwise it prints a plain line at
    most every ``min_interval`` seconds (and always the last one). Nothing when the
    ``"mechopt"`` logger's level is above INFO (module docstring).

    Parameters
    ----------
    total : int
        Units of work in all.
    label : str
        What is counted.
    stream : file, optional
        Where to write (default stderr).
    min_interval : float
        Seconds between plain lines.
    """

    def __init__(self, total: int, label: str, stream=None, min_interval: float = 2.0):
        self.total = max(int(total), 1)
        self.label = label
        self.stream = sys.stderr if stream is None else stream
        self.tty = bool(getattr(self.stream, "isatty", lambda: False)())
        self.min_interval = min_interval
        self._t0 = time.perf_counter()
        self._last = -float("inf")
        self._state = None
        self.silent = logging.getLogger("mechopt").level > logging.INFO

    def update(self, done: int, info: str = ""):
        """Report progress.

        Parameters
        ----------
        done : int
            Units of work done so far (of ``total``).
        info : str
            A short text shown after the count.
        """
        if self.silent:
            return
        now = time.perf_counter()
        self._state = (done, info)
        if self.tty:
            self._draw(now)
        elif done >= self.total or now - self._last >= self.min_interval:
            self.stream.write(f"{self.label}: {done}/{self.total} ({now - self._t0:.1f} s) {info}\n")
            self.stream.flush()
            self._last = now

    def _draw(self, now):
        done, info = self._state
        width = 30
        filled = int(width * done / self.total)
        bar = "#" * filled + "-" * (width - filled)
        self.stream.write(f"\r{self.label} [{bar}] {done}/{self.total} {now - self._t0:6.1f}s {info}  ")
        self.stream.flush()

    def message(self, log, text: str):
        """``log(text)`` without breaking the bar: on a TTY the bar's line is cleared
        first and redrawn after (``log`` may write to the same terminal).

        Parameters
        ----------
        log : callable
            ``log(text)``, e.g. a logger's method.
        text : str
            The message.
        """
        if not self.tty or self.silent:
            log(text)
            return
        self.stream.write("\r\033[K")
        self.stream.flush()
        log(text)
        if self._state is not None:
            self._draw(time.perf_counter())

    def close(self):
        """End the progress line (on a TTY, move to the next line)."""
        if self.tty and not self.silent:
            self.stream.write("\n")
            self.stream.flush()
