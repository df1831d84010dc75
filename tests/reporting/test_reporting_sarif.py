"""The `sarif` format: valid SARIF 2.1.0 and what GitHub code scanning needs."""

from __future__ import annotations

import json
import re
from pathlib import Path

import jsonschema
import pytest

from val3check.diagnostics import Severity
from val3check.reporting import render

SCHEMA_PATH = Path(__file__).resolve().parents[1] / "data" / "sarif-schema-2.1.0.json"


@pytest.fixture(scope="module")
def schema():
    return json.loads(SCHEMA_PATH.read_text(encoding="utf-8"))


def sample(make_result, d, workdir):
    (workdir / "a.pgx").write_text("begin\n  x = 1\n\tcall foo()\nend\n", encoding="utf-8")
    outside = str((workdir.parent / "outside dir" / "z.pgx").as_posix())
    return make_result(
        [
            d("F001", "cannot read", "b b/c#1.pgx"),
            d("F101", "unexpected 'endWhile'", "a.pgx", 3, 2, 3, 6),
            d("S301", "odd <&\">,:%\n é", "a.pgx", 2, 0),
            d("N201", "name", "a.pgx", 2, 3, severity=Severity.WARNING),
            d("X999", "not in catalogue", outside, 1, 1),
        ],
        files=["a.pgx", "b b/c#1.pgx", "clean.pgx", outside],
    )


def results(sarif):
    return sarif["runs"][0]["results"]


def test_validates_against_official_schema(schema, make_result, d, workdir):
    jsonschema.Draft7Validator.check_schema(schema)
    for result in (sample(make_result, d, workdir), make_result([], files=["a"])):
        sarif = json.loads(render("sarif", result))
        jsonschema.Draft7Validator(schema).validate(sarif)
        jsonschema.Draft4Validator(schema).validate(sarif)  # the schema's own dialect


def test_schema_catches_invalid_output(schema, make_result, d, workdir):
    sarif = json.loads(render("sarif", sample(make_result, d, workdir)))
    results(sarif)[1]["locations"][0]["physicalLocation"]["region"]["startLine"] = 0
    with pytest.raises(jsonschema.ValidationError):
        jsonschema.Draft7Validator(schema).validate(sarif)


def test_deterministic_and_sorted(make_result, d, workdir):
    first = render("sarif", sample(make_result, d, workdir))
    assert first == render("sarif", sample(make_result, d, workdir))
    assert json.dumps(json.loads(first), indent=2, sort_keys=True) + "\n" == first
    assert first.isascii()


def test_run_and_driver(make_result, d, workdir):
    sarif = json.loads(render("sarif", sample(make_result, d, workdir)))
    assert sarif["version"] == "2.1.0"
    assert sarif["$schema"].endswith("sarif-schema-2.1.0.json")
    assert len(sarif["runs"]) == 1
    run = sarif["runs"][0]
    assert run["columnKind"] == "unicodeCodePoints"
    driver = run["tool"]["driver"]
    assert driver["name"] == "val3check"
    assert driver["version"] == "1.2.3"
    assert [r["id"] for r in driver["rules"]] == ["F001", "F101", "N201", "S301", "X999"]  # only referenced
    f101 = driver["rules"][1]
    assert f101["name"] == "syntax-error"
    assert f101["shortDescription"]["text"] == "The code does not follow the VAL 3 syntax."
    assert "**closed**" in f101["fullDescription"]["text"]
    assert "**closed**" in f101["help"]["markdown"] and "2.2.5" in f101["help"]["markdown"]
    assert "2.2.5" in f101["help"]["text"]
    assert f101["defaultConfiguration"]["level"] == "error"
    assert "syntax and files" in f101["properties"]["tags"]
    assert driver["rules"][2]["defaultConfiguration"]["level"] == "note"  # info rule
    assert driver["rules"][3]["defaultConfiguration"]["level"] == "warning"


def test_results(make_result, d, workdir):
    sarif = json.loads(render("sarif", sample(make_result, d, workdir)))
    rules = sarif["runs"][0]["tool"]["driver"]["rules"]
    found = results(sarif)
    assert len(found) == 5
    for r in found:
        assert rules[r["ruleIndex"]]["id"] == r["ruleId"]
        assert r["level"] in ("error", "warning", "note")
        assert r["message"]["text"]
        for loc in r["locations"]:
            phys = loc["physicalLocation"]
            assert phys["region"]["startLine"] >= 1  # GitHub rejects startLine < 1, shows no line without one
            art = phys["artifactLocation"]
            assert " " not in art["uri"] and "\\" not in art["uri"]
            if art["uri"].startswith("file://"):
                assert "uriBaseId" not in art
            else:
                assert art["uriBaseId"] == "%SRCROOT%"
                assert not art["uri"].startswith("/")
    by_msg = {r["message"]["text"]: r for r in found}
    whole = by_msg["cannot read"]["locations"][0]["physicalLocation"]
    assert whole["region"] == {"startLine": 1}  # a whole-file finding: line 1 (issue 28 item 10)
    assert whole["artifactLocation"] == {"uri": "b%20b/c%231.pgx", "uriBaseId": "%SRCROOT%"}
    region = by_msg["unexpected 'endWhile'"]["locations"][0]["physicalLocation"]["region"]
    assert region == {"startLine": 3, "startColumn": 2, "endLine": 3, "endColumn": 6}
    region = by_msg["odd <&\">,:%\n é"]["locations"][0]["physicalLocation"]["region"]
    assert region["startLine"] == 2 and "startColumn" not in region and "endColumn" not in region
    assert by_msg["name"]["level"] == "warning"  # configured severity wins over the rule default
    outside = by_msg["not in catalogue"]["locations"][0]["physicalLocation"]["artifactLocation"]
    assert outside["uri"].startswith("file:///") and outside["uri"].endswith("/outside%20dir/z.pgx")


def fingerprints(result):
    return [r["partialFingerprints"]["val3check/v1"] for r in results(json.loads(render("sarif", result)))]


def test_fingerprint_survives_unrelated_edits(make_result, d, workdir):
    (workdir / "a.pgx").write_text("begin\n  call foo(x)\nend\n", encoding="utf-8")
    before = fingerprints(make_result([d("S301", "unused x", "a.pgx", 2, 3)]))
    (workdir / "a.pgx").write_text("begin\n  // new comment\n\n      call   foo(x)\nend\n", encoding="utf-8")
    after = fingerprints(make_result([d("S301", "unused x", "a.pgx", 4, 7)]))
    assert before == after


def test_fingerprint_distinguishes_findings(make_result, d, workdir):
    (workdir / "a.pgx").write_text("begin\n  call foo(x)\n  call bar(x)\n  call foo(x)\nend\n", encoding="utf-8")
    prints = fingerprints(
        make_result(
            [
                d("S301", "unused x", "a.pgx", 2, 3),
                d("S301", "unused x", "a.pgx", 3, 3),  # other line content
                d("S301", "unused x", "a.pgx", 4, 3),  # same content as line 2: numbered
                d("S301", "unused y", "a.pgx", 2, 3),  # other message
                d("F101", "unused x", "a.pgx", 2, 3),  # other code
            ]
        )
    )
    assert len(set(prints)) == 5
    # sorted order: (2, F101), (2, S301 x), (2, S301 y), (3, S301 x), (4, S301 x)
    line2, line3, line4 = prints[1], prints[3], prints[4]
    assert line2.endswith(":1") and line3.endswith(":1") and line4.endswith(":2")
    assert line2.split(":")[0] == line4.split(":")[0] != line3.split(":")[0]


def test_paths_are_relative_to_the_repository_root(schema, make_result, d, workdir):
    """A CI step run in a sub-folder: display paths are relative to it, SARIF's to the root."""
    sub = workdir / "cells"
    sub.mkdir()
    (sub / "a.pgx").write_text("begin\nend\n", encoding="utf-8")
    import os

    os.chdir(sub)
    result = make_result([d("F101", "x", "a.pgx", 1, 1)], files=["a.pgx"])
    result.root = str(workdir)
    sarif = json.loads(render("sarif", result, exit_code=1))
    jsonschema.Draft7Validator(schema).validate(sarif)
    run = sarif["runs"][0]
    assert results(sarif)[0]["locations"][0]["physicalLocation"]["artifactLocation"] == {
        "uri": "cells/a.pgx", "uriBaseId": "%SRCROOT%"}
    assert run["originalUriBaseIds"] == {"%SRCROOT%": {"uri": workdir.as_uri() + "/"}}
    assert run["invocations"] == [{"executionSuccessful": True, "exitCode": 1}]
    # the fingerprint uses the repository path: the same from any working folder
    first = fingerprints(result)
    os.chdir(workdir)
    again = make_result([d("F101", "x", "cells/a.pgx", 1, 1)], files=["cells/a.pgx"])
    again.root = str(workdir)
    assert fingerprints(again) == first


def test_tool_links_and_invocations(schema, make_result, d, workdir):
    sarif = json.loads(render("sarif", sample(make_result, d, workdir), exit_code=2))
    jsonschema.Draft7Validator(schema).validate(sarif)
    driver = sarif["runs"][0]["tool"]["driver"]
    assert driver["informationUri"] == "https://pypi.org/project/val3check/"
    assert all(r["helpUri"] == "https://pypi.org/project/val3check/1.2.3/" for r in driver["rules"] if "name" in r)
    assert sarif["runs"][0]["invocations"] == [{"executionSuccessful": False, "exitCode": 2}]
    # the format checker of the schema: helpUri, informationUri and the base URI are absolute URIs
    checker = jsonschema.Draft7Validator.FORMAT_CHECKER
    for uri in [driver["informationUri"], sarif["runs"][0]["originalUriBaseIds"]["%SRCROOT%"]["uri"],
                *(r["helpUri"] for r in driver["rules"] if "helpUri" in r)]:
        assert re.match(r"^[a-z][a-z0-9+.-]*:", uri), uri
        checker.check(uri, "uri") if "uri" in checker.checkers else None


def test_whole_file_findings_point_at_line_1(schema, tmp_path):
    """F009 (no project), F012 (a program file not listed) and F004 (not XML) concern a whole file:
    GitHub shows a result without a region with no line at all (issue 28 item 10)."""
    from support import lint

    from val3check.testing import write_app

    write_app(tmp_path, "begin\nend\n")
    (tmp_path / "Example" / "extra.pgx").write_text((tmp_path / "Example" / "stop.pgx").read_text())
    (tmp_path / "Example" / "stop.pgx").write_text("<Programs><Program")
    (tmp_path / "Lone").mkdir()
    (tmp_path / "Lone" / "a.pgx").write_text((tmp_path / "Example" / "start.pgx").read_text())
    (tmp_path / ".git").mkdir()
    outcome = lint([tmp_path / "Example", tmp_path / "Lone"], cwd=tmp_path)
    sarif = json.loads(render("sarif", outcome.result))
    jsonschema.Draft4Validator(schema).validate(sarif)
    shared = Path("/work/shared/schemas/sarif-schema-2.1.0.json")
    if shared.exists():
        assert json.loads(shared.read_text(encoding="utf-8")) == schema
    by_code = {r["ruleId"]: r["locations"][0]["physicalLocation"] for r in results(sarif)}
    assert {"F004", "F009", "F012"} <= set(by_code), by_code
    for code in ("F009", "F012"):
        assert by_code[code]["region"] == {"startLine": 1}, (code, by_code[code])
    assert by_code["F004"]["region"]["startLine"] >= 1
