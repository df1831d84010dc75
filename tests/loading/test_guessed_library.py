"""Issue 25 class 1: a library or user type found by name elsewhere in the repository (F016) is a
guess. Every finding that depends on it is at most a warning and says it was found by guessing,
and where; no certain fix is offered from it."""

from __future__ import annotations

from support import lint

from val3check.diagnostics import Severity

from .loadhelp import make_app, pgx, write


def _repo(tmp_path):
    (tmp_path / ".git").mkdir(parents=True)
    return tmp_path


def _fixture_lib(repo):
    """The repository's only io_System.pjx: a test fixture of its tools, with another interface."""
    lib = make_app(repo / "tools" / "tests" / "io_System", programs=("init",),
                   data_body='    <Data name="nOther" access="public" xsi:type="array" type="num" size="1" />\n')
    write(lib.parent / "init.pgx", pgx("init", access="public", extra=(
        '    <Parameters xmlns="http://www.staubli.com/robotics/VAL3/Param/1">\n'
        '      <Parameter name="x_n" type="num" xsi:type="element" />\n'
        "    </Parameters>\n")))
    return lib


def test_findings_from_a_guessed_library_are_warnings_that_say_so(tmp_path):
    repo = _repo(tmp_path)
    _fixture_lib(repo)
    app = make_app(repo / "cells" / "App", libraries=[("sys", "Disk://io_System")])
    write(app.parent / "start.pgx", pgx("start", "begin\n  call sys:reset()\n  call sys:init(1, 2)\n"
                                        "  sys:nCount = 1\n  sys:Nother = 2\nend"))
    found = lint([repo], cwd=repo).result.diagnostics
    mine = [d for d in found if d.path.startswith("cells/")]
    assert {d.code for d in mine} == {"F016", "L010", "T005", "N006"}
    assert all(d.severity <= Severity.WARNING for d in mine)
    for d in mine:
        if d.code != "F016":
            assert "found by guessing" in d.message and "tools/tests/io_System/io_System.pjx" in d.message


def test_no_certain_fix_comes_from_a_guess(tmp_path):
    repo = _repo(tmp_path)
    _fixture_lib(repo)
    app = make_app(repo / "App", libraries=[("sys", "Disk://io_System")])
    write(app.parent / "start.pgx", pgx("start", "begin\n  sys:Nother = 2\nend"))
    run = lint([app.parent], cwd=repo)
    case = [d for d in run.findings if d.code == "N006"]
    assert case and case[0].fix is None


def test_statements_that_do_not_use_the_guess_keep_their_errors(tmp_path):
    repo = _repo(tmp_path)
    _fixture_lib(repo)
    app = make_app(repo / "App", libraries=[("sys", "Disk://io_System")])
    write(app.parent / "start.pgx", pgx("start", "begin\n  if sys:nOther > 0\n    call nowhere()\n  endIf\n"
                                        "  sys:nMissing = 1\nend"))
    found = lint([app.parent], cwd=repo).result.diagnostics
    by_code = {d.code: d for d in found}
    assert by_code["N002"].severity is Severity.ERROR  # call nowhere(): no library involved
    assert by_code["L010"].severity is Severity.WARNING


def test_a_library_at_its_place_keeps_its_errors(tmp_path):
    repo = _repo(tmp_path)
    make_app(repo / "io_System", programs=())
    app = make_app(repo / "App", libraries=[("sys", "Disk://io_System")])
    write(app.parent / "start.pgx", pgx("start", "begin\n  call sys:reset()\nend"))
    found = lint([app.parent], cwd=repo).result.diagnostics
    assert [(d.code, d.severity) for d in found] == [("L010", Severity.ERROR)]


def test_a_guessed_user_type_too(tmp_path):
    repo = _repo(tmp_path)
    make_app(repo / "fixtures" / "Part", programs=(),
             data_body='    <Data name="nId" access="public" xsi:type="array" type="num" size="1" />\n')
    app = make_app(repo / "App", types=[("Part", "Disk://Part")],
                   data_body='    <Data name="uPart" access="public" xsi:type="array" type="Part" size="1" />\n')
    write(app.parent / "start.pgx", pgx("start", "begin\n  uPart.nWeight = 1\nend"))
    found = lint([app.parent], cwd=repo).result.diagnostics
    l013 = [d for d in found if d.code == "L013"]
    assert l013 and l013[0].severity is Severity.WARNING and "user type Part was found by guessing" in l013[0].message
