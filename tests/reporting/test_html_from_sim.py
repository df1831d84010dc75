"""The report model of a real run: `val3check sim --report json` on the bundled applications."""

from __future__ import annotations

import copy
import json
from pathlib import Path

import pytest

from val3check.cli import main
from val3check.reporting.html import ModelError, check_model, model_from_sim_report, render
from val3check.simulation.report_scene import ReportScene

ROOT = Path(__file__).resolve().parents[2]


def sim_json(app: str, capsys, *extra: str) -> dict:
    main(["sim", f"fixtures/valid/{app}", "--report", "json", "--duration", "20", *extra])
    return json.loads(capsys.readouterr().out)


@pytest.fixture(autouse=True)
def _in_root(monkeypatch):
    monkeypatch.chdir(ROOT)  # the report's paths are relative to the current folder


def test_model_of_a_run_with_an_arm_model(capsys):
    report = sim_json("Cell", capsys, "--robot", "tx2-60")
    model = model_from_sim_report(report, ReportScene(), fail_on="warning")  # the run's R009 (no scenario) fails it
    check_model(model)
    v = model["verdict"]
    assert v["counts"] == {s: report["summary"][s] for s in ("error", "warning", "info")}
    assert v["counts"]["warning"] >= 1 and v["passed"] is False and v["end_reason"] == report["end"]["reason"]
    d = model["diagnostics"][0]
    lines = (ROOT / d["path"]).read_text(encoding="utf-8").split("\n")
    ex = d["excerpt"]
    assert ex["lines"][d["line"] - ex["first_line"]] == lines[d["line"] - 1]
    assert model["scene"]["arm"]["name"] == "TX2-60" and model["scene"]["joints"] == [0.0] * 6
    assert model["tasks"] == [] and any("no task timeline" in n for n in model["limitations"])
    moved = report["motion"] is not None and report["motion"]["trajectory"]["segments"]
    assert (model["trajectory"] is not None) == bool(moved)
    render(model)


def test_model_of_a_run_that_passes_and_the_fail_on_threshold(capsys):
    report = sim_json("Supervisor", capsys)
    model = model_from_sim_report(report, ReportScene())
    assert model["verdict"]["passed"] and model["scene"] is None
    assert len(model["io"]) == report["summary"]["io_events"] and len(model["transcript"]) == 9
    warned = copy.deepcopy(report)
    warned["summary"]["warning"] = 1
    assert model_from_sim_report(warned, ReportScene(), fail_on="warning")["verdict"]["passed"] is False
    assert model_from_sim_report(warned, ReportScene(), fail_on="error")["verdict"]["passed"] is True
    assert model_from_sim_report(warned, ReportScene(), fail_on="never")["verdict"]["passed"] is True


def test_excerpts_quote_only_files_of_the_application(capsys, tmp_path):
    report = sim_json("Cell", capsys, "--robot", "tx2-60")
    secret = tmp_path / "secret.pgx"
    secret.write_text("line 1\nthe secret\n", encoding="utf-8")
    while len(report["diagnostics"]) < 2:  # two diagnostics to point elsewhere
        report["diagnostics"].append(dict(report["diagnostics"][0]))
    report["diagnostics"][0].update(path=str(secret), line=2)
    report["diagnostics"][1].update(path="fixtures/valid/Cell/../../../README.md", line=1)
    model = model_from_sim_report(report, ReportScene())
    assert [d["excerpt"] for d in model["diagnostics"]] == [None, None]
    assert model_from_sim_report(report, ReportScene(), roots=[str(tmp_path)])["diagnostics"][0]["excerpt"]["lines"] == ["line 1", "the secret"]


def test_not_a_sim_report():
    for bad in ({}, {"version": 3, "end": {}, "summary": {}}, [], {"version": 1}):
        with pytest.raises(ModelError, match="not a version 1 or 2 report"):
            model_from_sim_report(bad, ReportScene())


def test_command_renders_a_sim_report(capsys, tmp_path):
    report = sim_json("Supervisor", capsys)
    (tmp_path / "run.json").write_text(json.dumps(report), encoding="utf-8")
    out = tmp_path / "run.html"
    assert main(["html", "--sim-report", str(tmp_path / "run.json"), "-o", str(out)]) == 0
    assert "Supervisor" in out.read_text(encoding="utf-8")
    assert main(["html", "--sim-report", str(tmp_path / "missing.json"), "-o", str(out)]) == 2
    assert "cannot read" in capsys.readouterr().err


def _pickplace_json(capsys, *extra: str) -> dict:
    """The JSON report of the bundled example (its scenario; its cell beside it)."""
    assert main(["sim", "fixtures/valid/PickPlace", "--robot", "tx2-60", "--scenario",
                 "fixtures/scenarios/pickplace.toml", "--report", "json", *extra]) == 0
    return json.loads(capsys.readouterr().out)


def test_the_bundled_example_s_json_gives_its_motions_cycles_and_trajectory(capsys):
    """Issue 28 item 4: the page of a JSON report holding over a hundred motions, 18 or more
    cycles and the trajectory says so, not "No motion in this run" nor "the arm did not move"."""
    report = _pickplace_json(capsys)
    model = model_from_sim_report(report, ReportScene())
    check_model(model)
    runs = [m for m in report["motion"]["motions"] if m["start"] is not None]
    assert len(model["motions"]) == len(runs) > 100
    (loop,) = model["cycles"]  # the main task records its motions outside any loop: no cycle
    (robot,) = [c for c in report["motion"]["cycles"] if c["starts"]]
    n = robot["cycles"]
    assert sum(it["complete"] for it in loop["iterations"]) == n >= 18
    ct = model["verdict"]["cycle_time"]
    # the JSON rounds each time to 1e-6 s: the median of the rounded times is within 1e-6 of its own
    assert ct["seconds"] == pytest.approx(robot["median"], abs=2e-6) and f"median of {n} complete cycles" in ct["basis"]
    assert "while loop at line 9 of cycle.pgx" in ct["basis"]
    tr = model["trajectory"]
    assert len(tr["times"]) == 15001 and tr["times"][-1] == 60.0 and max(tr["tcp_speed"]) > 1000
    # the collision section's closest approach of each motion, and the cell's obstacles in the world
    closest = {c["motion"]: c["min_clearance"]["mm"] for c in report["collision"]["motions"]}
    assert [m["min_clearance"] for m in model["motions"]] == [closest[k] for k, m in
                                                              enumerate(report["motion"]["motions"])
                                                              if m["start"] is not None]
    assert {o["name"] for o in model["scene"]["obstacles"]} == set(report["collision"]["cell"]["obstacles"]) - {"pallet"}
    assert any("'pallet' is placed in fPallet" in n for n in model["limitations"])
    assert model["scene"]["tool"]["name"] == "tGripper" and len(model["scene"]["tool"]["solids"]) == 3
    html = render(model)
    for absent in ("No motion in this run", "did not move", "no complete loop iteration", "No TCP speed"):
        assert absent not in html
    # the motion table says which program each line is in (item 13), the whole position on hover
    assert '<th scope="col">program:line</th>' in html
    assert '<span title="fixtures/valid/PickPlace/start.pgx:15:3">start.pgx:15</span>' in html
    assert '<span title="fixtures/valid/PickPlace/pick.pgx:6:3">pick.pgx:6</span>' in html


def test_the_page_of_the_json_is_the_page_of_the_run(capsys):
    """The same run, its model built from the run's record and from its JSON report: the same
    motions (but the descriptors' vel and tvel, not in the JSON), cycles, trajectory (to the
    JSON's rounding), arm timeline (to a tick: a stop inside a motion is known to 4 ms) and tool."""
    import numpy as np

    from val3check.reporting import sim_json
    from val3check.reporting.html.from_run import model_from_run

    from .runhelp import pickplace

    _, run = pickplace(20.0)
    a = model_from_run(run)
    b = model_from_sim_report(json.loads(sim_json.render(run)), ReportScene())
    strip = [{k: v for k, v in m.items() if k not in ("vel", "tvel")} for m in a["motions"]]
    assert strip == [{k: v for k, v in m.items() if k not in ("vel", "tvel")} for m in b["motions"]]
    assert len(a["motions"]) > 30 and all(m["vel"] is None for m in b["motions"])
    assert a["cycles"] == b["cycles"]
    ca, cb = a["verdict"]["cycle_time"], b["verdict"]["cycle_time"]
    assert ca["basis"] == cb["basis"] and abs(ca["seconds"] - cb["seconds"]) <= 1e-6  # a median of two
    ta, tb = a["trajectory"], b["trajectory"]
    assert list(ta["times"]) == list(tb["times"]) and ta["joints"] == tb["joints"]  # both array("d")
    assert np.abs(np.array(ta["positions"]) - np.array(tb["positions"])).max() <= 5e-5 + 1e-9
    assert np.abs(np.array(ta["velocities"]) - np.array(tb["velocities"])).max() <= 5e-4 + 1e-9
    assert np.abs(np.array(ta["tcp_speed"]) - np.array(tb["tcp_speed"])).max() < 0.05  # mm/s
    la, lb = a["arm_timeline"], b["arm_timeline"]
    assert [s["state"] for s in la] == [s["state"] for s in lb]
    assert max(abs(x[k] - y[k]) for x, y in zip(la, lb) for k in ("start", "end")) < 0.004
    assert a["scene"]["tool"] == b["scene"]["tool"] and a["scene"]["arm"] == b["scene"]["arm"]


def test_a_motion_section_that_does_not_hold_together_is_refused(capsys):
    report = _pickplace_json(capsys, "--duration", "4")
    report["motion"]["trajectory"]["segments"][0]["positions"] = [[1, 2]]
    with pytest.raises(ModelError, match="`motion` section does not hold together"):
        model_from_sim_report(report, ReportScene())
    report["motion"]["trajectory"]["period"] = 0.008
    with pytest.raises(ModelError, match="period of 0.008 s"):
        model_from_sim_report(report, ReportScene())


def test_a_cell_outside_the_roots_is_not_read(capsys, tmp_path):
    report = _pickplace_json(capsys, "--duration", "4")
    outside = tmp_path / "cell.toml"
    outside.write_text((ROOT / "fixtures/valid/PickPlace/val3check-cell.toml").read_text(encoding="utf-8"))
    report["collision"]["cell"]["path"] = str(outside)
    model = model_from_sim_report(report, ReportScene())
    assert model["scene"]["obstacles"] == [] and any("outside the application's folder" in n
                                                     for n in model["limitations"])
    assert len(model_from_sim_report(report, ReportScene(), roots=[str(tmp_path)])["scene"]["obstacles"]) == 7


def test_the_page_of_a_json_report_is_bounded_as_the_page_of_the_run(monkeypatch):
    """Issue 29: the motion table, the arm timeline and the I/O changes of a page made from a JSON
    report hold their first rows (reporting/thinning.py), and its limitations say so in the words
    of the run's page; a short run's page holds all of them and says nothing."""
    from val3check.reporting import sim_json, thinning
    from val3check.reporting.html import from_run
    from val3check.reporting.html.from_run import model_from_run

    from .runhelp import pickplace

    _, run = pickplace(20.0)
    report = json.loads(sim_json.render(run))
    whole = model_from_sim_report(report, ReportScene())
    assert not [n for n in whole["limitations"] if "A long run" in n]
    assert len(whole["motions"]) > 30 and len(whole["arm_timeline"]) > 10 and len(whole["io"]) > 10
    keep = {"MOTION_ROWS": len(whole["motions"]) // 2, "ARM_SPANS": len(whole["arm_timeline"]) // 2,
            "IO_EVENTS": len(whole["io"]) // 2}
    for name, n in keep.items():
        monkeypatch.setattr(thinning, name, n)
    monkeypatch.setattr(from_run, "MOTION_ROWS", keep["MOTION_ROWS"])  # the run's page: its own name
    page = model_from_sim_report(report, ReportScene())
    assert page["motions"] == whole["motions"][:keep["MOTION_ROWS"]]
    assert page["arm_timeline"] == whole["arm_timeline"][:keep["ARM_SPANS"]]
    assert page["io"] == whole["io"][:keep["IO_EVENTS"]]
    notes = [n for n in page["limitations"] if n.startswith("A long run")]
    spans = whole["arm_timeline"]
    assert notes == [
        f"A long run: the motion table lists the first {keep['MOTION_ROWS']} of {len(report['motion']['motions'])} "
        "motions; the cycles, the findings and the plots cover the whole run.",
        f"A long run: the arm timeline holds the first {keep['ARM_SPANS']} of {len(spans)} moving and idle spans "
        f"(up to {spans[keep['ARM_SPANS']]['start']:g} s).",
        f"A long run: the I/O log holds the first {keep['IO_EVENTS']} of {len(whole['io'])} I/O changes "
        f"(up to {whole['io'][keep['IO_EVENTS']]['time']:g} s).",
    ]
    # the run's page says the same of its motions and I/O changes (its arm spans: to a tick)
    ran = [n for n in model_from_run(run)["limitations"] if n.startswith("A long run")]
    assert ran[0] == notes[0] and ran[-1] == notes[-1] and "moving and idle spans" in ran[1]
    html = render(page)
    assert all(f'<p class="synthetic" role="note">{n}</p>' in html for n in notes)
    check_model(page)
