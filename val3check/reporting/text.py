"""The default, human-readable format (ruff-like).

    App/start.pgx:12:5: F101 [error] unexpected 'endWhile'
       |
    12 |     endWhile
       |     ^^^^^^^^

    Found 1 error in 1 file (5 files checked).

A whole-file finding (line 0) prints only the header `path: CODE [severity] message`; a finding
without a column (col 0) prints `path:line:` and underlines the whole line. Tabs in the source
line are expanded to TAB_SIZE columns, in the caret line too, so the caret stays aligned.
With `statistics=True` a table of counts per code replaces the findings (as ruff --statistics).
`concise=True` prints the header line of each finding only (`--output-format concise`, for
editors' problem matchers); `quiet=True` leaves out the summary line.
"""

from __future__ import annotations

from collections import Counter

from ..diagnostics import Diagnostic, Severity
from ._common import SourceCache, plural, printable, rule_name, severity_counts, severity_of

TYPE_CHECKING = False  # not typing's: importing typing costs 3 ms at lint's start-up
if TYPE_CHECKING:
    from ..result import LintResult

TAB_SIZE = 4

_RESET = "\x1b[0m"
_BOLD = "\x1b[1m"
_SEVERITY_COLOR = {
    Severity.ERROR: "\x1b[31m",  # red
    Severity.WARNING: "\x1b[33m",  # yellow
    Severity.INFO: "\x1b[36m",  # cyan
}
_GUTTER = "\x1b[1;34m"  # bold blue
_PASS = "\x1b[1;32m"  # bold green


class _Style:
    def __init__(self, color: bool) -> None:
        self.color = color

    def __call__(self, text: str, *codes: str) -> str:
        if not self.color or not text:
            return text
        return "".join(codes) + text + _RESET


def _width(text: str) -> int:
    """Display width of a prefix of a source line (tabs expanded from the start of the line)."""
    return len(text.expandtabs(TAB_SIZE)) if "\t" in text else len(text)


# A source line longer than this is shown as a window around the finding (a generated or hostile
# file may hold a megabyte on one line, and thousands of findings on it).
MAX_SHOWN = 160


def _column_offset(source: str, col: int) -> int:
    """Display offset of 1-based code-point column `col` of `source` (may lie past the end)."""
    index = col - 1
    if "\t" not in source:
        return index
    if index <= len(source):
        return _width(source[:index])
    return _width(source) + (index - len(source))


def _underline(diag: Diagnostic, source: str) -> tuple[int, int] | None:
    """(start, end) display offsets of the caret run under `source`, or None for no caret line."""
    if diag.col <= 0:  # no column: underline the whole (non-blank) line
        display = source.expandtabs(TAB_SIZE)
        stripped = display.strip()
        if not stripped:
            return None
        start = len(display) - len(display.lstrip())
        return start, start + len(stripped)
    start = _column_offset(source, diag.col)
    end = start + 1
    if diag.end_line is not None and diag.end_line == diag.line:
        if diag.end_col is not None and diag.end_col > diag.col:
            end = _column_offset(source, diag.end_col)  # end_col is exclusive
    elif diag.end_line is not None and diag.end_line > diag.line:
        end = max(end, _width(source.rstrip()))  # span continues below: underline to end of line
    return start, max(end, start + 1)


def _header(diag: Diagnostic, severity: Severity, style: _Style, one_line: bool = False) -> str:
    where = style(diag.path, _BOLD)
    if diag.line > 0:
        where += f":{diag.line}"
        if diag.col > 0:
            where += f":{diag.col}"
    colour = _SEVERITY_COLOR[severity]
    code = style(diag.code, _BOLD, colour)
    label = style(f"[{severity.label}]", colour)
    message = printable(diag.message, keep_newlines=not one_line)
    return f"{where}: {code} {label} {message}"


def _snippet(diag: Diagnostic, severity: Severity, sources: SourceCache, style: _Style,
             prepared: dict | None = None) -> list[str]:
    if diag.line <= 0:
        return []
    key = (diag.path, diag.line)
    if prepared is not None and key in prepared:
        source, display = prepared[key]
    else:
        source = sources.line(diag.path, diag.line)
        if source is None:
            return []
        source = printable(source)
        display = source.expandtabs(TAB_SIZE).rstrip() if "\t" in source else source.rstrip()
        if prepared is not None:
            prepared[key] = (source, display)
    number = str(diag.line)
    pad = " " * len(number)
    bar = style("|", _GUTTER)
    span = _underline(diag, source)
    if len(display) > MAX_SHOWN:
        lo = max(0, (span[0] if span else 0) - MAX_SHOWN // 4)
        hi = lo + MAX_SHOWN
        head, tail = ("…" if lo > 0 else ""), ("…" if hi < len(display) else "")
        shown = head + display[lo:hi] + tail
        if span is not None:
            start, end = span[0] - lo + len(head), min(span[1], hi) - lo + len(head)
            span = (start, max(end, start + 1))
        display = shown
    lines = [f"{pad} {bar}", f"{style(number, _GUTTER)} {bar}" + (f" {display}" if display else "")]
    if span is not None:
        start, end = span
        carets = style("^" * (end - start), _BOLD, _SEVERITY_COLOR[severity])
        lines.append(f"{pad} {bar} {' ' * start}{carets}")
    return lines


def _statistics(result: "LintResult", style: _Style) -> list[str]:
    counts = Counter(d.code for d in result.diagnostics)
    severities: dict[str, Severity] = {}
    for diag in result.diagnostics:
        sev = severity_of(diag, result)
        severities[diag.code] = max(sev, severities.get(diag.code, sev))
    rows = sorted(counts.items(), key=lambda item: (-item[1], item[0]))
    count_width = max(len(str(n)) for _, n in rows)
    code_width = max(len(code) for code, _ in rows)
    label_width = max(len(f"[{severities[code].label}]") for code, _ in rows)
    lines = []
    for code, n in rows:
        sev = severities[code]
        label = f"[{sev.label}]".ljust(label_width)
        name = rule_name(code, result)
        row = (
            f"{str(n).rjust(count_width)}  "
            f"{style(code.ljust(code_width), _BOLD, _SEVERITY_COLOR[sev])}  "
            f"{style(label, _SEVERITY_COLOR[sev])}"
        )
        row = f"{row}  {name}" if name else row.rstrip()
        lines.append(row)
    return lines


def summary(result: "LintResult") -> str:
    checked = plural(len(result.files), "file") + " checked"
    if result.baselined:
        checked += f"; {plural(result.baselined, 'finding')} of the baseline not shown"
    if not result.diagnostics:
        return f"All checks passed ({checked})."
    counts = severity_counts(result)
    parts = []
    if counts[Severity.ERROR]:
        parts.append(plural(counts[Severity.ERROR], "error"))
    if counts[Severity.WARNING]:
        parts.append(plural(counts[Severity.WARNING], "warning"))
    if counts[Severity.INFO]:
        parts.append(f"{counts[Severity.INFO]} info")
    files = len({d.path for d in result.diagnostics})
    return f"Found {', '.join(parts)} in {plural(files, 'file')} ({checked})."


def render(result: "LintResult", *, color: bool = False, statistics: bool = False, quiet: bool = False,
           concise: bool = False) -> str:
    style = _Style(color)
    out: list[str] = []
    if statistics:
        if result.diagnostics:
            out.extend(_statistics(result, style))
            out.append("")
    elif concise:
        for diag in result.diagnostics:
            out.append(_header(diag, severity_of(diag, result), style, one_line=True))
        if result.diagnostics:
            out.append("")
    else:
        sources = SourceCache(result.quotable, result.sources)
        prepared: dict = {}
        for diag in result.diagnostics:
            severity = severity_of(diag, result)
            out.append(_header(diag, severity, style))
            out.extend(_snippet(diag, severity, sources, style, prepared))
            out.append("")
    if quiet:
        while out and out[-1] == "":
            out.pop()
        return "".join(line + "\n" for line in out)
    line = summary(result)
    out.append(style(line, _PASS if not result.diagnostics else _BOLD))
    return "\n".join(out) + "\n"
