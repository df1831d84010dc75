"""Turn a `SimResult` into what the reports show: diagnostics filtered and graded by the
user's configuration (rule selection, severities, like lint rules), display paths."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from ..diagnostics import Severity
from ..lint import display_path
from .simulate import SimResult


@dataclass
class SimReport:
    result: SimResult
    app_path: str
    tool_version: str
    diagnostics: list[dict] = field(default_factory=list)
    link_names: dict = field(default_factory=dict)

    def display(self, pos) -> Any:
        if not pos:
            return None
        path, line, col, program = pos
        return (display_path(path), line, col, program)


def build_report(result: SimResult, settings, rules: dict, tool_version: str, link_names: dict | None = None) -> SimReport:
    rep = SimReport(result, display_path(result.app_path), tool_version, link_names=link_names or {})
    kept = []
    for d in result.diagnostics:
        if settings is not None and not settings.enabled(d.code, d.path):
            continue
        rule = rules.get(d.code)
        sev = (settings.severity.get(d.code) if settings is not None else None) or (rule.severity if rule else Severity.ERROR)
        kept.append({
            "code": d.code, "name": rule.name if rule else None, "severity": sev.label, "message": d.message,
            "path": display_path(d.path), "line": d.line or None, "column": d.col or None,
            "time": round(d.time_us / 1_000_000, 6), "task": d.task or None, "program": d.program or None,
            "error": d.error,
        })
    kept.sort(key=lambda x: (x["time"], x["task"] or "", x["code"], x["path"], x["line"] or 0))
    rep.diagnostics = kept
    return rep
