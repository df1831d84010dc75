"""Mesh files of a cell (STL, OBJ, GLB), read with trimesh under the rules of docs/cell.md.

A mesh file must be inside the cell file's folder or the application's folder (symbolic links
resolved), at most `MAX_MESH_BYTES` long (`MAX_TOTAL_MESH_BYTES` for all of a cell's) and
`MAX_TRIANGLES` triangles. The bytes are read here and
handed to trimesh from memory, so a file cannot make trimesh open another one (an OBJ's material
library, a glTF buffer). A mesh that does not load, has no triangle, or is not watertight while the
cell says it is a solid is refused with the file's name and the reason.
"""

from __future__ import annotations

import io
import os
from pathlib import Path

import numpy as np

from .cell import MeshData

MAX_MESH_BYTES = 64 * 1024 * 1024  # one file
MAX_TOTAL_MESH_BYTES = 256 * 1024 * 1024  # all the files of a cell
MAX_TRIANGLES = 2_000_000
FILE_TYPES = {".stl": "stl", ".obj": "obj", ".glb": "glb"}


class MeshProblem(ValueError):
    """Why a mesh file cannot be used (the message names the file)."""


def resolve_mesh_path(name: str, cell_dir: str | os.PathLike, roots: list[str | os.PathLike]) -> Path:
    """The file `name` (relative to the cell file's folder) if it lies in the cell's folder or one
    of `roots`; MeshProblem otherwise."""
    base = Path(cell_dir).resolve()
    target = (base / name).resolve()
    allowed = [base, *(Path(r).resolve() for r in roots)]
    if not any(target == a or a in target.parents for a in allowed):
        raise MeshProblem(f"mesh file {name!r} is outside the cell file's folder and the application")
    if FILE_TYPES.get(target.suffix.lower()) is None:
        raise MeshProblem(f"mesh file {name!r}: only STL, OBJ and GLB files are read (.stl, .obj, .glb)")
    if not target.is_file():
        raise MeshProblem(f"mesh file {name!r} does not exist")
    return target


def load_mesh(path: Path, shown: str, scale: tuple[float, float, float], solid: bool,
              max_bytes: int = MAX_MESH_BYTES, roots: list | None = None) -> MeshData:
    """Read a mesh file through the file gate (val3check/confine.py: a regular file, inside
    `roots` when given, size checked); vertices multiplied by `scale` (per axis: the cell's unit
    in mm times the entry's own scale). `shown` is the name used in messages."""
    from .. import confine

    gate = confine.Roots([os.fspath(r) for r in roots]) if roots else confine.Roots.user_given()
    try:
        data = confine.read_bytes(os.fspath(path), gate, max_bytes)
    except confine.Refused as exc:
        if exc.code == "F002":
            raise MeshProblem(f"mesh file {shown!r} is larger than the {max_bytes} bytes read") from None
        raise MeshProblem(f"mesh file {shown!r}: cannot read: {exc.reason}") from None
    import trimesh

    kind = FILE_TYPES[path.suffix.lower()]
    try:
        mesh = trimesh.load(io.BytesIO(data), file_type=kind, force="mesh")
    except Exception as exc:  # trimesh raises anything on a bad file: report it, never a traceback
        raise MeshProblem(f"mesh file {shown!r} does not load as {kind.upper()}: {_short(exc)}") from None
    if not isinstance(mesh, trimesh.Trimesh) or len(mesh.faces) == 0:
        raise MeshProblem(f"mesh file {shown!r} holds no triangle")
    if len(mesh.faces) > MAX_TRIANGLES:
        raise MeshProblem(f"mesh file {shown!r} has {len(mesh.faces)} triangles, more than the {MAX_TRIANGLES} read")
    v = np.asarray(mesh.vertices, dtype=float)
    if not np.isfinite(v).all():
        raise MeshProblem(f"mesh file {shown!r} has vertices that are not finite numbers")
    if solid and not mesh.is_watertight:
        raise MeshProblem(
            f"mesh file {shown!r} is not watertight (it has open edges), so it does not enclose a volume: "
            "close it, or write solid = false to check it as a surface"
        )
    v = v * np.asarray(scale, dtype=float)
    faces = np.asarray(mesh.faces, dtype=np.int64)
    if np.linalg.det(np.diag(scale)) < 0:  # a mirroring scale turns the faces inside out
        faces = faces[:, ::-1].copy()
    return MeshData(file=shown, vertices=v, faces=faces, solid=solid)


def _short(exc: Exception) -> str:
    text = str(exc).strip().splitlines()
    msg = text[0] if text else type(exc).__name__
    return msg[:200]
