"""`--format github`: GitHub Actions workflow commands, one line per finding.

    ::error file=App/start.pgx,line=12,col=5,endLine=12,endColumn=13,title=F101 syntax-error::unexpected 'endWhile'

error -> `::error`, warning -> `::warning`, info -> `::notice`. `file` is relative to the
repository root (`LintResult.root`), as GitHub expects, whatever the step's working directory. Whole-file findings (line 0)
carry no line/col, findings without a column no col/endColumn. Escaping follows the Actions
runner: in the message `%`, `\\r`, `\\n` become `%25`, `%0D`, `%0A`; in property values also `:`
and `,` become `%3A` and `%2C`. No findings: empty output.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from ..diagnostics import Diagnostic, Severity
from ._common import printable, repository_path, root_of, rule_name, severity_of

if TYPE_CHECKING:
    from ..result import LintResult

COMMANDS = {Severity.ERROR: "error", Severity.WARNING: "warning", Severity.INFO: "notice"}


def escape_data(text: str) -> str:
    # other control characters (ESC...) would reach the CI log raw: shown as their pictures
    return printable(text.replace("%", "%25").replace("\r", "%0D").replace("\n", "%0A"))


def escape_property(text: str) -> str:
    return escape_data(text).replace(":", "%3A").replace(",", "%2C")


def _properties(diag: Diagnostic, result: "LintResult", root: str) -> list[tuple[str, str]]:
    props = [("file", repository_path(diag.path, root))]
    if diag.line > 0:
        props.append(("line", str(diag.line)))
        end_line = diag.end_line if diag.end_line is not None and diag.end_line >= diag.line else None
        if diag.col > 0:
            props.append(("col", str(diag.col)))
        if end_line is not None:
            props.append(("endLine", str(end_line)))
            if diag.col > 0 and diag.end_col is not None and diag.end_col > 0:
                props.append(("endColumn", str(diag.end_col)))
    name = rule_name(diag.code, result)
    props.append(("title", f"{diag.code} {name}" if name else diag.code))
    return props


def render(result: "LintResult") -> str:
    lines = []
    root = root_of(result)
    for diag in result.diagnostics:
        command = COMMANDS[severity_of(diag, result)]
        props = ",".join(f"{key}={escape_property(value)}" for key, value in _properties(diag, result, root))
        lines.append(f"::{command} {props}::{escape_data(diag.message)}")
    return "".join(line + "\n" for line in lines)
