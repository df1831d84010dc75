"""`--format junit`: JUnit XML for the test tabs of CI systems (GitLab, Jenkins, Azure DevOps).

Layout: `<testsuites>` holding one `<testsuite name="val3check">`.

A failure is what fails the build: a finding at or above `--fail-on` (`LintResult.fail_on`,
error by default; none with `never`), so the report's `failures` is 0 exactly when the exit code
is 0 (`--exit-zero` aside). Many JUnit consumers show only the first `<failure>` of a test case,
so every such finding gets a test case of its own (classname = file path, name = "CODE name at
L:C", with `file` and `line` attributes) holding exactly one `<failure>`; each file examined
without one gets one passing test case (classname = file path, name = "val3check", `file`).
Findings below `--fail-on` never fail: they are listed in the `<system-out>` of the file's first
test case. So `tests` = passing files + failing findings, `failures` = failing findings,
`errors` = `skipped` = 0, and a clean file still shows up as a passed test.

Escaping is done by ElementTree; characters that XML 1.0 cannot hold are written as escapes
("\\x00", "\\x1b": reporting._common.visible) and non-ASCII characters become character
references, so the output is pure ASCII.

This module is also the one JUnit XML writer of val3check (`testcase`, `document`): `sim --report
junit` (sim_junit.py) and the batch summary (batch/summary.py) write through it.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from typing import TYPE_CHECKING

from ..diagnostics import Diagnostic, Severity
from ._common import TOOL_NAME, rule_name, severity_of, visible

if TYPE_CHECKING:
    from ..result import LintResult


def xml_text(value: str) -> str:
    """Text XML 1.0 can hold: controls other than tab and newline, lone surrogates and
    non-characters written as escapes ("\\x1b", reporting._common.visible)."""
    return visible(value)



def testcase(classname: str, name: str, *, file: str | None = None, line: int = 0, time: bool = True) -> ET.Element:
    """A `<testcase>`: its class name and name, the file and line it is about, `time="0"` (no
    wall-clock value: the output is deterministic)."""
    attrs = {"classname": xml_text(classname), "name": xml_text(name)}
    if file is not None:
        attrs["file"] = xml_text(file)
    if line > 0:
        attrs["line"] = str(line)
    if time:
        attrs["time"] = "0"
    return ET.Element("testcase", attrs)


def document(name: str, cases: list[ET.Element], counts: dict[str, str], *, ascii_only: bool = True) -> str:
    """The JUnit XML document: `<testsuites>` holding one `<testsuite>`, both named `name` with
    the `counts` (tests, failures, errors, skipped...), indented; non-ASCII characters as
    character references unless `ascii_only` is false."""
    root = ET.Element("testsuites", {"name": xml_text(name), **counts})
    suite = ET.SubElement(root, "testsuite", {"name": xml_text(name), **counts})
    suite.extend(cases)
    ET.indent(root, space="  ")
    body = ET.tostring(root, encoding="unicode")
    if ascii_only:
        body = body.encode("ascii", "xmlcharrefreplace").decode("ascii")
    return '<?xml version="1.0" encoding="UTF-8"?>\n' + body + "\n"


def _position(diag: Diagnostic) -> str:
    if diag.line <= 0:
        return diag.path
    if diag.col <= 0:
        return f"{diag.path}:{diag.line}"
    return f"{diag.path}:{diag.line}:{diag.col}"


def _case_name(diag: Diagnostic, result: "LintResult") -> str:
    name = rule_name(diag.code, result)
    label = f"{diag.code} {name}" if name else diag.code
    if diag.line <= 0:
        return label
    if diag.col <= 0:
        return f"{label} at {diag.line}"
    return f"{label} at {diag.line}:{diag.col}"


def _finding_line(diag: Diagnostic, severity: Severity) -> str:
    return f"{_position(diag)}: {diag.code} [{severity.label}] {diag.message}"


def _fails(severity: Severity, fail_on: str) -> bool:
    return fail_on != "never" and severity >= Severity.parse(fail_on)


def _case(path: str, name: str, line: int = 0) -> ET.Element:
    return testcase(path, name, file=path, line=line)


def render(result: "LintResult") -> str:
    paths = sorted(set(result.files) | {d.path for d in result.diagnostics})
    failing: dict[str, list[tuple[Diagnostic, Severity]]] = {p: [] for p in paths}
    lower: dict[str, list[tuple[Diagnostic, Severity]]] = {p: [] for p in paths}
    fail_on = result.fail_on or "error"
    for diag in result.diagnostics:
        severity = severity_of(diag, result)
        (failing if _fails(severity, fail_on) else lower)[diag.path].append((diag, severity))

    cases: list[ET.Element] = []
    n_failures = 0
    for path in paths:
        first = None
        for diag, severity in failing[path]:
            case = _case(path, _case_name(diag, result), diag.line)
            failure = ET.SubElement(
                case, "failure", {"message": xml_text(f"{diag.code}: {diag.message}"), "type": xml_text(diag.code)}
            )
            text = _finding_line(diag, severity)
            summary = result.rules[diag.code].summary if diag.code in result.rules else ""
            failure.text = xml_text(f"{text}\n{summary}" if summary else text)
            cases.append(case)
            first = first if first is not None else case
            n_failures += 1
        if first is None:
            first = _case(path, TOOL_NAME)
            cases.append(first)
        if lower[path]:
            out = ET.SubElement(first, "system-out")
            out.text = xml_text("\n".join(_finding_line(d, s) for d, s in lower[path]))

    counts = {"tests": str(len(cases)), "failures": str(n_failures), "errors": "0", "skipped": "0", "time": "0"}
    return document(TOOL_NAME, cases, counts)
