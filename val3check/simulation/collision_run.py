"""The collision checks of a run (issue 14; docs/cell.md): the cell, the values the program gives
its frames and tools, every motion of `SimResult.motion` through `collision.CollisionChecker`,
the grippers' open/close, and the findings R030-R037 at the lines that commanded them.

    cell, diags = load_cell(path, app)                        # R030 for a cell file that cannot be used
    watch = ValueWatch(cell, machine)                         # arm.watch(watch): frames/tools as the run goes
    run, diags = check_run(arm_run, cell, watch, model, ...)  # -> CollisionRun, runtime diagnostics;
                                                              # arm_run.cell_timeline: the cell as placed

The watch of the program's frames and tools is simulation/value_watch.py.
"""

from __future__ import annotations

import functools
import math
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

from ..collision import CellError, CollisionChecker, arm_model, find_cell, read_cell
from ..collision.cell import Cell
from ..collision.path import samples_and_mids
from ..collision.results import Contact, MotionReport, PartDrop
from ..diagnostics import Diagnostic
from ..light_dataclass import dataclass, field
from ..rules import codes
from .budget import WALL
from .cell_timeline import TimelineLog
from .own_clock import Positions, own_clocks
from .value_watch import _NAME, US, ValueWatch, _read  # noqa: F401  (ValueWatch, _read: where callers find them)

BUDGET_EVERY = 32  # motions between two readings of the budgets when the checks are reused


@dataclass
class CollisionRun:
    """The collision checks of a run (`SimResult.collision`; docs/sim-report.md).

    cell        the `collision.cell.Cell` checked against, or None (no cell: self-collision only)
    cell_path   the cell file (as given or found), or None
    cell_found  how it was chosen: "option" (--cell), "found" (val3check-cell.toml beside the
                application), "none" (no file there) or "disabled" (--cell none)
    by_motion   {index in result.motion.motions: collision.results.MotionReport} for every motion
                the arm ran (min_clearance, first_contact, starts_in_collision, too_close,
                per-sample clearance)
    contacts    [(record index, Contact)] every contact, by time (kind "contact", "inside" or "self")
    drops       [PartDrop] parts left inside an obstacle or another part
    margin_mm   the cell's safety margin
    checks      distance and collision queries made
    reused      motions whose check was not made again: the same motion in the same scene before
                (docs/cell.md, "How checks are sampled")
    """

    cell: Cell | None
    cell_path: str | None
    cell_found: str
    by_motion: dict[int, MotionReport] = field(default_factory=dict)
    contacts: list[tuple[int, Contact]] = field(default_factory=list)
    drops: list[PartDrop] = field(default_factory=list)
    margin_mm: float = 0.0
    checks: int = 0
    reused: int = 0

    def clearance_trace(self) -> tuple[np.ndarray, np.ndarray]:
        """(times (N,), clearance to the cell (N,) in mm) over the motions checked, in time order:
        a lower bound of the true clearance, exact below the margin and at each motion's minimum
        (docs/cell.md). Empty without obstacles (nothing to be clear of)."""
        if self.cell is None or not (self.cell.obstacles or self.cell.parts):
            return np.zeros(0), np.zeros(0)
        ts, cs = [], []
        for i in sorted(self.by_motion):
            r = self.by_motion[i]
            ts.append(r.times)
            cs.append(r.clearance)
        if not ts:
            return np.zeros(0), np.zeros(0)
        return np.concatenate(ts), np.concatenate(cs)


def choose_cell(option: str | None, app_path: str) -> tuple[str | None, str]:
    """The cell file of a run: (path, how) with how "option" (--cell), "found" (beside the
    application, collision.cellfile.CELL_FILE_NAME), "none" (none there) or "disabled" (`--cell
    none`): without a cell the arm is checked against itself only."""
    if option == "none":
        return None, "disabled"
    if option:
        return option, "option"
    found = find_cell(Path(app_path).parent)
    return (str(found), "found") if found is not None else (None, "none")


def load_cell(path: str, app, found: bool = False, budget=None,
              out_of_time=None) -> tuple[Cell | None, list[Diagnostic]]:
    """Read a cell file for the application `app` (loading.model.Application): (cell, []) or
    (None, R030 diagnostics at every problem's line and column). `found`: beside the application
    (confined to its folder), not named by the user. `budget` and `out_of_time()`: the run's
    memory budget and whether its wall-clock budget has run out, applied to the cell's meshes."""
    unit = "mm" if getattr(app, "millimeter_unit", True) else "inch"
    try:
        return read_cell(path, app_dir=str(Path(app.path).parent), app_unit=unit, found=found, budget=budget,
                         out_of_time=out_of_time), []
    except CellError as exc:
        return None, [Diagnostic(codes.CELL_FILE_INVALID, f"cell file: {msg}", p, line, col, time_us=0, task="", program="")
                      for p, line, col, msg in exc.problems]


# ---- checking the run -------------------------------------------------------------------------------------


def check_run(motion: Any, cell: Cell | None, watch: ValueWatch, model: Any, *, cell_path: str | None = None,
              cell_found: str = "none", app_unit_mm: float = 1.0, io_log=(),
              link_names: dict | None = None, app_path: str = "",
              max_wall: float = math.inf, geometries=(),
              on_motion: Callable[[int, int], None] | None = None,
              out_of_budget: Any = None) -> tuple[CollisionRun | None, list[Diagnostic]]:
    """Check every motion of `motion` (the run's arm_record.ArmRun, on the arm `model`, a
    robot.RobotModel) in `cell` (None: the arm against itself only), with the grippers' events and the parts taken away (`cleared_by`, from
    the run's `io_log`; `link_names`: (kind, link) -> the globals linked to it); (CollisionRun,
    diagnostics R031-R036), or (None, [R037]) when there is nothing to check the motions with or
    the arm's solids cannot be read. The checks stop (R037) after `max_wall` seconds of wall clock,
    or when `out_of_budget()` says what the run's budgets have spent (simulation/budget.py).
    `geometries`: (from time, model) of each setDH (11.4): a motion is checked with the geometry in
    force when it starts (setDH waits for the motion to be empty). `on_motion(done, total)` is told
    before each motion is checked (the progress display)."""
    from ..robot import RobotError

    name = motion.scene.name
    epochs = None
    spent = out_of_budget() if out_of_budget is not None else None
    if spent is not None and motion.motions:  # not even the arm's solids are read
        why = (f"by the wall-clock budget (--max-wall {max_wall:g} s)" if spent.startswith(WALL) else f"({spent})")
        return None, [_not_checked(f"collision checks cut short {why}: 0 of {len(motion.motions)} motions checked",
                                   0.0, app_path)]
    try:
        arm = arm_model(model)
        if geometries:
            arm, epochs = _geometry_epochs(model, geometries)
    except RobotError as exc:
        return None, [_not_checked(f"collisions not checked: the collision solids of {name} cannot be read: {exc}",
                                   motion.end_s, app_path)]
    if not arm.bodies and (cell is None or not (cell.tools or cell.parts)):
        return None, [_not_checked(f"collisions not checked: the arm model {name} has no collision solids, and no "
                                   "cell gives tool solids or parts", motion.end_s, app_path)]
    log = TimelineLog(cell, watch, motion, app_unit_mm) if cell is not None else None  # what the reports draw
    checker = CollisionChecker(arm, cell if cell is not None else Cell(path=""),
                               frames=log.frame if log else watch.frame, tools=log.tool if log else watch.tool,
                               app_unit_mm=app_unit_mm, readings=watch.reading)
    run = CollisionRun(cell, cell_path, cell_found, margin_mm=checker.margin)
    diags: list[Diagnostic] = []
    traj = motion.trajectory
    spans = _spans(motion)
    events = _events(motion.tool_events, cell, io_log, link_names or {})
    names = _tool_names(cell)
    position = Positions(traj)
    joints_at = position.each(e[0] / US for e in events if not isinstance(e[2], str))  # the grippers' events, in order
    clocks = own_clocks(traj, ((start, end) for _, start, end in spans))  # a repeat is checked once
    ev = 0
    ongoing: set[tuple[str, str]] = set()  # pairs in contact since the last motion free of contact

    def event(e) -> list[Diagnostic]:
        t, e = e[0] / US, e[2]
        q = None
        if isinstance(e, str):
            checker.clear_parts(e)
            found = []
        else:
            q = next(joints_at)  # the arm's joints at t: for the checks and for the parts' spans
            found = _gripper(checker, e, names, q, run)
        if log is not None:
            log.after(checker, t, q)
        return found

    deadline = time.monotonic() + max_wall

    def cut(done: int, start: float) -> bool:  # the budgets spent: R037, and no more checks
        spent = out_of_budget() if out_of_budget is not None else None
        if spent is None and time.monotonic() <= deadline:
            return False
        why = (f"by the wall-clock budget (--max-wall {max_wall:g} s)" if spent is None or spent.startswith(WALL)
               else f"({spent})")
        diags.append(_not_checked(f"collision checks cut short {why}: {done} of {len(spans)} motions checked, "
                                  f"up to {start:.3f} s", start, app_path))
        return True

    for done, (index, start, end) in enumerate(spans):
        if on_motion is not None:
            on_motion(done, len(spans))
        # read every BUDGET_EVERY motions and before each sweep: a reused check costs microseconds,
        # less than the reading (the memory's is a read of /proc)
        if not done % BUDGET_EVERY and cut(done, start):
            events = events[:ev]
            break
        while ev < len(events) and events[ev][0] / US <= start + 1e-9:
            diags.extend(event(events[ev]))
            ev += 1
        rec = motion.motions[index]
        if epochs is not None:
            epochs.at(start)
        own = next(clocks)  # sampled from the motion's start
        span = _Span(index, rec)
        report = checker.reuse(span, start, own.key)
        if report is None:
            if done % BUDGET_EVERY and cut(done, start):
                events = events[:ev]
                break
            q_at = own.q_at
            if hasattr(q_at, "many"):  # the samples and the mid-steps (the motion bound) in one evaluation
                T = own.times
                joints, mids = samples_and_mids(q_at, T)
                report = checker.check_own(span, start, T, joints, q_at=q_at, key=own.key, mids=mids)
            else:
                report = checker.check_own(span, start, own.times, own.joints, q_at=q_at, key=own.key)
        run.by_motion[index] = report
        own_report = getattr(report, "own", report)  # a ShiftedReport's fields are computed when read
        if not own_report.contacts and own_report.starts_in_collision is None and not own_report.too_close:
            ongoing = set()  # no finding, no contact: what follows reads the same
            continue
        contacts = report.contacts
        diags.extend(_motion_findings(report, rec, ongoing, checker.margin))
        run.contacts.extend((index, c) for c in contacts)
        now = {(c.body_a, c.body_b) for c in contacts}
        if own_report.starts_in_collision is not None:
            first = report.starts_in_collision
            now.add((first.body_a, first.body_b))
        ongoing = ongoing | now if now else set()
    while ev < len(events):
        diags.extend(event(events[ev]))
        ev += 1
    for p in checker.problems:
        w = p.where
        path, line, col = (w.path, w.line, w.column) if w is not None else (cell_path or "", 0, 0)
        diags.append(Diagnostic(codes.CELL_FRAME_WITHOUT_VALUE, p.message, path, line, col, time_us=int(round(p.time * US)), task="",
                                program=""))
    run.checks, run.reused = checker.measurements, checker.reused
    if log is not None:
        motion.cell_timeline = log.timeline()
    return run, diags


class _GeometryEpochs:
    """The arm's links under each geometry of the run (setDH, 11.4), the one in force chosen motion by
    motion (`at`); the motion bound holds for all of them."""

    def __init__(self, epochs: list) -> None:
        self.epochs = epochs  # [(from time, links)], in time order
        self.current = epochs[0][1]

    def at(self, t: float) -> None:
        for start, links in self.epochs:
            if start <= t + 1e-9:
                self.current = links

    def __getattr__(self, name):
        return getattr(self.current, name)

    def reach_from_joint(self, link: str) -> dict[int, float]:
        out: dict[int, float] = {}
        for _, links in self.epochs:
            for k, r in links.reach_from_joint(link).items():
                out[k] = max(out.get(k, 0.0), r)
        return out


def _geometry_epochs(model: Any, geometries) -> tuple[Any, _GeometryEpochs]:
    """An arm of its own (not the shared one of `arm_model`) whose links follow the geometries."""
    from ..collision.armmodel import ArmModel
    from ..robot.links import arm_links

    arm = ArmModel(model)
    epochs = _GeometryEpochs([(-math.inf, arm.links), *((t, arm_links(m)) for t, m in geometries)])
    arm.links = epochs
    return arm, epochs


def _not_checked(message: str, end_s: float, path: str) -> Diagnostic:
    return Diagnostic(codes.COLLISIONS_NOT_CHECKED, message, path, 0, 0, time_us=int(round(end_s * US)), task="", program="")


def _events(tool_events, cell: Cell | None, io_log, link_names: dict) -> list[tuple[int, int, Any]]:
    """(time_us, order, event) in time order: the grippers' ToolEvents, and the part names whose
    `cleared_by` signal became true (a dio named or linked so)."""
    out: list[tuple[int, int, Any]] = [(e.time_us, k, e) for k, e in enumerate(tool_events)]
    clear: dict[str, list[str]] = {}
    for p in cell.parts if cell is not None else ():
        if p.cleared_by and p.name not in clear.setdefault(p.cleared_by, []):
            clear[p.cleared_by].append(p.name)
    if clear:
        n = len(out)
        for e in io_log:
            if e.kind != "dio" or e.value is not True:
                continue
            for key in (e.link, *link_names.get(("dio", e.link), ())):
                for name in clear.get(key, ()):
                    out.append((e.time_us, n, name))
                    n += 1
    out.sort(key=lambda x: (x[0], x[1]))
    return out


def _spans(motion: Any) -> list[tuple[int, float, float]]:
    """(record index, start, end) of every command the arm ran, in time order (stop() may move the
    arm after the run's end); a command not ended ends where the next one starts, or at the end of
    the run."""
    started = [(r.start, i) for i, r in enumerate(motion.motions) if r.start is not None]
    started.sort()
    out = []
    for k, (start, i) in enumerate(started):
        end = motion.motions[i].end
        if end is None:
            end = started[k + 1][0] if k + 1 < len(started) else max(motion.end_s, start)
        out.append((i, start, max(end, start)))
    return out


@functools.lru_cache(maxsize=256)
def _file_name(path: str) -> str:
    return Path(path).name


class _Span:
    """The `MotionSpan` of a motion record, its label made when read (a run keeps one per motion;
    the record itself is not held)."""

    __slots__ = ("id", "source", "kind", "target")

    def __init__(self, index: int, rec: Any) -> None:
        self.id = index
        self.source, self.kind, self.target = rec.source, rec.kind, rec.target

    @property
    def label(self) -> str:
        return _label(self)


def _label(rec: Any) -> str:
    where = f"{_file_name(rec.source.path)}:{rec.source.line}"
    return f"{rec.kind} {rec.target} ({where})" if rec.target else f"{rec.kind} ({where})"


def _tool_names(cell: Cell | None) -> dict[str, str]:
    """Tool names of the program's events ("tGripper") -> as the cell writes them ("tGripper[0]")."""
    out: dict[str, str] = {}
    if cell is None:
        return out
    for p in cell.parts:
        m = _NAME.match(p.tool)
        if m and not m.group(1) and int(m.group(3) or 0) == 0:
            out.setdefault(m.group(2), p.tool)
        out.setdefault(p.tool, p.tool)
    return out


def _gripper(checker: CollisionChecker, e: Any, names: dict[str, str], q: np.ndarray,
             run: CollisionRun) -> list[Diagnostic]:
    tool = names.get(e.tool)
    if tool is None:
        return []
    t = e.time_us / US
    drops = checker.gripper(tool, e.action, t, joints=q, source=e.position)
    run.drops.extend(drops)
    out = []
    path, line, col, program = e.position
    for d in drops:
        depth = f", {d.depth_mm:.1f} mm deep" if d.depth_mm is not None else ", inside it"
        out.append(Diagnostic(codes.PART_LEFT_IN_COLLISION, f"{e.action}({e.tool}) leaves {d.part} in {d.obstacle}{depth}, at "
                              f"{_pt(d.point)}", path, line, col, time_us=e.time_us, task=e.task, program=program))
    return out


def _pt(p) -> str:
    return "({:.1f}, {:.1f}, {:.1f}) mm".format(*p)


def _contact_text(c: Contact) -> str:
    """The first contact of a pair: where it starts (its depth there is the touch tolerance found
    by the search, not the deepest overlap: left out); a motion's first sample: how deep."""
    if c.kind == "inside":
        how = f"is inside {c.body_b}"
    else:
        how = f"hits {c.body_b}"
    depth = ""
    if c.depth_mm is not None and c.kind != "inside" and c.depth_mm >= 0.5:
        depth = f", {c.depth_mm:.1f} mm deep"
    return f"{c.body_a} {how} at {c.time:.3f} s{depth}, at {_pt(c.point)}"


def _motion_findings(r: MotionReport, rec: Any, ongoing: set[tuple[str, str]], margin: float) -> list[Diagnostic]:
    """R031-R034 of one motion; `ongoing`: pairs in contact in the motions before it, since the last
    one free of contact (a motion starting in such a contact goes on with it: said there)."""
    src = rec.source
    out = []

    def diag(code: str, message: str, time: float) -> None:
        out.append(Diagnostic(code, message, src.path, src.line, src.col, time_us=int(round(time * US)),
                              task=src.task, program=src.program))

    s = r.starts_in_collision
    if s is not None and (s.body_a, s.body_b) not in ongoing:
        code = codes.SELF_COLLISION if s.kind == "self" else codes.MOTION_STARTS_IN_COLLISION
        diag(code, f"{rec.kind} starts in collision: {_contact_text(s)}", s.time)
    for c in r.contacts:
        if s is not None and (c.body_a, c.body_b) == (s.body_a, s.body_b):
            continue
        if c.kind == "self":
            diag(codes.SELF_COLLISION, f"{rec.kind}: self-collision: {_contact_text(c)} (the arm's solids are envelopes: "
                 "check on the arm's own geometry)", c.time)
        else:
            diag(codes.COLLISION_WITH_CELL, f"{rec.kind}: {_contact_text(c)}", c.time)
    if r.too_close and r.min_clearance is not None:
        m = r.min_clearance
        diag(codes.NEAR_MISS, f"{rec.kind} comes {m.mm:.1f} mm from a collision (margin {margin:g} mm): {m.body_a} "
             f"and {m.body_b} at {m.time:.3f} s", m.time)
    return out
