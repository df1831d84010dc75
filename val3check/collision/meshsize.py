"""What a mesh file declares, read from its headers before any mesh is built (docs/cell.md).

trimesh builds the whole mesh before anyone can count its triangles: a 4.7 MB GLB placing one
12-triangle primitive 100,000 times took 31 s and 1.7 GB, a binary STL whose header lies sent
trimesh guessing a text encoding, a GLB buffer in another file made it fail on None. So the
file is read here first, in linear time and without building anything:

* binary STL: the 80-byte header, then the triangle count, which must match the file's size
  (84 + 50 bytes per triangle); otherwise the file must be an ASCII STL (UTF-8 text starting
  with `solid`), whose `facet` lines are counted;
* OBJ: UTF-8 text; `v` lines and the triangles of `f` lines (a polygon of k corners makes k - 2);
* GLB: the container header and its JSON chunk (at most `MAX_JSON_BYTES`); every buffer must be the file's own binary chunk
  (no `uri`), every accessor must fit in its buffer view and the view in the buffer; triangles
  and vertices are the accessors' counts summed over each primitive of each mesh, times the
  number of times the scene places that mesh (nodes may not form a cycle).

`declared(...)` gives (triangles, vertices, pieces) or raises MeshProblem naming the file and
what is wrong with it.
"""

from __future__ import annotations

import json
import re
import struct
from dataclasses import dataclass

from .errors import MeshProblem

MAX_TRIANGLES = 2_000_000
MAX_VERTICES = 6_000_000  # three per triangle: a mesh that shares no corner
MAX_PIECES = 5_000  # GLB primitives times the nodes placing them: trimesh takes ~0.3 ms each
MAX_JSON_BYTES = 4 * 1024 * 1024  # a GLB's JSON chunk: its scene (data is in the binary chunk)

_FACE = re.compile(rb"^[ \t]*f[ \t]+([^\r\n]*)", re.MULTILINE)
_COMPONENT_BYTES = {5120: 1, 5121: 1, 5122: 2, 5123: 2, 5125: 4, 5126: 4}
_TYPE_COMPONENTS = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4, "MAT2": 4, "MAT3": 9, "MAT4": 16}
_JSON_CHUNK, _BIN_CHUNK = 0x4E4F534A, 0x004E4942


@dataclass(frozen=True)
class Declared:
    triangles: int
    vertices: int
    pieces: int = 1  # separate geometries trimesh builds and joins


def declared(data: bytes, kind: str, shown: str) -> Declared:
    """What the file holds, from its headers; MeshProblem when they are wrong or over the limits."""
    if kind == "stl":
        d = _stl(data, shown)
    elif kind == "obj":
        d = _obj(data, shown)
    else:
        d = _glb(data, shown)
    if d.pieces > MAX_PIECES:
        raise MeshProblem(f"mesh file {shown!r} places more than {MAX_PIECES} primitives (primitives of its meshes "
                          f"times the nodes placing them), more than are read: join them into fewer meshes")
    if d.triangles > MAX_TRIANGLES:
        raise MeshProblem(f"mesh file {shown!r} has {d.triangles} triangles, more than the {MAX_TRIANGLES} read")
    if d.vertices > MAX_VERTICES:
        raise MeshProblem(f"mesh file {shown!r} has {d.vertices} vertices, more than the {MAX_VERTICES} read")
    if d.triangles == 0:
        raise MeshProblem(f"mesh file {shown!r} holds no triangle")
    return d


# ---- STL -------------------------------------------------------------------------------------------


def _stl(data: bytes, shown: str) -> Declared:
    if len(data) >= 84:
        (n,) = struct.unpack_from("<I", data, 80)
        if 84 + 50 * n == len(data):
            return Declared(n, 3 * n)
    if data.lstrip()[:5].lower() == b"solid":
        try:
            text = data.decode("utf-8")
        except UnicodeDecodeError as exc:
            raise MeshProblem(_stl_binary_mismatch(data, shown) + f"; as an ASCII STL it is not text (byte {exc.start})"
                              ) from None
        n = text.lower().count("endfacet")
        return Declared(n, 3 * n)
    raise MeshProblem(_stl_binary_mismatch(data, shown) + ", and it is not an ASCII STL (text starting with 'solid')")


def _stl_binary_mismatch(data: bytes, shown: str) -> str:
    if len(data) < 84:
        return f"mesh file {shown!r} is not a valid STL: {len(data)} bytes, too short for a binary STL (84 bytes at least)"
    (n,) = struct.unpack_from("<I", data, 80)
    return (f"mesh file {shown!r} is not a valid STL: as a binary STL its header declares {n} triangles, "
            f"{84 + 50 * n} bytes, but the file has {len(data)} bytes")


# ---- OBJ -------------------------------------------------------------------------------------------


def _obj(data: bytes, shown: str) -> Declared:
    try:
        data.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise MeshProblem(f"mesh file {shown!r} is not a valid OBJ: not UTF-8 text (byte {exc.start})") from None
    triangles = 0
    for m in _FACE.finditer(data):
        triangles += max(0, len(m.group(1).split()) - 2)
        if triangles > MAX_TRIANGLES:
            break
    # an upper bound of the `v` lines (their count, plus any "v " elsewhere): enough for a limit
    return Declared(triangles, data.count(b"v ") + data.count(b"v\t"))


# ---- GLB -------------------------------------------------------------------------------------------


def _glb(data: bytes, shown: str) -> Declared:
    def bad(why: str) -> MeshProblem:
        return MeshProblem(f"mesh file {shown!r} is not a valid GLB: {why}")

    if len(data) < 20 or data[:4] != b"glTF":
        raise bad("it does not start with the GLB header ('glTF', version, length)")
    version, length = struct.unpack_from("<II", data, 4)
    if version != 2:
        raise bad(f"version {version}; only glTF 2.0 binary files are read")
    if length != len(data):
        raise bad(f"its header declares {length} bytes, the file has {len(data)}")
    size, kind = struct.unpack_from("<II", data, 12)
    if kind != _JSON_CHUNK or 20 + size > len(data):
        raise bad("its first chunk is not a JSON chunk that fits in the file")
    if size > MAX_JSON_BYTES:  # parsing it would take seconds and ten times its size in memory
        raise bad(f"its JSON chunk (the scene) is {size} bytes, more than the {MAX_JSON_BYTES} read")
    try:
        doc = json.loads(data[20:20 + size].decode("utf-8"))
    except RecursionError:
        raise bad("its JSON is nested too deeply") from None
    except (UnicodeDecodeError, ValueError) as exc:
        raise bad(f"its JSON chunk does not parse ({str(exc)[:80]})") from None
    if not isinstance(doc, dict):
        raise bad("its JSON chunk is not an object")
    binary = 0
    rest = 20 + size
    if rest + 8 <= len(data):
        bsize, bkind = struct.unpack_from("<II", data, rest)
        if bkind == _BIN_CHUNK and rest + 8 + bsize <= len(data):
            binary = bsize
    return _Gltf(doc, binary, bad).declared()


def _list(doc: dict, key: str, bad) -> list:  # noqa: ANN001
    v = doc.get(key, [])
    if not isinstance(v, list):
        raise bad(f"'{key}' is not a list")
    return v


def _index(v, n: int) -> bool:  # noqa: ANN001
    return isinstance(v, int) and not isinstance(v, bool) and 0 <= v < n


class _Gltf:
    def __init__(self, doc: dict, binary: int, bad) -> None:  # noqa: ANN001
        self.doc, self.binary, self.bad = doc, binary, bad
        self.buffers = _list(doc, "buffers", bad)
        self.views = _list(doc, "bufferViews", bad)
        self.accessors = _list(doc, "accessors", bad)
        self.meshes = _list(doc, "meshes", bad)
        self.nodes = _list(doc, "nodes", bad)
        self._count: dict[int, int] = {}

    def declared(self) -> Declared:
        for i, b in enumerate(self.buffers):
            if not isinstance(b, dict):
                raise self.bad(f"buffer {i} is not an object")
            if "uri" in b:
                from ..excerpt import shown

                raise self.bad(f"buffer {i} is in another file or a data URI ({shown(b['uri'])}): only GLB files "
                               "that hold their data in their binary chunk are read")
            if i > 0 or not isinstance(b.get("byteLength"), int) or not 0 <= b["byteLength"] <= self.binary:
                raise self.bad(f"buffer {i} is not the file's binary chunk ({self.binary} bytes)")
        uses = self.instances()
        triangles = vertices = pieces = 0
        for m, mesh in enumerate(self.meshes):
            prims = mesh.get("primitives", []) if isinstance(mesh, dict) else None
            if not isinstance(prims, list):
                raise self.bad(f"mesh {m} has no list of primitives")
            times = uses.get(m, 1)  # a mesh no node places is still read: counted once
            pieces += times * len(prims)
            if pieces > MAX_PIECES:
                break
            for p, prim in enumerate(prims):
                t, v = self.primitive(prim, f"mesh {m} primitive {p}")
                triangles += times * t
                vertices += times * v
        return Declared(triangles, vertices, pieces)

    def primitive(self, prim, where: str) -> tuple[int, int]:  # noqa: ANN001
        if not isinstance(prim, dict) or not isinstance(prim.get("attributes"), dict):
            raise self.bad(f"{where} has no attributes")
        position = prim["attributes"].get("POSITION")
        if position is None:
            return 0, 0
        vertices = self.count(position, f"{where} POSITION")
        n = self.count(prim["indices"], f"{where} indices") if "indices" in prim else vertices
        mode = prim.get("mode", 4)
        triangles = n // 3 if mode == 4 else max(0, n - 2) if mode in (5, 6) else 0
        return triangles, vertices

    def count(self, a, where: str) -> int:  # noqa: ANN001
        """The element count of accessor `a`, checked against its buffer view and buffer."""
        if not _index(a, len(self.accessors)):
            raise self.bad(f"{where}: no accessor {a!r}")
        if a in self._count:
            return self._count[a]
        acc = self.accessors[a]
        if not isinstance(acc, dict):
            raise self.bad(f"accessor {a} is not an object")
        count, view = acc.get("count"), acc.get("bufferView")
        size = _COMPONENT_BYTES.get(acc.get("componentType"), 0) * _TYPE_COMPONENTS.get(acc.get("type"), 0)
        if not isinstance(count, int) or isinstance(count, bool) or count < 0 or size == 0:
            raise self.bad(f"accessor {a}: count, componentType or type is not valid")
        if not _index(view, len(self.views)) or not isinstance(self.views[view], dict):
            raise self.bad(f"accessor {a} has no data (no valid bufferView)")
        bv = self.views[view]
        offset, length = bv.get("byteOffset", 0), bv.get("byteLength")
        if not all(isinstance(x, int) and not isinstance(x, bool) and x >= 0 for x in (offset, length)) \
                or not _index(bv.get("buffer"), len(self.buffers)) or offset + length > self.binary:
            raise self.bad(f"buffer view {view} does not fit in the binary chunk ({self.binary} bytes)")
        stride = bv.get("byteStride") or size
        start = acc.get("byteOffset", 0)
        if not isinstance(stride, int) or not isinstance(start, int) or start < 0 or stride < size \
                or count and start + (count - 1) * stride + size > length:
            raise self.bad(f"accessor {a} declares {count} elements, more than its buffer view {view} holds "
                           f"({length} bytes)")
        self._count[a] = count
        return count

    def instances(self) -> dict[int, int]:
        """How many times the scenes place each mesh (paths from a scene's root nodes to a node
        holding it); MeshProblem when nodes form a cycle."""
        children: list[list[int]] = []
        for i, node in enumerate(self.nodes):
            kids = node.get("children", []) if isinstance(node, dict) else None
            if not isinstance(kids, list) or not all(_index(k, len(self.nodes)) for k in kids):
                raise self.bad(f"node {i} has children that are not nodes")
            children.append(kids)
        roots: list[int] = []
        scenes = _list(self.doc, "scenes", self.bad)
        for s in scenes:
            ns = s.get("nodes", []) if isinstance(s, dict) else None
            if not isinstance(ns, list) or not all(_index(k, len(self.nodes)) for k in ns):
                raise self.bad("a scene names nodes that do not exist")
            roots.extend(ns)
        if not scenes:
            roots = list(range(len(self.nodes)))
        order = self._topological(children)
        paths = [0] * len(self.nodes)
        for r in roots:
            paths[r] += 1
        for i in order:  # parents before children
            for k in children[i]:
                paths[k] = min(paths[k] + paths[i], MAX_PIECES + 1)
        uses: dict[int, int] = {}
        for i, node in enumerate(self.nodes):
            mesh = node.get("mesh") if isinstance(node, dict) else None
            if mesh is not None:
                if not _index(mesh, len(self.meshes)):
                    raise self.bad(f"node {i} names mesh {mesh!r}, which does not exist")
                uses[mesh] = min(uses.get(mesh, 0) + paths[i], MAX_PIECES + 1)
        return uses

    def _topological(self, children: list[list[int]]) -> list[int]:
        """The nodes, each before its children (Kahn's algorithm); MeshProblem on a cycle."""
        parents = [0] * len(children)
        for kids in children:
            for k in kids:
                parents[k] += 1
        todo = [i for i, n in enumerate(parents) if n == 0]
        order = []
        while todo:
            i = todo.pop()
            order.append(i)
            for k in children[i]:
                parents[k] -= 1
                if parents[k] == 0:
                    todo.append(k)
        if len(order) != len(children):
            raise self.bad("its nodes form a cycle (a node is its own ancestor)")
        return order
