"""Waits only the cell can end are not deadlocks (interpretation/deadlock.py): a task waiting for
a serial or socket peer, an operator's key or the controller's state that nothing in the run
plays gets R009 (a warning naming the scenario entry that would end it), as a wait on an input
does; a true deadlock (tasks waiting on each other, on variables nothing can change) stays R003."""

from __future__ import annotations

from .simsupport import gv, sim


def _codes(r):
    return sorted((d.task, d.code) for d in r.diagnostics if d.code in ("R003", "R009"))


def _msg(r, task):
    (d,) = [d for d in r.diagnostics if d.task == task and d.code in ("R003", "R009")]
    return d.message


READER = {"reader": {"code": "begin\n  nN = sioGet(siIn, nBuf)\n  bGot = true\nend\n"}}
SOCKET = {"siIn": "Socket\\In"}


def test_sioget_on_a_socket_nobody_feeds_is_r009_naming_the_serial_entry(tmp_path):
    r = sim(tmp_path, 'begin\n  taskCreate "reader", 10, reader()\nend', globals_=["sio siIn", "num nBuf", "num nN",
            "bool bGot"], programs=READER, links=SOCKET, duration=2)
    assert r.end_reason == "deadlock" and _codes(r) == [("reader", "R009")]
    assert '[[serial]]' in _msg(r, "reader") and 'sio = "siIn"' in _msg(r, "reader")
    assert r.end_message.startswith("every task waits for the cell")
    # the entry it names ends the wait
    fed = sim(tmp_path / "fed", 'begin\n  taskCreate "reader", 10, reader()\nend',
              globals_=["sio siIn", "num nBuf", "num nN", "bool bGot"], programs=READER, links=SOCKET, duration=2,
              scenario='[[serial]]\nsio = "siIn"\nat = 0.5\nbytes = [7]\n')
    assert fed.end_reason == "ended" and gv(fed, "nN") == 1 and gv(fed, "bGot") is True


def test_a_string_read_on_a_serial_line_is_r009(tmp_path):
    r = sim(tmp_path, "begin\n  sText = siLine\nend", globals_=["sio siLine", "string sText"],
            links={"siLine": "Serial0"})
    assert _codes(r) == [("Example~", "R009")] and "siLine" in _msg(r, "Example~")


def test_get_waiting_for_a_key_is_r009_naming_keys(tmp_path):
    r = sim(tmp_path, "begin\n  nKey = get()\nend", globals_=["num nKey"])
    assert _codes(r) == [("Example~", "R009")] and "[[keys]]" in _msg(r, "Example~")
    pressed = sim(tmp_path / "k", "begin\n  nKey = get()\nend", globals_=["num nKey"],
                  scenario="[[keys]]\nat = 1\nkey = 271\n")
    assert pressed.end_reason == "ended" and gv(pressed, "nKey") == 271


def test_a_wait_on_keys_or_on_the_controller_state_is_r009(tmp_path):
    progs = {"keys": {"code": "begin\n  wait(getKey() == 271)\nend\n"},
             "speed": {"code": "begin\n  wait(getMonitorSpeed() < 50)\nend\n"},
             "estop": {"code": "begin\n  wait(esStatus() == 2)\nend\n"}}
    code = 'begin\n  taskCreate "keys", 10, keys()\n  taskCreate "speed", 10, speed()\n  taskCreate "estop", 10, estop()\nend'
    r = sim(tmp_path, code, programs=progs)
    assert _codes(r) == [("estop", "R009"), ("keys", "R009"), ("speed", "R009")]
    assert "[[keys]]" in _msg(r, "keys")
    assert "monitor_speed" in _msg(r, "speed") and "[controller]" in _msg(r, "speed")
    assert "es_status" in _msg(r, "estop")
    played = sim(tmp_path / "p", code, programs=progs, scenario=(
        "[[keys]]\nat = 0.5\nkey = 271\n\n[controller]\nchanges = [ { at = 1.0, monitor_speed = 20 },"
        " { at = 1.5, es_status = 2 } ]\n"))
    assert played.end_reason == "ended" and _codes(played) == []


def test_a_task_waiting_for_what_a_cell_waiter_would_write_is_r009_else_r003(tmp_path):
    progs = dict(READER, user={"code": "begin\n  wait(bGot)\nend\n"}, stuck={"code": "begin\n  wait(bNever)\nend\n"})
    r = sim(tmp_path, 'begin\n  taskCreate "reader", 10, reader()\n  taskCreate "user", 10, user()\n'
            '  taskCreate "stuck", 10, stuck()\nend',
            globals_=["sio siIn", "num nBuf", "num nN", "bool bGot", "bool bNever"], programs=progs, links=SOCKET)
    # reader may set bGot once its peer answers; nothing can ever set bNever: a true deadlock
    assert _codes(r) == [("reader", "R009"), ("stuck", "R003"), ("user", "R009")]
    assert "reader" in _msg(r, "user")


def test_tasks_waiting_on_each_other_stay_a_deadlock(tmp_path):
    progs = {"a": {"code": "begin\n  wait(bB)\n  bA = true\nend\n"}, "b": {"code": "begin\n  wait(bA)\n  bB = true\nend\n"}}
    r = sim(tmp_path, 'begin\n  taskCreate "a", 10, a()\n  taskCreate "b", 10, b()\nend', globals_=["bool bA", "bool bB"],
            programs=progs)
    assert _codes(r) == [("a", "R003"), ("b", "R003")]


def test_a_wait_only_a_web_user_page_can_end_is_r009(tmp_path):
    """A CS9 web user page calls the application's programs (its bindings' callbacks): the
    operator's click ends the wait, which the simulation cannot play (Stäubli's safeCalibration
    template waits so for its "finished" button)."""
    progs = {"actDone": {"code": "begin\n  bDone = true\nend\n"}}
    r = sim(tmp_path, "begin\n  wait(bDone)\nend", globals_=["bool bDone"], programs=progs)
    assert _codes(r) == [("Example~", "R003")]  # no page: nothing calls actDone
    from .simsupport import build, run_folder

    folder = build(tmp_path / "web", "begin\n  wait(bDone)\nend", globals_=["bool bDone"], programs=progs)
    (folder / "interface").mkdir()
    (folder / "interface" / "main.bindings.json").write_text(
        '{"version": "1.0", "bindings": [], "callbacks": [{"id": "btn", "event": "click", "data": "actDone"}]}',
        encoding="utf-8")
    r = run_folder(folder)
    assert _codes(r) == [("Example~", "R009")] and "web user page" in _msg(r, "Example~")
