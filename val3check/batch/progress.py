"""Progress on standard error while a batch runs, on a terminal only (never in a CI log or a
pipe): cases done, failures so far, elapsed time, an estimate of the time left, and the phase
(shown from the start: the first cases take seconds)."""

from __future__ import annotations

import sys
import time


def _clock(seconds: float) -> str:
    s = int(round(seconds))
    return f"{s // 3600}:{s // 60 % 60:02d}:{s % 60:02d}" if s >= 3600 else f"{s // 60}:{s % 60:02d}"


class Progress:
    def __init__(self, total: int, stream=None, enabled: bool | None = None, unit: str = "cases") -> None:  # noqa: ANN001
        self.total, self.done, self.failed, self.unit = total, 0, 0, unit
        self.stream = stream or sys.stderr
        self.enabled = self.stream.isatty() if enabled is None else enabled
        self.start = time.monotonic()
        self.what = ""  # the phase the batch is in (starting a Dask cluster, running on N processes)

    def line(self, now: float | None = None) -> str:
        elapsed = (time.monotonic() if now is None else now) - self.start
        left = ""
        if 0 < self.done < self.total:
            left = f", about {_clock(elapsed / self.done * (self.total - self.done))} left"
        what = f": {self.what}" if self.what else ""
        return f"{self.done}/{self.total} {self.unit}, {self.failed} failed, {_clock(elapsed)} elapsed{left}{what}"

    def phase(self, what: str) -> None:
        """Shown at once: the batch's first seconds (processes or a cluster starting) say so."""
        self.what = what
        self.show()

    def update(self, passed: bool) -> None:
        self.done += 1
        self.failed += 0 if passed else 1
        self.show()

    def show(self) -> None:
        if self.enabled:
            self.stream.write("\r\x1b[K" + self.line())
            self.stream.flush()

    def finish(self) -> None:
        if self.enabled:
            self.stream.write("\r\x1b[K")
            self.stream.flush()
