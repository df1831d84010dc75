"""The uncertainty of the assumed accelerations, stated (issue 23): the cycle time with the range it
takes for accelerations half and twice the assumption, by re-timing the run's path (held here to
full runs of the same application with the accelerations scaled), in every report; a robot file
with measured accelerations removes it; `val3check robots fit` fits them to a measured cycle."""

from __future__ import annotations

import json
import statistics

import pytest

from interpretation.simsupport import build, sim
from val3check.cli import main
from val3check.config import Settings
from val3check.reporting.html.from_run import model_from_run
from val3check.reporting.sim_report import build_report
from val3check.robot import load_robot
from val3check.rules.catalogue import catalogue

TX = load_robot("TX2-60")
# a U cycle, blended at its corners, never waiting for the arm: the program stays ahead
LOOP = """begin
  movej({0, 20, 100, 0, 60, 0}, flange, mStop)
  waitEndMove()
  pA = here(flange, world)
  pB = compose(pA, world, {0, 0, 40, 0, 0, 0})
  pC = compose(pA, world, {0, 250, 40, 0, 0, 0})
  pD = compose(pA, world, {0, 250, 0, 0, 0, 0})
  mB.blend = joint
  mB.leave = 20
  mB.reach = 60
  mStop.blend = off
  for l_i = 1 to 6
    movel(pB, flange, mB)
    movel(pC, flange, mB)
    movel(pD, flange, mStop)
    movel(pC, flange, mB)
    movel(pB, flange, mB)
    movel(pA, flange, mStop)
  endFor
  waitEndMove()
end
"""
GLOBALS = ["point pA", "point pB", "point pC", "point pD", "mdesc mB", "mdesc mStop"]


def run(tmp_path, robot):
    return sim(tmp_path, LOOP, globals_=GLOBALS, locals_=["num l_i"], robot=robot)


def median_cycle(result):
    (st,) = [s for s in result.motion.cycles.values() if s.times]
    return st.task, statistics.median(st.times)


def test_the_range_is_the_cycle_with_the_accelerations_half_and_twice(tmp_path):
    assert TX.accelerations_assumed
    r = run(tmp_path / "a", TX)
    task, median = median_cycle(r)
    spread = r.motion.acceleration_range
    assert spread is not None and spread.factors == (0.5, 2.0) and spread.off_by == 2.0
    lo, hi = spread.cycle_time(task)
    # the same application run again with every acceleration scaled: the re-timing is exact here
    _, faster = median_cycle(run(tmp_path / "b", TX.with_acceleration_scale(2.0)))
    _, slower = median_cycle(run(tmp_path / "c", TX.with_acceleration_scale(0.5)))
    assert lo == pytest.approx(faster, rel=1e-6) and hi == pytest.approx(slower, rel=1e-6)
    assert lo < median < hi


def test_every_report_states_the_range(tmp_path, capsys):
    folder = build(tmp_path, LOOP, globals_=GLOBALS, locals_=["num l_i"])
    assert main(["sim", str(folder), "--robot", "TX2-60"]) == 0
    text = capsys.readouterr().out
    line = next(x for x in text.splitlines() if x.startswith("cycle time of task"))
    assert "s if the assumed accelerations are off by 2×)" in line
    assert main(["sim", str(folder), "--robot", "TX2-60", "--report", "json"]) == 0
    mo = json.loads(capsys.readouterr().out)["motion"]
    assert mo["accelerations_assumed"] is True and mo["acceleration_factors"] == [0.5, 2.0]
    (cycle,) = mo["cycles"]
    lo, hi = cycle["median_range"]
    assert lo < cycle["median"] < hi
    assert f"median {cycle['median']:.3f} s ({lo:.3f}–{hi:.3f} s if" in line
    r = run(tmp_path / "html", TX)
    page = model_from_run(build_report(r, Settings(), catalogue(), "test"))
    ct = page["verdict"]["cycle_time"]
    assert ct["range"] == pytest.approx([lo, hi], abs=1e-6) and ct["off_by"] == 2.0


def test_the_batch_summary_states_the_range(tmp_path, capsys):
    from val3check.batch.summary import render_text
    from val3check.batch.worker import CaseSummary

    s = CaseSummary(("a",), "a", "App", "App", "tx2-60", "TX2-60", "", "", (), "pass", cycle_time=2.88, cycles=5,
                    cycle_range=(2.41, 3.52))
    assert "2.880 s (5 cycles, 2.410–3.520 s if accelerations off 2×)" in render_text([s])
    assert s.as_dict()["cycle_time_range"] == [2.41, 3.52]


def test_measured_accelerations_remove_the_range(tmp_path, capsys):
    robot = tmp_path / "cell.toml"
    robot.write_text('arm = "TX2-60"\n[assume]\nramp_s = 0.3\n', encoding="utf-8")
    model = load_robot(str(robot))
    assert not model.accelerations_assumed
    r = run(tmp_path / "run", model)
    assert r.motion.acceleration_range is None
    folder = build(tmp_path / "app", LOOP, globals_=GLOBALS, locals_=["num l_i"])
    assert main(["sim", str(folder), "--robot", str(robot), "--report", "json"]) == 0
    mo = json.loads(capsys.readouterr().out)["motion"]
    assert mo["accelerations_assumed"] is False and mo["cycles"][0]["median_range"] is None


def test_robots_fit_gives_a_robot_file_that_reproduces_the_measured_cycle(tmp_path, capsys):
    _, simulated = median_cycle(run(tmp_path / "base", TX))
    measured = round(simulated * 1.15, 3)  # the real cell is slower than the assumption
    folder = build(tmp_path / "app", LOOP, globals_=GLOBALS, locals_=["num l_i"])
    out = tmp_path / "fitted.toml"
    assert main(["robots", "fit", str(folder), "--robot", "TX2-60", "--measured-cycle", str(measured),
                 "-o", str(out)]) == 0
    fitted = load_robot(str(out))
    assert not fitted.accelerations_assumed and fitted.nominal_speeds == TX.nominal_speeds
    ratios = [a / b for a, b in zip(fitted.accelerations, TX.accelerations)]
    assert max(ratios) == pytest.approx(min(ratios), rel=1e-5) and ratios[0] < 1.0  # one factor, slower
    r = run(tmp_path / "check", fitted)
    assert median_cycle(r)[1] == pytest.approx(measured, rel=2e-3)
    assert r.motion.acceleration_range is None
    # out of reach: shorter than the arm can be with any acceleration
    assert main(["robots", "fit", str(folder), "--robot", "TX2-60", "--measured-cycle", "0.01"]) == 2
    assert "shorter than the run's cycle" in capsys.readouterr().err
