"""Collision checking of the arm, its tool and the parts it carries along a joint trajectory.

    checker = CollisionChecker(arm_model(robot), cell, frames=..., tools=...)
    report = checker.check_motion(MotionSpan(id, source), times, joints)     -> MotionReport
    drops = checker.gripper("tGripper", "close", time)                        -> [PartDrop]

The checker only combines its collaborators (docs/cell.md, "How the check works"):

* `world.World`: the scene between motions: obstacles placed in their frames, the tool placed by
  the tool variables, parts carried and left in the cell, touch allowances; the grippers.
* `groups`: bodies grouped by what carries them (an arm link, the flange, the static set), and
  the *watches*: pairs of groups that must not touch (the allowed-collision matrix applied).
* `path.ArmPath`: the arm along one motion, at its samples and between them.
* `bounds`: the motion bound B = Σ_j |Δq_j| · r_j (`ArmModel.weights`), the broad phase's boxes,
  and the per-sample lower bounds of each watch (`Track`).
* `sweep.Sweep`: conservative advancement between the samples, then the clearance per sample and
  the motion's minimum; `measure.Probe` measures one watch at one position.
* `fcl_backend.FclBackend`: every distance and contact query, through python-fcl.

Lengths are millimetres, times seconds, joints VAL 3 values (degrees; mm for a prismatic axis).
Frame and tool poses come from the caller in the application's unit (`app_unit_mm` per unit).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Hashable
from typing import Any

import numpy as np

from .armmodel import ArmModel
from .cell import Cell
from .fcl_backend import FclBackend
from .groups import Group
from .path import ArmPath
from .poses import PoseSource
from .results import CellProblem, MotionReport, MotionSpan, PartDrop, ShiftedReport
from .sweep import Sweep
from .world import World


REUSE = 2048  # checks of motions kept for reuse (check_own); a motion's report holds its per-sample arrays


def shifted(own: MotionReport, motion: MotionSpan, start: float) -> ShiftedReport:
    """A report on a motion's own clock, for `motion` starting at `start` on the run's clock (the
    per-sample clearances are shared, never changed; the times computed when read)."""
    return ShiftedReport(motion, own, start)


class CollisionChecker:
    """Checks motions of one arm in one cell; keeps the state between motions (parts carried or
    left in the cell, frames and tools as last read: `world`).

    frames(name, time) / frames[name]: pose of an application frame in world; tools(name, time) /
    tools[name]: pose of a tool variable in the flange. A pose is a trsf (x, y, z, rx, ry, rz) in the
    application's unit and degrees, an object with those attributes (geometry.Trsf), or a 4x4 /
    3x4 matrix; None when the program has none (the solids on it are left out and a CellProblem
    says so). margin_mm: clearance below it is a warning (default: the cell's). touch_mm: a
    penetration up to it is touching, not a contact (default: the cell's). readings(time): a
    token that changes whenever frames and tools may answer otherwise at that time (the same
    token: the scene is not read again); None: they are read at every motion."""

    def __init__(self, arm: ArmModel, cell: Cell, *, frames: PoseSource = None, tools: PoseSource = None,
                 margin_mm: float | None = None, touch_mm: float | None = None, app_unit_mm: float = 1.0,
                 tolerance_mm: float = 0.05, readings: Callable[[float], Hashable] | None = None) -> None:
        self.arm = arm
        self.cell = cell
        self.margin = float(cell.margin_mm if margin_mm is None else margin_mm)
        self.touch = float(cell.touch_mm if touch_mm is None else touch_mm)
        self.tol = float(tolerance_mm)
        self.backend = FclBackend()
        self.world = World(arm, cell, self.backend, frames=frames, tools=tools, app_unit_mm=app_unit_mm,
                           touch_mm=self.touch, readings=readings)
        # radians (or mm) per joint unit
        self._per_unit = np.array([1.0 if p else math.pi / 180.0 for p in arm.links.prismatic])
        self._results: dict = {}  # (motion key, scene key) -> (report on the motion's own clock, pairs found apart)
        self.reused = 0  # motions whose check was reused (check_own)

    @property
    def problems(self) -> list[CellProblem]:
        """What of the cell could not be placed (frames and tools the program has no value for)."""
        return self.world.problems

    @property
    def measurements(self) -> int:
        """Distance and collision queries made so far."""
        return self.backend.measurements

    @property
    def carried(self) -> dict[str, Group]:
        """The parts the tool carries now, by name."""
        return self.world.carried

    def refresh(self, time: float) -> None:
        """Read the frames of the obstacles and the tool poses; the scene is rebuilt only when one
        of them changed."""
        self.world.refresh(time)

    def check_motion(self, motion: MotionSpan, times, joints, q_at: Callable[[float], Any] | None = None) -> MotionReport:
        """Check one motion given by its samples: times (N,) in s, joints (N, axes) in VAL 3 units.
        Between samples the arm is on the straight joint-space segment, or at q_at(t) when given
        (then each step's bound also covers how far q_at bends away from the segment; `q_at.many(ts)`,
        when q_at has it, gives the positions at many times at once)."""
        T, Q = self._samples(times, joints)
        self.world.refresh(float(T[0]))
        report = self._sweep(motion, T, Q, q_at)
        self.world.last_q = Q[-1].copy()
        self.world.time = float(T[-1])
        return report

    def check_own(self, motion: MotionSpan, start: float, times, joints, q_at: Callable[[float], Any] | None = None,
                  key: Hashable = None, mids=None) -> ShiftedReport:
        """Check one motion given on its own clock (docs/cell.md, "How checks are sampled"): it
        starts at `start` (s), `times` (N,) are from 0, `joints` and `q_at(t)` on that clock; the
        report is on the run's clock (start + its times). `key`: everything that determines times,
        joints and q_at (None: nothing is reused); the result of a motion with an equal key in an
        equal scene (`World.key`) with the same margin, touch and tolerance is computed once and
        reused, shifted to the new start (`reuse` finds it without the samples). `mids`: q_at halfway
        between the samples, when the caller has them (`path.samples_and_mids`)."""
        T, Q = self._samples(times, joints)
        hit = self.reuse(motion, start, key)
        if hit is not None:
            return hit
        full = self._full_key(key)
        allowed = self.world.allowed_names()
        own = self._sweep(motion, T, Q, q_at, mids)
        last_q = Q[-1].copy()
        last_q.flags.writeable = False  # shared by every reuse (`reuse`): never changed in place
        if full is not None:
            left = set(self.world.allowed_names())
            if len(self._results) >= REUSE:
                self._results.clear()  # bounded: a cyclic program fills it again within a cycle or two
            self._results[full] = (own, [p for p in allowed if p not in left], last_q, own.end)
        self.world.last_q = last_q
        self.world.time = start + float(T[-1])
        return shifted(own, motion, start)

    def reuse(self, motion: MotionSpan, start: float, key: Hashable) -> ShiftedReport | None:
        """The check of a motion with this key in the scene at `start` when it was made before
        (`check_own`), for `motion` starting at `start`; None when it was not (or key is None)."""
        self.world.refresh(start)
        full = self._full_key(key)
        hit = None if full is None else self._results.get(full)
        if hit is None:
            return None
        own, apart, last_q, end = hit
        world = self.world
        if apart:
            world.forget_allowed(apart)  # what the sweep ended in the scene
        world.last_q = last_q
        world.time = start + end
        self.reused += 1
        return ShiftedReport(motion, own, start)

    def _full_key(self, key: Hashable):
        if key is None:
            return None
        return key, self.world.key(), self.margin, self.world.touch, self.tol

    def _samples(self, times, joints) -> tuple[np.ndarray, np.ndarray]:
        T = np.asarray(times, dtype=float).reshape(-1)
        if len(T) == 0:
            raise ValueError("a motion needs at least one sample")
        Q = np.asarray(joints, dtype=float).reshape(len(T), -1)
        n_joints = self.arm.n_joints
        if Q.shape[1] != n_joints:
            raise ValueError(f"joints have {Q.shape[1]} values per sample, the arm has {n_joints} axes")
        if not (np.isfinite(T).all() and np.isfinite(Q).all()):
            raise ValueError("times and joints must be finite numbers")
        return T, Q

    def _sweep(self, motion: MotionSpan, T: np.ndarray, Q: np.ndarray, q_at, mids=None) -> MotionReport:
        before = self.backend.measurements
        path = ArmPath(self.arm, T, Q, q_at, mids)
        report = MotionReport(motion, T, np.zeros(len(T)), np.zeros(len(T), dtype=bool), margin_mm=self.margin,
                              tolerance_mm=self.tol)
        Sweep(self.world, self.backend, path, self.margin, self.tol).run(report, self._per_unit)
        report.checks = self.backend.measurements - before
        return report

    def gripper(self, tool: str, instruction: str, time: float, joints=None, source: Any = None) -> list[PartDrop]:
        """The program ran open(tool) or close(tool) (instruction "open"/"close") at `time`, the arm
        at `joints` (default: where the last motion ended). The cell's parts grasped by that tool
        on that instruction are attached; the parts it carries and releases on it are left in the
        cell where they are. Returns the parts left inside an obstacle or another part.

        Bodies touching at that moment (the part and the table it lies on, the jaws and the part
        they let go) may touch until they have moved apart."""
        return self.world.gripper(tool, instruction, time, joints, source)

    def clear_parts(self, name: str) -> int:
        """The parts named `name` left in the cell are taken away (the cell's `cleared_by`): how many
        solids left the cell."""
        return self.world.clear_parts(name)
