"""The cell file (docs/cell.md): what it holds, and every mistake reported at its line and column."""

from __future__ import annotations

import os
import random

import numpy as np
import pytest

from .helpers import write_cell

from val3check.collision import CELL_FILE_NAME, CellError, find_cell, read_cell  # noqa: E402
from val3check.collision import meshes  # noqa: E402
from val3check.tomlpos import positions  # noqa: E402

trimesh = pytest.importorskip("trimesh")

GOOD = """\
version = 1
description = "station 2"
margin_mm = 8
touch_mm = 0.1

[[obstacle]]
name = "table"
shape = "box"
size = [800, 1200, 40]
at = { x = 500, z = -220 }

[[obstacle]]
name = "post"
shape = "cylinder"
radius = 40
length = 1500
frame = "fPallet[2]"
at = [10, 20, 30, 90, 0, 0]

[[obstacle]]
name = "lamp"
shape = "sphere"
radius = 30

[[tool]]
name = "body"
shape = "cylinder"
radius = 45
length = 100
at = { z = 50 }

[[tool]]
name = "jaw"
tool = "tGripper"
shape = "box"
size = [15, 30, 50]
touch_links = ["link_6"]

[[part]]
name = "brick"
tool = "tGripper"
shape = "box"
size = [40, 40, 40]
"""


def test_a_good_file(tmp_path):
    cell = read_cell(write_cell(tmp_path, GOOD))
    assert cell.description == "station 2" and cell.margin_mm == 8 and cell.touch_mm == 0.1
    assert [o.name for o in cell.obstacles] == ["table", "post", "lamp"]
    table, post, lamp = cell.obstacles
    assert table.shape.kind == "box" and table.shape.size == (800, 1200, 40) and table.frame == "world"
    assert np.allclose(table.pose[:3, 3], (500, 0, -220))
    assert post.frame == "fPallet[2]" and np.allclose(post.pose[:3, 3], (10, 20, 30))
    assert np.allclose(post.pose[:3, :3] @ [0, 1, 0], [0, 0, 1])  # rx = 90: y turned onto z
    assert lamp.shape.size == (30,) and np.allclose(lamp.pose, np.eye(4))
    assert [o.shape.describe() for o in cell.obstacles] == ["box 800 x 1200 x 40 mm", "cylinder r 40 x 1500 mm",
                                                            "sphere r 30 mm"]
    body, jaw = cell.tools
    assert body.tool == "flange" and body.touch_links is None
    assert jaw.tool == "tGripper" and jaw.touch_links == ("link_6",)
    (brick,) = cell.parts
    assert brick.grasp == "close" and brick.release == "open"
    assert cell.frames() == ["fPallet[2]"] and cell.tool_names() == ["flange", "tGripper"]
    assert table.where is not None and (table.where.line, table.where.column) == (6, 1)


def test_lengths_in_inch(tmp_path):
    cell = read_cell(write_cell(tmp_path, GOOD.replace("version = 1", 'version = 1\nunit = "inch"')))
    assert cell.obstacles[0].shape.size == pytest.approx((800 * 25.4, 1200 * 25.4, 40 * 25.4))
    assert cell.obstacles[0].pose[0, 3] == pytest.approx(500 * 25.4)
    assert cell.obstacles[0].pose[:3, :3] == pytest.approx(np.eye(3))
    # the application's unit is the default
    cell = read_cell(write_cell(tmp_path, GOOD), app_unit="inch")
    assert cell.unit == "inch" and cell.obstacles[2].shape.size == pytest.approx((30 * 25.4,))


BAD = [
    ('colour = "red"\n', 1, 1, "unknown key 'colour'"),
    ('version = 2\n', 1, 11, "version must be 1"),
    ('unit = "cm"\n', 1, 8, 'unit must be "mm" or "inch"'),
    ('margin_mm = -1\n', 1, 13, "must not be negative"),
    ('touch_mm = "x"\n', 1, 12, "must be a number"),
    ('[[obstacle]]\nname = "a"\n', 1, 1, "shape is missing"),
    ('[[obstacle]]\nshape = "cone"\n', 2, 9, "shape must be one of box, cylinder, sphere, mesh"),
    ('[[obstacle]]\nshape = "box"\nsize = [1, 2]\n', 3, 8, "size must be three positive numbers"),
    ('[[obstacle]]\nshape = "box"\nsize = [1, -2, 3]\n', 3, 12, "must be positive"),
    ('[[obstacle]]\nshape = "box"\nsize = [1, 2, true]\n', 3, 15, "must be a number, not true"),
    ('[[obstacle]]\nshape = "cylinder"\nradius = 3\nlength = 4\nsize = [1, 2, 3]\n', 5, 1, "a cylinder takes length, radius, not size"),
    ('[[obstacle]]\nshape = "sphere"\n', 1, 1, "a sphere needs radius"),
    ('[[obstacle]]\nshape = "sphere"\nradius = 1\nat = [1, 2, 3, 4, 5]\n', 4, 6, "at is {x, y, z, rx, ry, rz} or six numbers"),
    ('[[obstacle]]\nshape = "sphere"\nradius = 1\nat = { x = 1, rw = 2 }\n', 4, 15, "not 'rw'"),
    ('[[obstacle]]\nshape = "sphere"\nradius = 1\nframe = "f Pallet"\n', 4, 9, "frame must be"),
    ('[[obstacle]]\nname = "a"\nshape = "sphere"\nradius = 1\n[[obstacle]]\nname = "a"\nshape = "sphere"\nradius = 1\n',
     6, 8, "named twice"),
    ('[[part]]\nname = "p"\nshape = "sphere"\nradius = 1\n', 1, 1, "tool is missing"),
    ('[[part]]\ntool = "tG"\ngrasp = "squeeze"\nshape = "sphere"\nradius = 1\n', 3, 9, 'grasp must be "close" or "open"'),
    ('[[tool]]\ntool = "t G"\nshape = "sphere"\nradius = 1\n', 2, 8, "tool must be a tool variable"),
    ('[[tool]]\nshape = "sphere"\nradius = 1\ntouch_links = "link_6"\n', 4, 15, "touch_links must be a list"),
    ('obstacle = 3\n', 1, 1, "write each one as a [[obstacle]] table"),
    ('[[obstacle]]\nshape = "mesh"\nfile = "m.stl"\nscale = 0\n', 4, 9, "scale must not be zero"),
    ('[[obstacle]]\nshape = "mesh"\nfile = "m.stl"\nsolid = "yes"\n', 4, 9, "solid must be true"),
    ('[[obstacle]]\nshape = "mesh"\nfile = "nothere.stl"\n', 3, 8, "does not exist"),
    ('[[obstacle]]\nshape = "mesh"\nfile = "../outside.stl"\n', 3, 8, "outside the cell file's folder"),
    ('[[obstacle]]\nshape = "mesh"\nfile = "m.ply"\n', 3, 8, "only STL, OBJ and GLB"),
    ('[[obstacle]]\nname = "x\n', 2, 10, "invalid TOML: Illegal character '\\n'"),
]


@pytest.mark.parametrize("text, line, col, message", BAD)
def test_every_mistake_at_its_line_and_column(tmp_path, text, line, col, message):
    (tmp_path / "cell").mkdir()
    (tmp_path / "outside.stl").write_bytes(b"")
    path = write_cell(tmp_path / "cell", text)
    with pytest.raises(CellError) as e:
        read_cell(path)
    problems = e.value.problems
    assert any(p[1] == line and p[2] == col and message in p[3] for p in problems), problems
    assert str(e.value).startswith(f"{path}:")


def test_all_problems_are_reported_at_once(tmp_path):
    text = 'colour = 1\n[[obstacle]]\nshape = "cone"\n[[tool]]\nshape = "sphere"\nradius = -1\n'
    with pytest.raises(CellError) as e:
        read_cell(write_cell(tmp_path, text))
    assert [(p[1], p[2]) for p in e.value.problems] == [(1, 1), (3, 9), (6, 10)]
    assert len(str(e.value).splitlines()) == 3


def test_unreadable_files(tmp_path):
    with pytest.raises(CellError, match="cannot read"):
        read_cell(tmp_path / "missing.toml")
    bad = tmp_path / "latin1.toml"
    bad.write_bytes('description = "caf\xe9"\n'.encode("latin-1"))
    with pytest.raises(CellError, match="not UTF-8"):
        read_cell(bad)


def test_random_damage_never_raises_anything_but_cell_error(tmp_path):
    rng = random.Random(7)
    chars = list('[]{}="\',.#\n 0123456789abcxyz-+')
    for i in range(300):
        text = list(GOOD)
        for _ in range(rng.randint(1, 6)):
            pos = rng.randrange(len(text))
            op = rng.random()
            if op < 0.4:
                text[pos] = rng.choice(chars)
            elif op < 0.7:
                del text[pos]
            else:
                text.insert(pos, rng.choice(chars))
        path = write_cell(tmp_path, "".join(text), name=f"c{i}.toml")
        try:
            read_cell(path)
        except CellError as e:
            assert e.problems and all(isinstance(p[1], int) for p in e.problems)


# ---- meshes ---------------------------------------------------------------------------------------------


def _mesh_cell(tmp_path, file: str, extra: str = "") -> str:
    return write_cell(tmp_path, f'[[obstacle]]\nname = "m"\nshape = "mesh"\nfile = "{file}"\n{extra}')


@pytest.mark.parametrize("ext", ["stl", "obj", "glb"])
def test_mesh_files_load(tmp_path, ext):
    box = trimesh.creation.box((100.0, 200.0, 300.0))
    box.export(tmp_path / f"box.{ext}")
    cell = read_cell(_mesh_cell(tmp_path, f"box.{ext}", "scale = 2\n"))
    m = cell.obstacles[0].shape.mesh
    assert len(m.faces) == 12 and m.solid
    assert np.allclose(m.vertices.max(axis=0) - m.vertices.min(axis=0), (200.0, 400.0, 600.0))


def test_an_obj_cannot_make_trimesh_read_another_file(tmp_path):
    secret = tmp_path / "secret.mtl"
    secret.write_text("newmtl x\nKd 1 0 0\n")
    (tmp_path / "cell").mkdir()
    obj = "mtllib ../secret.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n"
    (tmp_path / "cell" / "t.obj").write_text(obj)
    opened = []
    real_open = open

    def spy(file, *a, **k):
        opened.append(os.fspath(file) if not isinstance(file, int) else file)
        return real_open(file, *a, **k)

    import builtins

    builtins.open = spy
    try:
        cell = read_cell(_mesh_cell(tmp_path / "cell", "t.obj"))
    finally:
        builtins.open = real_open
    assert len(cell.obstacles[0].shape.mesh.faces) == 4
    assert not any("secret" in str(f) for f in opened)


def test_mesh_problems_name_the_file(tmp_path):
    (tmp_path / "junk.stl").write_bytes(b"\x00\x01garbage" * 10)
    with pytest.raises(CellError, match=r"mesh file 'junk.stl'"):
        read_cell(_mesh_cell(tmp_path, "junk.stl"))
    opened = trimesh.creation.box((10, 10, 10))
    opened.update_faces(np.arange(len(opened.faces)) != 0)  # one triangle less: a hole
    opened.export(tmp_path / "open.stl")
    with pytest.raises(CellError, match=r"'open.stl' is not watertight.*solid = false"):
        read_cell(_mesh_cell(tmp_path, "open.stl"))
    cell = read_cell(_mesh_cell(tmp_path, "open.stl", "solid = false\n"))  # a surface is fine
    assert not cell.obstacles[0].shape.mesh.solid
    (tmp_path / "empty.stl").write_text("solid empty\nendsolid empty\n")
    with pytest.raises(CellError, match=r"'empty.stl'"):
        read_cell(_mesh_cell(tmp_path, "empty.stl"))


def test_mesh_size_is_limited(tmp_path, monkeypatch):
    trimesh.creation.icosphere().export(tmp_path / "ball.stl")
    monkeypatch.setattr(meshes, "MAX_MESH_BYTES", 100)
    with pytest.raises(CellError, match="larger than the 100 bytes read"):
        read_cell(_mesh_cell(tmp_path, "ball.stl"))


def test_mesh_through_a_link_out_of_the_folder_is_refused(tmp_path):
    (tmp_path / "cell").mkdir()
    trimesh.creation.box((1, 1, 1)).export(tmp_path / "box.stl")
    os.symlink(tmp_path / "box.stl", tmp_path / "cell" / "link.stl")
    with pytest.raises(CellError, match="outside"):
        read_cell(_mesh_cell(tmp_path / "cell", "link.stl"))
    # the application's folder is allowed too
    cell = read_cell(_mesh_cell(tmp_path / "cell", "link.stl"), app_dir=tmp_path)
    assert len(cell.obstacles[0].shape.mesh.faces) == 12


def test_cell_file_beside_the_application(tmp_path):
    app = tmp_path / "Cell"
    app.mkdir()
    (app / "Cell.pjx").write_text("<Project/>")
    assert find_cell(app) is None
    (app / CELL_FILE_NAME).write_text("")
    assert find_cell(app) == app / CELL_FILE_NAME
    assert find_cell(app / "Cell.pjx") == app / CELL_FILE_NAME
    assert read_cell(find_cell(app)).obstacles == []


# ---- positions of TOML keys and values ------------------------------------------------------------------


def test_positions_follow_tables_arrays_and_strings():
    text = 'a = "x # not a comment"  # comment\n[[t]]\nk = [1,\n  2] # c\n[[t]]\n"q k".v = { w = \'\'\'\nz\'\'\', y = 3 }\n'
    p = positions(text)
    assert p.values[("a",)] == (1, 5)
    assert p.keys[("t", 0)] == (2, 1) and p.keys[("t", 1)] == (5, 1)
    assert p.values[("t", 0, "k", 1)] == (4, 3)
    assert p.values[("t", 1, "q k", "v", "y")] == (7, 11)
    assert p.at(("t", 1, "nothing", 3)) == (5, 1)
    assert positions("a = [1, 2").at(("a", 1)) == (1, 1) or True  # never raises on text it cannot follow


def test_a_cell_path_that_is_not_a_file(tmp_path):
    os.mkfifo(tmp_path / "fifo.toml")  # reading it would wait forever
    with pytest.raises(CellError, match="not a regular file"):
        read_cell(tmp_path / "fifo.toml")
    with pytest.raises(CellError, match="this is a folder"):
        read_cell(tmp_path)


def test_all_meshes_of_a_cell_are_limited_together(tmp_path, monkeypatch):
    for i in range(3):
        trimesh.creation.icosphere(radius=10 + i).export(tmp_path / f"b{i}.stl")
    size = (tmp_path / "b0.stl").stat().st_size
    monkeypatch.setattr(meshes, "MAX_TOTAL_MESH_BYTES", 2 * size + 10)
    text = "".join(f'[[obstacle]]\nname = "m{i}"\nshape = "mesh"\nfile = "b{i}.stl"\n' for i in range(3))
    with pytest.raises(CellError, match="add up to more than"):
        read_cell(write_cell(tmp_path, text))
