"""What the scheduler asks of everything that changes with simulated time besides the tasks.

A subsystem (the cell driven by the scenario, the arm's motion, later collision checks and
trace recording) tells the scheduler when its state next changes, and is brought up to date
before the tasks of a cycle run. When every task waits, the clock jumps straight to the
earliest of those times: no subsystem is polled cycle by cycle.

Tasks observe a subsystem through instructions (an input's value, `isEmpty()`...); a task
that waits for one (`waitEndMove()`, the end of motion before `open()`) waits on a condition
that the scheduler evaluates after each jump (`waiting.WAIT`).
"""

from __future__ import annotations

from typing import Protocol, runtime_checkable


@runtime_checkable
class Subsystem(Protocol):
    def next_time(self, now_us: int) -> int | None:
        """The earliest simulated time after `now_us` at which its state changes in a way tasks
        may observe; None when nothing is scheduled. A time not after `now_us` means: at the
        next tick."""
        ...

    def advance(self, to_us: int) -> None:
        """Bring its state up to `to_us` (called by the scheduler, in registration order, at
        the start of every cycle, before the tasks run)."""
        ...
