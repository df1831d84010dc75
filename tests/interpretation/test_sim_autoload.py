"""Libraries loaded at start: a declaration without `autoload` loads the library, and a library
loaded brings the libraries it declares with autoload (as drivers used on controllers expect)."""

from __future__ import annotations

from .simsupport import add_libraries, build, errors, gv, make_library, run_folder


def test_library_without_autoload_attribute_is_loaded_with_its_own_libraries(tmp_path):
    make_library(tmp_path, "LibB", globals_=["num nB"], values={"nB": "41"})
    lib_a = make_library(tmp_path, "LibA", globals_=["num nA"],
                         programs={"init": {"code": "begin\n  nA = lb:nB + 1\nend"}})
    add_libraries(lib_a, {"lb": "Disk://LibB/LibB.pjx"}, name="LibA", autoload=None)  # no attribute
    app = build(tmp_path, "begin\n  call la:init()\n  nX = la:nA\nend", globals_=["num nX"], name="App")
    add_libraries(app, {"la": "Disk://LibA/LibA.pjx"}, name="App", autoload="true")
    result = run_folder(app)
    assert errors(result) == []  # no error 80: both libraries were loaded at start
    assert gv(result, "nX") == 42


def test_autoload_false_is_not_loaded(tmp_path):
    make_library(tmp_path, "LibC", globals_=["num nC"])
    app = build(tmp_path, "begin\n  nX = lc:nC\nend", globals_=["num nX"], name="App")
    pjx = app / "App.pjx"
    pjx.write_text(pjx.read_text().replace(
        "<Libraries />", '<Libraries><Library alias="lc" path="Disk://LibC/LibC.pjx" autoload="false" /></Libraries>'))
    assert errors(run_folder(app)) == [80]  # 12.1: a library that is not loaded


def test_tasks_are_destroyed_as_soon_as_stop_stops_on_an_error(tmp_path):
    from .simsupport import sim

    progs = {"spin": {"code": "begin\n  while true\n    delay(0.1)\n  endWhile\nend"},
             "stop": {"code": "begin\n  nX = 1 / nZero\nend"}}
    r = sim(tmp_path, 'begin\n  taskCreate "spin", 10, spin()\n  while true\n    delay(1)\n  endWhile\nend',
            globals_=["num nX", "num nZero"], programs=progs, duration=3)
    ended = {t.name: t.ended for t in r.tasks}  # microseconds
    assert ended["~Example"] == ended["spin"] <= 3_000_100, ended  # not left running up to 2 s more
