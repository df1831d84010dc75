"""The tasks' states over time (interpretation/recorder.py TaskStateChange, noted by the scheduler
once per 4 ms cycle): what the HTML report's task timelines and the trace's /tasks show."""

from __future__ import annotations

from val3check.interpretation.recorder import Recorder, task_state_of

from .simsupport import sim


def _states(result, task):
    return [(c.time_us, c.state, c.detail) for c in result.task_states if c.task == task]


def test_delay_wait_mutex_error_and_end(tmp_path):
    r = sim(tmp_path, """begin
  bLock = true
  bGo = false
  taskCreate "sleeper", 10, sleeper()
  taskCreate "waiter", 10, waiter()
  taskCreate "locker", 10, locker()
  delay(1)
  bGo = true
  delay(1)
  bLock = false
end
""", globals_=["bool bLock", "bool bGo", "num nZero"], programs={
        "sleeper": {"code": "begin\n  delay(0.5)\nend\n"},
        "waiter": {"code": "begin\n  wait(bGo == true)\n  nZero = 1 / 0\nend\n"},
        "locker": {"code": "begin\n  setMutex(bLock)\n  putln(\"locked\")\nend\n"},
    }, duration=5)
    sleeper = _states(r, "sleeper")
    assert [s for _, s, _ in sleeper] == ["running", "waiting", "running", "ended"]
    assert sleeper[1] == (4000, "waiting", "delay") and sleeper[2][0] == 500_000
    waiter = _states(r, "waiter")
    assert [s for _, s, _ in waiter] == ["running", "waiting", "running", "stopped"]
    assert waiter[1][2] == "wait(bGo == true)" and waiter[2][0] == 1_000_000  # woken when bGo is set
    assert waiter[3][2] == "error"  # stopped on error 1/0
    locker = _states(r, "locker")
    assert [s for _, s, _ in locker] == ["running", "blocked", "running", "ended"]
    assert locker[1][2] == "setMutex" and locker[2][0] == 2_000_000
    times = [c.time_us for c in r.task_states]
    assert times == sorted(times)


def test_synchronous_task_waits_for_its_period(tmp_path):
    r = sim(tmp_path, """begin
  taskCreateSync "tick", 0.1, bOver, ticker()
  delay(1)
  taskKill("tick")
end
""", globals_=["num nTicks", "bool bOver"], programs={"ticker": {"code": "begin\n  while true\n    nTicks = nTicks + 1\n    delay(0)\n  endWhile\nend\n"}}, duration=3)
    tick = _states(r, "tick")
    runs = [t for t, s, _ in tick if s == "running"]
    assert len(runs) >= 9 and all(b - a == 100_000 for a, b in zip(runs[1:], runs[2:]))  # once per period
    assert {d for _, s, d in tick if s == "waiting"} == {"period"}
    assert tick[-1][1] == "ended"


def test_classification_of_what_a_task_waits_for():
    assert task_state_of("wait", "waitEndMove (end of motion)") == "blocked"
    assert task_state_of("wait", "movel (the motion queue is full)") == "blocked"
    assert task_state_of("wait", "get") == "blocked" and task_state_of("wait", "sio read") == "blocked"
    assert task_state_of("wait", "wait(bTarget == true)") == "waiting"  # not a `get`
    assert task_state_of("delay", "delay") == "waiting"
    assert task_state_of("stopped", "") == "stopped" and task_state_of("held", "") == "stopped"
    assert task_state_of("preempted", "") == "running"


def test_only_changes_are_kept_and_a_later_note_at_the_same_time_wins():
    rec = Recorder(10, 10, lambda *a: None)
    rec.task_state(0, "a", "running")
    rec.task_state(4000, "a", "waiting", "delay")
    rec.task_state(4000, "a", "running")  # it ran again in the next cycle: replaces the note
    rec.task_state(8000, "a", "running")
    rec.task_state(12000, "a", "blocked", "get")
    assert [(c.time_us, c.state) for c in rec.finish_task_states()] == [(0, "running"), (12000, "blocked")]


def test_the_timeline_has_a_budget():
    full = []
    rec = Recorder(10, 1, lambda message, task: full.append(message))
    for k in range(30):
        rec.task_state(k * 4000, "a", "running" if k % 2 else "waiting", "")
    rec.finish_task_states()
    assert len(rec.task_states) == rec.max_task_states == 10
    assert len(full) == 1 and "task timeline is full" in full[0]


def test_states_noted_only_after_a_turn_are_those_noted_every_cycle(tmp_path, monkeypatch):
    """The scheduler notes the task states only after a cycle where a task took a turn or the
    task list changed (a wait's condition, evaluated by the cycle itself, changes no state): the
    timelines are those of noting at every cycle, here with delays, waits on the cell and on
    globals, a watch's timeout, a synchronous task, suspend/resume, kill and an error."""
    code = """begin
  taskCreate "sleeper", 10, sleeper()
  taskCreate "waiter", 10, waiter()
  taskCreateSync "tick", 0.1, bOver, ticker()
  delay(0.3)
  taskSuspend("sleeper")
  delay(0.5)
  bGo = true
  taskResume("sleeper", 0)
  delay(0.6)
  taskKill("tick")
  delay(1)
end
"""
    programs = {
        "sleeper": {"code": "begin\n  while nN < 40\n    nN = nN + 1\n    delay(0.05)\n  endWhile\nend\n"},
        "waiter": {"code": "begin\n  wait(bGo == true)\n  bOk = watch(bNever == true, 0.2)\n  wait(diIn == true)\n"
                           "  nN = 1 / nZero\nend\n"},
        "ticker": {"code": "begin\n  nTicks = nTicks + 1\nend\n"},
    }
    scenario = 'version = 1\n[inputs]\ndiIn = false\n[[events]]\nat = 2.5\nset = { diIn = true }\n'
    globals_ = ["bool bGo", "bool bOk", "bool bNever", "bool bOver", "num nN", "num nTicks", "num nZero",
                "dio diIn"]
    links = {"diIn": "BasicIO-1\\%I0"}
    noted = sim(tmp_path / "a", code, globals_=globals_, programs=programs, scenario=scenario, duration=4, links=links)
    from val3check.interpretation.scheduler import Scheduler

    # every cycle notes (what the scheduler did before): a flag that is always set
    monkeypatch.setattr(Scheduler, "_changed", property(lambda self: True, lambda self, value: None), raising=False)
    every = sim(tmp_path / "b", code, globals_=globals_, programs=programs, scenario=scenario, duration=4, links=links)
    assert len(noted.task_states) > 40
    assert {c.task for c in noted.task_states} >= {"sleeper", "waiter", "tick"}
    assert [(c.time_us, c.task, c.state, c.detail) for c in noted.task_states] == \
        [(c.time_us, c.task, c.state, c.detail) for c in every.task_states]
