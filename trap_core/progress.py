"""Progress lines for long work: ``label: done/total (pct) rate/s ETA``, at most a few a second."""
from __future__ import annotations

import sys
import time
from typing import TextIO


class Progress:
    """Counts work units and prints a throttled one-line status to a stream (stderr by default)."""

    def __init__(self, total: int | None, label: str, unit: str = "frames", stream: TextIO | None = None,
                 every_s: float = 1.0) -> None:
        self.total, self.label, self.unit = total, label, unit
        self.stream = stream if stream is not None else sys.stderr
        self.every_s = every_s
        self.done = 0
        self.start = time.perf_counter()
        self._last_print = -1e9

    def advance(self, count: int = 1) -> None:
        """Record ``count`` more units and print if the last line is old enough."""
        self.done += count
        now = time.perf_counter()
        if now - self._last_print >= self.every_s:
            self._last_print = now
            self.stream.write(self.line() + "\n")
            self.stream.flush()

    def line(self) -> str:
        """The current status line."""
        elapsed = max(time.perf_counter() - self.start, 1e-9)
        rate = self.done / elapsed
        if self.total:
            left = max(self.total - self.done, 0)
            eta = f", ETA {left / rate:.0f} s" if rate > 0 and left else ""
            return (f"{self.label}: {self.done}/{self.total} {self.unit} ({100 * self.done / self.total:.0f} %), "
                    f"{rate:.1f} {self.unit}/s{eta}")
        return f"{self.label}: {self.done} {self.unit}, {rate:.1f} {self.unit}/s"

    def finish(self) -> float:
        """Print the final line; return elapsed seconds."""
        self.stream.write(self.line() + f" in {time.perf_counter() - self.start:.1f} s\n")
        self.stream.flush()
        return time.perf_counter() - self.start
