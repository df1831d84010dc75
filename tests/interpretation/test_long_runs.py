"""Long runs bounded (issue 21 H, issue 26's budgets, issue 29's memory and output): repeated
findings folded with their count and first/last times in every format, the trajectory of the
JSON report and of the trace thinned to a bounded number of samples (and said), the motion tables
capped, and the wall-clock and memory budgets covering the collision checks and the report
writers. The bounds are made small here (monkeypatch) so that short runs show them; the wall
budget reads a clock of the test's (simsupport.StepClock): nothing depends on the machine's speed."""

from __future__ import annotations

import itertools
import json

import pytest
from mcap.reader import make_reader

from val3check.config import Settings
from val3check.diagnostics import Diagnostic
from val3check.reporting import mcap_trace, sim_json, sim_text, thinning
from val3check.reporting.html import from_run
from val3check.reporting.sim_report import build_report
from val3check.robot import load_robot
from val3check.rules.catalogue import catalogue
from val3check.simulation import folding
from val3check.simulation.budget import RunBudget

from .simsupport import StepClock, frozen_clock, sim

TX2_60 = load_robot("tx2-60")
# a movej loop between two joint positions: 0.744 s a pass, every motion of 0.37 s
LOOP = """begin
  jA.j1 = 30
  jB.j1 = -30
  jB.j2 = 20
  while true
    movej(jA, flange, mD)
    movej(jB, flange, mD)
    waitEndMove()
  endWhile
end
"""
LOOP_GLOBALS = ["joint jA", "joint jB", "mdesc mD"]
# issue 26: a movej to where the arm stands, in the idle loop (one R016 a pass)
IDLE = """begin
  while true
    jHere = herej()
    movej(jHere, flange, mD)
    waitEndMove()
  endWhile
end
"""


def _report(result):
    return build_report(result, Settings(), catalogue(), "test")


# ---- repeated findings folded -----------------------------------------------------------------------


def test_a_finding_repeated_at_one_line_is_one_finding_with_its_count(tmp_path):
    r = sim(tmp_path, IDLE, globals_=["joint jHere", "mdesc mD"], robot=TX2_60, duration=1.0, wall_clock=frozen_clock,
            max_lines=200_000)
    r016 = [d for d in r.diagnostics if d.code == "R016"]
    assert len(r016) == 1
    d = r016[0]
    assert d.count > 1000 and d.count == sum(1 for m in r.motion.motions if m.id is not None)
    assert d.last_time_us >= d.time_us
    assert f"[repeated {d.count} times, from {d.time_us / 1e6:.3f} s to {d.last_time_us / 1e6:.3f} s]" in d.message
    report = _report(r)
    data = json.loads(sim_json.render(report))
    [j] = [x for x in data["diagnostics"] if x["code"] == "R016"]
    assert j["count"] == d.count and j["last_time"] == round(d.last_time_us / 1e6, 6)
    text = sim_text.render(report)
    assert text.count("R016") == 1 and f"repeated {d.count} times" in text


def test_fold_keeps_distinct_findings_and_bounds_their_number(monkeypatch):
    def diag(msg, t, line=3):
        return Diagnostic("R016", msg, "a.pgx", line, 5, time_us=t, task="T", program="start")

    diags = [diag("same", 10), diag("other", 20), diag("same", 30), diag("same", 40, line=4)]
    out = folding.fold(diags)
    assert [(d.message.split(" [")[0], d.line, d.count, d.time_us, d.last_time_us) for d in out] == [
        ("same", 3, 2, 10, 30), ("other", 3, 1, 20, None), ("same", 4, 1, 40, None)]
    assert folding.fold(out) == out  # folding twice changes nothing
    monkeypatch.setattr(folding, "MAX_KEPT", 2)
    out = folding.fold([diag(f"m{i}", i) for i in range(5)], "app.pjx", 99)
    assert [d.code for d in out] == ["R016", "R016", "R006"]
    assert "3 of R016" in out[-1].message and out[-1].time_us == 99


# ---- the trajectory thinned, the tables capped ----------------------------------------------------------


@pytest.fixture(scope="module")
def loop_run(tmp_path_factory):
    """20 s of the movej loop: about 5,000 ticks of motion, 54 motions."""
    return sim(tmp_path_factory.mktemp("loop"), LOOP, globals_=LOOP_GLOBALS, robot=TX2_60, duration=20.0,
               wall_clock=frozen_clock)


def test_a_short_run_keeps_every_tick(loop_run):
    data = json.loads(sim_json.render(_report(loop_run)))
    tr = data["motion"]["trajectory"]
    assert tr["period"] == 0.004 and "thinned" not in tr and "omitted" not in tr
    assert "motions_omitted" not in data["motion"]


def test_the_json_trajectory_is_thinned_to_its_bound(loop_run, monkeypatch):
    ticks = thinning.moving_ticks(loop_run.motion)
    assert 4500 < ticks < 5500
    full = json.loads(sim_json.render(_report(loop_run)))["motion"]["trajectory"]
    monkeypatch.setattr(sim_json, "JSON_TICKS", 1000)
    tr = json.loads(sim_json.render(_report(loop_run)))["motion"]["trajectory"]
    every = -(-ticks // 1000)
    assert tr["thinned"]["every_ticks"] == every and tr["period"] == round(0.004 * every, 6)
    assert f"every {every * 4:g} ms" in tr["thinned"]["why"]
    samples = sum(len(s["positions"]) for s in tr["segments"])
    assert samples <= 1000 + 2 * len(tr["segments"])
    # the samples kept are the full trajectory's at the same times
    full_at = {round(s["start"] + i * 0.004, 6): row for s in full["segments"] for i, row in enumerate(s["positions"])}
    for s in tr["segments"]:
        assert s["start"] == round(s["first_tick"] * tr["period"], 6)
        for i, row in enumerate(s["positions"]):
            t = round(s["start"] + i * tr["period"], 6)
            if t in full_at:
                assert row == full_at[t]


def test_the_motion_tables_keep_their_first_rows(loop_run, monkeypatch):
    n = len(loop_run.motion.motions)
    monkeypatch.setattr(sim_json, "MOTION_ROWS", 10)
    monkeypatch.setattr(from_run, "MOTION_ROWS", 10)
    data = json.loads(sim_json.render(_report(loop_run)))
    assert [m["line"] for m in data["motion"]["motions"]] == [m.source.line for m in loop_run.motion.motions[:10]]
    assert data["motion"]["motions_omitted"]["count"] == n - 10
    assert data["motion"]["summary"]["commands"] == n  # the summary covers the whole run
    model = from_run.model_from_run(_report(loop_run))
    assert len(model["motions"]) == 10
    assert any(f"first 10 of {n} motions" in x for x in model["limitations"])


def test_the_trace_is_thinned_and_says_so(loop_run, tmp_path, monkeypatch):
    monkeypatch.setattr(mcap_trace, "TRACE_TICKS", 500)
    path = tmp_path / "run.mcap"
    mcap_trace.write_trace(_report(loop_run), str(path))
    with open(path, "rb") as f:
        reader = make_reader(f)
        times = [m.log_time for _, ch, m in reader.iter_messages() if ch.topic == "/joint_states"]
        meta = {k: v for m in reader.iter_metadata() for k, v in m.metadata.items()}
    every = -(-thinning.moving_ticks(loop_run.motion) // 500)
    assert meta["arm_period_s"] == f"{0.004 * every:.6f}" and "thinned" in meta
    assert len(times) <= 500 + 50
    steps = {b - a for a, b in itertools.pairwise(times)}
    assert min(steps) == round(0.004 * every * 1e9)


# ---- the budgets cover the collision checks and the reports ---------------------------------------------


def test_the_reports_leave_out_the_trajectory_once_the_budget_is_spent(loop_run, tmp_path):
    assert loop_run.budget is None  # the API's caller writes its reports when it likes
    loop_run.budget = RunBudget(lambda: 1e9, 0.0, 60.0, None)
    try:
        report = _report(loop_run)
        tr = json.loads(sim_json.render(report))["motion"]["trajectory"]
        assert tr["segments"] == [] and "wall-clock budget (--max-wall 60 s) is spent" in tr["omitted"]
        path = tmp_path / "run.mcap"
        mcap_trace.write_trace(report, str(path))
        with open(path, "rb") as f:
            reader = make_reader(f)
            n = sum(1 for _, ch, _ in reader.iter_messages() if ch.topic == "/joint_states")
            meta = {k: v for m in reader.iter_metadata() for k, v in m.metadata.items()}
        assert n == 1 and "is spent" in meta["omitted"]  # the arm at t = 0 only
        limits: list[str] = []
        assert from_run._trajectory(report, loop_run.motion, limits) is None
        assert "is spent" in limits[0]
    finally:
        loop_run.budget = None


def test_the_sim_command_s_reports_are_within_the_run_s_budget(tmp_path):
    from val3check.simulation.case import CaseSpec, run_case
    from val3check.testing import write_app

    folder = write_app(tmp_path, LOOP, name="Loop", globals_=LOOP_GLOBALS)
    outcome = run_case(CaseSpec(str(folder), Settings(), robot="tx2-60", duration=2.0))
    budget = outcome.result.budget
    assert isinstance(budget, RunBudget) and budget.max_wall == 60.0 and budget.spent() is None


def test_the_memory_budget_counts_too():
    class Over:
        def over(self):
            return "the simulation uses 900 MB, more than its memory budget of 200 MB (--max-memory)"

    assert RunBudget(frozen_clock, 10.0, 10.0, Over()).spent().startswith("the simulation uses 900 MB")
    assert RunBudget(frozen_clock, 10.0, 10.0, None).spent() is None


def test_the_collision_checks_stop_at_the_runs_budget(tmp_path):
    # 1 ms per reading: the simulation ends at 3/4 of the 2 s budget (1,500 readings); then 20 ms
    # per reading: the checks read the budgets every BUDGET_EVERY motions (and before each sweep)
    # and stop at about the 25th reading after the simulation, with about 800 of 1,500 motions checked
    class Slower(StepClock):
        def __call__(self) -> float:
            return super().__call__() + max(self.reads - 1500, 0) * 0.019

    clock = Slower(0.001)
    r = sim(tmp_path, LOOP, globals_=LOOP_GLOBALS, robot=TX2_60, duration=100_000, max_wall=2.0, wall_clock=clock,
            collisions=True)
    assert r.end_reason == "wall-clock"
    cut = [d for d in r.diagnostics if d.code == "R037"]
    assert len(cut) == 1 and "cut short by the wall-clock budget (--max-wall 2 s)" in cut[0].message
    done, total = (int(x) for x in cut[0].message.split(": ")[1].split(" motions")[0].split(" of "))
    assert 0 < done < total == len(r.motion.motions)
    assert len(r.collision.by_motion) == done


def test_the_checks_read_the_budgets_before_each_sweep_and_every_few_reused_motions(loop_run):
    from val3check.simulation.collision_run import BUDGET_EVERY, ValueWatch, check_run

    asked = []
    run, diags = check_run(loop_run.motion, None, ValueWatch(None), TX2_60, max_wall=3600.0, app_path="a.pjx",
                           out_of_budget=lambda: asked.append(len(asked)))
    n = len(loop_run.motion.motions)
    swept = n - run.reused
    assert not diags and n > BUDGET_EVERY and 0 < swept < n
    # one before the arm's solids are read, one at each BUDGET_EVERY-th motion, one before each other
    # sweep: at most those
    assert 1 + -(-n // BUDGET_EVERY) <= len(asked) <= 1 + -(-n // BUDGET_EVERY) + swept
    # spent at the first sweep after the first motion: the check stops before it
    asked.clear()
    run, diags = check_run(loop_run.motion, None, ValueWatch(None), TX2_60, max_wall=3600.0, app_path="a.pjx",
                           out_of_budget=lambda: asked.append(0) or ("over" if len(asked) > 2 else None))
    done = int(diags[0].message.split(": ")[1].split(" of ")[0])
    assert [d.code for d in diags] == ["R037"] and 0 < done < BUDGET_EVERY and len(run.by_motion) == done


def test_no_collision_check_starts_once_the_budget_is_spent(loop_run):
    from val3check.simulation.collision_run import ValueWatch, check_run

    run, diags = check_run(loop_run.motion, None, ValueWatch(None), TX2_60, max_wall=10.0, app_path="a.pjx",
                           out_of_budget=lambda: "the simulation uses 900 MB, more than its memory budget of 200 MB")
    assert run is None and [d.code for d in diags] == ["R037"]
    assert "(the simulation uses 900 MB" in diags[0].message
    assert f"0 of {len(loop_run.motion.motions)} motions checked" in diags[0].message
