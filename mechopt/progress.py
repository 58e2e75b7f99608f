"""Progress on long runs: a bar on a terminal, plain lines in a pipe or CI."""
from __future__ import annotations

import sys
import time

__all__ = ["Progress"]


class Progress:
    """``Progress(total, label)``; call ``update(done, info="")`` and ``close()``.

    On a TTY it redraws one line with a bar; otherwise it prints a plain line at
    most every ``min_interval`` seconds (and always the last one).
    """

    def __init__(self, total: int, label: str, stream=None, min_interval: float = 2.0):
        self.total = max(int(total), 1)
        self.label = label
        self.stream = sys.stderr if stream is None else stream
        self.tty = bool(getattr(self.stream, "isatty", lambda: False)())
        self.min_interval = min_interval
        self._t0 = time.perf_counter()
        self._last = -float("inf")

    def update(self, done: int, info: str = ""):
        now = time.perf_counter()
        elapsed = now - self._t0
        frac = done / self.total
        if self.tty:
            width = 30
            bar = "#" * int(width * frac) + "-" * (width - int(width * frac))
            self.stream.write(f"\r{self.label} [{bar}] {done}/{self.total} {elapsed:6.1f}s {info}  ")
            self.stream.flush()
        elif done >= self.total or now - self._last >= self.min_interval:
            self.stream.write(f"{self.label}: {done}/{self.total} ({elapsed:.1f} s) {info}\n")
            self.stream.flush()
            self._last = now

    def close(self):
        if self.tty:
            self.stream.write("\n")
            self.stream.flush()
