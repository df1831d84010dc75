"""`--format json`: the documented, versioned machine-readable report (docs/json-format.md).

Deterministic byte for byte: keys sorted, 2-space indent, ASCII only (non-ASCII characters as
\\u escapes), trailing newline, no timestamps. Bump VERSION on any incompatible change.
"""

from __future__ import annotations

import json
from typing import TYPE_CHECKING, Any

from ..diagnostics import Diagnostic, Severity
from ._common import TOOL_NAME, severity_counts, severity_of, tool_version

if TYPE_CHECKING:
    from ..result import LintResult

VERSION = 1


def _position(value: int | None) -> int | None:
    return value if value is not None and value > 0 else None


def _diagnostic(diag: Diagnostic, result: "LintResult") -> dict[str, Any]:
    rule = result.rules.get(diag.code)
    line = _position(diag.line)
    column = _position(diag.col) if line is not None else None
    end_line = _position(diag.end_line) if line is not None else None
    end_column = _position(diag.end_col) if end_line is not None and column is not None else None
    return {
        "code": diag.code,
        "name": rule.name if rule is not None else None,
        "severity": severity_of(diag, result).label,
        "message": diag.message,
        "path": diag.path,
        "line": line,
        "column": column,
        "end_line": end_line,
        "end_column": end_column,
        "manual": (rule.manual or None) if rule is not None else None,
    }


def report(result: "LintResult") -> dict[str, Any]:
    counts = severity_counts(result)
    return {
        "version": VERSION,
        "tool": {"name": TOOL_NAME, "version": tool_version(result)},
        "summary": {
            "error": counts[Severity.ERROR],
            "warning": counts[Severity.WARNING],
            "info": counts[Severity.INFO],
            "total": len(result.diagnostics),
            "files_checked": len(result.files),
            "files_with_diagnostics": len({d.path for d in result.diagnostics}),
            "applications_checked": len(result.applications),
            "baselined": result.baselined,
        },
        "files": list(result.files),
        "applications": list(result.applications),
        "diagnostics": [_diagnostic(d, result) for d in result.diagnostics],
    }


def statistics_report(result: "LintResult") -> dict[str, Any]:
    """`--statistics --output-format json`: counts per rule, most frequent first, then by code."""
    counts: dict[str, int] = {}
    severities: dict[str, Severity] = {}
    for diag in result.diagnostics:
        counts[diag.code] = counts.get(diag.code, 0) + 1
        sev = severity_of(diag, result)
        severities[diag.code] = max(sev, severities.get(diag.code, sev))
    rows = []
    for code, n in sorted(counts.items(), key=lambda item: (-item[1], item[0])):
        rule = result.rules.get(code)
        rows.append({"code": code, "name": rule.name if rule is not None else None, "count": n,
                     "severity": severities[code].label, "fixable": bool(rule is not None and rule.fix)})
    body = report(result)
    return {"version": VERSION, "tool": body["tool"], "summary": body["summary"], "statistics": rows}


def render(result: "LintResult", *, statistics: bool = False) -> str:
    body = statistics_report(result) if statistics else report(result)
    return json.dumps(body, indent=2, sort_keys=True, ensure_ascii=True) + "\n"
