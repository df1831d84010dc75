"""Shrinking a failing variant toward the nominal times, as property-based testers shrink
(docs/explore.md): the smallest deviation found that still fails with the same cause.

Two passes, each a series of rounds; the variants of a round run together on the executor, and
what the next round tries depends only on the results of the previous ones (never on their
order of arrival), so the result is the same whatever -j and the executor:

1. timings put back to their nominal value, one at a time, as long as one can be (the first in
   file order that still fails is kept, and the round is tried again);
2. each timing left moved, in file order: its deviation searched between 0 (passes) and its
   value (fails), in milliseconds, `SPLIT` points per round, keeping the smallest that fails.

The search assumes that failing is monotonic in each deviation on the way back to nominal; where
it is not (a failure that happens only inside a window), the result still fails but a smaller
failing deviation may exist outside the points tried."""

from __future__ import annotations

from collections.abc import Callable

from .timings import RESOLUTION, Timing

SPLIT = 7  # points tried per round of the search of one deviation: 8× narrower per round
MAX_RUNS = 400  # runs spent on one failure at most

Check = Callable[[list[tuple[float, ...]]], list[bool]]  # variants -> each still fails (same cause)


def shrink(ts: list[Timing], failing: tuple[float, ...], check: Check) -> tuple[tuple[float, ...], int]:
    """The shrunk variant and the number of runs it took."""
    nominal = tuple(t.nominal for t in ts)
    cur, runs = failing, 0
    while runs < MAX_RUNS:
        moved = [i for i in range(len(ts)) if cur[i] != nominal[i]]
        if len(moved) <= 1:  # the nominal itself does not fail so (the caller's condition)
            break
        tries = [cur[:i] + (nominal[i],) + cur[i + 1:] for i in moved]
        ok = check(tries)
        runs += len(tries)
        kept = [v for v, still in zip(tries, ok, strict=True) if still]
        if not kept:
            break
        cur = kept[0]
    for i, t in enumerate(ts):
        if cur[i] == nominal[i] or runs >= MAX_RUNS:
            continue
        sign = 1 if cur[i] > nominal[i] else -1
        passing, fails = 0, max(1, round(abs(cur[i] - nominal[i]) / RESOLUTION))
        top = cur[i]  # the value at `fails` steps (it may not be a whole number of steps: a range's end)
        while fails - passing > 1 and runs < MAX_RUNS:
            steps = sorted({passing + (fails - passing) * k // (SPLIT + 1) for k in range(1, SPLIT + 1)}
                           - {passing, fails})
            values = [t.clamp(nominal[i] + sign * s * RESOLUTION) for s in steps]
            ok = check([cur[:i] + (v,) + cur[i + 1:] for v in values])
            runs += len(steps)
            first = next((k for k, still in enumerate(ok) if still), None)
            if first is None:
                passing = steps[-1]
            else:
                fails, top = steps[first], values[first]
                passing = steps[first - 1] if first else passing
        cur = cur[:i] + (top,) + cur[i + 1:]
    return cur, runs
