"""Mesh files of a cell (STL, OBJ, GLB), read with trimesh under the rules of docs/cell.md.

A mesh file must be inside the cell file's folder or the application's folder (symbolic links
resolved), at most `MAX_MESH_BYTES` long (`MAX_TOTAL_MESH_BYTES` for all of a cell's). The bytes
are read here and handed to trimesh from memory, so a file cannot make trimesh open another one
(an OBJ's material library, a glTF buffer). Before trimesh builds anything, `meshsize` reads what
the file declares (triangles, vertices, GLB primitives and instances: at most `MAX_TRIANGLES`...)
and the run's budgets are applied: the memory the mesh will take is priced against
`--max-memory`, and no mesh is read once `--max-wall` has run out. A mesh that does not load, has
no triangle, or is not watertight while the cell says it is a solid is refused with the file's
name and the reason.
"""

from __future__ import annotations

import io
import os
from pathlib import Path

import numpy as np

from ..rules import codes
from .cell import MeshData
from .errors import MeshProblem
from .meshsize import MAX_PIECES, MAX_TRIANGLES, MAX_VERTICES, Declared, declared

__all__ = ["MAX_MESH_BYTES", "MAX_PIECES", "MAX_TOTAL_MESH_BYTES", "MAX_TRIANGLES", "MAX_VERTICES", "MeshProblem",
           "load_mesh", "resolve_mesh_path"]

MAX_MESH_BYTES = 64 * 1024 * 1024  # one file
MAX_TOTAL_MESH_BYTES = 256 * 1024 * 1024  # all the files of a cell
MAX_COORDINATE_MM = 1e6  # a vertex, once scaled: 1 km from the origin (as every length of a cell)
FILE_TYPES = {".stl": "stl", ".obj": "obj", ".glb": "glb"}
# What trimesh's loading and checks take at their peak (measured on CPython 3.11, trimesh 4, rounded
# up): per triangle, per vertex, per separate geometry (a GLB primitive), per byte of the file.
BYTES_PER_TRIANGLE = 700
BYTES_PER_VERTEX = 120
BYTES_PER_PIECE = 20_000
BYTES_PER_FILE_BYTE = 2


def resolve_mesh_path(name: str, cell_dir: str | os.PathLike, roots: list[str | os.PathLike]) -> Path:
    """The file `name` (relative to the cell file's folder) if it lies in the cell's folder or one
    of `roots`; MeshProblem otherwise."""
    from ..excerpt import shown

    if not name.isprintable():  # a NUL cannot name a file; other controls are a mistake
        raise MeshProblem(f"mesh file {shown(name)}: a file name cannot hold control characters")
    base = Path(cell_dir).resolve()
    try:
        target = (base / name).resolve()
    except (OSError, ValueError) as exc:
        raise MeshProblem(f"mesh file {shown(name)}: not a usable file name ({exc})") from None
    allowed = [base, *(Path(r).resolve() for r in roots)]
    if not any(target == a or a in target.parents for a in allowed):
        raise MeshProblem(f"mesh file {shown(name)} is outside the cell file's folder and the application")
    if FILE_TYPES.get(target.suffix.lower()) is None:
        raise MeshProblem(f"mesh file {shown(name)}: only STL, OBJ and GLB files are read (.stl, .obj, .glb)")
    if not target.is_file():
        raise MeshProblem(f"mesh file {shown(name)} does not exist")
    return target


def price(d: Declared, file_bytes: int) -> int:
    """Bytes the process grows by while trimesh loads and checks a mesh (its peak)."""
    return (BYTES_PER_TRIANGLE * d.triangles + BYTES_PER_VERTEX * d.vertices + BYTES_PER_PIECE * d.pieces
            + BYTES_PER_FILE_BYTE * file_bytes)


def load_mesh(path: Path, shown: str, scale: tuple[float, float, float], solid: bool,
              max_bytes: int | None = None, roots: list | None = None, budget=None,  # noqa: ANN001
              out_of_time=None) -> MeshData:  # noqa: ANN001
    """Read a mesh file through the file gate (val3check/confine.py: a regular file, inside
    `roots` when given, size checked); vertices multiplied by `scale` (per axis: the cell's unit
    in mm times the entry's own scale). `shown` is the name used in messages. `budget`: the
    run's memory budget (`reserve(bytes, what)` raises MemoryError); `out_of_time()`: true once
    the run's wall-clock budget (--max-wall) has run out: no mesh is read then."""
    from .. import confine

    gate = confine.Roots([os.fspath(r) for r in roots]) if roots else confine.Roots.user_given()
    max_bytes = MAX_MESH_BYTES if max_bytes is None else max_bytes
    try:
        data = confine.read_bytes(os.fspath(path), gate, max_bytes)
    except confine.Refused as exc:
        if exc.code == codes.FILE_TOO_LARGE:
            raise MeshProblem(f"mesh file {shown!r} is larger than the {max_bytes} bytes read") from None
        raise MeshProblem(f"mesh file {shown!r}: cannot read: {exc.reason}") from None
    kind = FILE_TYPES[path.suffix.lower()]
    d = declared(data, kind, shown)
    if out_of_time is not None and out_of_time():
        raise MeshProblem(f"mesh file {shown!r} is not read: the run's wall-clock budget (--max-wall) ran out "
                          "while the cell was read")
    if budget is not None:
        try:
            budget.reserve(price(d, len(data)), f"mesh file {shown!r} ({d.triangles} triangles)")
        except MemoryError as exc:
            raise MeshProblem(str(exc)) from None
        except Exception:  # noqa: BLE001 -- the budget's clock: --max-wall ran out
            raise MeshProblem(f"mesh file {shown!r} is not read: the run's wall-clock budget (--max-wall) ran out "
                              "while the cell was read") from None
    import trimesh

    try:
        mesh = trimesh.load(io.BytesIO(data), file_type=kind, force="mesh")
    except Exception as exc:  # trimesh raises anything on a bad file: report it, never a traceback
        raise MeshProblem(f"mesh file {shown!r} does not load as {kind.upper()}: {_short(exc)}") from None
    if not isinstance(mesh, trimesh.Trimesh) or len(mesh.faces) == 0:
        raise MeshProblem(f"mesh file {shown!r} holds no triangle")
    if len(mesh.faces) > MAX_TRIANGLES:  # cannot happen after `declared`; kept as the last word
        raise MeshProblem(f"mesh file {shown!r} has {len(mesh.faces)} triangles, more than the {MAX_TRIANGLES} read")
    v = np.asarray(mesh.vertices, dtype=float)
    f = np.asarray(mesh.faces)
    if v.ndim != 2 or v.shape[1] != 3 or f.ndim != 2 or f.shape[1] != 3 or f.min() < 0 or f.max() >= len(v):
        # trimesh keeps what the file says: "v 0 0" makes two-number vertices
        raise MeshProblem(f"mesh file {shown!r} does not load as {kind.upper()}: its vertices are not all three "
                          "numbers x, y, z, or its faces name vertices it does not have")
    if not np.isfinite(v).all():
        raise MeshProblem(f"mesh file {shown!r} has vertices that are not finite numbers")
    v = v * np.asarray(scale, dtype=float)
    far = float(np.abs(v).max()) if len(v) else 0.0
    if not far <= MAX_COORDINATE_MM:
        raise MeshProblem(f"mesh file {shown!r}: once scaled, a vertex lies {far:.3g} mm from the origin; a cell "
                          f"holds at most {MAX_COORDINATE_MM:g} mm (1 km): check its scale and unit")
    if solid and not mesh.is_watertight:
        raise MeshProblem(
            f"mesh file {shown!r} is not watertight (it has open edges), so it does not enclose a volume: "
            "close it, or write solid = false to check it as a surface"
        )
    faces = np.asarray(mesh.faces, dtype=np.int64)
    if np.linalg.det(np.diag(scale)) < 0:  # a mirroring scale turns the faces inside out
        faces = faces[:, ::-1].copy()
    return MeshData(file=shown, vertices=v, faces=faces, solid=solid)


def _short(exc: Exception) -> str:
    from ..excerpt import excerpt

    text = str(exc).strip().splitlines()
    return excerpt(text[0] if text else type(exc).__name__, 200)
