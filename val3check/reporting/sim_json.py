"""`val3check sim --report json`: the documented, versioned run report (docs/sim-report.md).

Deterministic byte for byte: keys sorted, 2-space indent, ASCII only, times in simulated
seconds, no wall-clock value. Bump VERSION on any incompatible change.
"""

from __future__ import annotations

import json
from typing import Any

from ._common import TOOL_NAME

VERSION = 1


def _t(us: int | None) -> float | None:
    return None if us is None else round(us / 1_000_000, 6)


def _pos(pos) -> dict | None:
    if not pos:
        return None
    path, line, col, program = pos
    return {"path": path, "line": line or None, "column": col or None, "program": program or None}


def report(run: Any) -> dict[str, Any]:
    """`run` is a `SimReport` (cli): the SimResult plus kept diagnostics with severities."""
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
            "error": sum(1 for d in run.diagnostics if d["severity"] == "error"),
            "warning": sum(1 for d in run.diagnostics if d["severity"] == "warning"),
            "info": sum(1 for d in run.diagnostics if d["severity"] == "info"),
            "tasks": len(r.tasks),
            "transcript_entries": len(r.transcript),
            "io_events": len(r.io_log),
        },
        "tasks": [
            {
                "name": t["name"],
                "program": t["program"],
                "library": t["library"],
                "priority": t["priority"],
                "period": t["period"],
                "created": _t(t["created"]),
                "ended": _t(t["ended"]),
                "end": t["end"],
                "state_at_end_of_run": t["state_at_end_of_run"],
                "error": t["error"],
                "error_text": t["error_text"],
                "blocked_on": t["blocked_on"],
                "position": _pos(run.display(t["position"])),
                "lines_executed": t["lines"],
            }
            for t in r.tasks
        ],
        "destroyed": list(r.destroyed),
        "diagnostics": [
            {k: d[k] for k in ("code", "name", "severity", "message", "path", "line", "column", "time", "task",
                               "program", "error")}
            for d in run.diagnostics
        ],
        "transcript": [
            {"time": _t(at), "task": task, "kind": kind, "text": text, "screen": screen}
            for at, task, kind, text, screen in r.transcript
        ],
        "io_log": [
            {"time": _t(at), "kind": kind, "link": link, "names": run.link_names.get((kind, link), []),
             "value": value if not isinstance(value, float) or value == value else None, "source": source}
            for at, kind, link, value, source in r.io_log
        ],
        "screen": r.screen,
    }


def render(run: Any) -> str:
    return json.dumps(report(run), indent=2, sort_keys=True, ensure_ascii=True) + "\n"
