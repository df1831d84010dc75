"""The progress display of `val3check sim` on a terminal: simulated time, wall time, motions done.

    progress = Progress.for_stream(sys.stderr)    # None unless the stream is a terminal
    SimOptions(progress=progress)                 # the run calls it now and then
    progress.close()                              # clears the line

Shown only when the stream is a terminal and the run has lasted more than a second of wall time
(a short run prints nothing), redrawn at most ten times a second on one line (carriage return),
cleared at the end. After the simulated time, each phase that takes time says what it does
(`checking collisions: motion 12 of 111`). Never written to a file or a pipe: reports stay byte-for-byte the same.
"""

from __future__ import annotations

import time
from typing import Callable, TextIO

SHOW_AFTER_S = 1.0
EVERY_S = 0.1


class Progress:
    def __init__(self, stream: TextIO, clock: Callable[[], float] = time.monotonic, total_s: float | None = None) -> None:
        self.stream = stream
        self.total_s = total_s  # --duration, shown beside the simulated time
        self.clock = clock
        self.start = clock()
        self.next = self.start + SHOW_AFTER_S
        self.shown = False

    @classmethod
    def for_stream(cls, stream: TextIO, total_s: float | None = None) -> "Progress | None":
        try:
            tty = stream.isatty()
        except (AttributeError, ValueError):
            tty = False
        return cls(stream, total_s=total_s) if tty else None

    def __call__(self, sim_s: float, motions_done: Callable[[], int]) -> None:
        now = self.clock()
        if now < self.next:
            return
        self.next = now + EVERY_S
        self.shown = True
        of = f" of {self.total_s:g}" if self.total_s else ""
        line = (f"val3check sim: {sim_s:9.3f}{of} s simulated, {now - self.start:6.1f} s wall, "
                f"{motions_done()} motions done")
        self.stream.write("\r" + line + "\x1b[K")
        self.stream.flush()

    def phase(self, text: str) -> None:
        """A phase of the run after its simulated time (the collision checks of its motions), shown
        in place of the simulated time so that the line never freezes on it."""
        now = self.clock()
        if now < self.next:
            return
        self.next = now + EVERY_S
        self.shown = True
        self.stream.write(f"\rval3check sim: {text}, {now - self.start:6.1f} s wall\x1b[K")
        self.stream.flush()

    def close(self) -> None:
        if self.shown:
            self.stream.write("\r\x1b[K")
            self.stream.flush()
            self.shown = False
