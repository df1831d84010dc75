"""Issue 11 item 5: a library that is not at its Disk:// place is looked for by name in the
repository (git top level, else the folder given), never outside it (rule F016)."""

from __future__ import annotations

from .loadhelp import codes, make_app, write

from support import lint
from val3check.confine import git_top_level
from val3check.loading import load


def _repo(tmp_path):
    (tmp_path / ".git").mkdir(parents=True)
    return tmp_path


def test_unique_application_of_that_name_is_used_and_said(tmp_path):
    repo = _repo(tmp_path)
    app = make_app(repo / "cells" / "App", libraries=[("lib", "Disk://MyLib")])
    lib = make_app(repo / "sub" / "folder" / "MyLib", programs=())
    ws, diags = load([str(app)])
    assert [(d.code, d.path, d.line) for d in diags] == [("F016", str(app), 11)]
    assert "sub/folder/MyLib/MyLib.pjx" in diags[0].message and "'Disk://MyLib'" in diags[0].message
    assert ws.apps[str(app)].libraries["lib"].resolved == str(lib)
    assert str(lib) in ws.apps


def test_found_library_symbols_are_checked(tmp_path):
    repo = _repo(tmp_path)
    app = make_app(repo / "App", libraries=[("lib", "Disk://libs/MyLib/MyLib.pjx")])
    (app.parent / "start.pgx").write_text((app.parent / "start.pgx").read_text().replace(
        "begin\nend", "begin\n  call lib:missing()\nend"))
    make_app(repo / "vendor" / "MyLib", programs=())
    found = lint([app.parent], cwd=repo).result.diagnostics
    assert {d.code for d in found} == {"F016", "L010"}  # checked, as a warning: the library is a guess


def test_several_candidates_are_listed_and_none_is_chosen(tmp_path):
    repo = _repo(tmp_path)
    app = make_app(repo / "App", libraries=[("lib", "Disk://MyLib")])
    make_app(repo / "a" / "MyLib", programs=())
    make_app(repo / "b" / "mylib", name="MyLib", programs=())
    ws, diags = load([str(app)])
    assert [d.code for d in diags] == ["L001"]
    assert "2 applications named MyLib" in diags[0].message
    assert "a/MyLib/MyLib.pjx" in diags[0].message and "b/mylib/MyLib.pjx" in diags[0].message
    assert ws.apps[str(app)].libraries["lib"].resolved is None


def test_user_types_too(tmp_path):
    repo = _repo(tmp_path)
    app = make_app(repo / "App", types=[("Part", "Disk://Part")])
    part = make_app(repo / "types" / "Part", programs=())
    ws, diags = load([str(app)])
    assert [d.code for d in diags] == ["F016"]
    assert ws.apps[str(app)].types["Part"].resolved == str(part)


def test_without_git_the_lint_root_is_searched(tmp_path):
    top = tmp_path / "checkout"
    make_app(top / "App", libraries=[("lib", "Disk://MyLib")])
    make_app(top / "deep" / "MyLib", programs=())
    ws, diags = load([str(top)])  # the lint root holds the library
    assert codes(diags, "F016") and not codes(diags, "L001")
    ws, diags = load([str(top / "App")])  # the lint root is App: the library is outside it
    assert [d.code for d in diags] == ["L001"]


def test_never_outside_the_repository(tmp_path):
    repo = _repo(tmp_path / "repo")
    app = make_app(repo / "App", libraries=[("lib", "Disk://MyLib")])
    make_app(tmp_path / "elsewhere" / "MyLib", programs=())  # beside the repository, not in it
    ws, diags = load([str(app)])
    assert [d.code for d in diags] == ["L001"]


def test_the_io_library_is_not_looked_for(tmp_path):
    repo = _repo(tmp_path)
    app = make_app(repo / "App", libraries=[("io", "Disk://io")])
    make_app(repo / "x" / "io", programs=())
    ws, diags = load([str(app)])
    assert [d.code for d in diags] == ["L003"]


def test_git_top_level_is_a_dot_git_entry(tmp_path):
    deep = tmp_path / "a" / "b"
    deep.mkdir(parents=True)
    assert git_top_level(str(deep)) in (None, *[str(p) for p in tmp_path.parents])
    write(tmp_path / "a" / ".git", "gitdir: /elsewhere/.git/worktrees/a\n")  # a worktree: .git is a file
    assert git_top_level(str(deep)) == str(tmp_path / "a")


def test_the_simulator_loads_the_library_found_in_the_repository(tmp_path):
    from interpretation.simsupport import add_libraries, build, gv, make_library, run_folder

    repo = _repo(tmp_path)
    make_library(repo / "vendor", "LibA", globals_=["num nA"], values={"nA": "41"})
    app = build(repo, "begin\n  nX = la:nA + 1\nend", globals_=["num nX"], name="App")
    add_libraries(app, {"la": "Disk://LibA"}, name="App", autoload="true")
    result = run_folder(app)
    assert gv(result, "nX") == 42
