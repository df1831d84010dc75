"""The scheduler's own cost per idle cycle (issue 29): one task waiting on a false condition,
two subsystems that do nothing and whose next event is the next cycle, so that every cycle of
`Scheduler.loop` is a cycle where nothing runs (the ~10,000 of the bundled cell's 15,677 cycles
an hour where every task waits). What it measures is the loop, `cycle`, the condition's call and
`next_event`, not the arm.

    python bench/bench_idle_cycle.py [--cycles 200000] [--rounds 5]

Prints microseconds per idle cycle (best and median of the rounds). Under valgrind, the
difference of two runs with different --cycles divided by their difference is the instruction
count per idle cycle, which does not move with the machine's load (docs/performance.md, "The
interpreter's share of a cycle, second round").
"""

from __future__ import annotations

import argparse
import statistics
import time
import types

from val3check.interpretation.clock import TICK_US, Clock
from val3check.interpretation.machine import Budgets
from val3check.interpretation.scheduler import WAIT, EndRun, Scheduler, Task


class _Idle:
    """A subsystem with nothing to do, whose next event is the next cycle."""

    def advance(self, now: int) -> None:
        pass

    def next_time(self, now: int) -> int:
        return now + TICK_US


def idle_scheduler() -> Scheduler:
    """A scheduler with one task waiting on a condition that stays false."""
    clock = Clock()
    machine = types.SimpleNamespace(
        clock=clock, budgets=Budgets(duration_us=10**15, wall_s=1e9), wall_start=time.monotonic(),
        cell=types.SimpleNamespace(budget=types.SimpleNamespace(over=lambda: None)), progress=None,
        stopping=False, stop_done=lambda: False, recorder=types.SimpleNamespace(task_state=lambda *a: None))
    scheduler = Scheduler(machine, clock)
    scheduler.add_subsystem(_Idle())
    scheduler.add_subsystem(_Idle())
    task = Task(machine, "idle", types.SimpleNamespace(model=types.SimpleNamespace(stack_size=5000)), "idle", 10)

    def program(t):
        while True:
            yield

    task.gen = program(task)
    task.state, task.cond, task.waiting_for = WAIT, (lambda: False), "wait(bNever == true)"
    scheduler.add(task)
    return scheduler


def per_cycle(cycles: int) -> float:
    """Seconds per idle cycle over `cycles` cycles."""
    scheduler = idle_scheduler()
    start = time.perf_counter()
    try:
        scheduler.loop(cycles * TICK_US)
    except EndRun as end:
        assert end.reason == "duration", end.reason
    return (time.perf_counter() - start) / cycles


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cycles", type=int, default=200_000)
    ap.add_argument("--rounds", type=int, default=5)
    args = ap.parse_args()
    times = [per_cycle(args.cycles) * 1e6 for _ in range(args.rounds)]
    print(f"idle cycle: {min(times):.2f} us best, {statistics.median(times):.2f} us median "
          f"({args.rounds} rounds of {args.cycles} cycles)")


if __name__ == "__main__":
    main()
