"""The arm and the cell a JSON sim report names, rebuilt for its HTML page (reporting/html/from_sim.py).

    model = model_from_sim_report(report, ReportScene(), fail_on="error")

A JSON report records the arm by name (`robot.name`: a catalogue arm, or a URDF given here) and the
cell by its file, not their geometry: the page's 3D view, its joints and its TCP speed need them
rebuilt. This is where that happens, so that the page writer reads plain data and imports nothing
of robot/, geometry/ or collision/ (docs/architecture.md).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from ..geometry.rotation import matrix
from .arm_record import tcp_speed
from .collect import ModelKinematics


class ReportArm:
    """The arm model of a report (robot.RobotModel) as its page reads it: the joints' names, the
    chain of the 3D view, the TCP speed along the report's trajectory."""

    def __init__(self, model: Any, source: str) -> None:
        """`source`: how the 3D view names the arm's URDF."""
        self.model = model
        self.joint_names = model.joint_names
        self.source = source

    def chain(self) -> dict:
        """The kinematic chain and solids of the 3D view (robot.chain.arm_chain)."""
        from ..robot.chain import arm_chain

        m = self.model
        return arm_chain(m.source, world_frame=m.world_frame, flange_frame=m.flange_frame,
                         joint_names=m.joint_names, name=m.name, source=self.source)

    def tcp_speed(self, tool_uses, times, positions, velocities) -> np.ndarray:
        """The TCP's speed (mm/s) at samples of the trajectory (arm_record.tcp_speed): `tool_uses`
        (start, tool in the flange 4x4 or None) of each motion."""
        return tcp_speed(ModelKinematics(self.model), self.model.flange_frame, tool_uses, times, positions, velocities)


class ReportScene:
    """What a JSON report names and its page rebuilds: the arm (`arm`), the cell (`cell`), and
    the tools' VAL 3 trsfs as matrices (`trsf_matrix`). `arm_urdf`: the arm's URDF when the
    report's `robot.name` is not a catalogue arm."""

    def __init__(self, arm_urdf: str | None = None) -> None:
        """Nothing is read yet."""
        self.arm_urdf = arm_urdf

    def arm(self, name: str) -> ReportArm:
        """The arm model the report names (robot.RobotError when there is none)."""
        from ..robot import load_robot

        model = load_robot(self.arm_urdf or name)
        return ReportArm(model, self.arm_urdf or f"robots/{Path(model.source).name}")

    @staticmethod
    def cell(path: str, roots: list[str]) -> tuple[Any, str | None]:
        """(the cell read again from its file (collision.cell.Cell), None), or (None, why it
        cannot be read). Its meshes: beside it or in the roots."""
        from ..collision import CellError, read_cell

        try:
            return read_cell(path, roots=list(roots), found=True), None
        except (CellError, OSError) as exc:
            return None, str(exc)

    @staticmethod
    def trsf_matrix(trsf) -> Any:
        """A VAL 3 trsf (x, y, z mm, rx, ry, rz degrees, 9.3.2) as a 4x4 matrix; None stays None."""
        if trsf is None:
            return None
        M = np.eye(4)
        M[:3, :3] = np.asarray(matrix(*trsf[3:6]), dtype=float).reshape(3, 3)  # row-major
        M[:3, 3] = trsf[:3]
        return M
