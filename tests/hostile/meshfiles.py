"""Mesh files built byte by byte for the hostile tests (issue 21 G, Q): binary and ASCII STL, OBJ
and GLB, well formed or lying in their headers."""

from __future__ import annotations

import json
import struct

# A unit cube: 8 corners, 12 outward triangles.
CUBE_VERTICES = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
CUBE_FACES = [(0, 2, 1), (0, 3, 2), (4, 5, 6), (4, 6, 7), (0, 1, 5), (0, 5, 4),
              (1, 2, 6), (1, 6, 5), (2, 3, 7), (2, 7, 6), (3, 0, 4), (3, 4, 7)]


def stl_binary(faces=CUBE_FACES, vertices=CUBE_VERTICES, declared: int | None = None) -> bytes:
    """A binary STL; `declared`: the triangle count its header states (default: the true one)."""
    out = [b"binary stl".ljust(80, b" "), struct.pack("<I", len(faces) if declared is None else declared)]
    for f in faces:
        out.append(struct.pack("<3f", 0, 0, 0))
        for i in f:
            out.append(struct.pack("<3f", *vertices[i]))
        out.append(b"\0\0")
    return b"".join(out)


def stl_ascii(faces=CUBE_FACES, vertices=CUBE_VERTICES) -> bytes:
    lines = ["solid cube"]
    for f in faces:
        lines += ["facet normal 0 0 0", "outer loop", *(f"vertex {x} {y} {z}" for x, y, z in (vertices[i] for i in f)),
                  "endloop", "endfacet"]
    return ("\n".join(lines + ["endsolid cube"]) + "\n").encode()


def obj(faces=CUBE_FACES, vertices=CUBE_VERTICES) -> bytes:
    return ("".join(f"v {x} {y} {z}\n" for x, y, z in vertices)
            + "".join("f " + " ".join(str(i + 1) for i in f) + "\n" for f in faces)).encode()


def glb(document: dict | str, binary: bytes = b"") -> bytes:
    """A GLB container (glTF 2.0 binary): the JSON chunk (a document or its text), then the BIN
    chunk when there is one."""
    j = (document if isinstance(document, str) else json.dumps(document, separators=(",", ":"))).encode()
    j += b" " * (-len(j) % 4)
    b = binary + b"\0" * (-len(binary) % 4)
    chunks = struct.pack("<II", len(j), 0x4E4F534A) + j
    if binary:
        chunks += struct.pack("<II", len(b), 0x004E4942) + b
    return struct.pack("<4sII", b"glTF", 2, 12 + len(chunks)) + chunks


def cube_document(primitives: int = 1, nodes: int = 1, uri: str | None = None,
                  count: int | None = None) -> tuple[dict, bytes]:
    """A cube as a glTF document and its binary data: one mesh of `primitives` copies of the same
    primitive, placed by `nodes` nodes; `uri`: the buffer is an external file instead of the BIN
    chunk; `count`: what the index accessor claims."""
    pos = b"".join(struct.pack("<3f", *v) for v in CUBE_VERTICES)
    idx = b"".join(struct.pack("<3H", *f) for f in CUBE_FACES)
    buffer = {"byteLength": len(pos) + len(idx)}
    if uri is not None:
        buffer["uri"] = uri
    doc = {
        "asset": {"version": "2.0"},
        "buffers": [buffer],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": len(pos)},
                        {"buffer": 0, "byteOffset": len(pos), "byteLength": len(idx)}],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 8, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 1]},
            {"bufferView": 1, "componentType": 5123, "count": 36 if count is None else count, "type": "SCALAR"},
        ],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}] * primitives}],
        "nodes": [{"mesh": 0, "translation": [2.0 * i, 0, 0]} for i in range(nodes)],
        "scenes": [{"nodes": list(range(nodes))}],
        "scene": 0,
    }
    return doc, b"" if uri is not None else pos + idx


def cube_glb(primitives: int = 1, nodes: int = 1, uri: str | None = None, count: int | None = None) -> bytes:
    """`cube_document` as a GLB file (the JSON text of many primitives written by repetition)."""
    doc, binary = cube_document(1, nodes, uri, count)
    text = json.dumps(doc, separators=(",", ":"))
    one = json.dumps(doc["meshes"][0]["primitives"][0], separators=(",", ":"))
    return glb(text.replace(f"[{one}]", "[" + ",".join([one] * primitives) + "]", 1), binary)
