"""Collisions of the arm, its tool and the parts it carries with the cell (issue 14; docs/cell.md).

Imported by the simulator only (python-fcl, trimesh, numpy: the `sim` extra); never by lint.

Modules
-------
- `cellfile`   reading a cell file: `read_cell`, `find_cell`, `CELL_FILE_NAME`; `tomlpos` finds
               the line and column of every TOML key and value for its messages
- `cell`       the cell: `Cell`, `Obstacle`, `ToolSolid`, `Part`, `Shape`, `MeshData`
- `meshes`     STL/OBJ/GLB files through trimesh, confined and size-checked
- `bodies`     solids as python-fcl objects with their bounding boxes; point-in-mesh
- `acm`        the allowed-collision matrix, computed as MoveIt's setup assistant does
- `armmodel`   `ArmModel` / `arm_model(robot)`: the arm's link solids, matrix and motion bounds
- `poses`      frames and tools from the caller as 4x4 matrices; comparing two readings
- `fcl_backend` `FclBackend`: every distance and contact query between two bodies (python-fcl)
- `groups`     `Group` (bodies carried by one link, or the static set) and `Watch` (two groups
               that must not touch)
- `world`      `World`: the scene between motions: obstacles in their frames, the tool, parts
               carried and left in the cell, touch allowances; open/close
- `path`       `ArmPath`: the arm along one motion, at its samples and between them
- `bounds`     the motion bound, the broad phase's boxes and each watch's per-sample `Track`
- `measure`    `Probe`: one watch measured at one position (`Measurement`, `Nearest`, `Hit`)
- `sweep`      `Sweep`: conservative advancement along a motion, the clearance per sample and
               the motion's minimum
- `checker`    `CollisionChecker`: combines the world, the sweep and the backend (the API below)
- `records`    what comes back: `MotionReport`, `Contact`, `Clearance`, `PartDrop`, `CellProblem`

Imports go one way (tests/collision/test_structure.py): checker -> sweep -> measure, bounds ->
path -> groups -> armmodel; the sweep and the probe read the world; world -> groups,
fcl_backend, poses; fcl_backend -> bodies; nothing but the package imports the checker.

API
---
    cell = read_cell(path, app_dir=None, app_unit="mm")       # CellError lists every problem
    path = find_cell(app_dir)                                   # val3check-cell.toml, or None
    arm = arm_model(robot)                                      # robot: val3check.robot.RobotModel
    checker = CollisionChecker(arm, cell, frames=f, tools=t, app_unit_mm=1.0)
        f(name, time) or {name: pose}: an application frame in world ("fPallet", "fPallet[2]")
        t(name, time) or {name: pose}: a tool variable in the flange ("tGripper")
        pose: (x, y, z, rx, ry, rz) in the application's unit and degrees, a geometry.Trsf, or a
        3x4/4x4 matrix; None when the program has none
    report = checker.check_motion(MotionSpan(id, source, label), times, joints, q_at=None)
        times (N,) s, joints (N, axes) VAL 3 units; q_at(t) for positions between samples
        -> MotionReport: starts_in_collision, first_contact (Contact: time, the two solids'
           labels, point, depth, kind "contact" | "self" | "inside"), min_clearance (Clearance: mm,
           time, solids, nearest points; to the cell), too_close (below the margin), clearance
           (per sample, mm, a lower bound) and exact (per sample), contacts, checks
        the motion is checked between its samples too (conservative advancement, docs/cell.md)
    drops = checker.gripper(tool_name, "open" | "close", time, joints=None, source=None)
        -> [PartDrop]; parts grasped or left in the cell as the cell file says
    checker.problems                                            # [CellProblem]: frames/tools not found
"""

from __future__ import annotations

from .acm import ACM, compute_acm
from .armmodel import ArmModel, arm_model
from .cell import Cell, MeshData, Obstacle, Part, Shape, ToolSolid, Where
from .cellfile import CELL_FILE_NAME, find_cell, read_cell
from .checker import CollisionChecker
from .errors import CellError
from .results import CellProblem, Clearance, Contact, MotionReport, MotionSpan, PartDrop

__all__ = [
    "ACM",
    "CELL_FILE_NAME",
    "ArmModel",
    "Cell",
    "CellError",
    "CellProblem",
    "Clearance",
    "CollisionChecker",
    "Contact",
    "MeshData",
    "MotionReport",
    "MotionSpan",
    "Obstacle",
    "Part",
    "PartDrop",
    "Shape",
    "ToolSolid",
    "Where",
    "arm_model",
    "compute_acm",
    "find_cell",
    "read_cell",
]
