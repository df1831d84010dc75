"""The cell as the collision checks placed it over a run (arm_record.CellTimeline), for the reports
that draw it (the HTML report's 3D view, the MCAP trace).

    log = TimelineLog(cell, watch, arm_run, app_unit_mm)
    checker = CollisionChecker(..., frames=log.frame, tools=log.tool)   # the reads are logged
    checker.gripper(...); log.after(checker, t, q)                      # q: the joints then
    arm_run.cell_timeline = log.timeline()

Frames and tools are logged as the checker reads them (at a motion's start, at an open()/close():
docs/cell.md), so an obstacle is drawn where it was checked; only changes are kept. The parts are
followed through the checker's state after each gripper event and each `cleared_by`: what it
carries (`checker.carried`) and what it left in the cell (its world's `dropped` solids).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ..collision.poses import as_matrix
from .arm_record import CellTimeline, PartSpan, PoseChange


class TimelineLog:
    """Logs what the checker of one run reads and does (see the module docstring). `watch`: the
    run's collision_run.ValueWatch; `run`: its arm_record.ArmRun (the flange's pose at a release)."""

    def __init__(self, cell: Any, watch: Any, run: Any, unit_mm: float = 1.0) -> None:
        self.cell = cell
        self.watch = watch
        self.run = run
        self.unit = float(unit_mm)
        self.frames: dict[str, list[PoseChange]] = {}
        self.tools: dict[str, list[PoseChange]] = {}
        self.tool_solids = {t.tool for t in cell.tools if t.tool != "flange"}
        self.spans: list[dict] = []  # open and closed spans: name, tool, carried, start, end, pose, bodies (left: ids of its solids in the checker)
        self._flange: dict[bytes, np.ndarray] = {}  # joints (bits) -> the flange's pose there
        self._lying: list[dict] = []  # the spans of parts left in the cell and not yet taken away (end None)
        self._carried: set[str] = set()
        self._poses: dict[bytes, np.ndarray] = {}  # `_shared`
        self._left: set[int] = set()
        self._last_tool: tuple | None = None  # `_matrix`

    # ---- the checker's pose sources ----------------------------------------------------------------

    def frame(self, name: str, t: float):
        """ValueWatch.frame, logged."""
        value = self.watch.frame(name, t)
        self._log(self.frames, name, t, value)
        return value

    def tool(self, name: str, t: float):
        """ValueWatch.tool, logged (the tools tool solids hang on)."""
        value = self.watch.tool(name, t)
        if name in self.tool_solids:
            self._log(self.tools, name, t, value)
        return value

    def _log(self, into: dict[str, list[PoseChange]], name: str, t: float, value) -> None:
        M = None if value is None else as_matrix(value, self.unit)
        changes = into.setdefault(name.replace(" ", ""), [])  # "fPallet[ 1 ]" is fPallet[1]
        if changes:
            last = changes[-1].matrix
            if (last is None) == (M is None) and (M is None or np.array_equal(last, M)):
                return
            if changes[-1].time == t:
                changes.pop()
        changes.append(PoseChange(float(t), M))

    # ---- the parts -------------------------------------------------------------------------------

    def after(self, checker: Any, t: float, q=None) -> None:
        """After an open()/close() or a `cleared_by` at `t` (q: the arm's joints then, when known):
        the parts taken, left, taken away."""
        carried = set(checker.carried)
        left_now = {id(b) for b in getattr(checker.world, "dropped", ())}
        for name in sorted(carried - self._carried):
            self._take(name, t)
        for name in sorted(self._carried - carried):
            self._leave(name, t, left_now - self._left, q)
        lying = []
        for span in self._lying:  # only these can end here (a long run has many spans)
            if span["bodies"] & left_now:
                lying.append(span)
            else:
                span["end"] = float(t)
        self._lying = lying
        self._carried = carried
        self._left = left_now

    def _take(self, name: str, t: float) -> None:
        tool = next(p.tool for p in self.cell.parts if p.name == name)
        T = None if tool == "flange" else self.watch.tool(tool, t)  # the checker took it: the tool has a value
        self.spans.append({"name": name, "tool": tool, "carried": True, "start": float(t), "end": None,
                           "pose": self._shared(np.eye(4) if T is None else self._matrix(T)), "bodies": set()})

    def _matrix(self, T) -> np.ndarray:
        """as_matrix(T) in the log's unit; the last one kept with T itself (held: the watch gives
        the same object again while the tool's value is the same reading, and never changes it)."""
        last = self._last_tool
        if last is None or last[0] is not T:
            last = self._last_tool = (T, as_matrix(T, self.unit))
        return last[1]

    def _leave(self, name: str, t: float, bodies: set[int], q=None) -> None:
        span = next(s for s in reversed(self.spans) if s["carried"] and s["name"] == name and s["end"] is None)
        span["end"] = float(t)
        q = self.run.trajectory.position(t) if q is None else q
        # (the geometry in force at t too, when setDH changed it: collect.ModelKinematics)
        key = (np.asarray(q, dtype=float).tobytes(), self.run.scene.kinematics.geometry_at(t))
        F = self._flange.get(key)
        if F is None:  # a cyclic program leaves its parts from a few positions: computed once each
            scene = self.run.scene
            F = scene.kinematics.link_poses(q, t)[scene.flange_frame]
            if len(self._flange) >= 1024:
                self._flange.clear()
            self._flange[key] = F
        self.spans.append({"name": name, "tool": span["tool"], "carried": False, "start": float(t), "end": None,
                           "pose": self._shared(F @ span["pose"]), "bodies": bodies})
        self._lying.append(self.spans[-1])

    def _shared(self, M: np.ndarray) -> np.ndarray:
        """One matrix per pose (bit for bit): a cyclic program takes and leaves its parts at a few
        poses, and a long run keeps a span for each time."""
        key = M.tobytes()
        out = self._poses.get(key)
        if out is None:
            if len(self._poses) >= 4096:
                self._poses.clear()
            out = self._poses[key] = M
        return out

    def timeline(self) -> CellTimeline:
        """What was logged, as the run's record keeps it."""
        spans = sorted(self.spans, key=lambda s: s["start"])  # stable: a part left, then taken again
        return CellTimeline({k: tuple(v) for k, v in sorted(self.frames.items())},
                            {k: tuple(v) for k, v in sorted(self.tools.items())},
                            tuple(PartSpan(s["name"], s["tool"], s["carried"], s["start"], s["end"], s["pose"])
                                  for s in spans))
