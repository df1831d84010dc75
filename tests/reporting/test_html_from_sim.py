"""The report model of a real run: `val3check sim --report json` on the bundled applications."""

from __future__ import annotations

import copy
import json
from pathlib import Path

import pytest

from val3check.cli import main
from val3check.reporting.html import ModelError, check_model, model_from_sim_report, render

ROOT = Path(__file__).resolve().parents[2]


def sim_json(app: str, capsys, *extra: str) -> dict:
    main(["sim", f"fixtures/valid/{app}", "--report", "json", "--duration", "20", *extra])
    return json.loads(capsys.readouterr().out)


@pytest.fixture(autouse=True)
def _in_root(monkeypatch):
    monkeypatch.chdir(ROOT)  # the report's paths are relative to the current folder


def test_model_of_a_run_with_an_arm_model(capsys):
    report = sim_json("Cell", capsys, "--robot", "tx2-60")
    model = model_from_sim_report(report, fail_on="warning")  # the run's R009 (no scenario) fails it
    check_model(model)
    v = model["verdict"]
    assert v["counts"] == {s: report["summary"][s] for s in ("error", "warning", "info")}
    assert v["counts"]["warning"] >= 1 and v["passed"] is False and v["end_reason"] == report["end"]["reason"]
    d = model["diagnostics"][0]
    lines = (ROOT / d["path"]).read_text(encoding="utf-8").split("\n")
    ex = d["excerpt"]
    assert ex["lines"][d["line"] - ex["first_line"]] == lines[d["line"] - 1]
    assert model["scene"]["arm"]["name"] == "TX2-60" and model["scene"]["joints"] == [0.0] * 6
    assert model["trajectory"] is None and model["tasks"] == []
    assert any("does not show the arm's motion" in n for n in model["limitations"])
    html = render(model)
    assert "does not show the arm" in html and 'id="play"' not in html


def test_model_of_a_run_that_passes_and_the_fail_on_threshold(capsys):
    report = sim_json("Supervisor", capsys)
    model = model_from_sim_report(report)
    assert model["verdict"]["passed"] and model["scene"] is None
    assert len(model["io"]) == report["summary"]["io_events"] and len(model["transcript"]) == 9
    warned = copy.deepcopy(report)
    warned["summary"]["warning"] = 1
    assert model_from_sim_report(warned, fail_on="warning")["verdict"]["passed"] is False
    assert model_from_sim_report(warned, fail_on="error")["verdict"]["passed"] is True
    assert model_from_sim_report(warned, fail_on="never")["verdict"]["passed"] is True


def test_excerpts_quote_only_files_of_the_application(capsys, tmp_path):
    report = sim_json("Cell", capsys, "--robot", "tx2-60")
    secret = tmp_path / "secret.pgx"
    secret.write_text("line 1\nthe secret\n", encoding="utf-8")
    while len(report["diagnostics"]) < 2:  # two diagnostics to point elsewhere
        report["diagnostics"].append(dict(report["diagnostics"][0]))
    report["diagnostics"][0].update(path=str(secret), line=2)
    report["diagnostics"][1].update(path="fixtures/valid/Cell/../../../README.md", line=1)
    model = model_from_sim_report(report)
    assert [d["excerpt"] for d in model["diagnostics"]] == [None, None]
    assert model_from_sim_report(report, roots=[str(tmp_path)])["diagnostics"][0]["excerpt"]["lines"] == ["line 1", "the secret"]


def test_not_a_sim_report():
    for bad in ({}, {"version": 3, "end": {}, "summary": {}}, [], {"version": 1}):
        with pytest.raises(ModelError, match="not a version 1 or 2 report"):
            model_from_sim_report(bad)


def test_command_renders_a_sim_report(capsys, tmp_path):
    from val3check.reporting.html.__main__ import main as html_main

    report = sim_json("Supervisor", capsys)
    (tmp_path / "run.json").write_text(json.dumps(report), encoding="utf-8")
    out = tmp_path / "run.html"
    assert html_main(["--sim-report", str(tmp_path / "run.json"), "-o", str(out)]) == 0
    assert "Supervisor" in out.read_text(encoding="utf-8")
    assert html_main(["--sim-report", str(tmp_path / "missing.json"), "-o", str(out)]) == 2
    assert "cannot read" in capsys.readouterr().err
