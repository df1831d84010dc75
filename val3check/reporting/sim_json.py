"""`val3check sim --report json`: the documented, versioned run report (docs/sim-report.md).

Deterministic byte for byte: keys sorted, 2-space indent, ASCII only, times in simulated
seconds, no wall-clock value. Bump VERSION on any incompatible change.
"""

from __future__ import annotations

import json
from typing import Any

from ..diagnostics import Severity
from ._common import TOOL_NAME

VERSION = 1


def _t(us: int | None) -> float | None:
    return None if us is None else round(us / 1_000_000, 6)


def _pos(pos) -> dict | None:
    if not pos:
        return None
    path, line, col, program = pos
    return {"path": path, "line": line or None, "column": col or None, "program": program or None}


def _diagnostic(run: Any, d) -> dict[str, Any]:
    return {"code": d.code, "name": run.rule_name(d.code), "severity": d.severity.label, "message": d.message,
            "path": d.path, "line": d.line or None, "column": d.col or None, "time": _t(d.time_us),
            "task": d.task or None, "program": d.program or None, "error": d.error}


def report(run: Any) -> dict[str, Any]:
    """`run` is a `SimReport` (sim_report.py): the SimResult plus kept diagnostics."""
    r = run.result
    return {
        "version": VERSION,
        "tool": {"name": TOOL_NAME, "version": run.tool_version},
        "application": {"name": r.application, "path": run.app_path},
        "robot": r.robot,
        "end": {"reason": r.end_reason, "message": r.end_message},
        "simulated_duration": _t(r.sim_time_us),
        "lines_executed": r.lines,
        "summary": {
            "error": sum(1 for d in run.diagnostics if d.severity is Severity.ERROR),
            "warning": sum(1 for d in run.diagnostics if d.severity is Severity.WARNING),
            "info": sum(1 for d in run.diagnostics if d.severity is Severity.INFO),
            "tasks": len(r.tasks),
            "transcript_entries": len(r.transcript),
            "io_events": len(r.io_log),
        },
        "tasks": [
            {
                "name": t.name,
                "program": t.program,
                "library": t.library,
                "priority": t.priority,
                "period": t.period,
                "created": _t(t.created),
                "ended": _t(t.ended),
                "end": t.end,
                "state_at_end_of_run": t.state_at_end_of_run,
                "error": t.error,
                "error_text": t.error_text,
                "blocked_on": t.blocked_on,
                "position": _pos(run.display(t.position)),
                "lines_executed": t.lines,
            }
            for t in r.tasks
        ],
        "destroyed": list(r.destroyed),
        "diagnostics": [_diagnostic(run, d) for d in run.diagnostics],
        "transcript": [
            {"time": _t(e.time_us), "task": e.task, "kind": e.kind, "text": e.text, "screen": e.screen}
            for e in r.transcript
        ],
        "io_log": [
            {"time": _t(e.time_us), "kind": e.kind, "link": e.link, "names": run.link_names.get((e.kind, e.link), []),
             "value": e.value if not isinstance(e.value, float) or e.value == e.value else None, "source": e.source}
            for e in r.io_log
        ],
        "screen": r.screen,
    }


def render(run: Any) -> str:
    return json.dumps(report(run), indent=2, sort_keys=True, ensure_ascii=True) + "\n"
