"""Issue 21 G, Q and I (mesh names): a cell's mesh files are judged by what they declare before
trimesh builds anything, within the run's budgets; a file that lies in its header, keeps its data
in another file or places one primitive 100,000 times is refused with its name and what is wrong
(R030 at the cell file's line), quickly, with trimesh never called."""

from __future__ import annotations

import struct
from pathlib import Path

import pytest

pytest.importorskip("trimesh")

from tests.hostile import meshfiles  # noqa: E402
from val3check.collision import CellError, meshes, meshsize, read_cell  # noqa: E402


def _cell(folder: Path, file: str, extra: str = "") -> Path:
    p = folder / "cell.toml"
    p.write_text(f'[[obstacle]]\nname = "m"\nshape = "mesh"\nfile = "{file}"\n{extra}', encoding="utf-8")
    return p


@pytest.fixture
def no_trimesh(monkeypatch):
    """trimesh.load may not be reached: the file is refused from its headers."""
    import trimesh

    def refuse(*a, **k):  # noqa: ANN002, ANN003
        raise AssertionError("trimesh.load was called")

    monkeypatch.setattr(trimesh, "load", refuse)


def _problem(folder: Path, file: str, data: bytes, extra: str = "") -> str:
    (folder / file).write_bytes(data)
    with pytest.raises(CellError) as e:
        read_cell(_cell(folder, file, extra))
    (p,) = e.value.problems
    assert (p[1], p[2]) == (4, 8), p  # at the file key
    return p[3]


# ---- Q: what is wrong with the file -----------------------------------------------------------------

def test_an_stl_whose_header_declares_the_wrong_count(tmp_path, no_trimesh):
    msg = _problem(tmp_path, "bad.stl", meshfiles.stl_binary(declared=1000))
    assert msg == ("obstacle 'm': mesh file 'bad.stl' is not a valid STL: as a binary STL its header declares 1000 "
                   "triangles, 50084 bytes, but the file has 684 bytes, and it is not an ASCII STL (text starting "
                   "with 'solid')")


def test_an_stl_starting_with_solid_that_is_not_text(tmp_path, no_trimesh):
    data = bytearray(meshfiles.stl_binary(declared=7))
    data[:5] = b"solid"
    data[100] = 0xFF
    msg = _problem(tmp_path, "b.stl", bytes(data))
    assert "declares 7 triangles" in msg and "as an ASCII STL it is not text (byte 100)" in msg


def test_a_glb_with_an_external_buffer(tmp_path, no_trimesh):
    msg = _problem(tmp_path, "ext.glb", meshfiles.cube_glb(uri="../secret.bin"))
    assert "mesh file 'ext.glb' is not a valid GLB: buffer 0 is in another file or a data URI ('../secret.bin')" in msg


@pytest.mark.parametrize("data,fragment", [
    (meshfiles.cube_glb(count=36_000), "accessor 1 declares 36000 elements, more than its buffer view 1 holds (72 bytes)"),
    (b"glTF" + struct.pack("<II", 2, 99) + b"\0" * 20, "its header declares 99 bytes, the file has 32"),
    (b"glTF" + struct.pack("<II", 1, 20) + b"\0" * 8, "version 1; only glTF 2.0"),
    (meshfiles.glb({"asset": {}, "nodes": [{"children": [1]}, {"children": [0], "mesh": 0}],
                    "meshes": [{"primitives": []}]}), "its nodes form a cycle"),
    (b"glTF" + struct.pack("<III", 2, 28, 8) + b"BIN\0" + b"{}      ", "first chunk is not a JSON chunk"),
    (b"glTF" + struct.pack("<III", 2, 28, 8) + struct.pack("<I", 0x4E4F534A) + b"{[}]    ", "does not parse"),
    (b"not a glb at all", "does not start with the GLB header"),
])
def test_glb_headers_that_lie(tmp_path, no_trimesh, data, fragment):
    assert fragment in _problem(tmp_path, "x.glb", data)


def test_deep_glb_json_is_refused(tmp_path, no_trimesh):
    body = b"[" * 100_000 + b"]" * 100_000
    data = b"glTF" + struct.pack("<II", 2, 20 + len(body)) + struct.pack("<II", len(body), 0x4E4F534A) + body
    assert "nested too deeply" in _problem(tmp_path, "deep.glb", data)


# ---- G: limits before the mesh is built ---------------------------------------------------------

def test_one_primitive_placed_100000_times_is_refused_before_trimesh(tmp_path, no_trimesh):
    data = meshfiles.cube_glb(primitives=100_000)  # 4.2 MB: 31 s and 1.7 GB in trimesh before
    msg = _problem(tmp_path, "many.glb", data)
    json_bytes = struct.unpack_from("<I", data, 12)[0]
    assert msg.endswith(f"its JSON chunk (the scene) is {json_bytes} bytes, more than the {meshsize.MAX_JSON_BYTES} read")


def test_primitives_times_instances_are_limited(tmp_path, no_trimesh):
    msg = _problem(tmp_path, "m.glb", meshfiles.cube_glb(primitives=100, nodes=51))  # 5100 placed
    assert f"places more than {meshsize.MAX_PIECES} primitives" in msg


def test_nodes_multiply_their_mesh(tmp_path, no_trimesh):
    # a chain of nodes, each placing the next twice: 2^20 instances of one cube from 21 nodes
    doc, binary = meshfiles.cube_document()
    doc.update(nodes=[{"children": [i + 1, i + 1]} for i in range(20)] + [{"mesh": 0}], scenes=[{"nodes": [0]}])
    assert "places more than" in _problem(tmp_path, "tree.glb", meshfiles.glb(doc, binary))


def test_an_obj_with_too_many_triangles_is_refused_before_trimesh(tmp_path, no_trimesh, monkeypatch):
    monkeypatch.setattr(meshsize, "MAX_TRIANGLES", 1000)
    obj = b"v 0 0 0\nv 1 0 0\nv 0 1 0\n" + b"f 1 2 3\n" * 1001
    assert "has 1001 triangles, more than the 1000 read" in _problem(tmp_path, "t.obj", obj)
    poly = b"v 0 0 0\n" + b"f " + b" ".join(b"1" for _ in range(1003)) + b"\n"  # 1003 corners: 1001 triangles
    assert "has 1001 triangles" in _problem(tmp_path, "p.obj", poly)


def test_a_binary_stl_over_the_limit_is_refused_from_its_header(tmp_path, no_trimesh, monkeypatch):
    monkeypatch.setattr(meshsize, "MAX_TRIANGLES", 10)
    faces = meshfiles.CUBE_FACES * 2  # 24 triangles
    assert "has 24 triangles, more than the 10 read" in _problem(tmp_path, "c.stl", meshfiles.stl_binary(faces))
    assert "has 24 triangles" in _problem(tmp_path, "a.stl", meshfiles.stl_ascii(faces))


def test_the_memory_budget_is_applied_before_trimesh(tmp_path, no_trimesh, monkeypatch):
    from val3check.interpretation.memory_budget import MemoryBudget

    (tmp_path / "cube.stl").write_bytes(meshfiles.stl_binary())
    monkeypatch.setattr(meshes, "BYTES_PER_TRIANGLE", 10**7)  # as if each of its 12 triangles took 10 MB
    budget = MemoryBudget(100)
    with pytest.raises(CellError) as e:
        read_cell(_cell(tmp_path, "cube.stl"), budget=budget)
    assert "mesh file 'cube.stl' (12 triangles) would need about" in str(e.value) and "--max-memory" in str(e.value)


def test_no_mesh_is_read_once_the_wall_clock_budget_ran_out(tmp_path, no_trimesh):
    (tmp_path / "cube.stl").write_bytes(meshfiles.stl_binary())
    with pytest.raises(CellError, match=r"not read: the run's wall-clock budget \(--max-wall\) ran out"):
        read_cell(_cell(tmp_path, "cube.stl"), out_of_time=lambda: True)


@pytest.mark.parametrize("kind", ["stl", "ascii.stl", "obj", "glb"])
def test_good_files_of_every_kind_still_load(tmp_path, kind):
    data = {"stl": meshfiles.stl_binary(), "ascii.stl": meshfiles.stl_ascii(), "obj": meshfiles.obj(),
            "glb": meshfiles.cube_glb(nodes=2)}[kind]
    (tmp_path / f"m.{kind}").write_bytes(data)
    cell = read_cell(_cell(tmp_path, f"m.{kind}", "scale = 100\n"))
    mesh = cell.obstacles[0].shape.mesh
    assert len(mesh.faces) == (24 if kind == "glb" else 12) and abs(mesh.vertices).max() <= 302


# ---- I: file names -----------------------------------------------------------------------------------

@pytest.mark.parametrize("name", ["a\\u0000.stl", "a\\u001b[31m.stl", "\\u0007"])
def test_control_characters_in_a_mesh_name(tmp_path, name):
    (tmp_path / "cell.toml").write_text(f'[[obstacle]]\nname = "m"\nshape = "mesh"\nfile = "{name}"\n')
    with pytest.raises(CellError) as e:
        read_cell(tmp_path / "cell.toml")
    (p,) = e.value.problems
    assert (p[1], p[2]) == (4, 8) and "control characters" in p[3] and "\\x" in p[3], p


def test_a_nul_never_reaches_the_file_system():
    with pytest.raises(meshes.MeshProblem, match="control characters"):
        meshes.resolve_mesh_path("a\x00.stl", ".", [])


def test_a_scaled_mesh_beyond_a_kilometre(tmp_path):
    (tmp_path / "cube.stl").write_bytes(meshfiles.stl_binary())
    (tmp_path / "cell.toml").write_text('unit = "inch"\n[[obstacle]]\nname = "m"\nshape = "mesh"\n'
                                        'file = "cube.stl"\nscale = 78741\n')  # 78741 inches: 2e6 mm
    with pytest.raises(CellError, match=r"once scaled, a vertex lies 2e\+06 mm from the origin; a cell holds at most"):
        read_cell(tmp_path / "cell.toml")


def test_an_obj_whose_vertices_have_two_numbers(tmp_path):
    # found by the fuzz suite: trimesh keeps "v 0 0" as a two-number vertex (a numpy error after)
    data = meshfiles.obj().replace(b"v 0 0 0\n", b"v 0 0\n", 1)
    assert "its vertices are not all three numbers x, y, z" in _problem(tmp_path, "two.obj", data)
