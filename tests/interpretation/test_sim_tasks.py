"""Tasks, sequencing, waits, deadlocks and budgets (manual chapter 5)."""

from __future__ import annotations

from .simsupport import codes, errors, out, sim

SYNCHRO = """begin
  n = n + 1
  wait((n==nN) or (bSynch==true))
  bSynch = true
  n = n - 1
  wait((n==0) or (bSynch == false))
  bSynch = false
end
"""


def test_synchronisation_example_5_8(tmp_path):
    # 5.8: three tasks of different speeds meet in synchro() before going on
    worker = """begin
  delay(x_nDelay)
  call synchro(nCount, bSync, 3)
  putln(x_sName)
end
"""
    r = sim(tmp_path, """begin
  nCount = 0
  bSync = false
  taskCreate "fast", 10, worker("fast", 0.1)
  taskCreate "mid", 10, worker("mid", 0.5)
  taskCreate "slow", 10, worker("slow", 2)
end
""", globals_=["num nCount", "bool bSync"], programs={
        "synchro": {"params": ["num& n", "bool& bSynch", "num nN"], "code": SYNCHRO},
        "worker": {"params": ["string x_sName", "num x_nDelay"], "code": worker},
    })
    assert r.end_reason == "ended"
    assert sorted(out(r)) == ["fast", "mid", "slow"]
    times = [t for t, _, kind, _, _ in r.transcript if kind == "putln"]
    assert min(times) >= 2_000_000  # nobody leaves before the slowest arrives
    assert max(times) - min(times) < 50_000


def test_mutex_example_5_9(tmp_path):
    # 5.9: display(c) fills the screen with one character, one task at a time
    display = """begin
  setMutex(bEcran)
  c = c % 10
  for y = 0 to 13
    gotoxy(x, y)
    put(c)
  endFor
  delay(0.2)
  bEcran = false
end
"""
    r = sim(tmp_path, """begin
  bEcran = false
  taskCreate "t1", 10, display(1)
  taskCreate "t2", 10, display(2)
  taskCreate "t3", 10, display(13)
end
""", globals_=["bool bEcran"], programs={"display": {"params": ["num c"], "locals": ["num x", "num y"], "code": display}})
    assert r.end_reason == "ended"
    seq = [(task, text) for _, task, kind, text, _ in r.transcript if kind == "put"]
    # each task writes its 14 characters without another task in between
    assert [t for t, _ in seq] == ["t1"] * 14 + ["t2"] * 14 + ["t3"] * 14
    assert {text for t, text in seq if t == "t3"} == {"3"}


def test_taskcreate_example_wait_taskstatus(tmp_path):
    # 5.10 taskCreate example: wait for the end of t1, then use its result
    r = sim(tmp_path, """begin
  taskCreate "t1", 10, read(sMessage)
  wait(taskStatus("t1") == -1)
  putln(sMessage)
end
""", globals_=["string sMessage"], programs={"read": {"params": ["string& x_s"], "code": "begin\n  delay(1)\n  x_s = \"hello\"\nend\n"}})
    assert out(r) == ["hello"]
    assert r.end_reason == "ended"


def test_start_and_stop_task_names(tmp_path):
    r = sim(tmp_path, "begin\n  putln(\"a\")\nend\n", programs={"stop": {"code": "begin\n  putln(\"b\")\nend\n"}})
    assert [(task, text) for _, task, kind, text, _ in r.transcript] == [("Example~", "a"), ("~Example", "b")]


def test_priority_is_lines_per_turn(tmp_path):
    loop = "begin\n  while true\n    nC[x_i] = nC[x_i] + 1\n  endWhile\nend\n"
    r = sim(tmp_path, """begin
  taskCreate "a", 1, count(0)
  taskCreate "b", 5, count(1)
end
""", globals_=["num nC[2]"], programs={"count": {"params": ["num x_i"], "code": loop}}, duration=0.5)
    a = next(t for t in r.tasks if t.name == "a").lines
    b = next(t for t in r.tasks if t.name == "b").lines
    assert 4.5 < b / a < 5.5
    assert r.end_reason == "duration"


def test_busy_loop_ends_at_duration(tmp_path):
    r = sim(tmp_path, "begin\n  while true\n  endWhile\nend\n", duration=2)
    assert r.end_reason == "duration"
    assert r.sim_time_us == 2_000_000
    assert "R007" in codes(r)


def test_delay_and_clock(tmp_path):
    r = sim(tmp_path, """begin
  nT = clock()
  delay(1.5)
  putln(roundDown((clock() - nT) * 10))
  nT = clock()
  while clock() - nT < 0.5
  endWhile
  putln(roundDown((clock() - nT) * 10))
end
""", globals_=["num nT"])
    assert out(r) == ["15", "5"]


def test_watch_timeout_and_condition(tmp_path):
    r = sim(tmp_path, """begin
  if watch(diSignal==true, 2) == false
    putln("timeout")
  endIf
  if watch(diSignal==true, 20) == true
    putln("signal")
  endIf
  putln(roundDown(clock()))
end
""", globals_=["dio diSignal"], scenario="[[events]]\nat = 5\nset = { diSignal = true }\n",
        links={"diSignal": "BasicIO-1\\%I0"})
    assert out(r) == ["timeout", "signal", "5"]


def test_deadlock_reports_each_blocked_task(tmp_path):
    r = sim(tmp_path, """begin
  taskCreate "t1", 10, waiter()
  wait(bGo)
end
""", globals_=["bool bGo"], programs={"waiter": {"code": "begin\n  wait(bGo)\nend\n"}})
    assert r.end_reason == "deadlock"
    dl = [d for d in r.diagnostics if d.code == "R003"]
    assert sorted(d.task for d in dl) == ["Example~", "t1"]
    assert all("wait" in d.message for d in dl)
    assert r.sim_time_us < 100_000


def test_a_wait_for_an_input_nothing_sets_is_r009_not_a_deadlock_error(tmp_path):
    r = sim(tmp_path, "begin\n  wait(diPart == true)\nend\n", globals_=["dio diPart"],
            links={"diPart": "BasicIO-1\\%I0"})
    assert r.end_reason == "deadlock" and [d.code for d in r.diagnostics] == ["R009"]
    d = r.diagnostics[0]
    assert "wait(diPart == true)" in open(d.path, encoding="utf-8").read().split("\n")[d.line - 1]
    assert "diPart" in d.message and d.severity is None  # the rule's severity (warning) is set by the report
    assert r.end_message.startswith("every task waits for the cell (inputs, serial or socket peers")
    # a task that also waits for a variable nobody sets: a deadlock of the program (R003)
    r = sim(tmp_path / "both", """begin
  taskCreate "t1", 10, waiter()
  wait(diPart == true)
end
""", globals_=["dio diPart", "bool bGo"], links={"diPart": "BasicIO-1\\%I0"},
            programs={"waiter": {"code": "begin\n  wait(bGo)\nend\n"}})
    assert sorted(d.code for d in r.diagnostics) == ["R003", "R009"]
    assert r.end_message.startswith("deadlock:")


def test_unknown_task_and_duplicate(tmp_path):
    r = sim(tmp_path, "begin\n  taskSuspend(\"nobody\")\nend\n")
    assert errors(r) == [30]
    r = sim(tmp_path / "dup", """begin
  taskCreate "t1", 10, idle()
  taskCreate "t1", 10, idle()
end
""", programs={"idle": {"code": "begin\n  delay(1)\nend\n"}})
    assert errors(r) == [31]
    r = sim(tmp_path / "prio", "begin\n  taskCreate \"t1\", 0, idle()\nend\n", programs={"idle": {"code": "begin\nend\n"}})
    assert errors(r) == [70]


def test_suspend_resume_kill_status(tmp_path):
    r = sim(tmp_path, """begin
  taskCreate "t1", 10, ticker()
  delay(0.1)
  taskSuspend("t1")
  putln(taskStatus("t1"))
  nSeen = nTicks
  delay(0.5)
  if nTicks == nSeen
    putln("frozen")
  endIf
  taskResume("t1", 0)
  putln(taskStatus("t1"))
  delay(0.1)
  taskKill("t1")
  putln(taskStatus("t1"))
end
""", globals_=["num nTicks", "num nSeen"], programs={"ticker": {"code": "begin\n  while true\n    nTicks = nTicks + 1\n    delay(0.01)\n  endWhile\nend\n"}})
    assert out(r) == ["0", "frozen", "1", "-1"]
    assert r.end_reason == "ended"


def test_error_then_taskresume(tmp_path):
    # 5.2: a task stopped on an error can be resumed on the same line once fixed
    r = sim(tmp_path, """begin
  taskCreate "calc", 10, calc()
  delay(0.1)
  putln(taskStatus("calc"))
  nDiv = 2
  taskResume("calc", 0)
  delay(0.1)
  putln(nRes)
end
""", globals_=["num nDiv", "num nRes"], programs={"calc": {"code": "begin\n  nRes = 10 / nDiv\nend\n"}})
    assert out(r) == ["10", "5"]
    assert errors(r) == [10]


def test_deep_recursion_is_error_41(tmp_path):
    r = sim(tmp_path, "begin\n  call rec(0)\nend\n",
            programs={"rec": {"params": ["num x_n"], "code": "begin\n  call rec(x_n + 1)\nend\n"}})
    assert errors(r) == [41]
    assert r.end_reason == "stalled"


def test_reentrant_locals(tmp_path):
    # 2.2.2: each call has its own locals
    r = sim(tmp_path, "begin\n  call fact(5, nR)\n  putln(nR)\nend\n", globals_=["num nR"], programs={"fact": {
        "params": ["num x_n", "num& x_r"], "locals": ["num l_sub"],
        "code": "begin\n  if x_n <= 1\n    x_r = 1\n  else\n    call fact(x_n - 1, l_sub)\n    x_r = x_n * l_sub\n  endIf\nend\n"}})
    assert out(r) == ["120"]


def test_sync_task_runs_each_period(tmp_path):
    r = sim(tmp_path, """begin
  taskCreateSync "sup", 0.02, bOver, tick()
  delay(1)
  putln(nTicks)
  taskKill("sup")
end
""", globals_=["num nTicks", "bool bOver"], programs={"tick": {"code": "begin\n  while true\n    nTicks = nTicks + 1\n    delay(0)\n  endWhile\nend\n"}})
    assert out(r) in (["50"], ["49"], ["51"])


def test_sync_period_below_the_4ms_cycle_runs_once_per_cycle(tmp_path):
    """5.10 taskCreateSync: "Le système accepte toutes les durées positives": 0.002 s is not
    refused (no error 70); nothing runs more often than the 4 ms cycle, so the task runs once
    per cycle, as with 0.004 s. A period that is not positive is an invalid parameter (70)."""
    code = """begin
  taskCreateSync "fast", {period}, bOver, tick()
  delay(0.2)
  taskKill("fast")
  putln(nTicks)
end
"""
    progs = {"tick": {"code": "begin\n  while true\n    nTicks = nTicks + 1\n    delay(0)\n  endWhile\nend\n"}}
    fast = sim(tmp_path / "a", code.format(period="0.002"), globals_=["num nTicks", "bool bOver"], programs=progs)
    cycle = sim(tmp_path / "b", code.format(period="0.004"), globals_=["num nTicks", "bool bOver"], programs=progs)
    assert errors(fast) == [] and out(fast) == out(cycle)
    assert int(out(fast)[0]) in (49, 50, 51)  # 0.2 s / 4 ms
    zero = sim(tmp_path / "c", code.format(period="0"), globals_=["num nTicks", "bool bOver"], programs=progs)
    assert errors(zero) == [70]


def test_two_sync_periods_only(tmp_path):
    r = sim(tmp_path, """begin
  taskCreateSync "a", 0.004, bOver, tick()
  taskCreateSync "b", 0.008, bOver, tick()
  taskCreateSync "c", 0.012, bOver, tick()
end
""", globals_=["bool bOver"], programs={"tick": {"code": "begin\n  delay(0)\nend\n"}})
    assert 32 in errors(r)


def test_help_of_a_task_error(tmp_path):
    # 5.10 help example: show the error of task "robot"
    r = sim(tmp_path, """begin
  taskCreate "robot", 10, bad()
  delay(0.1)
  nCodeErreur = taskStatus("robot")
  if (nCodeErreur > 1)
    gotoxy(0,12)
    put(help(nCodeErreur))
  endif
end
""", globals_=["num nCodeErreur"], programs={"bad": {"code": "begin\n  nCodeErreur = 1 / 0\nend\n"}},
        check_lint=False)
    assert out(r) == ["invalid numeric computation (division by zero)"]


def test_library_not_loaded_is_error_80(tmp_path):
    from .simsupport import build

    folder = build(tmp_path, "begin\n  call lib:init()\nend\n")
    text = (folder / "Example.pjx").read_text().replace("<Libraries />", '<Libraries><Library alias="lib" path="Disk://Nowhere" /></Libraries>')
    (folder / "Example.pjx").write_text(text)
    from val3check.config import Settings
    from val3check.simulation import SimOptions, simulate
    from val3check.lint import run

    lr = run([str(folder)], Settings())
    res = simulate(lr.workspace, lr.workspace.apps[lr.workspace.targets[0]], SimOptions(duration=1))
    assert errors(res) == [80]


def test_blocking_call_in_wait_condition_is_not_simulated(tmp_path):
    r = sim(tmp_path, "begin\n  wait(get() == 270)\nend\n", check_lint=False)
    assert "R004" in codes(r)


def test_stop_that_never_ends_is_r006_at_the_duration(tmp_path, capsys):
    """The application ends, its stop() runs and never ends: the run reaches --duration
    (documented reason "duration", R007) and R006 says stop() did not end, at its line (was the
    undocumented reason "stop-timeout", without diagnostic)."""
    from val3check.cli import main

    from .simsupport import build

    stop = {"stop": {"code": "begin\n  while true\n    delay(1)\n  endWhile\nend\n"}}
    r = sim(tmp_path, "begin\n  putln(\"start\")\nend\n", programs=stop, duration=5)
    assert (r.end_reason, r.sim_time_us) == ("duration", 5_000_000)
    assert [(d.code, d.message, d.task, d.program) for d in r.diagnostics] == [
        ("R006", "stop() did not end: still running at --duration 5 s", "~Example", "stop"),
        ("R007", "run stopped at --duration 5 s; tasks still alive: ~Example", "", "")]
    assert r.diagnostics[0].line > 0
    folder = build(tmp_path / "cli", "begin\nend\n", programs=stop)
    assert main(["sim", str(folder), "--duration", "3", "--report", "json"]) == 0
    assert '"reason": "duration"' in capsys.readouterr().out
    assert main(["sim", str(folder), "--duration", "3", "--fail-on", "warning"]) == 1


def test_a_task_created_in_a_round_takes_its_turn_in_that_round(tmp_path):
    """5.4: tasks take turns in creation order, and delay(0) hands over to the next task at
    once: the tasks the creator just made run before its next line (they used to wait for the
    next round, after the creator)."""
    r = sim(tmp_path, "begin\n  taskCreate \"t2\", 10, say(\"b\")\n  taskCreate \"t3\", 10, say(\"c\")\n  delay(0)\n"
                      "  putln(\"a\")\nend\n",
            programs={"say": {"params": ["string x_s"], "code": "begin\n  putln(x_s)\nend\n"}})
    assert [(e.task, e.text) for e in r.transcript] == [("t2", "b"), ("t3", "c"), ("Example~", "a")]
    assert all(e.time_us < 4000 for e in r.transcript)  # one cycle


def test_a_new_task_runs_after_the_tasks_created_before_it(tmp_path):
    # t1 exists before start() creates t2: in the round, t1's turn comes first, then t2's
    r = sim(tmp_path, "begin\n  taskCreate \"t1\", 1, count(\"1\")\n  delay(0)\n  taskCreate \"t2\", 1, count(\"2\")\n"
                      "  delay(0)\nend\n",
            programs={"count": {"params": ["string x_s"], "code": "begin\n  putln(x_s)\n  putln(x_s)\nend\n"}})
    assert [(e.task, e.text) for e in r.transcript] == [("t1", "1"), ("t1", "1"), ("t2", "2"), ("t2", "2")]
