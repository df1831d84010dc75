"""What `sim --explore` found: the causes of failure of the variants, grouped (docs/explore.md).

A cause is what makes a run fail, named by where it points: a runtime diagnostic at or above
--fail-on (rule, file, line: a runtime error, a deadlock, a collision, an unreachable target), a
cycle longer than the scenario's `[explore] max_cycle_time`, or a case that could not run or
ended in a crash or over its budget. Variants that fail for the same cause are one group, however
many: its count, its smallest deviation seen, and one reproducer shrunk toward the nominal."""

from __future__ import annotations

from dataclasses import dataclass, field

from .timings import Timing

NOT_RUN = ("not-run", "crash", "over-budget")


@dataclass(frozen=True)
class Cause:
    code: str  # a rule code, "cycle-time", or the verdict of a case that did not run to its end
    path: str
    line: int
    col: int = 0
    severity: str = "error"
    message: str = ""
    time_us: int | None = None
    task: str = ""

    @property
    def key(self) -> tuple:
        return (self.code, self.path, self.line)

    def where(self) -> str:
        if self.code == "cycle-time":
            return f"the arm's cycle ([explore] max_cycle_time of {self.path})"
        return f"{self.path}:{self.line}:{self.col}" if self.line else (self.path or "the run")

    def when(self) -> str:
        parts = []
        if self.time_us is not None:
            parts.append(f"at {self.time_us / 1e6:.3f} s of simulated time")
        if self.task:
            parts.append(f"in task {self.task}")
        return ", ".join(parts)


def causes(summary, max_cycle: float | None) -> list[Cause]:
    """The causes of failure of one run, without repeats (in the run's order)."""
    if summary.verdict in NOT_RUN:
        return [Cause(summary.verdict, "", 0, message=summary.reason or summary.verdict)]
    out = [Cause(code, path, line, col, severity, message, time_us, task)
           for code, severity, path, line, col, time_us, task, message in summary.causes]
    if max_cycle is not None and summary.cycle_max is not None and summary.cycle_max > max_cycle:
        out.append(Cause("cycle-time", summary.scenario.rsplit("#", 1)[0], 0,
                         message=f"a cycle of {summary.cycle_max:.3f} s, above the bound of {max_cycle:g} s"
                                 " ([explore] max_cycle_time)"))
    seen: dict[tuple, Cause] = {}
    for c in out:
        seen.setdefault(c.key, c)
    return list(seen.values())


def size(ts: list[Timing], values: tuple[float, ...]) -> tuple[float, int]:
    """How far a variant is from the nominal: the sum of the deviations (s), then how many moved."""
    ds = [abs(v - t.nominal) for t, v in zip(ts, values, strict=True)]
    return round(sum(ds), 6), sum(1 for d in ds if d)


@dataclass
class Group:
    """The variants that failed for one cause."""

    cause: Cause
    count: int = 0
    nominal: bool = False  # the nominal run fails so too: no timing is needed
    smallest: tuple[float, ...] = ()  # the variant of smallest deviation that failed so
    shrunk: tuple[float, ...] = ()  # after shrinking (the reproducer's values)
    shrunk_cause: Cause | None = None  # the cause as the shrunk variant shows it (its time)
    runs: int = 0  # runs spent shrinking
    reproducer: str = ""  # its file name under the out folder
    variants: list[int] = field(default_factory=list)  # the variants that failed so (1-based)


def deviations(ts: list[Timing], values: tuple[float, ...]) -> list[dict]:
    return [{"timing": t.label, "line": t.line, "nominal": t.nominal, "value": v, "delta": round(v - t.nominal, 6)}
            for t, v in zip(ts, values, strict=True) if v != t.nominal]
