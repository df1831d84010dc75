"""Budgets and bad input: a busy loop ends at --duration, a deep recursion ends with the stack
diagnostic, bad scenarios are rejected with their line, and every valid fixture gives
byte-identical JSON reports on two runs. The wall budget reads a clock of the test's
(simsupport.StepClock, frozen_clock): nothing here depends on the machine's speed (issue 28
item 11); how fast the simulator runs is measured by bench/bench_sim.py."""

from __future__ import annotations

from pathlib import Path

import pytest

from val3check.cli import main
from val3check.simulation.scenario import ScenarioError

from .simsupport import StepClock, build, codes, errors, frozen_clock, run_folder, sim

ROOT = Path(__file__).resolve().parents[2]


@pytest.mark.parametrize("body", ["while true\n  endWhile", "do\n  until false",
                                  "while true\n    nX = nX + 1\n  endWhile"])
def test_busy_loop_ends_at_duration(tmp_path, body):
    r = sim(tmp_path, f"begin\n  {body}\nend\n", globals_=["num nX"], duration=20, max_lines=50_000_000,
            wall_clock=frozen_clock)
    assert r.end_reason == "duration"
    assert r.sim_time_us == 20_000_000
    assert r.lines == pytest.approx(20 * 250_000, rel=0.01)  # 4 µs per line
    assert "R007" in codes(r)


def test_busy_loop_with_wall_budget(tmp_path):
    # 1 ms per reading of the clock: the simulation's share of the 0.5 s budget (3/4: the rest is
    # kept for the checks and reports, simulation/budget.py) is spent after 375 readings, long
    # before the line budget (the scheduler reads the clock once per cycle of a few hundred lines)
    clock = StepClock(0.001)
    r = sim(tmp_path, "begin\n  while true\n  endWhile\nend\n", duration=100_000, max_wall=0.5,
            max_lines=50_000_000, wall_clock=clock)
    assert r.end_reason == "wall-clock"
    assert "R006" in codes(r)
    assert 375 <= clock.reads < 475 and r.lines < 1_000_000


def test_busy_loop_with_line_budget(tmp_path):
    r = sim(tmp_path, "begin\n  while true\n  endWhile\nend\n", duration=1000, max_lines=100_000,
            wall_clock=frozen_clock)
    assert r.end_reason == "steps"
    assert "R006" in codes(r)


@pytest.mark.parametrize("stack", [5000, 10_000_000])
def test_deep_recursion_ends_with_error_41(tmp_path, stack):
    # with the default 5000 bytes, or a stack size so large that the simulator's own depth
    # limit comes first: error 41 either way, never an internal error
    folder = build(tmp_path, "begin\n  call rec(0)\nend\n", globals_=["num nDepth"],
                   programs={"rec": {"params": ["num x_n"], "code": "begin\n  nDepth = x_n\n  call rec(x_n + 1)\nend\n"}})
    pjx = folder / "Example.pjx"
    pjx.write_text(pjx.read_text().replace('stackSize="5000"', f'stackSize="{stack}"'))
    r = run_folder(folder, wall_clock=frozen_clock)
    assert errors(r) == [41], r.diagnostics
    assert r.end_reason == "stalled"


def test_transcript_full_does_not_stop_the_run(tmp_path):
    r = sim(tmp_path, "begin\n  while true\n    putln(\"busy\")\n  endWhile\nend\n", duration=1)
    assert r.end_reason == "duration"
    assert len(r.transcript) == 10_000
    assert [d.message for d in r.diagnostics if d.code == "R006"] == [
        "the user page transcript is full (10000 entries): later entries are not recorded (the page itself is still kept)"]
    assert r.screen["lines"][-2] == "busy"


@pytest.mark.parametrize("scenario,line,text", [
    ("[inputs]\ndiIn = false\n\n[[events]]\nat = 1\nset = { diNope = true }\n", 6, "diNope"),
    ("[inputs]\ndiIn = 3\n", 2, "a dio takes true or false"),
    ("[inputs]\naiIn = true\n", 2, "an aio takes a number"),
    ("[inputs]\ndiUnlinked = true\n", 2, "not linked"),
    ("version = 1\n[oops]\nx = 1\n", 2, "unknown table"),
    ("[[events]]\nat = -1\nset = { diIn = true }\n", 2, "at = seconds"),
    ("[[keys]]\nat = 1\nkey = 5000\n", 3, "key code"),
    ("[[keys]]\nat = 1\ncode = 271\n", 3, "unknown key 'code'"),
    ("[[serial]]\nsio = \"diIn\"\nsend = \"x\"\n", 2, "expected sio"),
    ("[[serial]]\nsio = \"siLine\"\nbytes = [1, 300]\n", 3, "bytes"),
    ("[controller]\nworking_mode = 7\n", 2, "working_mode"),
    ("[controller]\nmonitor_speed = 150\n", 2, "monitor_speed"),
    ("[io]\ndiIn = { status = 5 }\n", 2, "status"),
    ("[io]\ndiIn = { integer = true }\n", 2, "for an aio only"),
    ("[io]\nnope = { status = 0 }\n", 2, "unknown signal"),
    ("[io]\ndiIn = { color = 1 }\n", 2, "unknown key 'color'"),
    ("[reactions]\nwhen = 1\n", 1, "reactions must be an array"),
    ("[inputs\n", 1, "invalid TOML"),
])
def test_bad_scenarios_are_rejected_with_their_line(tmp_path, scenario, line, text):
    with pytest.raises(ScenarioError) as exc:
        sim(tmp_path, "begin\nend\n", globals_=["dio diIn", "aio aiIn", "dio diUnlinked", "sio siLine"],
            links={"diIn": "IO\\%I0", "aiIn": "IO\\%IW0", "siLine": "Serial0"}, scenario=scenario)
    assert exc.value.line == line, exc.value
    assert text in str(exc.value)


def _runnable_fixtures() -> list[str]:
    """Every application of fixtures/valid that has a start() program (relative paths)."""
    base = ROOT / "fixtures" / "valid"
    return sorted(str(p.parent.relative_to(base)) for p in base.glob("**/start.pgx"))


@pytest.mark.parametrize("name", _runnable_fixtures())
def test_two_runs_give_identical_json(name, capsys):
    args = ["sim", str(ROOT / "fixtures" / "valid" / name), "--report", "json", "--duration", "20"]
    a = main(args)
    first = capsys.readouterr().out
    b = main(args)
    second = capsys.readouterr().out
    assert a == b
    assert first == second and first.startswith("{")
