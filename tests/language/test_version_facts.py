"""Limits that depend on the VAL 3 version, one rule for lint and sim (issue 25 classes 2 and 8):
the s7 manual's 9999 values per variable (2.5.4) and 15-character task names (5.10) are certain
up to s7; s8 code exceeds them, so on s8 they are not errors and the simulator runs such code."""

from __future__ import annotations

import pytest
from support import lint

from val3check.diagnostics import Severity
from val3check.language.version_facts import over, task_name_problem
from val3check.testing import write_app


def test_the_manual_limits_are_certain_up_to_s7_and_unknown_beyond_what_s8_code_uses():
    assert over("values", 9999, 7) is None
    assert over("values", 10_000, 7).certain and over("values", 10_000, None).certain
    assert over("values", 10_000, 8) is None  # an s8.15 application saved by SRS declares 10,000
    p = over("values", 20_000, 8)
    assert p is not None and not p.certain and "not known" in p.why
    assert task_name_problem("socketServerTask", 7).certain
    assert task_name_problem("socketServerTask", 8) is None
    assert task_name_problem("a" * 20, 8) is None and not task_name_problem("a" * 21, 8).certain
    assert task_name_problem("bad name", 8).certain  # the characters hold for every version


def _findings(tmp_path, version, code="begin\nend", globals_=()):
    folder = write_app(tmp_path, code, globals_=globals_, version=version)
    return lint([folder], cwd=tmp_path).result.diagnostics


@pytest.mark.parametrize("version,expect", [("s7.11", Severity.ERROR), ("s8.15", None)])
def test_an_array_of_10000_values(tmp_path, version, expect):
    found = [d for d in _findings(tmp_path, version, globals_=["num nLog[10000]"]) if d.code == "T026"]
    assert [d.severity for d in found] == ([expect] if expect else [])


def test_beyond_what_s8_code_uses_is_a_warning_that_says_why(tmp_path):
    found = [d for d in _findings(tmp_path, "s8.15", globals_=["num nLog[20000]"]) if d.code == "T026"]
    assert [d.severity for d in found] == [Severity.WARNING]
    assert "the s8 limit is not known" in found[0].message


@pytest.mark.parametrize("version,expect", [("s7.11", ["T023"]), ("s8.15", [])])
def test_lint_and_sim_agree_on_a_16_character_task_name(tmp_path, version, expect):
    pytest.importorskip("numpy")
    from val3check.simulation import SimOptions, simulate

    code = 'begin\n  taskCreate "socketServerTask", 10, serve()\nend'
    folder = write_app(tmp_path, code, version=version,
                       programs={"serve": {"code": "begin\n  putln(\"served\")\nend\n"}})
    run = lint([folder], cwd=tmp_path)
    assert [d.code for d in run.result.diagnostics if d.code == "T023"] == expect
    ws = run.workspace
    result = simulate(ws, ws.apps[ws.targets[0]], SimOptions(duration=1.0))
    stopped = [d for d in result.diagnostics if d.error == 29]
    assert bool(stopped) == bool(expect)  # sim stops exactly where lint reports


def test_sim_runs_an_s8_application_with_10000_values(tmp_path):
    pytest.importorskip("numpy")
    from val3check.simulation import SimOptions, simulate

    folder = write_app(tmp_path, "begin\n  nLog[9999] = 1\n  putln(toString(\"\", nLog[9999]))\nend",
                       globals_=["num nLog[10000]"], version="s8.15")
    run = lint([folder], cwd=tmp_path)
    assert not [d for d in run.result.diagnostics if d.severity is Severity.ERROR]  # `sim` is not refused
    ws = run.workspace
    result = simulate(ws, ws.apps[ws.targets[0]], SimOptions(duration=1.0))
    assert [text for *_, kind, text, _ in result.transcript if kind == "putln"] == ["1"]
