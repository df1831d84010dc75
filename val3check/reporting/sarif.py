"""`--format sarif`: SARIF 2.1.0 as GitHub code scanning reads it.

One run; `tool.driver.rules` holds the catalogue entry of every rule referenced by a result (in
code order), results point at it with `ruleId` and `ruleIndex`. Paths are relative to the
repository root (`LintResult.root`: the git top level, else the configuration's folder), not to
the current folder, so that a CI step run in a sub-folder still puts alerts on the right files:
URIs with `uriBaseId: "%SRCROOT%"`, and `originalUriBaseIds` says where %SRCROOT% was. Files
outside it become `file://` URIs. Whole-file findings (line 0: an unreadable file, an application
without project, ...) point at line 1 (`region: {startLine: 1}`): without a region GitHub shows
an alert with no line, and it rejects startLine 0. Columns count Unicode code points, as val3check's do. `invocations` holds the
exit code and whether the run could read its input (exit code 2: `executionSuccessful` false).

`partialFingerprints["val3check/v1"]` hashes the code, repository path, message and the text of
the flagged line with all whitespace removed, not its number, so that an alert keeps its identity
when unrelated lines are inserted above it or the line is re-indented; a ":N" suffix numbers
otherwise identical findings in the same file.

Output is deterministic: sorted keys, 2-space indent, ASCII only, trailing newline.
"""

from __future__ import annotations

import hashlib
import json
import os
import re
from typing import TYPE_CHECKING, Any
from urllib.parse import quote

from ..diagnostics import Diagnostic, Severity
from ._common import TOOL_NAME, SourceCache, repository_path, root_of, severity_of, tool_version

if TYPE_CHECKING:
    from ..result import LintResult
    from ..rules.catalogue import Rule

SCHEMA_URI = "https://docs.oasis-open.org/sarif/sarif/v2.1.0/errata01/os/schemas/sarif-schema-2.1.0.json"
SRCROOT = "%SRCROOT%"
FINGERPRINT_KEY = "val3check/v1"

LEVELS = {Severity.ERROR: "error", Severity.WARNING: "warning", Severity.INFO: "note"}
# Where val3check is published: `informationUri`, and `helpUri` of every rule (that release's page,
# whose README explains `val3check rule CODE`); a rule's whole documentation is in its `help`.
INFORMATION_URI = "https://pypi.org/project/val3check/"

_DRIVE = re.compile(r"^[A-Za-z]:[/\\]")
_SEMVER = re.compile(r"^\d+\.\d+\.\d+(?:[-+].*)?$")


def _manual_line(rule: "Rule") -> str:
    return f"VAL 3 reference manual, section {rule.manual}." if rule.manual else ""


def help_uri(version: str) -> str:
    return f"{INFORMATION_URI}{quote(version)}/" if _SEMVER.match(version) else INFORMATION_URI


def _rule_descriptor(code: str, rule: "Rule | None", version: str) -> dict[str, Any]:
    if rule is None:  # a code missing from the catalogue: still a valid descriptor
        return {"id": code}
    summary = rule.summary.strip() or rule.name
    explanation = rule.explanation.strip()
    manual = _manual_line(rule)
    help_text = "\n\n".join(p for p in (summary, explanation, manual) if p)
    help_markdown = "\n\n".join(
        p for p in (f"**{rule.code} {rule.name}**: {summary}", explanation, manual and f"*{manual}*") if p
    )
    descriptor: dict[str, Any] = {
        "id": rule.code,
        "name": rule.name,
        "shortDescription": {"text": summary},
        "fullDescription": {"text": explanation or summary},
        "help": {"text": help_text, "markdown": help_markdown},
        "defaultConfiguration": {"level": LEVELS[rule.severity]},
        "helpUri": help_uri(version),
        "properties": {"tags": [t for t in ("val3", rule.family_name) if t]},
    }
    if explanation:
        descriptor["fullDescription"]["markdown"] = explanation
    if rule.manual:
        descriptor["properties"]["manual"] = rule.manual
    return descriptor


def artifact_location(path: str) -> dict[str, str]:
    # Windows paths get forward slashes; on POSIX a backslash is part of a name (display paths
    # write an undecodable byte as \xE9) and is percent-encoded like any other character.
    windows = os.sep == "\\" or _DRIVE.match(path) or path.startswith("\\\\")
    posix = path.replace("\\", "/") if windows else path
    if posix.startswith("//"):  # UNC path
        return {"uri": "file:" + quote(posix)}
    if posix.startswith("/"):
        return {"uri": "file://" + quote(posix)}
    if _DRIVE.match(path):
        return {"uri": "file:///" + quote(posix, safe="/:")}
    return {"uri": quote(posix), "uriBaseId": SRCROOT}


def _region(diag: Diagnostic) -> dict[str, int]:
    if diag.line < 1:  # the whole file
        return {"startLine": 1}
    region = {"startLine": diag.line}
    end_line = diag.end_line if diag.end_line is not None and diag.end_line >= diag.line else diag.line
    region["endLine"] = end_line
    if diag.col >= 1:
        region["startColumn"] = diag.col
        end_col = diag.end_col
        if end_col is not None and end_col >= 1 and (end_line > diag.line or end_col > diag.col):
            region["endColumn"] = end_col
    return region


def fingerprint(diag: Diagnostic, path: str, sources: SourceCache) -> str:
    """The code, `path`, message and the flagged line's text without whitespace, hashed."""
    content = sources.line(diag.path, diag.line) or ""
    normalized = "".join(content.split())
    data = "\0".join((diag.code, path, diag.message, normalized))
    return hashlib.sha256(data.encode("utf-8", "surrogatepass")).hexdigest()


def _root_uri(root: str) -> str:
    posix = root.replace("\\", "/")
    if _DRIVE.match(root):
        return "file:///" + quote(posix.rstrip("/"), safe="/:") + "/"
    return "file://" + quote(posix.rstrip("/")) + "/"


def report(result: "LintResult", exit_code: int | None = None) -> dict[str, Any]:
    codes = sorted({d.code for d in result.diagnostics})
    index = {code: i for i, code in enumerate(codes)}
    sources = SourceCache(result.quotable, result.sources)
    root = root_of(result)
    seen: dict[str, int] = {}
    results = []
    for diag in result.diagnostics:
        path = repository_path(diag.path, root)
        physical: dict[str, Any] = {"artifactLocation": artifact_location(path), "region": _region(diag)}
        digest = fingerprint(diag, path, sources)
        seen[digest] = seen.get(digest, 0) + 1
        results.append(
            {
                "ruleId": diag.code,
                "ruleIndex": index[diag.code],
                "level": LEVELS[severity_of(diag, result)],
                "message": {"text": diag.message or diag.code},
                "locations": [{"physicalLocation": physical}],
                "partialFingerprints": {FINGERPRINT_KEY: f"{digest}:{seen[digest]}"},
            }
        )
    version = tool_version(result)
    driver: dict[str, Any] = {
        "name": TOOL_NAME,
        "version": version,
        "informationUri": INFORMATION_URI,
        "rules": [_rule_descriptor(code, result.rules.get(code), version) for code in codes],
    }
    if _SEMVER.match(version):
        driver["semanticVersion"] = version
    invocation: dict[str, Any] = {"executionSuccessful": exit_code in (None, 0, 1)}
    if exit_code is not None:
        invocation["exitCode"] = exit_code
    return {
        "$schema": SCHEMA_URI,
        "version": "2.1.0",
        "runs": [
            {
                "tool": {"driver": driver},
                "columnKind": "unicodeCodePoints",
                "originalUriBaseIds": {SRCROOT: {"uri": _root_uri(root)}},
                "invocations": [invocation],
                "results": results,
            }
        ],
    }


def render(result: "LintResult", exit_code: int | None = None) -> str:
    return json.dumps(report(result, exit_code), indent=2, sort_keys=True, ensure_ascii=True) + "\n"
