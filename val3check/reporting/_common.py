"""Helpers shared by the output formats (stdlib only, imported lazily by the formats)."""

from __future__ import annotations

from ..diagnostics import Diagnostic, Severity

TYPE_CHECKING = False  # not typing's: importing typing costs 3 ms at lint's start-up
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


# C0 controls (other than tab) and DEL would move the cursor or colour a terminal, are not
# allowed in XML 1.0 and are parse errors in HTML. In the text reports they are shown as their
# Control Pictures (NUL as U+2400 '␀', ESC as '␛', DEL as '␡'), one character each so that
# columns still line up under a caret; C1 controls, lone surrogates (undecodable bytes of a file
# name: they cannot even be written as UTF-8) and the non-characters U+FFFE, U+FFFF as U+FFFD.
_CONTROL = {c: 0x2400 + c for c in (*range(0x00, 0x09), *range(0x0A, 0x20))}
_CONTROL.update({0x7F: 0x2421, 0xFFFE: 0xFFFD, 0xFFFF: 0xFFFD})
_CONTROL.update({c: 0xFFFD for c in (*range(0x80, 0xA0), *range(0xD800, 0xE000))})
_CONTROL_KEEP_NEWLINE = {c: r for c, r in _CONTROL.items() if c != 0x0A}
# In HTML and XML, where no column lines up and many fonts have no Control Pictures, they are
# written as escapes, legible in any font: "\x00", "\x1b", "\x9b"; a lone surrogate of an
# undecodable byte as that byte ("\xff"), any other as "\udXXX"; U+FFFE, U+FFFF as "\ufffe".
_ESCAPED = {c: f"\\x{c:02x}" for c in (*range(0x00, 0x09), *range(0x0B, 0x20), 0x7F, *range(0x80, 0xA0))}
_ESCAPED.update({c: f"\\x{c - 0xDC00:02x}" for c in range(0xDC80, 0xDD00)})
_ESCAPED.update({c: f"\\u{c:04x}" for c in (*range(0xD800, 0xDC80), *range(0xDD00, 0xE000), 0xFFFE, 0xFFFF)})


def printable(text: str, *, keep_newlines: bool = False) -> str:
    """`text` safe on a terminal: every control character shown as one visible character (see
    _CONTROL); `keep_newlines` keeps line feeds."""
    return text.translate(_CONTROL_KEEP_NEWLINE if keep_newlines else _CONTROL)


def visible(text: str) -> str:
    """`text` as HTML and XML 1.0 text may hold it: tabs and line feeds kept, every other control
    character, lone surrogate and non-character written as an escape (see _ESCAPED)."""
    return text.translate(_ESCAPED)


def visible_data(value):  # noqa: ANN001, ANN201
    """`value` (JSON-like: dicts, lists, strings, numbers) with `visible` applied to every string
    and key (iterative: no depth limit)."""
    root = [value]
    todo = [(root, 0)]
    while todo:
        holder, key = todo.pop()
        v = holder[key]
        if isinstance(v, str):
            holder[key] = visible(v)
        elif isinstance(v, (list, tuple)):
            copy = list(v)
            holder[key] = copy
            # only what may hold a string (a page's long lists are numbers)
            todo.extend((copy, i) for i, x in enumerate(copy) if isinstance(x, (str, list, tuple, dict)))
        elif isinstance(v, dict):
            copy = {visible(k) if isinstance(k, str) else k: x for k, x in v.items()}
            holder[key] = copy
            todo.extend((copy, k) for k in copy)
    return root[0]


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
