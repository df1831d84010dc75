"""Reading a cell file (docs/cell.md): TOML, every field checked, every problem with its line and column.

    read_cell(path, app_dir=None, app_unit="mm") -> Cell      raises CellError (all problems found)
    find_cell(app_dir) -> Path | None                          the cell file beside an application

tomllib parses (through val3check.tomlfile: a hostile text is a positioned error);
`tomlpos.positions` finds where each key and value is written, so that a message
points at the value at fault (`cell.toml:12:8: obstacle 'table': size must be three positive
numbers`). Bad input is a CellError, never a traceback.
"""

from __future__ import annotations

import math
import os
import re
from pathlib import Path
from typing import Any

import numpy as np

from .. import tomlfile
from ..excerpt import shown
from ..lengths import INCH_MM
from ..tomlpos import positions
from . import meshes
from .cell import SHAPES, Cell, MeshData, Obstacle, Part, Shape, ToolSolid, Where
from .errors import CellError

CELL_FILE_NAME = "val3check-cell.toml"  # found beside the application (find_cell)
CELL_VERSION = 1
MAX_CELL_BYTES = 4 * 1024 * 1024
MAX_ENTRIES = 10_000
# The sane range of every number of a cell (docs/cell.md "Limits"): beyond, fcl's arithmetic loses
# all precision (a 1e100 mm box around the arm was "nothing in reach") or overflows.
MAX_LENGTH_MM = 1e6  # positions and sizes: 1 km
MIN_SIZE_MM = 1e-3  # sizes, radii and lengths of solids: 1 µm
MAX_ANGLE_DEG = 36_000.0  # rx, ry, rz: a hundred turns
MIN_SCALE, MAX_SCALE = 1e-6, 1e6  # a mesh's scale (its file's unit to the cell's)
MAX_TOLERANCE_MM = 10_000.0  # margin_mm, touch_mm
MAX_NAME = 200  # characters of a name, a tool or frame, a link name

_TOP = {"version", "description", "unit", "margin_mm", "touch_mm", "obstacle", "tool", "part"}
_SHAPE_KEYS = {"box": {"size"}, "cylinder": {"radius", "length"}, "sphere": {"radius"}, "mesh": {"file", "scale", "solid"}}
_ALL_SHAPE_KEYS = {"shape", "size", "radius", "length", "file", "scale", "solid"}
_ENTRY = {
    "obstacle": {"name", "frame", "at"} | _ALL_SHAPE_KEYS,
    "tool": {"name", "tool", "at", "touch_links"} | _ALL_SHAPE_KEYS,
    "part": {"name", "tool", "grasp", "at", "cleared_by"} | _ALL_SHAPE_KEYS,
}
_TRSF = ("x", "y", "z", "rx", "ry", "rz")
# a VAL 3 variable, optionally one array element: fPallet, fPallet[3], lib:fBase (a library's frame)
_VARIABLE = re.compile(r"^(?:[A-Za-z_][A-Za-z0-9_]*:)?[A-Za-z_][A-Za-z0-9_]*(?:\[\s*\d+\s*\])?$")


def find_cell(app_dir: str | os.PathLike) -> Path | None:
    """`val3check-cell.toml` in the application's folder (the folder holding its .pjx), if any."""
    p = Path(app_dir)
    if p.is_file():
        p = p.parent
    f = p / CELL_FILE_NAME
    return f if f.is_file() else None


def read_cell(path: str | os.PathLike, app_dir: str | os.PathLike | None = None, app_unit: str = "mm",
              roots: list[str | os.PathLike] | None = None, found: bool = False, budget=None,  # noqa: ANN001
              out_of_time=None) -> Cell:  # noqa: ANN001
    """Read and check a cell file. Mesh files may lie in the cell file's folder, the application's
    folder (`app_dir`) or one of `roots`. Lengths are in the cell's `unit` (default: the
    application's, `app_unit`); the Cell holds millimetres. `found`: the file was found beside the
    application, not named by the user: a link may not lead out of that folder. `budget` (the
    run's memory budget) and `out_of_time()` (true once --max-wall has run out) apply to its
    meshes (meshes.load_mesh)."""
    from .. import confine

    shown = str(path)
    # a path the user gave: read wherever it is, if a plain file; found beside the application: there only
    where = confine.Roots([os.path.dirname(os.path.abspath(path))]) if found else confine.Roots.user_given()
    try:
        raw = confine.read_bytes(os.fspath(path), where, MAX_CELL_BYTES)
    except confine.Refused as exc:
        raise CellError([(shown, 0, 0, f"cannot read the cell file: {exc.reason}")]) from None
    try:
        data, text = tomlfile.load_bytes(raw)
    except tomlfile.TomlError as exc:
        raise CellError([(shown, exc.line, exc.col, exc.message)]) from None
    r = _Reader(shown, text, Path(path).resolve().parent, app_dir, roots or [], app_unit)
    r.budget, r.out_of_time = budget, out_of_time
    cell = r.cell(data)
    if r.problems:
        raise CellError(r.problems)
    return cell


class _Reader:
    def __init__(self, shown: str, text: str, folder: Path, app_dir, roots, app_unit: str) -> None:
        self.shown = shown
        self.pos = positions(text)
        self.folder = folder
        self.roots = ([app_dir] if app_dir is not None else []) + list(roots)
        self.app_unit = app_unit
        self.problems: list[tuple[str, int, int, str]] = []
        self.scale = 1.0
        self._meshes: dict[tuple, MeshData] = {}
        self._mesh_files: set[str] = set()
        self._mesh_bytes = 0
        self.budget = None  # read_cell: the run's memory budget and wall-clock budget
        self.out_of_time = None

    # ---- reporting --------------------------------------------------------------------------------

    def fail(self, path: tuple, message: str, key: bool = False) -> None:
        line, col = self.pos.at(path, key=key)
        self.problems.append((self.shown, line, col, message))

    def where(self, path: tuple) -> Where:
        line, col = self.pos.at(path, key=True)
        return Where(self.shown, line, col)

    # ---- values -----------------------------------------------------------------------------------

    def number(self, v: Any, path: tuple, what: str, positive: bool = False, min0: bool = False) -> float | None:
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
            self.fail(path, f"{what} must be a number, not {_show(v)}")
            return None
        if positive and not v > 0:
            self.fail(path, f"{what} must be positive, not {_show(v)}")
            return None
        if min0 and v < 0:
            self.fail(path, f"{what} must not be negative, not {_show(v)}")
            return None
        return float(v)

    def length(self, v: Any, path: tuple, what: str, size: bool = False) -> float | None:
        """A length in the cell's unit, in millimetres, within ±MAX_LENGTH_MM; a size (`size`) from
        MIN_SIZE_MM to MAX_LENGTH_MM."""
        x = self.number(v, path, what, positive=size)
        if x is None:
            return None
        mm = x * self.scale
        if size and not MIN_SIZE_MM <= mm <= MAX_LENGTH_MM or not abs(mm) <= MAX_LENGTH_MM:
            unit = f" inches ({mm:.6g} mm)" if self.scale != 1.0 else " mm"
            low = f"{MIN_SIZE_MM:g}" if size else f"{-MAX_LENGTH_MM:,.0f}"
            self.fail(path, f"{what} must be from {low} to {MAX_LENGTH_MM:,.0f} mm (1 km), not {_show(v)}{unit}")
            return None
        return mm

    def bounded(self, v: Any, path: tuple, what: str, low: float, high: float, unit: str) -> float | None:
        x = self.number(v, path, what, min0=low == 0)
        if x is not None and not low <= x <= high:
            self.fail(path, f"{what} must be from {low:,g} to {high:,g} {unit}, not {_show(v)}")
            return None
        return x

    def string(self, v: Any, path: tuple, what: str, longest: int = MAX_NAME) -> str | None:
        if not isinstance(v, str) or not v.strip():
            self.fail(path, f"{what} must be a non-empty string, not {_show(v)}")
            return None
        if not v.isprintable() or len(v) > longest:
            why = "control characters" if not v.isprintable() else f"more than {longest} characters"
            self.fail(path, f"{what} must be printable text of at most {longest} characters, not {_show(v)} ({why})")
            return None
        return v.strip()

    def keys(self, table: dict, allowed: set[str], path: tuple, what: str) -> None:
        for k in table:
            if k not in allowed:
                self.fail(path + (k,), f"{what}: unknown key {shown(k)} (known: {', '.join(sorted(allowed))})", key=True)

    # ---- the document -----------------------------------------------------------------------------

    def cell(self, data: dict) -> Cell:
        self.keys(data, _TOP, (), "cell file")
        v = data.get("version", CELL_VERSION)
        if v != CELL_VERSION or isinstance(v, bool):
            self.fail(("version",), f"version must be {CELL_VERSION} (the only version), not {_show(v)}")
        unit = data.get("unit", self.app_unit)
        if unit not in ("mm", "inch"):
            self.fail(("unit",), f"unit must be \"mm\" or \"inch\", not {_show(unit)}")
            unit = "mm"
        self.scale = INCH_MM if unit == "inch" else 1.0
        cell = Cell(path=self.shown, unit=unit)
        desc = data.get("description", "")
        if not isinstance(desc, str):
            self.fail(("description",), f"description must be a string, not {_show(desc)}")
        else:
            cell.description = desc
        if "margin_mm" in data:
            m = self.bounded(data["margin_mm"], ("margin_mm",), "margin_mm", 0.0, MAX_TOLERANCE_MM, "mm")
            cell.margin_mm = m if m is not None else 0.0
        if "touch_mm" in data:
            t = self.bounded(data["touch_mm"], ("touch_mm",), "touch_mm", 0.0, MAX_TOLERANCE_MM, "mm")
            cell.touch_mm = t if t is not None else cell.touch_mm
        for kind in ("obstacle", "tool", "part"):
            entries = data.get(kind, [])
            if not isinstance(entries, list) or not all(isinstance(e, dict) for e in entries):
                self.fail((kind,), f"{kind}: write each one as a [[{kind}]] table", key=True)
                continue
            if len(entries) > MAX_ENTRIES:
                self.fail((kind,), f"more than {MAX_ENTRIES} [[{kind}]] entries", key=True)
                continue
            for i, e in enumerate(entries):
                item = self.entry(kind, e, (kind, i))
                if item is None:
                    continue
                if kind == "obstacle":
                    if any(o.name == item.name for o in cell.obstacles):
                        self.fail((kind, i, "name"), f"obstacle {item.name!r} is named twice: give each obstacle its own name")
                    cell.obstacles.append(item)
                elif kind == "tool":
                    cell.tools.append(item)
                else:
                    cell.parts.append(item)
        self.check_parts(cell)
        return cell

    def entry(self, kind: str, e: dict, path: tuple):
        self.keys(e, _ENTRY[kind], path, f"[[{kind}]]")
        default = f"{kind} {path[1] + 1}"
        name = self.string(e["name"], path + ("name",), "name") if "name" in e else default
        label = f"{kind} {name!r}" if name else kind
        shape = self.shape(e, path, label)
        pose = self.trsf(e.get("at"), path + ("at",), label)
        where = self.where(path)
        if shape is None or pose is None or name is None:
            return None
        if kind == "obstacle":
            frame = e.get("frame", "world")
            if not isinstance(frame, str) or not _VARIABLE.match(frame.strip()):
                self.fail(path + ("frame",), f"{label}: frame must be \"world\" or a frame variable of the application "
                          f"(fPallet, fPallet[2]), not {_show(frame)}")
                return None
            return Obstacle(name, shape, _compact(frame), pose, where)
        tool = e.get("tool", "flange" if kind == "tool" else None)
        if tool is None:
            self.fail(path, f"{label}: tool is missing: the tool variable that grasps it (tGripper)", key=True)
            return None
        if not isinstance(tool, str) or not _VARIABLE.match(tool.strip()):
            self.fail(path + ("tool",), f"{label}: tool must be a tool variable of the application (tGripper, flange), "
                      f"not {_show(tool)}")
            return None
        tool = _compact(tool)
        if kind == "tool":
            touch = e.get("touch_links")
            links = None
            if touch is not None:
                if not isinstance(touch, list) or not all(isinstance(t, str) and t and t.isprintable()
                                                          and len(t) <= MAX_NAME for t in touch):
                    self.fail(path + ("touch_links",), f"{label}: touch_links must be a list of link names of the arm")
                    return None
                links = tuple(touch)
            return ToolSolid(name, tool, shape, pose, links, where)
        grasp = e.get("grasp", "close")
        if grasp not in ("close", "open"):
            self.fail(path + ("grasp",), f"{label}: grasp must be \"close\" or \"open\" (the instruction that takes "
                      f"the part), not {_show(grasp)}")
            return None
        cleared = e.get("cleared_by")
        if cleared is not None and (not isinstance(cleared, str) or not cleared.strip()
                                    or not cleared.isprintable() or len(cleared) > MAX_NAME):
            self.fail(path + ("cleared_by",), f"{label}: cleared_by must be the name or the link of a digital "
                      f"input or output of the application (doPalletFull), not {_show(cleared)}")
            return None
        return Part(name, tool, grasp, shape, pose, where, cleared.strip() if cleared else None)

    def shape(self, e: dict, path: tuple, label: str) -> Shape | None:
        kind = e.get("shape")
        if kind is None:
            self.fail(path, f"{label}: shape is missing (one of {', '.join(SHAPES)})", key=True)
            return None
        if kind not in SHAPES:
            self.fail(path + ("shape",), f"{label}: shape must be one of {', '.join(SHAPES)}, not {_show(kind)}")
            return None
        wanted = _SHAPE_KEYS[kind]
        bad = False
        for k in _ALL_SHAPE_KEYS - {"shape"} - wanted:
            if k in e:
                self.fail(path + (k,), f"{label}: a {kind} takes {', '.join(sorted(wanted))}, not {k}", key=True)
                bad = True
        for k in sorted(wanted - {"scale", "solid"}):
            if k not in e:
                self.fail(path, f"{label}: a {kind} needs {k}", key=True)
                bad = True
        if bad:
            return None
        if kind == "box":
            size = e["size"]
            if not (isinstance(size, list) and len(size) == 3):
                self.fail(path + ("size",), f"{label}: size must be three positive numbers [x, y, z], not {_show(size)}")
                return None
            vals = [self.length(v, path + ("size", i), f"{label}: size", size=True) for i, v in enumerate(size)]
            if None in vals:
                return None
            return Shape("box", tuple(vals))  # type: ignore[arg-type]
        if kind == "cylinder":
            r = self.length(e["radius"], path + ("radius",), f"{label}: radius", size=True)
            ln = self.length(e["length"], path + ("length",), f"{label}: length", size=True)
            if r is None or ln is None:
                return None
            return Shape("cylinder", (r, ln))
        if kind == "sphere":
            r = self.length(e["radius"], path + ("radius",), f"{label}: radius", size=True)
            return None if r is None else Shape("sphere", (r,))
        return self.mesh(e, path, label)

    def mesh(self, e: dict, path: tuple, label: str) -> Shape | None:
        name = self.string(e["file"], path + ("file",), f"{label}: file", longest=4096)
        if name is None:
            return None
        sc = e.get("scale", 1.0)
        if isinstance(sc, list):
            if len(sc) != 3:
                self.fail(path + ("scale",), f"{label}: scale is one number or three [sx, sy, sz], not {_show(sc)}")
                return None
            vals = [self.number(v, path + ("scale", i), f"{label}: scale") for i, v in enumerate(sc)]
        else:
            vals = [self.number(sc, path + ("scale",), f"{label}: scale")] * 3
        if None in vals:
            return None
        if any(v == 0 for v in vals):  # type: ignore[comparison-overlap]
            self.fail(path + ("scale",), f"{label}: scale must not be zero")
            return None
        if not all(MIN_SCALE <= abs(v) <= MAX_SCALE for v in vals):  # type: ignore[arg-type]
            self.fail(path + ("scale",), f"{label}: scale must be from {MIN_SCALE:g} to {MAX_SCALE:g} "
                      f"(or its negative: a mirror), not {_show(sc)}")
            return None
        solid = e.get("solid", True)
        if not isinstance(solid, bool):
            self.fail(path + ("solid",), f"{label}: solid must be true (a closed volume) or false (a surface), not {_show(solid)}")
            return None
        scale = tuple(v * self.scale for v in vals)  # type: ignore[operator]
        try:
            target = meshes.resolve_mesh_path(name, self.folder, self.roots)
            key = (str(target), scale, solid)
            if key not in self._meshes:
                size = target.stat().st_size
                if str(target) not in self._mesh_files:
                    self._mesh_bytes += size
                    self._mesh_files.add(str(target))
                if self._mesh_bytes > meshes.MAX_TOTAL_MESH_BYTES:
                    raise meshes.MeshProblem(f"mesh file {shown(name)}: the cell's meshes add up to more than "
                                             f"{meshes.MAX_TOTAL_MESH_BYTES} bytes")
                self._meshes[key] = meshes.load_mesh(target, name, scale, solid,  # type: ignore[arg-type]
                                                     roots=[self.folder, *self.roots], budget=self.budget,
                                                     out_of_time=self.out_of_time)
        except OSError as exc:
            self.fail(path + ("file",), f"{label}: mesh file {shown(name)}: cannot read: {exc.strerror or exc}")
            return None
        except meshes.MeshProblem as exc:
            self.fail(path + ("file",), f"{label}: {exc}")
            return None
        return Shape("mesh", (), self._meshes[key])

    def trsf(self, v: Any, path: tuple, label: str) -> np.ndarray | None:
        """`at`: {x, y, z, rx, ry, rz} (fields left out are 0) or [x, y, z, rx, ry, rz]; lengths in the
        cell's unit, angles in degrees (VAL 3 trsf, 9.3.2). Default: the identity."""
        if v is None:
            return np.eye(4)
        if isinstance(v, list):
            if len(v) != 6:
                self.fail(path, f"{label}: at is {{x, y, z, rx, ry, rz}} or six numbers, not {_show(v)}")
                return None
            vals = [self.coordinate(x, path + (i,), f"{label}: at", i) for i, x in enumerate(v)]
        elif isinstance(v, dict):
            for k in v:
                if k not in _TRSF:
                    self.fail(path + (k,), f"{label}: at has the fields x, y, z, rx, ry, rz, not {shown(k)}", key=True)
                    return None
            vals = [self.coordinate(v[k], path + (k,), f"{label}: at.{k}", i) if k in v else 0.0
                    for i, k in enumerate(_TRSF)]
        else:
            self.fail(path, f"{label}: at is {{x, y, z, rx, ry, rz}} or six numbers, not {_show(v)}")
            return None
        if None in vals:
            return None
        return trsf_matrix(vals)

    def coordinate(self, v: Any, path: tuple, what: str, i: int) -> float | None:
        """x, y, z (i < 3): a length, in mm; rx, ry, rz: an angle in degrees."""
        if i < 3:
            return self.length(v, path, what)
        return self.bounded(v, path, what, -MAX_ANGLE_DEG, MAX_ANGLE_DEG, "degrees")

    def check_parts(self, cell: Cell) -> None:
        grasp: dict[str, tuple[str, str]] = {}
        cleared: dict[str, str | None] = {}
        for i, p in enumerate(cell.parts):
            if cleared.setdefault(p.name, p.cleared_by) != p.cleared_by:
                self.fail(("part", i, "cleared_by"), f"part {p.name!r}: its solids must have the same cleared_by")
            seen = grasp.setdefault(p.name, (p.tool, p.grasp))
            if seen != (p.tool, p.grasp):
                self.fail(("part", i, "tool"), f"part {p.name!r}: its solids must hang on one tool with one grasp "
                          f"({seen[0]}, on {seen[1]})")


def trsf_matrix(t) -> np.ndarray:
    """A VAL 3 trsf (x, y, z in mm, rx, ry, rz in degrees, R = Rx·Ry·Rz, 9.3.2) as a 4x4 matrix."""
    from ..geometry.rotation import matrix

    x, y, z, rx, ry, rz = (float(v) for v in t)
    T = np.eye(4)
    T[:3, :3] = np.asarray(matrix(rx, ry, rz), dtype=float).reshape(3, 3)
    T[:3, 3] = (x, y, z)
    return T


def _compact(name: str) -> str:
    return re.sub(r"\s+", "", name)


def _show(v: Any) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, str):
        return shown(v)
    if isinstance(v, dict):
        return "a table"
    if isinstance(v, list):
        return "a list" if len(v) > 6 else "[" + ", ".join(_show(x) for x in v) + "]"
    return shown(v)
