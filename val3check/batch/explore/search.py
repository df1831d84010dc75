"""Which variants `sim --explore` runs (docs/explore.md): first the ones a timing bug is most
likely to hide behind, then uniform draws, all fixed by the seed.

The directed variants move one timing at a time (the others nominal), in this order:

1. each timing at the ends of its range (a slow clamp, an early sensor), the widest ranges first;
2. each timing moved so that the moment it acts falls just before and just after a *boundary*
   of the nominal run: the end of a wait of a task (a `delay`, `wait`, `watch` that returned)
   or the moment another timing acts (two events swap their order). The moment a reaction acts
   is its trigger in the nominal run (the output it answers) plus its delay;
3. pairs of timings at opposite ends (one early, the other late).

Each list is cut to what the budget allows: in 2, the smallest deviations first, the timings in
turn. What is left of the budget is uniform draws: variant `k` of seed `s` is drawn
from its own generator seeded with `(s, k)`, so a variant does not depend on how many there
are, the executor, -j, or the machine (Python's Mersenne Twister and IEEE doubles)."""

from __future__ import annotations

import itertools
import random
from collections import Counter
from collections.abc import Iterator
from dataclasses import dataclass, field

from .timings import RESOLUTION, Timing

EDGE = RESOLUTION  # s: how far before and after a boundary a timing is put
PER_TIMING = 16  # boundary variants kept per timing (the closest to the nominal)
MAX_MOMENTS = 8  # moments a reaction acts at in the nominal run that are aimed at boundaries
MAX_AIMED = 64  # timings aimed at boundaries and paired (the widest ranges): a scenario of
MAX_BOUNDS = 4096  # thousands of events stays linear; boundaries kept (the earliest)


@dataclass
class Observed:
    """What the nominal run shows: the ends of waits, and when each signal changed."""

    wait_ends: list[float] = field(default_factory=list)  # s, sorted
    changes: dict[str, list[tuple[float, object]]] = field(default_factory=dict)  # signal name -> (s, value)


def observe(result) -> Observed:
    """The boundaries of the nominal run: a task going from waiting (or blocked) to running,
    and every change of an input or output, under each name the scenario may give it."""
    ends, last = set(), {}
    for ch in result.task_states:
        if ch.state == "running" and last.get(ch.task) in ("waiting", "blocked"):
            ends.add(round(ch.time_us / 1e6, 6))
        last[ch.task] = ch.state
    names: dict[str, list[str]] = {}
    for (kind, link), variables in result.link_names.items():
        names.setdefault(link, []).extend([link, *variables])
    changes: dict[str, list[tuple[float, object]]] = {}
    before: dict[str, object] = {}
    for ev in result.io_log:
        if ev.kind != "dio" and ev.kind != "aio":
            continue
        if before.get(ev.link, None) == ev.value and ev.link in before:
            continue
        before[ev.link] = ev.value
        for n in names.get(ev.link, [ev.link]):
            changes.setdefault(n, []).append((ev.time_us / 1e6, ev.value))
    return Observed(sorted(ends), changes)


def moments(t: Timing, seen: Observed) -> list[float]:
    """When `t` acts in the nominal run (s): its time, or its trigger plus its delay."""
    if t.absolute:
        return [t.nominal]
    if t.path[0] == "reactions":
        return [at + t.nominal for at, v in seen.changes.get(t.when, []) if v == t.becomes][:MAX_MOMENTS]
    return []  # a serial answer: its trigger is not in the I/O log


def directed(ts: list[Timing], seen: Observed) -> Iterator[tuple[float, ...]]:
    """The directed variants, in the order they are worth running, without repeats; made as
    they are taken (a scenario of thousands of times asks for a few of them)."""
    nominal = tuple(t.nominal for t in ts)
    done = {nominal}

    def new(v: tuple[float, ...]) -> bool:
        if v in done:
            return False
        done.add(v)
        return True

    order = sorted(range(len(ts)), key=lambda i: (-(ts[i].hi - ts[i].lo), i))  # the widest ranges first
    for i in order:
        for v in (ts[i].lo, ts[i].hi):
            if new(w := _with(nominal, i, v)):
                yield w
    acts = [moments(t, seen) for t in ts]
    ends = sorted(set(seen.wait_ends) | {m for ms in acts for m in ms})[:MAX_BOUNDS]
    waits, shared = set(seen.wait_ends), Counter(m for ms in acts for m in set(ms))
    per: list[list[tuple[int, float]]] = []
    for i in order[:MAX_AIMED]:
        t = ts[i]
        own = set(acts[i])  # its own moments, unless a wait ends or another timing acts then too
        bounds = {b for b in ends if b not in own or b in waits or shared[b] > 1}
        aims = sorted({t.clamp(t.nominal + b + s - m) for b in bounds for m in acts[i] for s in (-EDGE, EDGE)
                       if t.lo <= t.nominal + b + s - m <= t.hi}, key=lambda v: (abs(v - t.nominal), v))
        per.append([(i, v) for v in aims[:PER_TIMING]])
    for group in itertools.zip_longest(*per):
        for iv in group:
            if iv is not None and new(w := _with(nominal, *iv)):
                yield w
    for i, j in itertools.combinations(sorted(order[:MAX_AIMED]), 2):
        for a, b in ((ts[i].lo, ts[j].hi), (ts[i].hi, ts[j].lo)):
            if new(w := _with(_with(nominal, i, a), j, b)):
                yield w


def uniform(ts: list[Timing], seed: int, k: int) -> tuple[float, ...]:
    """Draw `k` of seed `seed`: each timing uniform in its range, in milliseconds."""
    rng = random.Random(f"val3check-explore:{seed}:{k}")
    return tuple(t.clamp(round(rng.uniform(t.lo, t.hi) / RESOLUTION) * RESOLUTION) for t in ts)


def variants(ts: list[Timing], seen: Observed, n: int, seed: int) -> list[tuple[float, ...]]:
    """`n` variants (fewer when the ranges hold fewer distinct ones): at most three quarters
    directed, the rest uniform draws; never the nominal, never twice the same."""
    nominal = tuple(t.nominal for t in ts)
    chosen = list(itertools.islice(directed(ts, seen), n - n // 4))
    known = set(chosen) | {nominal}
    k = 0
    while len(chosen) < n and k < 20 * n:
        v = uniform(ts, seed, k)
        k += 1
        if v not in known:
            known.add(v)
            chosen.append(v)
    return chosen


def _with(values: tuple[float, ...], i: int, v: float) -> tuple[float, ...]:
    return values[:i] + (v,) + values[i + 1:]
