"""The cycle: the loop that moves the arm once per part (motion/cycle.py, docs/motion.md "Cycle
time"). Applications with inner loops, loops in called programs, no repeating loop, several tasks,
and `--cycles N`, against cycle times computed by hand: every motion is a rest-to-rest `movej`
of joint 1 alone (blend off) recorded ahead of the arm, so a pass takes the sum of its moves'
bang-bang times exactly."""

from __future__ import annotations

import json
import math

import pytest

from interpretation.simsupport import build, code_pos, codes, sim
from val3check.cli import main
from val3check.motion.cycle import Loop, LoopTracker, Pass
from val3check.robot import load_robot

TX = load_robot("TX2-60")


def bang_axis(d: float, k: int) -> float:
    """Joint k (0-based) alone over d degrees from rest to rest at 100 % (accel = decel)."""
    v, a, d = TX.nominal_speeds[k], TX.accelerations[k], abs(d)
    return d / v + v / a if d >= v * v / a else 2 * math.sqrt(d / a)


def bang(d: float) -> float:
    """Joint 1 alone over d degrees."""
    return bang_axis(d, 0)


def j1(deg: float) -> str:
    return f"movej({{{deg:g}, 20, 100, 0, 60, 0}}, flange, mD)"


def run(tmp_path, code, globals_=("mdesc mD",), **kw):
    kw.setdefault("duration", 6.0)
    return sim(tmp_path, code, globals_=list(globals_), robot=TX, **kw)


def cycle(r, task="Example~"):
    return r.motion.cycles[task]


def line_of(r, line, program="start"):
    return code_pos(r, line, 1, program)[0]


# ---- inner loops are not the cycle -----------------------------------------------------------------------

POCKET = """begin
  mD.blend = off
  {home}
  while true
    {a}
    INNER
    {home}
  endWhile
end
"""
INNER = {
    "for": "for nI = 1 to 3\n      {b}\n      {a}\n    endFor",
    "while": "nI = 0\n    while nI < 3\n      {b}\n      {a}\n      nI = nI + 1\n    endWhile",
    "do": "nI = 0\n    do\n      {b}\n      {a}\n      nI = nI + 1\n    until nI >= 3",
}


@pytest.mark.parametrize("inner", ["for", "while", "do"])
def test_an_inner_loop_of_the_main_loop_is_not_the_cycle(tmp_path, inner):
    """A pocket: from home (j1 = 0) to 10, three strokes 10 -> 20 -> 10, back home. The inner loop
    repeats a 2 x 10-degree stroke; the part's cycle is the main loop: 8 moves of 10 degrees."""
    code = POCKET.replace("INNER", INNER[inner]).format(home=j1(0), a=j1(10), b=j1(20))
    r = run(tmp_path, code, ["mdesc mD", "num nI"])
    st = cycle(r)
    assert (st.kind, st.program, st.marker[1]) == ("while", "start", line_of(r, 4))
    assert st.count >= 2 and st.passes >= st.count + 1
    for t in st.times:
        assert t == pytest.approx(8 * bang(10), abs=1e-9)  # not 2 x bang(10), the inner loop's
    assert "outermost" in st.why


def test_a_loop_in_a_called_program(tmp_path):
    """start() moves home and calls run(), whose `while true` is the cycle."""
    r = run(tmp_path, f"begin\n  mD.blend = off\n  {j1(0)}\n  call run()\nend\n", programs={
        "run": {"code": f"begin\n  while true\n    {j1(30)}\n    {j1(-30)}\n  endWhile\nend\n"}})
    st = cycle(r)
    assert (st.kind, st.program, st.marker[1]) == ("while", "run", line_of(r, 2, "run"))
    assert st.marker[0].endswith("run.pgx")
    assert st.times[0] == pytest.approx(bang(30) + bang(60), abs=1e-9)  # from home, then from -30
    assert all(t == pytest.approx(2 * bang(60), abs=1e-9) for t in st.times[1:])


def test_the_main_loop_calls_programs_that_move_and_loop(tmp_path):
    """The main loop of start() calls pick() (a `for` of two strokes) and place(): the cycle is
    start()'s loop, 6 moves of 20 degrees a pass."""
    pick = f"begin\n  for nI = 1 to 2\n    {j1(20)}\n    {j1(0)}\n  endFor\nend\n"
    place = f"begin\n  {j1(-20)}\n  {j1(0)}\nend\n"
    r = run(tmp_path, f"begin\n  mD.blend = off\n  {j1(0)}\n  do\n    call pick()\n    call place()\n  until false\nend\n",
            ["mdesc mD", "num nI"], programs={"pick": {"code": pick}, "place": {"code": place}})
    st = cycle(r)
    assert (st.kind, st.program, st.marker[1]) == ("do", "start", line_of(r, 4))
    assert st.count >= 2 and all(t == pytest.approx(6 * bang(20), abs=1e-9) for t in st.times)


# ---- no cycle, or not yet --------------------------------------------------------------------------------


def test_no_loop_no_cycle(tmp_path):
    r = run(tmp_path, f"begin\n  mD.blend = off\n  {j1(30)}\n  {j1(0)}\n  {j1(30)}\n  waitEndMove()\nend\n")
    st = cycle(r)
    assert st.marker is None and st.kind is None and st.count == 0 and "outside any loop" in st.why


def test_a_loop_run_once_is_no_cycle_the_loop_inside_it_is(tmp_path):
    """`for nI = 1 to 1` around a `for nJ = 1 to 4` of strokes: the outer loop records motions in
    one pass and the task left it; the strokes repeat: the inner loop is the cycle."""
    r = run(tmp_path, f"""begin
  mD.blend = off
  {j1(0)}
  for nI = 1 to 1
    for nJ = 1 to 4
      {j1(40)}
      {j1(0)}
    endFor
  endFor
  waitEndMove()
end
""", ["mdesc mD", "num nI", "num nJ"])
    st = cycle(r)
    assert (st.kind, st.marker[1]) == ("for", line_of(r, 5)) and st.count == 3 and st.passes == 4
    assert all(t == pytest.approx(2 * bang(40), abs=1e-9) for t in st.times)
    assert "one pass only" in st.why


def test_a_loop_that_never_repeats_its_motions_is_no_cycle(tmp_path):
    r = run(tmp_path, f"begin\n  mD.blend = off\n  for nI = 1 to 1\n    {j1(40)}\n    {j1(0)}\n  endFor\nend\n",
            ["mdesc mD", "num nI"])
    st = cycle(r)
    assert st.marker is None and st.count == 0 and "one pass only" in st.why


def test_the_run_ends_in_the_first_pass_of_the_main_loop(tmp_path):
    """The main loop's first pass is longer than the run: that loop is still the cycle (the task
    is in it), with no complete cycle; its inner loop, which repeated, is not."""
    r = run(tmp_path, f"""begin
  mD.blend = off
  while true
    for nI = 1 to 100
      {j1(10)}
      {j1(0)}
    endFor
  endWhile
end
""", ["mdesc mD", "num nI"], duration=2.0)
    st = cycle(r)
    assert (st.kind, st.marker[1]) == ("while", line_of(r, 3)) and st.count == 0 and st.passes == 1
    assert "first pass" in st.why


# ---- several tasks ---------------------------------------------------------------------------------------


def test_each_task_has_its_cycle_and_the_verdict_quotes_the_one_that_moves(tmp_path, capsys):
    """start() moves home once and creates two tasks: "robot" moves the arm in its loop, "io"
    loops without moving it. Only the tasks that record motions have an entry."""
    folder = build(tmp_path, f"""begin
  mD.blend = off
  {j1(0)}
  waitEndMove()
  taskCreate "robot", 10, cycle()
  taskCreate "io", 10, lights()
end
""", globals_=["mdesc mD", "num nBlink"], programs={
        "cycle": {"code": f"begin\n  while true\n    {j1(45)}\n    {j1(-45)}\n  endWhile\nend\n"},
        "lights": {"code": "begin\n  while true\n    nBlink = nBlink + 1\n    delay(0.1)\n  endWhile\nend\n"}})
    assert main(["sim", str(folder), "--robot", "TX2-60", "--duration", "4", "--report", "json"]) == 0
    data = json.loads(capsys.readouterr().out)
    cycles = {c["task"]: c for c in data["motion"]["cycles"]}
    assert set(cycles) == {"Example~", "robot"}
    assert cycles["Example~"]["loop"] is None and "outside any loop" in cycles["Example~"]["why"]
    robot = cycles["robot"]
    assert (robot["loop"], robot["program"]) == ("while", "cycle") and robot["path"].endswith("cycle.pgx")
    assert robot["times"][1:] and all(t == pytest.approx(2 * bang(90), abs=1e-6) for t in robot["times"][1:])
    # the text report leads with it
    assert main(["sim", str(folder), "--robot", "TX2-60", "--duration", "4"]) == 0
    text = capsys.readouterr().out
    assert f"cycle time of task robot (the while loop at {robot['path']}:{robot['line']})" in text


# ---- --cycles N ------------------------------------------------------------------------------------------


def test_cycles_option_stops_after_n_complete_cycles_and_counts_only_those(tmp_path, capsys):
    """The program records up to 16 commands ahead of the arm (10.2.1): when the arm starts the 4th
    pass the run ends; the passes recorded ahead are not cycles, their motions never started
    (null start in the JSON report)."""
    code = f"begin\n  mD.blend = off\n  {j1(0)}\n  while true\n    {j1(30)}\n    {j1(-30)}\n  endWhile\nend\n"
    r = run(tmp_path / "run", code, duration=60.0, cycles=3)
    st = cycle(r)
    assert r.end_reason == "cycles" and st.count == 3 and len(st.starts) == 4
    assert st.times == pytest.approx([bang(30) + bang(60), 2 * bang(60), 2 * bang(60)], abs=1e-9)
    # the run ends when the arm starts the 4th pass (at the 4 ms cycle of that moment), after the
    # move home from the initial zeros (the slowest of j2, j3 and j5) and the three cycles
    home = max(bang_axis(d, k) for k, d in ((1, 20), (2, 100), (4, 60)))
    assert st.starts[0] == pytest.approx(home, abs=1e-5)  # recorded a few microseconds in
    fourth = st.starts[0] + bang(30) + bang(60) + 4 * bang(60)
    assert st.starts[-1] == pytest.approx(fourth, abs=1e-9)
    assert fourth <= r.sim_time_us / 1e6 <= fourth + 0.004 + 1e-6
    never = [m for m in r.motion.motions if m.start is None]
    assert len(never) >= 4 and all(m.state == "pending" and m.end is None for m in never)
    folder = build(tmp_path / "json", code, globals_=["mdesc mD"])
    assert main(["sim", str(folder), "--robot", "TX2-60", "--cycles", "3", "--report", "json"]) == 0
    data = json.loads(capsys.readouterr().out)
    (cy,) = data["motion"]["cycles"]
    assert cy["cycles"] == 3 and len(cy["starts"]) == 4 and cy["loop"] == "while"
    pending = [m for m in data["motion"]["motions"] if m["state"] == "pending"]
    assert [m["start"] for m in pending].count(None) >= 4
    assert all(m["start"] is None or m["start"] <= data["simulated_duration"] for m in data["motion"]["motions"])


def test_cycles_counts_the_main_loop_not_an_inner_one(tmp_path):
    code = POCKET.replace("INNER", INNER["for"]).format(home=j1(0), a=j1(10), b=j1(20))
    r = run(tmp_path, code, ["mdesc mD", "num nI"], duration=60.0, cycles=2)
    st = cycle(r)
    assert r.end_reason == "cycles" and st.count == 2 and st.marker[1] == line_of(r, 4)
    assert st.times == pytest.approx([8 * bang(10)] * 2, abs=1e-9)
    assert "R006" not in codes(r)


# ---- the rule itself -------------------------------------------------------------------------------------

MAIN = Loop("a.pgx", 4, 3, "start", "while")
WARM = Loop("a.pgx", 2, 3, "start", "for")
INNER_FOR = Loop("a.pgx", 6, 5, "start", "for")


def test_of_two_repeating_loops_the_one_with_the_most_passes_ties_to_the_later():
    t = LoopTracker()
    i = 0
    for k in (1, 2, 3):  # a warm-up of three passes
        t.note((Pass(WARM, 1, k),), i)
        i += 1
    for k in (1, 2):  # the main loop, two passes so far
        t.note((Pass(MAIN, 1, k), Pass(INNER_FOR, k, 1)), i)
        t.note((Pass(MAIN, 1, k), Pass(INNER_FOR, k, 2)), i + 1)
        i += 2
    group, why = t.choose(())
    assert group.loop == WARM and "most passes" in why
    t.note((Pass(MAIN, 1, 3),), i)
    group, _ = t.choose(())
    assert group.loop == MAIN  # three passes each: the later


def test_the_verdict_junit_and_the_batch_summary_quote_the_main_loop(tmp_path, capsys):
    """The issue's symptom: an inner loop's 2 x bang(10) headlined as the cycle time. The HTML
    verdict, the JUnit property and the batch summary all quote the main loop's 8 x bang(10)."""
    import xml.etree.ElementTree as ET

    from val3check.batch.worker import _cycle
    from val3check.config import Settings
    from val3check.reporting.html.from_run import model_from_run
    from val3check.reporting.sim_report import build_report
    from val3check.rules.catalogue import catalogue

    code = POCKET.replace("INNER", INNER["for"]).format(home=j1(0), a=j1(10), b=j1(20))
    r = run(tmp_path / "run", code, ["mdesc mD", "num nI"])
    expected = 8 * bang(10)
    model = model_from_run(build_report(r, Settings(), catalogue(), "test"))
    ct = model["verdict"]["cycle_time"]
    assert ct["seconds"] == pytest.approx(expected, abs=1e-6) and "while loop at line" in ct["basis"]
    seconds, count, spread = _cycle(r.motion)
    assert seconds == pytest.approx(expected, abs=1e-6) and count == cycle(r).count
    assert spread[0] < seconds < spread[1]  # the same loop re-timed (accelerations assumed: issue 23)
    folder = build(tmp_path / "junit", code, globals_=["mdesc mD", "num nI"])
    main(["sim", str(folder), "--robot", "TX2-60", "--duration", "6", "--report", "junit"])
    props = {p.get("name"): p.get("value") for p in ET.fromstring(capsys.readouterr().out).iter("property")}
    assert float(props["cycle_time_s"]) == pytest.approx(expected, abs=1e-6)
