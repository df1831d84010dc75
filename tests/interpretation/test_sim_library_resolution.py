"""One resolution of library paths for lint and sim (loading.libraries.find_library): what lint
finds through its guess by name in the repository (F016) or --disk-root, libLoad and the
autoloaded libraries find too, even on a path no Library entry declares (a driver loading the
interface of its controller: `libInterface:libLoad("ros_libs/UserInterface/interfaceCS8")`)."""

from __future__ import annotations

from val3check.config import Settings
from val3check.lint import run
from val3check.simulation import SimOptions, simulate

from .simsupport import add_libraries, build, errors, gv, make_library

CODE = 'begin\n  nCode = li:libLoad("ros_libs/UI/ifCS8")\n  nV = li:nV\n  nA = auto:nV\nend'


def _libraries(where):
    make_library(where, "ifDefault", globals_=["num nV"], values={"nV": "1"})
    make_library(where, "ifCS8", globals_=["num nV"], values={"nV": "8"})


def _app(root):
    app = build(root / "cells", CODE, globals_=["num nCode", "num nV", "num nA"], name="App")
    add_libraries(app, {"li": "Disk://ros_libs/UI/ifDefault", "auto": "Disk://ros_libs/UI/ifDefault"},
                  name="App", autoload="false")
    pjx = app / "App.pjx"
    pjx.write_text(pjx.read_text(encoding="utf-8").replace(
        '<Library alias="auto" path="Disk://ros_libs/UI/ifDefault" autoload="false" />',
        '<Library alias="auto" path="Disk://ros_libs/UI/ifDefault" autoload="true" />'), encoding="utf-8")
    return app


def _sim(app, disk_roots=()):
    settings = Settings()
    settings.disk_roots = [str(d) for d in disk_roots]
    lr = run([str(app)], settings)
    ws = lr.workspace
    return lr, simulate(ws, ws.apps[ws.targets[0]], SimOptions(duration=1, disk_roots=list(settings.disk_roots)))


def test_libload_finds_what_lint_finds_by_name_in_the_repository(tmp_path):
    (tmp_path / ".git").mkdir()
    _libraries(tmp_path / "vendor" / "driver")  # not where Disk:// leads: found by name (F016)
    lr, r = _sim(_app(tmp_path))
    assert sorted({d.code for d in lr.result.diagnostics}) == ["F016"]
    assert errors(r) == [] and r.end_reason == "ended"
    assert gv(r, "nCode") == 0 and gv(r, "nV") == 8 and gv(r, "nA") == 1  # autoload: the declared one
    guess = [e.text for e in r.transcript if e.kind == "disk"]
    assert len(guess) == 1 and "ros_libs/UI/ifCS8" in guess[0] and "a guess" in guess[0]


def test_libload_finds_what_lint_finds_under_disk_root(tmp_path):
    _libraries(tmp_path / "disk" / "ros_libs" / "UI")
    lr, r = _sim(_app(tmp_path), disk_roots=[tmp_path / "disk"])
    assert not [d for d in lr.result.diagnostics if d.code.startswith(("L", "F"))]
    assert errors(r) == [] and gv(r, "nCode") == 0 and gv(r, "nV") == 8 and gv(r, "nA") == 1
    assert [e for e in r.transcript if e.kind == "disk"] == []  # found where the path leads: no guess


def test_two_applications_of_that_name_are_not_a_guess(tmp_path):
    (tmp_path / ".git").mkdir()
    _libraries(tmp_path / "vendor" / "driver")
    make_library(tmp_path / "old", "ifCS8", globals_=["num nV"])
    _lr, r = _sim(_app(tmp_path))
    assert gv(r, "nCode") == 39  # 6.6: not found


def test_6_2_private_globals_are_the_librarys_own(tmp_path):
    """6.2: "Les programmes et variables globales privés ne peuvent être utilisés que par les
    programmes de la librairie": the library's programs use its private global; the application
    does not see it (isDefined false, libExist false), whichever way the library was found."""
    (tmp_path / ".git").mkdir()
    lib = make_library(tmp_path / "vendor", "Counter", globals_=["private num nHidden", "num nShown"],
                       programs={"bump": {"code": "begin\n  nHidden = nHidden + 1\n  nShown = nHidden * 10\nend"}})
    pjx = lib / "Counter.pjx"
    text = (lib / "bump.pgx").read_text(encoding="utf-8").replace('access="private"', 'access="public"')
    (lib / "bump.pgx").write_text(text, encoding="utf-8")
    assert pjx.exists()
    app = build(tmp_path / "cells", 'begin\n  call ct:bump()\n  call ct:bump()\n  nGot = ct:nShown\n'
                '  bSeen = isDefined(ct:nHidden)\n  bExist = ct:libExist("nHidden")\nend',
                globals_=["num nGot", "bool bSeen", "bool bExist"], name="App")
    add_libraries(app, {"ct": "Disk://Counter"}, name="App", autoload="true")
    _lr, r = _sim(app)
    assert errors(r) == [] and gv(r, "nGot") == 20
    assert gv(r, "bSeen") is False and gv(r, "bExist") is False
