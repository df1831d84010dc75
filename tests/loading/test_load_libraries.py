"""Library and user-type resolution (manual chapters 6 and 7), cycles."""

from __future__ import annotations

from .loadhelp import codes, make_app, pjx, write

from val3check.loading import LoadOptions, load


def test_disk_root_is_the_parent_of_the_application_folder(tmp_path):
    app = make_app(tmp_path / "val3" / "ros_server", libraries=[("q", "Disk://ros_libs/Queue/Queue.pjx")])
    queue = make_app(tmp_path / "val3" / "ros_libs" / "Queue")
    ws, diags = load([str(app)])
    assert diags == []
    assert ws.targets == [str(app)]  # the library is loaded but is not a target
    assert list(ws.apps) == [str(app), str(queue)]
    lib = ws.library(ws.apps[str(app)], "q")
    assert lib is not None and lib.name == "Queue"
    assert ws.apps[str(app)].libraries["q"].resolved == str(queue)


def test_disk_root_option(tmp_path):
    app = make_app(tmp_path / "repo" / "App", libraries=[("lib", "Disk://shared/Lib/Lib.pjx")])
    lib = make_app(tmp_path / "elsewhere" / "shared" / "Lib")
    ws, diags = load([str(app)])
    assert [(d.code, d.path, d.line, d.col) for d in diags] == [("L001", str(app), 11, 5)]
    assert "Disk://shared/Lib/Lib.pjx" in diags[0].message
    assert ws.apps[str(app)].libraries["lib"].resolved is None
    ws, diags = load([str(app)], LoadOptions(disk_roots=[str(tmp_path / "nothing"), str(tmp_path / "elsewhere")]))
    assert diags == []
    assert ws.apps[str(app)].libraries["lib"].resolved == str(lib)


def test_default_location_wins_over_disk_root(tmp_path):
    app = make_app(tmp_path / "repo" / "App", libraries=[("lib", "Disk://Lib")])
    near = make_app(tmp_path / "repo" / "Lib")
    make_app(tmp_path / "other" / "Lib")
    ws, diags = load([str(app)], LoadOptions(disk_roots=[str(tmp_path / "other")]))
    assert ws.apps[str(app)].libraries["lib"].resolved == str(near)


def test_controller_usrapp_for_nested_applications(tmp_path):
    usrapp = tmp_path / "ctrl" / "usr" / "usrapp"
    app = make_app(usrapp / "cells" / "Cell", libraries=[("t", "Disk://Tools")])
    tools = make_app(usrapp / "Tools")
    ws, diags = load([str(app)])
    assert diags == []
    assert ws.apps[str(app)].libraries["t"].resolved == str(tools)


def test_folder_paths_relative_paths_and_backslashes(tmp_path):
    app = make_app(
        tmp_path / "val3" / "App",
        libraries=[
            ("a", "Disk://libs/A"),  # a folder: <dir>/<dir>.pjx
            ("b", "./sub/B.pjx"),
            ("c", "../libs/C/C.pjx"),
            ("d", "D.pjx"),  # bare name: the project folder
            ("e", "Disk:\\\\libs\\E\\E.pjx"),
            ("f", "libs/F"),  # bare path: not beside the project, so Disk://libs/F
        ],
    )
    a = make_app(tmp_path / "val3" / "libs" / "A")
    b = make_app(tmp_path / "val3" / "App" / "sub", name="B")
    c = make_app(tmp_path / "val3" / "libs" / "C")
    d = make_app(tmp_path / "val3" / "App", name="D", programs=())
    e = make_app(tmp_path / "val3" / "libs" / "E")
    f = make_app(tmp_path / "val3" / "libs" / "F")
    ws, diags = load([str(app)])
    assert diags == []
    got = {k: r.resolved for k, r in ws.apps[str(app)].libraries.items()}
    assert got == {"a": str(a), "b": str(b), "c": str(c), "d": str(d), "e": str(e), "f": str(f)}


def test_case_insensitive_resolution(tmp_path):
    app = make_app(
        tmp_path / "repo" / "App",
        libraries=[("lib", "Disk://ROS_LIBS/queue/QUEUE.PJX")],
        types=[("Part", "disk://types/part")],
    )
    queue = make_app(tmp_path / "repo" / "ros_libs" / "Queue")
    part = make_app(tmp_path / "repo" / "Types" / "Part", programs=())
    ws, diags = load([str(app)])
    assert diags == []
    assert ws.apps[str(app)].libraries["lib"].resolved == str(queue)
    assert ws.apps[str(app)].types["Part"].resolved == str(part)
    assert ws.user_type(ws.apps[str(app)], "Part").name == "Part"


def test_missing_library_and_type_and_io(tmp_path):
    app = make_app(
        tmp_path / "App",
        libraries=[("io", "Disk://io"), ("lib", "Disk://nowhere/lib.pjx")],
        types=[("Part", "./types/Part.pjx")],
    )
    ws, diags = load([str(app)])
    got = [(d.code, d.line) for d in diags]
    assert got == [("L003", 11), ("L001", 12), ("L002", 15)]
    assert "controller's own I/O library" in diags[0].message and "io: symbols are not checked" in diags[0].message
    assert "lib: symbols are not checked" in diags[1].message
    assert "relative to the project folder" in diags[2].message


def test_io_library_found_in_the_tree_is_loaded(tmp_path):
    app = make_app(tmp_path / "App", libraries=[("io", "Disk://io")])
    io = make_app(tmp_path / "io")
    ws, diags = load([str(app)])
    assert diags == [] and ws.apps[str(app)].libraries["io"].resolved == str(io)


def test_libraries_of_libraries_are_loaded_once(tmp_path):
    app = make_app(tmp_path / "App", libraries=[("a", "Disk://A"), ("b", "Disk://B")])
    a = make_app(tmp_path / "A", libraries=[("c", "Disk://C")])
    b = make_app(tmp_path / "B", libraries=[("c", "Disk://C"), ("c2", "../C/C.pjx")])
    c = make_app(tmp_path / "C", libraries=[("x", "Disk://X")])
    ws, diags = load([str(app)])
    assert list(ws.apps) == [str(app), str(a), str(b), str(c)]
    assert [(d.code, d.path) for d in diags] == [("L001", str(c))]  # once, where C declares it


def test_broken_library_is_reported_in_its_own_file(tmp_path):
    app = make_app(tmp_path / "App", libraries=[("lib", "Disk://Lib")])
    lib = write(tmp_path / "Lib" / "Lib.pjx", "<Project><oops></Project>")
    ws, diags = load([str(app)])
    assert [(d.code, d.path) for d in diags] == [("F004", str(lib))]
    ref = ws.apps[str(app)].libraries["lib"]
    assert ref.resolved == str(lib) and ws.library(ws.apps[str(app)], "lib") is None


def test_circular_libraries(tmp_path):
    a = make_app(tmp_path / "A", libraries=[("b", "Disk://B")])
    b = make_app(tmp_path / "B", libraries=[("c", "Disk://C"), ("z", "Disk://Z")])
    c = make_app(tmp_path / "C", libraries=[("a", "Disk://A")])
    make_app(tmp_path / "Z")
    ws, diags = load([str(a)])
    l004 = codes(diags, "L004")
    assert [(d.path, d.line) for d in l004] == [(str(a), 11), (str(b), 11), (str(c), 11)]
    assert "A -> B -> C -> A" in l004[0].message
    assert "B -> C -> A -> B" in l004[1].message
    assert "manual 6.6" in l004[0].message
    assert len(diags) == 3
    # the same cycle seen from another target is still reported once per declaration
    ws, diags = load([str(a), str(c), str(tmp_path)])
    assert len(codes(diags, "L004")) == 3


def test_self_referencing_library(tmp_path):
    a = make_app(tmp_path / "A", libraries=[("me", "./A.pjx")])
    ws, diags = load([str(a)])
    assert [(d.code, d.line) for d in diags] == [("L004", 11)]
    assert "A -> A" in diags[0].message


def test_circular_user_types(tmp_path):
    app = make_app(tmp_path / "App", types=[("Part", "Disk://Part")])
    part = make_app(
        tmp_path / "Part",
        programs=(),
        types=[("Box", "Disk://Box")],
        data_body='    <Data name="box" access="public" xsi:type="array" type="Box" size="1" />\n',
    )
    box = make_app(
        tmp_path / "Box",
        programs=(),
        types=[("Part", "Disk://Part")],
        data_body='    <Data name="part" access="public" xsi:type="array" type="Part" size="1" />\n',
    )
    ws, diags = load([str(app)])
    l005 = codes(diags, "L005")
    assert [(d.path, d.line) for d in l005] == [(str(part), 12), (str(box), 12)]
    assert "Part -> Box -> Part" in l005[0].message
    assert codes(diags, "L004") == []


def test_pgx_only_applications_have_no_libraries(tmp_path):
    write(tmp_path / "loose" / "a.pgx", "<Programs xmlns='http://www.staubli.com/robotics/VAL3/Program/2'/>")
    ws, diags = load([str(tmp_path / "loose")])
    assert [d.code for d in diags] == ["F009"]


def test_s6_alias_with_path(tmp_path):
    folder = tmp_path / "App"
    make_app(folder, programs=())
    text = pjx([]).replace("<Libraries>", '<Libraries>\n    <Library alias="x" path="" />')
    write(folder / "App.pjx", text)
    ws, diags = load([str(folder)])
    assert [(d.code, d.line) for d in diags] == [("F007", 9)]
    s6 = """<?xml version="1.0" encoding="utf-8" ?>
<project xmlns="ProjectNameSpace" >
  <parameters version="s6.4.2" stackSize="5000" millimeterUnit="true" />
  <programSection />
  <dataSection />
  <aliasSection>
    <alias name="io" interface="io" autoload="true" password="" />
    <alias name="prog" interface="prog" autoload="true" password="" path="./Lib/Lib.pjx" />
    <alias name="tooldata" interface="tooldata" autoload="false" password="" />
  </aliasSection>
</project>
"""
    write(folder / "App.pjx", s6)
    lib = make_app(folder / "Lib")
    tooldata = make_app(tmp_path / "tooldata")
    ws, diags = load([str(folder / "App.pjx")])
    assert [(d.code, d.line) for d in diags] == [("L003", 7)]
    libs = ws.apps[str(folder / "App.pjx")].libraries
    assert (libs["prog"].resolved, libs["prog"].autoload) == (str(lib), True)
    assert (libs["tooldata"].resolved, libs["tooldata"].autoload) == (str(tooldata), False)
