"""How much of a long run a report writes: its size bounded by design, not by the length of the run
(docs/performance.md, "Long runs").

The trajectory is written on the controller's 4 ms clock up to a number of samples where the arm
moves; beyond, on a multiple of 4 ms chosen so that the samples stay under that number (the report
says which). The motion table keeps its first rows; the run's cycles, folded findings and summary
tell the rest.

    every = tick_multiple(m, JSON_TICKS)     # 1 for a short run
    for k0, q, v in m.trajectory.segments(m.end_s, TICK_S * every): ...
"""

from __future__ import annotations

import math
from typing import Any

TICK_S = 0.004  # the controller's clock (manual 5.x: the 4 ms cycle)
JSON_TICKS = 75_000  # samples of the JSON trajectory: 5 minutes of motion at 4 ms (about 9 MB)
TRACE_TICKS = 40_000  # ticks of the MCAP trace's arm messages: 160 s of motion at 4 ms (about 15 MB)
MOTION_ROWS = 5_000  # rows of the motion tables (JSON, HTML): about 2.5 MB of JSON
TASK_CHANGES = 20_000  # task state changes of the HTML timelines and the trace's /tasks (about 1.2 MB)


def moving_ticks(m: Any) -> int:
    """The 4 ms ticks at which the arm of the run record `m` (arm_record.ArmRun) moves."""
    return sum(math.ceil((b - a) / TICK_S) + 1 for a, b in m.trajectory.moving(m.end_s))


def tick_multiple(m: Any, max_ticks: int) -> int:
    """The multiple of 4 ms at which the trajectory of `m` fits in `max_ticks` samples (1: every
    tick)."""
    return max(1, -(-moving_ticks(m) // max_ticks))


def thinned_note(every: int, max_ticks: int) -> str:
    """What a report says when it samples the trajectory every `every` ticks."""
    return (f"a long run: the trajectory is sampled every {every * TICK_S * 1000:g} ms ({every} ticks of 4 ms), "
            f"so that it holds at most about {max_ticks} samples")


def left_out(result: Any, what: str) -> str | None:
    """Why a report writer leaves out `what` (something that grows with the run) for the run
    `result` (a SimResult): the run's budgets are spent (simulation/budget.py); None: write it."""
    budget = getattr(result, "budget", None)
    why = budget.spent() if budget is not None else None
    return None if why is None else f"{what} not written: {why}"


def task_changes(result: Any) -> tuple[list, str | None]:
    """The task state changes a report shows of the run `result` (a SimResult): the first
    TASK_CHANGES, and what a report says when there were more (None: all of them)."""
    changes = result.task_states
    if len(changes) <= TASK_CHANGES:
        return changes, None
    until = changes[TASK_CHANGES].time_us / 1e6
    return changes[:TASK_CHANGES], (f"a long run: the task timelines hold the first {TASK_CHANGES} of "
                                    f"{len(changes)} task state changes (up to {until:g} s)")
