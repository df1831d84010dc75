"""The closing line of a run (issue 28 item 2): PASSED or FAILED as the exit code says, the
diagnostics counted by severity, the cycle time, and what was written. The text report ends
with it; `sim` prints it on standard error whenever the report is not text on standard output
(`-o FILE`, `--report json|html|junit`, `--trace`), so that a run never ends silent."""

from __future__ import annotations

import statistics
from typing import Any

from ..diagnostics import Severity


def failed(report: Any, fail_on: str) -> bool:
    """What the exit code says: a diagnostic at or above `fail_on` ("never": none)."""
    if fail_on == "never":
        return False
    threshold = Severity.parse(fail_on)
    return any(d.severity >= threshold for d in report.diagnostics)


def _counts(report: Any) -> str:
    n = {s: 0 for s in Severity}
    for d in report.diagnostics:
        n[d.severity] += 1
    parts = []
    for s in (Severity.ERROR, Severity.WARNING, Severity.INFO):
        word = s.label if s is Severity.INFO else s.label + ("s" if n[s] != 1 else "")
        parts.append(f"{n[s]} {word}")
    return ", ".join(parts)


def _cycle(report: Any) -> str:
    m = report.result.motion
    if m is None:
        return "no cycle time (no arm model)"
    from ..simulation.arm_record import main_cycle

    best = main_cycle(m.cycles)
    if best is None:
        return "no cycle time (no loop of the arm completed a cycle)"
    return f"cycle time {statistics.median(best.times):.3f} s (median of {best.count}, task {best.task})"


def closing_line(report: Any, fail_on: str, written: list[str] | tuple[str, ...] = ()) -> str:
    """`PASSED: 0 errors, 1 warning, 2 info; cycle time 2.799 s (median of 3, task robot); wrote r.html`."""
    verdict = "FAILED" if failed(report, fail_on) else "PASSED"
    below = f" (--fail-on {fail_on})" if fail_on != "error" else ""
    line = f"{verdict}{below}: {_counts(report)}; {_cycle(report)}"
    return line + (f"; wrote {', '.join(written)}" if written else "")
