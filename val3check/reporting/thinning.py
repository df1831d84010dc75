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
from itertools import islice
from typing import Any

TICK_S = 0.004  # the controller's clock (manual 5.x: the 4 ms cycle)
JSON_TICKS = 75_000  # samples of the JSON trajectory: 5 minutes of motion at 4 ms (about 9 MB)
TRACE_TICKS = 40_000  # ticks of the MCAP trace's arm messages: 160 s of motion at 4 ms (about 15 MB)
MOTION_ROWS = 5_000  # rows of the motion tables (JSON, HTML): about 2.5 MB of JSON
TASK_CHANGES = 20_000  # task state changes of the HTML timelines and the trace's /tasks (about 1.2 MB)
ARM_SPANS = 10_000  # moving and idle spans of the HTML arm timeline (about 0.3 MB; 6,828 in the 1-hour cell)
IO_EVENTS = 10_000  # I/O changes of the HTML I/O lanes and the trace's /io (about 0.3 MB; 7,335 in 1 hour)
PART_SPANS = 3_000  # part spans of the HTML 3D view and the trace's /scene (about 0.4 MB; 2,276 in 1 hour)


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


def first(items, bound: int, where: str, what: str, time_of) -> tuple[list, str | None]:
    """The first `bound` of `items` (in time order; any iterable: those beyond are counted, not
    kept), and what a report says when there were more (None: all of them): "a long run: {where}
    the first N of M {what} (up to the time of the first one left out)"."""
    rest = iter(items)
    kept = list(islice(rest, bound + 1))
    if len(kept) <= bound:
        return kept, None
    total = len(kept) + sum(1 for _ in rest)
    return kept[:bound], (f"a long run: {where} the first {bound} of {total} {what} "
                          f"(up to {time_of(kept[bound]):g} s)")


def task_changes(result: Any) -> tuple[list, str | None]:
    """The task state changes a report shows of the run `result` (a SimResult): the first
    TASK_CHANGES, and what a report says when there were more (None: all of them)."""
    return first(result.task_states, TASK_CHANGES, "the task timelines hold", "task state changes",
                 lambda c: c.time_us / 1e6)


def arm_spans(segments, start=lambda s: s["start"]) -> tuple[list, str | None]:
    """The first ARM_SPANS of the arm timeline's moving and idle `segments` ({"start", ...}; or
    anything whose `start` is given), any iterable."""
    return first(segments, ARM_SPANS, "the arm timeline holds", "moving and idle spans", start)


def io_events(result: Any) -> tuple[list, str | None]:
    """The first IO_EVENTS of the I/O changes of the run `result` (its `io_log`)."""
    return first(result.io_log, IO_EVENTS, "the I/O log holds", "I/O changes", lambda e: e.time_us / 1e6)


def part_spans(spans) -> tuple[list, str | None]:
    """The first PART_SPANS of the parts' spans (simulation.arm_record.PartSpan, by start)."""
    return first(spans, PART_SPANS, "the parts drawn are", "part spans", lambda s: s.start)
