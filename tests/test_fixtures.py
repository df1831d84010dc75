"""The bundled applications: valid ones are clean, each broken one gives its finding where planted.

fixtures/expected.toml lists, per case, the findings a good tool must report (code, file, line,
and column where it matters).
"""

from __future__ import annotations

import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

from val3check.diagnostics import Severity
from support import lint

FIXTURES = Path(__file__).resolve().parent.parent / "fixtures"
EXPECTED = tomllib.loads((FIXTURES / "expected.toml").read_text(encoding="utf-8"))["case"]
VALID = sorted(p for p in (FIXTURES / "valid").iterdir() if p.is_dir())


def _found(diagnostics):
    return {(d.code, d.path, d.line, d.col) for d in diagnostics}


@pytest.mark.parametrize("case", EXPECTED, ids=[c["path"] for c in EXPECTED])
def test_case_reports_what_was_planted(case):
    outcome = lint([FIXTURES / case["path"]], cwd=FIXTURES)
    found = _found(outcome.result.diagnostics)
    expect = case.get("expect", [])
    if not expect:
        errors = [d for d in outcome.result.diagnostics if d.severity == Severity.ERROR]
        assert not errors, errors
    for e in expect:
        hits = {f for f in found if f[0] == e["code"] and f[1] == e["file"] and f[2] == e["line"]}
        if "col" in e:
            hits = {f for f in hits if f[3] == e["col"]}
        assert hits, f"expected {e} in {sorted(found)}"


@pytest.mark.parametrize("app", VALID, ids=[p.name for p in VALID])
def test_valid_application_has_no_error(app):
    outcome = lint([app], cwd=FIXTURES)
    errors = [d for d in outcome.result.diagnostics if d.severity == Severity.ERROR]
    assert not errors, errors
    assert outcome.result.applications


def test_one_run_over_everything_reports_every_case_and_no_traceback():
    r = subprocess.run(
        [sys.executable, "-m", "val3check", "lint", ".", "--format", "json"],
        cwd=FIXTURES, capture_output=True, text=True, timeout=300,
        env={"PYTHONPATH": str(FIXTURES.parent), "PATH": "/usr/bin:/bin"},
    )
    assert r.returncode == 1, r.stderr
    assert r.stderr == ""
    import json

    report = json.loads(r.stdout)
    found = {(d["code"], d["path"], d["line"]) for d in report["diagnostics"]}
    for case in EXPECTED:
        for e in case.get("expect", []):
            if e["code"] == "F008":  # only for a folder named on the command line
                continue
            assert (e["code"], e["file"], e["line"]) in found, e


def test_sarif_of_a_whole_run_is_valid():
    import jsonschema

    r = subprocess.run(
        [sys.executable, "-m", "val3check", "lint", ".", "--format", "sarif"],
        cwd=FIXTURES, capture_output=True, text=True, timeout=300,
        env={"PYTHONPATH": str(FIXTURES.parent), "PATH": "/usr/bin:/bin"},
    )
    import json

    sarif = json.loads(r.stdout)
    schema = json.loads((FIXTURES.parent / "tests" / "data" / "sarif-schema-2.1.0.json").read_text(encoding="utf-8"))
    jsonschema.Draft4Validator(schema).validate(sarif)
    results = sarif["runs"][0]["results"]
    assert results and all(res["locations"][0]["physicalLocation"]["artifactLocation"].get("uriBaseId") == "%SRCROOT%"
                           for res in results)
    assert {res["ruleId"] for res in results} <= {rule["id"] for rule in sarif["runs"][0]["tool"]["driver"]["rules"]}
