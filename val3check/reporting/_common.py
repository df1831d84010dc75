"""Helpers shared by the output formats (stdlib only, imported lazily by the formats)."""

from __future__ import annotations

from typing import TYPE_CHECKING

from ..diagnostics import Diagnostic, Severity

if TYPE_CHECKING:
    from ..result import LintResult

TOOL_NAME = "val3check"


def tool_version(result: "LintResult") -> str:
    if result.tool_version:
        return result.tool_version
    from .. import __version__

    return __version__


def root_of(result: "LintResult") -> str:
    """The folder the CI formats make paths relative to (absolute)."""
    import os

    return os.path.abspath(result.root) if result.root else os.getcwd()


def repository_path(display: str, root: str) -> str:
    """A display path (relative to the current folder, or absolute) made relative to `root`
    with `/` separators; absolute when it lies outside `root`."""
    import os

    absolute = os.path.abspath(display)
    rel = os.path.relpath(absolute, root)
    if rel == ".." or rel.startswith(".." + os.sep) or os.path.isabs(rel):
        return absolute.replace(os.sep, "/") if os.sep != "/" else absolute
    return rel.replace(os.sep, "/")


def severity_of(diag: Diagnostic, result: "LintResult") -> Severity:
    """The diagnostic's severity; the pipeline always sets it, the fallbacks are defensive."""
    if diag.severity is not None:
        return Severity(diag.severity)
    rule = result.rules.get(diag.code)
    return rule.severity if rule is not None else Severity.WARNING


def rule_name(code: str, result: "LintResult") -> str:
    rule = result.rules.get(code)
    return rule.name if rule is not None else ""


def severity_counts(result: "LintResult") -> dict[Severity, int]:
    counts = {s: 0 for s in Severity}
    for diag in result.diagnostics:
        counts[severity_of(diag, result)] += 1
    return counts


def plural(n: int, word: str) -> str:
    return f"{n} {word}" if n == 1 else f"{n} {word}s"


# C0 controls (other than tab) and DEL would move the cursor or colour a terminal, and are not
# allowed in XML 1.0: show them as U+FFFD, which keeps the column count unchanged.
_CONTROL = {c: "\ufffd" for c in (*range(0x00, 0x09), *range(0x0A, 0x20), 0x7F)}


_CONTROL_KEEP_NEWLINE = {c: r for c, r in _CONTROL.items() if c != 0x0A}


def printable(text: str, *, keep_newlines: bool = False) -> str:
    return text.translate(_CONTROL_KEEP_NEWLINE if keep_newlines else _CONTROL)


class SourceCache:
    """Lines of source files, each file read at most once per render.

    Lines are split on "\\n" only (as the positions in diagnostics count them), with a trailing
    "\\r" removed. A missing or unreadable file gives None: the reporters then omit the snippet.
    Only files the run read as VAL 3 (`quotable`: display path -> path on disk) are ever quoted:
    a finding about any other file (outside the application, not VAL 3) names it but never shows
    its content. `quotable=None` (results built by hand) allows any regular file.
    """

    MAX_SIZE = 64 * 1024 * 1024

    def __init__(self, quotable: dict[str, str] | None = None, sources: dict[str, bytes] | None = None) -> None:
        self._files: dict[str, list[str] | None] = {}
        self._quotable = quotable
        self._sources = sources or {}  # display path -> unsaved text (an editor's buffer, stdin)

    def lines(self, path: str) -> list[str] | None:
        if path not in self._files:
            self._files[path] = None
            real = path if self._quotable is None else self._quotable.get(path)
            if path in self._sources:
                text = self._sources[path].decode("utf-8-sig", errors="replace")
                self._files[path] = [ln[:-1] if ln.endswith("\r") else ln for ln in text.split("\n")]
            elif real is not None:
                from ..confine import Refused, Roots, read_bytes

                try:
                    data = read_bytes(real, Roots.user_given(), self.MAX_SIZE)
                except Refused:
                    pass
                else:
                    text = data.decode("utf-8-sig", errors="replace")
                    self._files[path] = [ln[:-1] if ln.endswith("\r") else ln for ln in text.split("\n")]
        return self._files[path]

    def line(self, path: str, line: int) -> str | None:
        """The text of 1-based `line`, or None if unknown."""
        if line < 1:
            return None
        lines = self.lines(path)
        if lines is None or line > len(lines):
            return None
        return lines[line - 1]
