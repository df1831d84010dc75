"""Cycle time: how long one iteration of a task's loop takes the arm.

A task that moves the arm in a loop passes again and again at the same motion instructions. Its
cycle starts at the first motion instruction of the loop: the first instruction (by file, line
and column) that the task records a second time — anything before it (a move to a home
position before `while true`) is not part of the cycle. The cycle time is the time between
successive starts of the arm on that instruction's command.
"""

from __future__ import annotations

from dataclasses import dataclass, field


@dataclass
class CycleStats:
    """The cycle of one task (module docstring): where its loop starts and when the arm started it, each pass."""
    task: str
    marker: tuple[str, int, int] | None  # (path, line, col) of the first motion of the loop
    starts: list[float] = field(default_factory=list)  # when the arm started that command, each pass

    @property
    def times(self) -> list[float]:
        """The cycle times: between successive starts."""
        return [b - a for a, b in zip(self.starts, self.starts[1:])]

    @property
    def count(self) -> int:
        """Complete cycles."""
        return max(len(self.starts) - 1, 0)


def _key(src) -> tuple[str, int, int]:
    """Where a motion instruction is written: (path, line, col)."""
    return (src.path, src.line, src.col)


def cycle_stats(records) -> dict[str, CycleStats]:
    """Per task, from the motion records (in recording order)."""
    by_task: dict[str, list] = {}
    for r in records:
        if r.id is None:  # connection moves belong to no instruction
            continue
        by_task.setdefault(r.source.task, []).append(r)
    out: dict[str, CycleStats] = {}
    for task, recs in by_task.items():
        seen: set = set()
        marker = None
        for r in recs:
            k = _key(r.source)
            if k in seen:
                marker = k
                break
            seen.add(k)
        st = CycleStats(task, marker)
        if marker is not None:
            st.starts = [r.start for r in recs if _key(r.source) == marker and r.start is not None]
        out[task] = st
    return out


class CycleCounter:
    """Live count for `--cycles N`: feed it each recorded command's (task, source, time) as the
    program records them; `completed(task)` counts passes at the loop's first motion minus one."""

    def __init__(self) -> None:
        """No command noted yet."""
        self._seen: dict[str, set] = {}
        self._marker: dict[str, tuple] = {}
        self._passes: dict[str, int] = {}

    def note(self, task: str, source) -> None:
        """A command recorded by `task` at `source` (its path, line, col)."""
        k = _key(source)
        m = self._marker.get(task)
        if m is None:
            seen = self._seen.setdefault(task, set())
            if k in seen:
                self._marker[task] = k
                self._passes[task] = 2
            else:
                seen.add(k)
        elif k == m:
            self._passes[task] += 1

    def completed(self, task: str | None = None) -> int:
        """Complete cycles of `task` (or the most of any task)."""
        if task is not None:
            return max(self._passes.get(task, 0) - 1, 0)
        return max((p - 1 for p in self._passes.values()), default=0)
