"""What `paths` may name: projects, folders, trees, controller trees, .pgx files."""

from __future__ import annotations

import os

from .loadhelp import codes, make_app, pgx, pjx, write

from val3check.loading import load


def test_pjx_file_and_app_folder(tmp_path):
    app = make_app(tmp_path / "Cell")
    for target in (app, app.parent):
        ws, diags = load([str(target)])
        assert diags == [] and ws.targets == [str(app)]
        assert ws.apps[str(app)].name == "Cell"


def test_folder_with_a_single_differently_named_pjx(tmp_path):
    app = make_app(tmp_path / "Folder", name="Other")
    ws, diags = load([str(tmp_path / "Folder")])
    assert ws.targets == [str(app)] and ws.apps[str(app)].name == "Other"


def test_many_applications_at_any_depth(tmp_path):
    a = make_app(tmp_path / "repo" / "val3" / "ros_server")
    b = make_app(tmp_path / "repo" / "val3" / "ros_libs" / "Queue")
    c = make_app(tmp_path / "repo" / "cells" / "A" / "deep" / "er" / "Z")
    make_app(tmp_path / "repo" / ".git" / "Hidden")
    make_app(tmp_path / "repo" / "node_modules" / "Nm")
    make_app(tmp_path / "repo" / "venv" / "V")
    write(tmp_path / "repo" / "env2" / "pyvenv.cfg", "home = /usr\n")
    make_app(tmp_path / "repo" / "env2" / "W")
    ws, diags = load([str(tmp_path / "repo")])
    assert diags == []
    assert ws.targets == [str(c), str(b), str(a)]  # sorted walk: cells < val3, ros_libs < ros_server


def test_nested_type_applications_are_found_too(tmp_path):
    lib = make_app(tmp_path / "Lib", types=[("Msg", "./_Msg/Msg.pjx")])
    typ = make_app(tmp_path / "Lib" / "_Msg", name="Msg", programs=())
    ws, diags = load([str(tmp_path / "Lib")])
    assert ws.targets == [str(lib), str(typ)]
    assert ws.apps[str(lib)].types["Msg"].resolved == str(typ)


def test_controller_tree(tmp_path):
    ctrl = tmp_path / "CS8C"
    write(ctrl / "usr" / "configs" / "arm.cfx", '<String name="arm" value="tx60-S1" />\n')
    app = make_app(ctrl / "usr" / "usrapp" / "Cell", libraries=[("lib", "Disk://Tools/Tools.pjx")])
    tools = make_app(ctrl / "usr" / "usrapp" / "Tools")
    ws, diags = load([str(ctrl)])
    assert diags == []
    assert ws.targets == [str(app), str(tools)]
    assert ws.apps[str(app)].libraries["lib"].resolved == str(tools)


def test_missing_path_is_f001(tmp_path):
    missing = tmp_path / "nope" / "App.pjx"
    ws, diags = load([str(missing), str(make_app(tmp_path / "Ok"))])
    assert [(d.code, d.path, d.line) for d in diags] == [("F001", str(missing), 0)]
    assert ws.targets == [str(tmp_path / "Ok" / "Ok.pjx")]


def test_relative_input_paths_become_absolute(tmp_path, monkeypatch):
    make_app(tmp_path / "App")
    monkeypatch.chdir(tmp_path)
    ws, diags = load(["App"])
    assert ws.targets == [str(tmp_path / "App" / "App.pjx")]
    assert all(os.path.isabs(f) for f in ws.apps[ws.targets[0]].files)


def test_folder_without_val3_files_is_f008(tmp_path):
    write(tmp_path / "docs" / "README.md", "# nothing\n")
    write(tmp_path / "docs" / "x" / "data.dtx", "<Database/>\n")
    ws, diags = load([str(tmp_path / "docs")])
    assert [(d.code, d.path, d.line) for d in diags] == [("F008", str(tmp_path / "docs"), 0)]
    assert ws.targets == [] and ws.apps == {}


def test_missing_listed_file_is_reported_on_the_pjx_line(tmp_path):
    folder = tmp_path / "App"
    make_app(folder)
    write(folder / "App.pjx", pjx(["start.pgx", "gone.pgx", "stop.pgx"], ["App.dtx"]))
    os.mkdir(folder / "sub")
    ws, diags = load([str(folder)])
    assert [(d.code, d.path, d.line, d.col) for d in diags] == [
        ("F001", str(folder / "App.pjx"), 6, 5),
        ("F001", str(folder / "App.pjx"), 10, 5),
    ]
    assert "gone.pgx" in diags[0].message and "App.dtx" in diags[1].message
    assert set(ws.apps[str(folder / "App.pjx")].programs) == {"start", "stop"}


def test_listed_files_case_insensitive_and_backslashes(tmp_path):
    folder = tmp_path / "App"
    make_app(folder, programs=())
    write(folder / "Sub" / "Start.pgx", pgx("start"))
    write(folder / "App.pjx", pjx(["sub\\START.PGX"]))
    ws, diags = load([str(folder)])
    assert diags == []
    assert ws.apps[str(folder / "App.pjx")].programs["start"].origin.path == str(folder / "Sub" / "Start.pgx")


def test_pgx_only_folder(tmp_path):
    folder = tmp_path / "loose"
    write(folder / "b.pgx", pgx("b"))
    write(folder / "a.pgx", pgx("a"))
    ws, diags = load([str(folder)])
    assert [(d.code, d.path, d.line) for d in diags] == [("F009", str(folder), 0)]
    assert "global data, libraries and user types are unknown" in diags[0].message
    app = ws.apps[str(folder)]
    assert (app.name, app.layout, app.globals_known, app.path, app.folder) == (
        "loose",
        "pgx-only",
        False,
        str(folder),
        str(folder),
    )
    assert list(app.programs) == ["a", "b"] and app.files == [str(folder / "a.pgx"), str(folder / "b.pgx")]


def test_single_pgx_alone(tmp_path):
    write(tmp_path / "x" / "a.pgx", pgx("a"))
    f = write(tmp_path / "x" / "b.pgx", pgx("b"))
    ws, diags = load([str(f)])
    assert [d.code for d in diags] == ["F009"]
    app = ws.apps[ws.targets[0]]
    assert app.layout == "pgx-only" and list(app.programs) == ["b"]  # only the file asked for


def test_single_pgx_of_an_application_loads_the_application(tmp_path):
    app = make_app(tmp_path / "Cell", data_body="")
    write(tmp_path / "Cell" / "stray.pgx", pgx("stray"))
    ws, diags = load([str(tmp_path / "Cell" / "stop.pgx")])
    assert diags == [] and ws.targets == [str(app)]
    assert set(ws.apps[str(app)].programs) == {"start", "stop"}
    # a .pgx of the folder that the project does not list: loaded alone
    ws, diags = load([str(tmp_path / "Cell" / "stray.pgx")])
    assert [d.code for d in diags] == ["F009"]
    assert ws.apps[ws.targets[0]].layout == "pgx-only"


def test_folder_with_pjx_ignores_unlisted_pgx_but_broken_pjx_falls_back(tmp_path):
    folder = tmp_path / "Cell"
    make_app(folder)
    write(folder / "extra.pgx", pgx("extra"))
    ws, diags = load([str(folder)])
    assert [(d.code, d.path) for d in diags] == [("F012", str(folder / "extra.pgx"))]  # said once, not checked
    assert set(ws.apps[str(folder / "Cell.pjx")].programs) == {"start", "stop"}
    write(folder / "Cell.pjx", "<Project")
    ws, diags = load([str(folder)])
    assert [d.code for d in diags] == ["F004", "F009"]
    assert "could not be read" in diags[1].message
    assert set(ws.apps[str(folder)].programs) == {"extra", "start", "stop"}


def test_directory_symlink_loop(tmp_path):
    app = make_app(tmp_path / "repo" / "App")
    os.symlink(tmp_path / "repo", tmp_path / "repo" / "App" / "loop")
    os.symlink(tmp_path / "repo" / "App", tmp_path / "repo" / "alias")
    os.symlink("self", tmp_path / "repo" / "self")  # a link to itself
    ws, diags = load([str(tmp_path / "repo")])
    assert diags == []
    assert ws.targets == [str(app)]
    # the looping link itself given as a path
    ws, diags = load([str(tmp_path / "repo" / "self")])
    assert [(d.code, d.line) for d in diags] == [("F001", 0)]
    assert "symbolic links" in diags[0].message


def test_symlinked_project_file_loop(tmp_path):
    folder = tmp_path / "App"
    make_app(folder)
    os.remove(folder / "start.pgx")
    os.symlink(folder / "start.pgx", folder / "start.pgx")
    ws, diags = load([str(folder)])
    assert [(d.code, d.path, d.line) for d in diags] == [("F001", str(folder / "App.pjx"), 5)]


def test_directory_named_like_a_file(tmp_path):
    folder = tmp_path / "App"
    make_app(folder)
    os.remove(folder / "stop.pgx")
    os.mkdir(folder / "stop.pgx")
    ws, diags = load([str(folder)])
    assert [(d.code, d.line) for d in diags] == [("F001", 6)]
    assert "folder" in diags[0].message


def test_same_application_named_twice_is_loaded_once(tmp_path):
    app = make_app(tmp_path / "App")
    ws, diags = load([str(app), str(app.parent), str(tmp_path)])
    assert ws.targets == [str(app)] and len(ws.apps) == 1


def test_other_file_names_are_sniffed(tmp_path):
    f = write(tmp_path / "notes.txt", "just text\n")
    ws, diags = load([str(f)])
    assert [d.code for d in diags] == ["F006"] and "not a VAL 3 file" in diags[0].message
    f = write(tmp_path / "page.xml", "<html/>\n")
    ws, diags = load([str(f)])
    assert [d.code for d in diags] == ["F006"]
    f = write(tmp_path / "P" / "prog.xml", pgx("p"))
    ws, diags = load([str(f)])
    assert [d.code for d in diags] == ["F009"] and "p" in ws.apps[ws.targets[0]].programs
    d = write(tmp_path / "D" / "D.dtx", "<Database/>")
    ws, diags = load([str(d)])
    assert [x.code for x in diags] == ["F008"]


def test_deterministic(tmp_path):
    for name in ("b", "a", "c"):
        make_app(tmp_path / name, libraries=[("lib", "Disk://missing")])
    r1 = load([str(tmp_path)])
    r2 = load([str(tmp_path)])
    assert r1[0].targets == r2[0].targets == [str(tmp_path / n / f"{n}.pjx") for n in "abc"]
    assert r1[1] == r2[1]
    assert len(codes(r1[1], "L001")) == 3
