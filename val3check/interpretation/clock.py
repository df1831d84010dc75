"""Simulated time (docs/sim.md, "Time and scheduling").

The clock counts integer microseconds from 0; the controller's 4 ms cycle is its tick. Inside
a cycle, each VAL 3 line costs `LINE_US` (a cycle runs at most `LINES_PER_CYCLE` lines), so
the time seen by an instruction is the cycle's start plus the lines already run in it.
Integer times keep runs deterministic.
"""

from __future__ import annotations

from typing import Any

TICK_US = 4000  # the controller's cycle (4 ms)
LINES_PER_CYCLE = 1000  # simulated cost: 4 µs per VAL 3 line
LINE_US = TICK_US // LINES_PER_CYCLE


class Clock:
    """`now` is the start of the current cycle. The scheduler keeps `cycle_lines` (lines run
    in the cycle so far), `current` (the task running) and `turn_given` (its quantum), so that
    `time_of(task)` is exact in the middle of a turn."""

    __slots__ = ("now", "cycle_lines", "turn_given", "current")

    def __init__(self) -> None:
        self.now = 0
        self.cycle_lines = 0
        self.turn_given = 0
        self.current: Any = None

    def time_of(self, task: Any = None) -> int:
        """Simulated time inside the cycle: cycle start + lines already run (those of the
        running task's turn included)."""
        lines = self.cycle_lines
        if task is not None and task is self.current:
            q = task.q
            lines += self.turn_given - q if q > 0 else self.turn_given
        return self.now + (lines if lines < LINES_PER_CYCLE else LINES_PER_CYCLE) * LINE_US

    def wake_time(self, task: Any, seconds: float) -> int:
        """The tick at which a wait of `seconds` started now ends (nearest tick, at least the
        next one: delay(), watch(), 5.10). (`time_of` inlined: every delay() comes here.)"""
        lines = self.cycle_lines
        if task is not None and task is self.current:
            q = task.q
            lines += self.turn_given - q if q > 0 else self.turn_given
        target = self.now + (lines if lines < LINES_PER_CYCLE else LINES_PER_CYCLE) * LINE_US + int(round(
            seconds * 1_000_000))
        tick = (target + TICK_US // 2) // TICK_US
        return max(tick * TICK_US, self.now + TICK_US)

    def end_of_cycle(self) -> int:
        """The time at which a task that ends now is recorded as ended."""
        return self.now + min(self.cycle_lines, LINES_PER_CYCLE) * LINE_US
