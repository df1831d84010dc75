"""The `json` format: documented, versioned, deterministic."""

from __future__ import annotations

import json
import re
from pathlib import Path

from val3check.diagnostics import Severity
from val3check.reporting import render

DOC = Path(__file__).resolve().parents[2] / "docs" / "json-format.md"


def sample(make_result, d):
    return make_result(
        [
            d("F001", "cannot read", "b.pgx"),
            d("F101", "unexpected 'endWhile'", "a.pgx", 12, 5, 12, 13),
            d("S301", "odd <&\">,:%\n message é – 日本", "a.pgx", 3, 0),
            d("N201", "name", "a.pgx", 4, 2, severity=Severity.WARNING),
            d("X999", "not in catalogue", "c/d.pgx", 1, 1),
        ],
        files=["a.pgx", "b.pgx", "c/d.pgx", "clean.pgx"],
        applications=["App", "Other"],
    )


def test_deterministic_and_sorted(make_result, d):
    first = render("json", sample(make_result, d))
    second = render("json", sample(make_result, d))
    assert first == second
    assert first.endswith("}\n") and not first.endswith("\n\n")
    data = json.loads(first)
    assert json.dumps(data, indent=2, sort_keys=True) + "\n" == first  # sorted keys, 2-space indent
    assert first.isascii()
    assert '\n  "version": 1\n' in first


def test_contents(make_result, d):
    data = json.loads(render("json", sample(make_result, d)))
    assert data["version"] == 1
    assert data["tool"] == {"name": "val3check", "version": "1.2.3"}
    assert data["files"] == ["a.pgx", "b.pgx", "c/d.pgx", "clean.pgx"]
    assert data["applications"] == ["App", "Other"]
    assert data["summary"] == {
        "error": 2,
        "warning": 3,
        "info": 0,
        "total": 5,
        "files_checked": 4,
        "files_with_diagnostics": 3,
        "applications_checked": 2,
        "baselined": 0,
    }
    by_message = {x["message"]: x for x in data["diagnostics"]}
    assert [x["path"] for x in data["diagnostics"]] == ["a.pgx", "a.pgx", "a.pgx", "b.pgx", "c/d.pgx"]
    assert by_message["unexpected 'endWhile'"] == {
        "code": "F101",
        "name": "syntax-error",
        "severity": "error",
        "message": "unexpected 'endWhile'",
        "path": "a.pgx",
        "line": 12,
        "column": 5,
        "end_line": 12,
        "end_column": 13,
        "manual": "2.2.5",
    }
    whole_file = by_message["cannot read"]
    assert (whole_file["line"], whole_file["column"], whole_file["end_line"], whole_file["manual"]) == (None,) * 4
    no_col = by_message["odd <&\">,:%\n message é – 日本"]
    assert (no_col["line"], no_col["column"], no_col["end_column"]) == (3, None, None)
    assert by_message["name"]["severity"] == "warning"  # the diagnostic's severity, not the rule's
    assert by_message["not in catalogue"]["name"] is None


def test_version_falls_back_to_package(make_result, d):
    import val3check

    data = json.loads(render("json", make_result([], files=["a"], version="")))
    assert data["tool"]["version"] == val3check.__version__


def test_every_key_is_documented(make_result, d):
    doc = DOC.read_text(encoding="utf-8")
    documented = set(re.findall(r"^\| `(\w+)` \|", doc, flags=re.M))
    data = json.loads(render("json", sample(make_result, d)))
    keys = set(data) | set(data["tool"]) | set(data["summary"]) | set(data["diagnostics"][0])
    assert keys - {"name"} <= documented  # `name` appears in prose for `tool`
    assert documented <= keys
    example = re.search(r"```json\n(.*?)```", doc, flags=re.S).group(1)
    assert json.dumps(json.loads(example), indent=2, sort_keys=True) + "\n" == example
    assert set(json.loads(example)["diagnostics"][0]) == set(data["diagnostics"][0])
