"""Libraries loaded at start: a declaration without `autoload` loads the library, and a library
loaded brings the libraries it declares with autoload (as drivers used on controllers expect)."""

from __future__ import annotations

import os
from pathlib import Path

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


def test_a_library_that_cannot_load_is_reported_with_its_own_finding(tmp_path):
    """A library whose program has a syntax error is not loaded (6.6, libLoad code 12): R040
    reports the library's finding at its position, once, and each error 80 says why."""
    make_library(tmp_path, "Part", globals_=["num nValue"], programs={"init": {"code": "begin\n  nValue = (3\nend\n"}})
    folder = build(tmp_path, "begin\n  nGot = part:nValue\n  call part:init()\n  nCode = other:libLoad(\"Part\")\nend\n",
                   globals_=["num nGot", "num nCode"])
    add_libraries(folder, {"part": "Disk://Part"}, autoload="true")
    pjx = folder / "Example.pjx"
    pjx.write_text(pjx.read_text(encoding="utf-8").replace(
        "</Libraries>", '<Library alias="other" path="Disk://Part" autoload="false" /></Libraries>'), encoding="utf-8")
    r = run_folder(folder, tmp_path=tmp_path)
    r040 = [d for d in r.diagnostics if d.code == "R040"]
    assert len(r040) == 1  # once per library, not per identifier nor per use
    (d,) = r040
    assert Path(d.path).name == "init.pgx" and (d.line, d.col) > (0, 0)
    assert "F101" in d.message and "libLoad returns 12" in d.message and d.task == ""
    eighty = [d for d in r.diagnostics if d.code == "R001"]
    assert [d.error for d in eighty] == [80]  # the task stops at the first use
    assert "loading Disk://Part at start returned 12" in eighty[0].message
    assert f"F101 at Part{os.sep}init.pgx:{d.line}:{d.col}" in eighty[0].message


def test_a_library_loaded_later_clears_the_failure(tmp_path):
    make_library(tmp_path, "Bad", globals_=["num nValue"], programs={"init": {"code": "begin\n  nValue = (3\nend\n"}})
    make_library(tmp_path, "Good", globals_=["num nValue"], values={"nValue": "7"})
    folder = build(tmp_path, "begin\n  nA = part:libLoad(\"Bad\")\n  nB = part:libLoad(\"Good\")\n  nGot = part:nValue\nend\n",
                   globals_=["num nA", "num nB", "num nGot"])
    add_libraries(folder, {"part": "Disk://Good"})
    r = run_folder(folder, tmp_path=tmp_path)
    assert [d.code for d in r.diagnostics] == ["R040"]
    assert (gv(r, "nA"), gv(r, "nB"), gv(r, "nGot")) == (12.0, 0.0, 7.0)
