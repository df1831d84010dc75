"""The sim report: a `SimResult` as the reports show it (sim_text.py, sim_json.py).

Runtime diagnostics are filtered and graded by the user's configuration like lint findings
(rule selection, severities), their paths made relative to the current folder, and sorted by
simulated time."""

from __future__ import annotations

import os
from typing import Any

from ..diagnostics import Diagnostic, Severity
from ..light_dataclass import dataclass, field
from ..lint import display_path
from ..simulation.result import SimResult


@dataclass
class SimReport:
    """A run's result as the reports show it: its diagnostics (severities set, paths as displayed),
    the rule catalogue, and the names of the I/O links."""

    result: SimResult
    app_path: str  # display path of the application
    tool_version: str
    diagnostics: list[Diagnostic] = field(default_factory=list)  # kept, severity set, display paths
    rules: dict = field(default_factory=dict)  # the rule catalogue, by code
    link_names: dict = field(default_factory=dict)  # (kind, link) -> variable names

    # (path, current folder) -> display path, once: thousands of motions name a few files
    shown: dict = field(default_factory=dict, repr=False, compare=False)

    def display(self, pos) -> Any:
        """A (path, line, col, program) position with a display path."""
        if not pos:
            return None
        path, line, col, program = pos
        key = (path, os.getcwd())  # what display_path reads
        shown = self.shown.get(key)
        if shown is None:
            shown = self.shown[key] = display_path(path)
        return (shown, line, col, program)

    def rule_name(self, code: str) -> str | None:
        rule = self.rules.get(code)
        return rule.name if rule else None


def _sort_key(d: Diagnostic) -> tuple:
    return (round(d.time_us / 1_000_000, 6), d.task or "", d.code, d.path, d.line or 0)


def build_report(result: SimResult, settings, rules: dict, tool_version: str) -> SimReport:
    kept = []
    for d in result.diagnostics:
        if settings is not None and not settings.enabled(d.code, d.path):
            continue
        rule = rules.get(d.code)
        sev = (settings.severity.get(d.code) if settings is not None else None) or (rule.severity if rule else Severity.ERROR)
        kept.append(Diagnostic(d.code, d.message, display_path(d.path), d.line, d.col, d.end_line, d.end_col, sev,
                               d.time_us, d.task, d.program, d.error, count=d.count, last_time_us=d.last_time_us))
    kept.sort(key=_sort_key)
    return SimReport(result, display_path(result.app_path), tool_version, kept, rules, link_names=result.link_names)
