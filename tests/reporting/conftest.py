"""Fixtures for the reporter tests: a small fake rule catalogue and a LintResult factory."""

from __future__ import annotations

import pytest

from val3check.diagnostics import Diagnostic, Severity
from val3check.result import LintResult
from val3check.rules.catalogue import Rule

FAKE_RULES = {
    "F001": Rule("F001", "file-unreadable", Severity.ERROR, "", "A file cannot be read.", ""),
    "F101": Rule(
        "F101",
        "syntax-error",
        Severity.ERROR,
        "2.2.5",
        "The code does not follow the VAL 3 syntax.",
        "VAL 3 blocks must be **closed** by the matching `end` keyword.\n\nFix the block.",
    ),
    "N201": Rule("N201", "bad-name", Severity.INFO, "2.3.1", "A name breaks the naming rules.", "Names < 15 & ok."),
    "S301": Rule(
        "S301", "unused-variable", Severity.WARNING, "3.1", "A local variable is never used.", "Remove it."
    ),
}


def diag(code: str, message: str, path: str, line: int = 0, col: int = 0, end_line=None, end_col=None, severity=None):
    if severity is None:
        severity = FAKE_RULES[code].severity if code in FAKE_RULES else Severity.WARNING
    return Diagnostic(code, message, path, line, col, end_line, end_col, severity)


@pytest.fixture
def rules() -> dict[str, Rule]:
    return dict(FAKE_RULES)


@pytest.fixture
def make_result():
    def make(diagnostics, files=None, applications=("App",), version="1.2.3"):
        diagnostics = sorted(diagnostics, key=Diagnostic.sort_key)
        if files is None:
            files = sorted({d.path for d in diagnostics})
        return LintResult(list(diagnostics), list(files), list(applications), dict(FAKE_RULES), version)

    return make


@pytest.fixture
def d():
    """`d(code, message, path, line, col, end_line, end_col, severity)` builds a Diagnostic."""
    return diag


@pytest.fixture
def workdir(tmp_path, monkeypatch):
    """An empty current directory, so that diagnostics can use relative display paths."""
    monkeypatch.chdir(tmp_path)
    return tmp_path
