"""Timed events of the cell and the controller, and the timeline that orders them.

The scenario (docs/scenario.md) schedules most of them; the cell's reactions to outputs,
serial replies and `enablePower()`'s delay schedule the others while the application runs.
Events at the same time keep the order in which they were scheduled: runs are deterministic.
"""

from __future__ import annotations

import heapq
from typing import Any, Union

from ..light_dataclass import dataclass  # (frozen record classes made without dataclasses' cost)


@dataclass(frozen=True, slots=True)
class InputsChange:
    """Inputs take new values (a scenario event, or the cell reacting to an output)."""

    settings: tuple  # ((IOPoint, value), ...)


@dataclass(frozen=True, slots=True)
class SerialData:
    """Bytes arrive on a serial line or socket (sio, 3.7)."""

    io: Any  # IOPoint
    data: bytes


@dataclass(frozen=True, slots=True)
class KeyPress:
    """A key of the scenario is pressed: the keys themselves are in the user page's queue;
    the event only makes the clock stop at that time."""


@dataclass(frozen=True, slots=True)
class PowerChange:
    """The arm power comes on after enablePower()'s delay (8.1)."""

    on: bool


@dataclass(frozen=True, slots=True)
class ControllerChange:
    """The scenario changes the controller's state (working mode, emergency stop... chapter 8)."""

    changes: tuple  # ((field, value), ...)


Event = Union[InputsChange, SerialData, KeyPress, PowerChange, ControllerChange]


class Timeline:
    """Events in time order (then scheduling order)."""

    __slots__ = ("heap", "_seq")

    def __init__(self) -> None:
        self.heap: list[tuple[int, int, Event]] = []  # (time, order, event); heap[0] is the next
        self._seq = 0

    def push(self, at: int, event: Event) -> None:
        self._seq += 1
        heapq.heappush(self.heap, (at, self._seq, event))

    def next_time(self) -> int | None:
        return self.heap[0][0] if self.heap else None

    def pop_due(self, now: int) -> tuple[int, Event] | None:
        """The next event at or before `now`, removed from the timeline; None when there is
        none (events scheduled while applying one are seen by the next call)."""
        heap = self.heap
        if heap and heap[0][0] <= now:
            at, _, event = heapq.heappop(heap)
            return at, event
        return None

    def __len__(self) -> int:
        return len(self.heap)
