"""The HTML report model built from a real run (reporting/html/from_run.py): every figure is
held to the run it comes from, to the arm model, or to the cell file."""

from __future__ import annotations

import json
import statistics
from pathlib import Path
from types import SimpleNamespace

import jsonschema
import numpy as np
import pytest

from val3check.collision.cellfile import read_cell
from val3check.collision.results import Clearance, MotionReport, MotionSpan
from val3check.reporting.html import check_model, render
from val3check.reporting.html.from_run import model_from_run
from val3check.robot import load_robot

from .runhelp import CELL, moving_run, pickplace

SCHEMA = json.loads((Path(__file__).resolve().parents[2] / "docs" / "html-report.schema.json").read_text(encoding="utf-8"))


@pytest.fixture(scope="module")
def run():
    return pickplace(20.0)


@pytest.fixture(scope="module")
def model(run):
    model = model_from_run(run[1])
    check_model(model)
    return model


def test_verdict_and_cycle_time_come_from_the_run(run, model):
    result, _ = run
    v = model["verdict"]
    assert v["passed"] and v["end_reason"] == "duration" and v["simulated_duration"] == 20.0
    assert v["counts"] == {"error": 0, "warning": 0, "info": 1}
    st = result.motion.cycles["robot"]
    assert v["cycle_time"]["seconds"] == pytest.approx(statistics.median(st.times), abs=1e-6)
    assert v["cycle_time"]["task"] == "robot" and f"median of {st.count} complete cycles" in v["cycle_time"]["basis"]
    (cy,) = model["cycles"]
    its = cy["iterations"]
    assert [it["complete"] for it in its] == [True] * st.count + [False]
    assert [it["start"] for it in its] == pytest.approx(st.starts)
    assert its[-1]["start"] + its[-1]["duration"] == pytest.approx(20.0)


def test_motion_table_is_the_run_s_records(run, model):
    result, _ = run
    moved = [r for r in result.motion.motions
             if r.start is not None and r.start <= 20.0]  # (the next one is planned to start after the run)
    assert len(model["motions"]) == len(moved) > 20
    for mo, rec in zip(model["motions"], moved):
        assert (mo["kind"], mo["line"], mo["task"] or "") == (rec.kind, rec.source.line, rec.source.task)
        assert mo["start"] == pytest.approx(rec.start, abs=1e-6)
        assert mo["dominant_limit"] == (rec.dominant_limit or None)
    # mApproach (tvel 250 mm/s, vel 50 %) on the two descents to the part and to the pallet
    pick = next(mo for mo in model["motions"] if mo["target"] == "pPick")
    assert (pick["kind"], pick["vel"], pick["tvel"]) == ("movel", 50.0, 250.0)


def test_trajectory_samples_the_run_every_4_ms_and_tcp_speed_is_the_tool_s(run, model):
    result, _ = run
    tr = model["trajectory"]
    assert tr["times"][0] == 0.0 and tr["times"][-1] == pytest.approx(20.0) and len(tr["times"]) == 5001
    k = 1000  # 4 s
    q = result.motion.trajectory.position(tr["times"][k])
    assert [row[k] for row in tr["positions"]] == pytest.approx(list(q), abs=1e-5)
    assert [j["name"] for j in tr["joints"]] == list(result.motion.scene.joint_names)
    # the TCP speed against a finite difference of the model's FK with tGripper (TCP 120 mm out)
    model_ = load_robot(result.motion.scene.name)
    tool = np.eye(4)
    tool[2, 3] = 120.0
    for k in (470, 520, 1100):  # within motions, the tool in use: tGripper
        t = tr["times"][k]
        h = 1e-5
        a = np.array(model_.fk_matrix(result.motion.trajectory.position(t - h), tool))[:, 3]
        b = np.array(model_.fk_matrix(result.motion.trajectory.position(t + h), tool))[:, 3]
        assert tr["tcp_speed"][k] == pytest.approx(np.linalg.norm(b - a) / (2 * h), rel=1e-3, abs=0.05)
    assert max(tr["tcp_speed"]) <= 2000.0 * (1 + 1e-3)  # mFast's tvel


def test_task_and_arm_timelines(run, model):
    result, _ = run
    tasks = {t["name"]: t["segments"] for t in model["tasks"]}
    robot = tasks["robot"]
    states = {s["state"] for s in robot}
    assert states == {"running", "waiting", "blocked"}
    assert any(s["detail"] == "wait(diPartPresent == true)" for s in robot if s["state"] == "waiting")
    assert any("end of motion" in (s["detail"] or "") for s in robot if s["state"] == "blocked")
    for segs in tasks.values():  # in order, not overlapping, within the run
        for a, b in zip(segs, segs[1:]):
            assert a["end"] <= b["start"] + 1e-9
        assert segs[-1]["end"] <= 20.0
    assert robot[-1]["end"] == 20.0  # alive at the end
    assert tasks["PickPlace~"][-1]["end"] < 1.0  # start() ends once it has created the robot task
    arm = model["arm_timeline"]
    assert arm[0]["start"] == 0.0 and arm[-1]["end"] == 20.0
    assert all(a["end"] == b["start"] for a, b in zip(arm, arm[1:]))
    moving = sum(s["end"] - s["start"] for s in arm if s["state"] == "moving")
    assert moving == pytest.approx(result.motion.busy_s, abs=1e-3)


def test_io_transcript_and_diagnostics(run, model):
    result, report = run
    assert len(model["io"]) == len(result.io_log) > 10
    assert model["io"][0]["names"]
    assert [e["text"] for e in model["transcript"]] == [e.text for e in result.transcript]
    (d,) = model["diagnostics"]
    assert d["code"] == "R007" and d["severity"] == "info"


def test_scene_has_the_arm_and_the_tool_but_no_cell_without_one(model):
    scene = model["scene"]
    assert scene["arm"]["name"] == "TX2-60" and scene["arm"]["joint_names"] == [f"joint_{i}" for i in range(1, 7)]
    assert scene["tool"]["name"] == "tGripper" and scene["tool"]["tcp"][2][3] == 120.0
    assert scene["obstacles"] == [] and any("No cell file" in s for s in model["limitations"])


def test_cell_obstacles_tool_solids_and_clearance(run):
    result, report = run
    cell = read_cell(CELL)
    rec = next(r for r in result.motion.motions if r.id is not None and r.start is not None)
    clear = MotionReport(MotionSpan(rec.id), np.zeros(0), np.zeros(0), np.zeros(0, bool),
                         min_clearance=Clearance(42.5, rec.start, "tool tGripper 'jaws'", "obstacle 'table'",
                                                         (0, 0, 0), (0, 0, 1)))
    result.collision = SimpleNamespace(cell=cell, by_motion={result.motion.motions.index(rec): clear})
    rec.clearance = clear  # the motion's clearances slot (simulation/arm_record.py)
    try:
        model = model_from_run(report)
    finally:
        del result.collision
        rec.clearance = None
    check_model(model)
    obstacles = {o["name"]: o for o in model["scene"]["obstacles"]}
    assert set(obstacles) == {"table", "pallet", "post"}
    assert obstacles["table"]["shape"] == "box" and obstacles["table"]["size"] == [500.0, 1200.0, 40.0]
    assert [row[3] for row in obstacles["table"]["pose"]] == [450.0, 0.0, -130.0]
    # the pallet sits in fPallet at (70, 70, -10); without the collision checks' timeline, fPallet
    # is where the run left it (300, 120, -80 in the world), from t = 0 on, and the page says so
    tracks = model["scene"]["tracks"]
    fpallet = result.motion.scene.frames["fPallet"].matrix
    assert obstacles["pallet"]["track"] == "fPallet" and [row[3] for row in obstacles["pallet"]["pose"]] == [70, 70, -10]
    assert tracks["fPallet"]["times"] == [0.0] and tracks["fPallet"]["poses"] == [[list(r) for r in fpallet[:3]]]
    assert "track" not in obstacles["table"]
    assert obstacles["post"]["radius"] == 40.0 and obstacles["post"]["length"] == 800.0
    solids = {s["name"]: s for s in model["scene"]["tool"]["solids"]}
    assert solids["body"]["pose"][2][3] == 30.0 and "track" not in solids["body"]  # on the flange
    assert solids["jaws"]["track"] == "tGripper" and solids["jaws"]["pose"][2][3] == -30.0  # in tGripper,
    assert tracks["tGripper"]["poses"][0][2][3] == 120.0  # 120 mm out of the flange
    first = next(mo for mo in model["motions"] if mo["motion_id"] == rec.id)
    assert (first["min_clearance"], first["clearance_to"]) == (42.5, "table")
    assert not any("No cell file" in s for s in model["limitations"])
    assert model["scene"]["parts"] == []
    assert [s for s in model["limitations"] if "collision checks did not run" in s] == [
        ("The collision checks did not run: obstacles placed in application frames are drawn where those frames "
         "are at the end of the run."),
        "The collision checks did not run: the parts of the cell file (what the tool carries) are not drawn."]
    assert "pallet" in render(model)


def test_frames_and_parts_as_the_collision_checks_placed_them(tmp_path):
    """A run that moves the frame an obstacle hangs on and carries a part (runhelp.MOVING): the
    frame's two values with the times the checks read them, the part's two spans, no warning."""
    result, report = moving_run(tmp_path)
    model = model_from_run(report)
    check_model(model)
    # its JSON form: the trajectory's series are array('d') in process (reporting/html/series.py)
    jsonschema.Draft202012Validator(SCHEMA).validate(json.loads(json.dumps(model, default=list)))
    assert not [d for d in result.diagnostics if d.code.startswith("R03")]
    assert not any("frames" in s or "parts" in s for s in model["limitations"]), model["limitations"]
    scene = model["scene"]
    motions = result.motion.motions
    # fBlock: x = -400 from the start, x = 400 from the start of the first motion recorded after the
    # program moved it (the fourth, movel appro(pPlace)): the checks placed the block there for it
    after = motions[3]
    assert after.kind == "movel" and after.start > motions[2].end
    track = scene["tracks"]["fBlock"]
    assert track["times"] == [pytest.approx(motions[0].start), pytest.approx(after.start)]
    assert [p[0][3] for p in track["poses"]] == [-400.0, 400.0]
    (block,) = [o for o in scene["obstacles"] if o["name"] == "block"]
    assert block["track"] == "fBlock" and [r[3] for r in block["pose"]] == [0.0, 500.0, 100.0]
    # the brick: on the flange from close() to open(), in tGrip (100 mm out of the flange), at
    # (0, 0, 20) in it; then left where open() leaves it, the TCP at pPlace (400, 200, 40) pointing down
    (brick,) = scene["parts"]
    close, open_ = (e.time_us / 1e6 for e in result.motion.tool_events)
    assert [s["name"] for s in brick["solids"]] == ["brick"] and [r[3] for r in brick["solids"][0]["pose"]] == [0, 0, 20]
    carried, left = brick["spans"]
    assert (carried["start"], carried["end"], carried["carried"]) == (close, open_, True)
    assert carried["pose"] == [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 100]]
    assert (left["start"], left["end"], left["carried"]) == (open_, None, False)
    assert np.asarray(left["pose"]) == pytest.approx(np.array([[-1, 0, 0, 400], [0, 1, 0, 200], [0, 0, -1, 40]]),
                                                      abs=1e-6)


def test_same_run_same_page(run):
    a = render(model_from_run(run[1]))
    b = render(model_from_run(run[1]))
    assert a == b and len(a) < 5_000_000


def test_a_scara_run_joint_3_in_mm_and_its_tcp_speed(tmp_path):
    from interpretation.simsupport import sim

    from val3check.config import Settings
    from val3check.reporting.sim_report import build_report
    from val3check.robot import load_robot
    from val3check.rules.catalogue import catalogue

    ts = load_robot("TS2-60")
    r = sim(tmp_path, """begin
  movej({0, 90, 150, 0}, flange, mFast)
  waitEndMove()
  pA = here(flange, world)
  pB = compose(pA, world, {0, 0, -50, 0, 0, 0})
  mSlow.vel = 20
  mSlow.blend = off
  movel(pB, flange, mSlow)
  waitEndMove()
end
""", globals_=["pointRs pA", "pointRs pB", "mdesc mFast", "mdesc mSlow"], robot=ts)
    model = model_from_run(build_report(r, Settings(), catalogue(), "test"))
    check_model(model)
    tr = model["trajectory"]
    assert [j["unit"] for j in tr["joints"]] == ["deg", "deg", "mm", "deg"]
    movel = model["motions"][-1]
    k = tr["times"].index(round(round((movel["start"] + movel["end"]) / 2 / 0.004) * 0.004, 6))
    t, h = tr["times"][k], 1e-5
    a = np.array(ts.fk_matrix(r.motion.trajectory.position(t - h)))[:, 3]
    b = np.array(ts.fk_matrix(r.motion.trajectory.position(t + h)))[:, 3]
    assert tr["tcp_speed"][k] == pytest.approx(np.linalg.norm(b - a) / (2 * h), rel=1e-3)
    assert tr["tcp_speed"][k] > 10.0  # the straight line down, on the prismatic axis


def test_sim_report_html_same_input_same_bytes(tmp_path, monkeypatch):
    from val3check.cli import main

    from .runhelp import ROOT

    monkeypatch.chdir(ROOT)
    pages = []
    for n in (1, 2):
        out = tmp_path / f"r{n}.html"
        assert main(["sim", "fixtures/valid/PickPlace", "--robot", "tx2-60", "--scenario",
                     "fixtures/scenarios/pickplace.toml", "--duration", "10", "--report", "html", "-o", str(out)]) == 0
        pages.append(out.read_bytes())
    assert pages[0] == pages[1] and b"PickPlace" in pages[0]


def test_a_long_run_is_sampled_at_a_multiple_of_4_ms():
    from val3check.reporting.html.from_run import MAX_SAMPLES, sample_period

    assert sample_period(60.0) == 0.004 and sample_period(600.0) == 0.004  # 150,001 samples
    assert sample_period(600.004) == 0.008
    assert sample_period(3600.0) == pytest.approx(0.024) and 3600.0 / 0.024 + 1 <= MAX_SAMPLES


def test_a_part_taken_again_where_it_was_left_leaves_the_cell(tmp_path):
    """docs/cell.md: a part taken where a part of the same name was left is that part. The brick of
    runhelp.MOVING is taken again at pPlace after open(): its left span ends there, a new carried
    span starts, and nothing is left in the cell at the end."""
    from interpretation.simsupport import sim

    from .runhelp import MOVING, MOVING_CELL, MOVING_GLOBALS

    code = MOVING.replace("  open(tGrip)\n", "  open(tGrip)\n  close(tGrip)\n")
    cell = tmp_path / "cell.toml"
    cell.write_text(MOVING_CELL, encoding="utf-8")
    result = sim(tmp_path, code, globals_=MOVING_GLOBALS, robot=load_robot("tx2-60"), collisions=True,
                 cell=str(cell))
    close1, open_, close2 = (e.time_us / 1e6 for e in result.motion.tool_events)
    spans = [(s.carried, s.start, s.end) for s in result.motion.cell_timeline.parts]
    assert spans == [(True, close1, open_), (False, open_, close2), (True, close2, None)]


def test_the_rows_limits_and_clearances_rounded_once_per_object_are_each_row_s(run):
    """The motion table rounds each limits and closest-approach object's numbers once (a cyclic run's
    rows share a few objects): every row as if rounded alone, whichever objects repeat, another
    object with other values (0.0 and -0.0 too) giving its own."""
    from dataclasses import replace

    from val3check.reporting.html.from_run import _motions, _r

    result, report = run
    base = next(mo for mo in result.motion.motions if mo.limits is not None and mo.start is not None)
    one = base.limits
    others = [replace(one, vel=one.vel + 0.0004), replace(one, tvel=None), replace(one, vel=0.0),
              replace(one, vel=-0.0), replace(one, tvel=(one.tvel or 100.0) + 0.7)]
    limits = [one, others[0], one, others[1], others[0], others[2], others[3], one, others[4], others[4]]
    motions = [replace(base, limits=lim, start=base.start + k, end=base.start + k + 0.5) for k, lim in enumerate(limits)]
    near = [Clearance(mm, 1.0, "tool tGripper 'jaws'", "obstacle 'table'", (0, 0, 0), (0, 0, 1))
            for mm in (42.5004, 17.25, 0.0, -0.0)]
    close = {k: MotionReport(MotionSpan(k), np.zeros(0), np.zeros(0), np.zeros(0, bool), min_clearance=near[k % 4])
             for k in range(len(motions)) if k != 3}
    rows = _motions(report, SimpleNamespace(motions=motions), 100.0, close)
    assert len(rows) == len(motions)
    for k, (row, mo) in enumerate(zip(rows, motions)):
        want = (_r(mo.limits.vel, 3), _r(mo.limits.tvel, 3) if mo.limits.tvel is not None else None,
                _r(near[k % 4].mm, 3) if k != 3 else None)
        assert repr((row["vel"], row["tvel"], row["min_clearance"])) == repr(want)
