"""`val3check sim --report junit` (reporting/sim_junit.py): one test case per application and
scenario; it fails exactly when the exit code is 1, with the diagnostics at or above --fail-on,
their file and line, in the failure text."""

from __future__ import annotations

import xml.etree.ElementTree as ET
from pathlib import Path

from val3check.cli import main
from val3check.reporting.sim_junit import render_runs

from .runhelp import pickplace

ROOT = Path(__file__).resolve().parents[2]


def _sim(capsys, monkeypatch, *args):
    monkeypatch.chdir(ROOT)
    code = main(["sim", *args, "--report", "junit"])
    return code, ET.fromstring(capsys.readouterr().out)


def test_failing_run_is_a_failed_test_case_with_file_and_line(capsys, monkeypatch):
    code, root = _sim(capsys, monkeypatch, "fixtures/valid/Cell", "--robot", "tx2-60", "--scenario",
                      "fixtures/scenarios/cell.toml", "--duration", "30")
    assert code == 1
    assert root.get("tests") == "1" and root.get("failures") == "1"
    (case,) = root.iter("testcase")
    assert case.get("classname") == "fixtures/valid/Cell/Cell.pjx"
    assert case.get("name") == "sim Cell with fixtures/scenarios/cell.toml"
    failure = case.find("failure")
    assert failure.get("type") == "R015"
    assert failure.text.splitlines() == [
        "fixtures/valid/Cell/moves.pgx:29:3: R015 [error] error 154: movec: the positions are too close to define "
        "an arc (at 1.912 s, task robot)"]  # 1.928 s before the exact ramps of issue 23
    props = {p.get("name"): p.get("value") for p in case.iter("property")}
    assert props["end_reason"] == "stalled" and props["robot"] == "TX2-60"


def test_passing_run_lists_lower_diagnostics_in_system_out(capsys, monkeypatch):
    code, root = _sim(capsys, monkeypatch, "fixtures/valid/PickPlace", "--robot", "tx2-60", "--scenario",
                      "fixtures/scenarios/pickplace.toml", "--duration", "10")
    assert code == 0 and root.get("failures") == "0"
    (case,) = root.iter("testcase")
    assert case.find("failure") is None
    assert "R007 [info] run stopped at --duration 10 s" in case.find("system-out").text
    props = {p.get("name"): p.get("value") for p in case.iter("property")}
    assert props["simulated_duration_s"] == "10.000000" and float(props["cycle_time_s"]) > 2.0


def test_fail_on_decides_what_fails(capsys, monkeypatch):
    code, root = _sim(capsys, monkeypatch, "fixtures/valid/PickPlace", "--robot", "tx2-60", "--scenario",
                      "fixtures/scenarios/pickplace.toml", "--duration", "5", "--fail-on", "info")
    assert code == 1 and root.get("failures") == "1"
    (case,) = root.iter("testcase")
    assert "PickPlace.pjx: R007 [info]" in case.find("failure").text and case.find("system-out") is None


def test_several_runs_one_case_each_and_same_bytes():
    _, report = pickplace(20.0)
    a = render_runs([(report, None), (report, "b.toml")], "error")
    assert a == render_runs([(report, None), (report, "b.toml")], "error")
    root = ET.fromstring(a)
    assert [c.get("name") for c in root.iter("testcase")] == ["sim PickPlace", "sim PickPlace with b.toml"]
    assert root.get("tests") == "2" and root.get("failures") == "0"
