"""The cell around the arm, as read from a cell file (docs/cell.md): obstacles, tool, parts.

Every length is in millimetres here (the reader converts from the cell's unit); poses are 4x4
numpy matrices. An obstacle is placed in `world` or in a frame of the application, named as the
program names it (`fPallet`, `fPallet[1]`): the checker asks its caller where that frame is.
Tool solids are attached to a tool variable of the application (`tGripper`, or `flange`), parts
are grasped by a tool on `close` (or `open`) and left in the cell on the other instruction.
"""

from __future__ import annotations

import numpy as np

from ..lengths import INCH_MM
from ..light_dataclass import dataclass, field
from .errors import CellError

SHAPES = ("box", "cylinder", "sphere", "mesh")


@dataclass(frozen=True)
class MeshData:
    """Triangles of a mesh file, vertices in mm. `solid`: the cell says it is a closed volume
    (then it is watertight: the reader checked), else a surface."""

    file: str
    vertices: np.ndarray = field(repr=False)
    faces: np.ndarray = field(repr=False)
    solid: bool = True


@dataclass(frozen=True)
class Shape:
    """box: size (x, y, z), centred; cylinder: (radius, length) along the local Z, centred;
    sphere: (radius,); mesh: `mesh` (the file's own origin)."""

    kind: str
    size: tuple[float, ...] = ()
    mesh: MeshData | None = None

    def describe(self) -> str:
        if self.kind == "box":
            return "box {:g} x {:g} x {:g} mm".format(*self.size)
        if self.kind == "cylinder":
            return "cylinder r {:g} x {:g} mm".format(*self.size)
        if self.kind == "sphere":
            return "sphere r {:g} mm".format(*self.size)
        assert self.mesh is not None
        return f"mesh {self.mesh.file} ({len(self.mesh.faces)} triangles)"


@dataclass(frozen=True)
class Where:
    """Where an entry is written in the cell file."""

    path: str
    line: int
    column: int

    def __str__(self) -> str:
        return f"{self.path}:{self.line}:{self.column}"


@dataclass(frozen=True)
class Obstacle:
    """A fixed solid of the cell, at `pose` in `frame` ("world" or an application frame)."""

    name: str
    shape: Shape
    frame: str
    pose: np.ndarray = field(repr=False)
    where: Where | None = None


@dataclass(frozen=True)
class ToolSolid:
    """A solid of the tool, at `pose` in the frame of the tool variable `tool` (flange: the
    flange itself). `touch_links`: arm links it may touch (it is mounted on them)."""

    name: str
    tool: str
    shape: Shape
    pose: np.ndarray = field(repr=False)
    touch_links: tuple[str, ...] | None = None  # None: the flange link and its parent
    where: Where | None = None


@dataclass(frozen=True)
class Part:
    """A solid carried by `tool` once `grasp` ("close" or "open") has run, at `pose` in that tool's
    frame; the other instruction leaves it in the cell where it is. Solids with the same name are
    one part."""

    name: str
    tool: str
    grasp: str
    shape: Shape
    pose: np.ndarray = field(repr=False)
    where: Where | None = None
    # a digital input/output of the application (its name or link): when it becomes true, the parts
    # of this name left in the cell are taken away (an operator changes the full pallet)
    cleared_by: str | None = None

    @property
    def release(self) -> str:
        return "open" if self.grasp == "close" else "close"


@dataclass
class Cell:
    """A cell file, read and checked (`cellfile.read_cell`)."""

    path: str
    unit: str = "mm"
    margin_mm: float = 0.0
    touch_mm: float = 0.05
    description: str = ""
    obstacles: list[Obstacle] = field(default_factory=list)
    tools: list[ToolSolid] = field(default_factory=list)
    parts: list[Part] = field(default_factory=list)

    @property
    def unit_mm(self) -> float:
        return INCH_MM if self.unit == "inch" else 1.0

    def frames(self) -> list[str]:
        """The application frames the obstacles are placed in (world excluded), in file order."""
        out: list[str] = []
        for o in self.obstacles:
            if o.frame != "world" and o.frame not in out:
                out.append(o.frame)
        return out

    def tool_names(self) -> list[str]:
        """The tool variables the tool solids and parts hang on (flange included), in file order."""
        out: list[str] = []
        for t in [*self.tools, *self.parts]:
            if t.tool not in out:
                out.append(t.tool)
        return out


__all__ = ["SHAPES", "Cell", "CellError", "MeshData", "Obstacle", "Part", "Shape", "ToolSolid", "Where"]
