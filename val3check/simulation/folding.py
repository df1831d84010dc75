"""Repeated findings of a run folded into one (issue 26): a finding of one rule at one place, with
the same message, task and error, is kept once with its count and its first and last simulated
times, in every report (the message says it; `Diagnostic.count`, `last_time_us`).

A loop that re-issues a `movej` to where the arm stands gives one R016 per pass: hundreds of
thousands in a long run. Folded, the report keeps one line per distinct finding, and at most
MAX_KEPT of them: beyond, one R006 says how many more there were (memory and size bounded by
design, not by the length of the run).
"""

from __future__ import annotations

from ..diagnostics import Diagnostic
from ..rules import codes

MAX_KEPT = 10_000  # distinct findings a run reports


def _key(d: Diagnostic) -> tuple:
    return (d.code, d.path, d.line, d.col, d.task, d.program, d.error, d.message)


def fold(diags: list[Diagnostic], app_path: str = "", end_us: int | None = None) -> list[Diagnostic]:
    """`diags` (in time order) with repeats folded, the order of first occurrences kept."""
    first: dict[tuple, int] = {}
    counts: list[int] = []
    lasts: list[int | None] = []
    kept: list[Diagnostic] = []
    dropped: dict[str, int] = {}
    for d in diags:
        if d.time_us is None:  # not a runtime finding: as it is
            kept.append(d)
            counts.append(1)
            lasts.append(None)
            continue
        k = _key(d)
        i = first.get(k)
        if i is not None:
            counts[i] += d.count
            lasts[i] = max(lasts[i] or 0, d.last_time_us if d.last_time_us is not None else d.time_us)
            continue
        if len(first) >= MAX_KEPT:
            dropped[d.code] = dropped.get(d.code, 0) + d.count
            continue
        first[k] = len(kept)
        kept.append(d)
        counts.append(d.count)
        lasts.append(d.last_time_us if d.last_time_us is not None else d.time_us)
    out = []
    for d, n, last in zip(kept, counts, lasts):
        if n > 1 and d.count != n:
            d = _folded(d, n, last)
        out.append(d)
    if dropped:
        what = ", ".join(f"{n} of {code}" for code, n in sorted(dropped.items()))
        out.append(Diagnostic(codes.BUDGET_EXCEEDED, f"findings not reported: {what} (a run reports at most {MAX_KEPT} distinct "
                              "findings, repeats folded)", app_path, 0, 0,
                              time_us=end_us if end_us is not None else 0, task="", program=""))
    return out


def _folded(d: Diagnostic, n: int, last: int | None) -> Diagnostic:
    """`d` standing for `n` occurrences, the last at `last` (µs)."""
    base = d.message.split(" [repeated ", 1)[0] if d.count > 1 else d.message
    span = f"from {d.time_us / 1e6:.3f} s to {(last or 0) / 1e6:.3f} s" if d.time_us is not None else ""
    message = f"{base} [repeated {n} times, {span}]"
    return Diagnostic(d.code, message, d.path, d.line, d.col, d.end_line, d.end_col, d.severity, d.time_us, d.task,
                      d.program, d.error, d.fix, d.at_most, count=n, last_time_us=last)
