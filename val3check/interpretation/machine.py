"""The virtual controller: what a run is made of, and the run itself (2.1.3).

A `Machine` holds the loaded units (the application and its libraries, units.py), the clock
(clock.py), the scheduler and its tasks (scheduler.py), the subsystems the scheduler asks
for the next moment anything changes (the cell and its scenario, io_cell.py; the arm's motion,
`val3check.motion`), the user page (user_page.py), the controller's state (controller.py),
the arm port (arm_port.py) and what the run records: diagnostics, the user page transcript
and the I/O log (recorder.py).

`val3check.simulation` assembles a machine (registry of instructions, arm, subsystems) and
runs it: `start()` runs in task "APP~"; the application ends when its last task ends, then
`stop()` runs in "~APP"; a run cut short is stopped as from the pendant. All times are
integer microseconds: runs are deterministic.
"""

from __future__ import annotations

import os
import time as _time
from dataclasses import dataclass
from sys import _getframe
from typing import Any, Callable, NamedTuple

from ..diagnostics import Diagnostic
from ..geometry.frames import kept, pose_values
from ..language.runtime_errors import RUNTIME_CODES, Val3RuntimeError
from ..lengths import app_mm
from ..loading.model import Application, Workspace
from ..rules import codes
from .clock import TICK_US, Clock
from .compiler import Compiled
from .compiler.legacy import array_parameters
from .controller import Controller, default_versions
from .deadlock import report_blocked
from .io_cell import Cell, CellSubsystem
from .libraries import autoload_libraries
from .memory import TypeSpace
from .memory_budget import MemoryBudget
from .not_simulated import ARM_LIMIT, SimLimit, arm_message, limit_code
from .recorder import IOEvent, Recorder, ToolEvent, TranscriptEntry
from .registry import Registry
from .scheduler import ERROR, HELD, START_PRIORITY, WAIT, EndRun, Scheduler, Task
from .system_io import SystemIO
from .units import Unit
from .user_page import UserPage
from .values import Arr, IOPoint, Screen
from .virtual_disk import VirtualDisk


@dataclass
class Budgets:
    duration_us: int = 60_000_000
    wall_s: float = 60.0
    max_lines: int = 50_000_000
    max_transcript: int = 10_000
    max_io_log: int = 100_000
    stop_us: int = 2_000_000  # simulated time left to stop() after a run is cut short
    max_memory_mb: float = 512.0  # growth of the process (memory_budget.py), loading included
    # the clock the wall budget reads, in seconds: tests give one of their own (a clock that
    # advances with each reading), so that what they check does not depend on the machine's speed
    wall_clock: Callable[[], float] = _time.monotonic
    # the share of wall_s the simulation itself may take: the rest is kept for what follows it (the
    # collision checks, the run's record, the reports: simulation/budget.py)
    run_share: float = 1.0

    def run_deadline(self, start: float) -> float:
        """When the simulation of a run that started at `start` (wall clock) must end."""
        return start + self.wall_s * self.run_share


class FinalState(NamedTuple):
    """What a task was doing when the run ended (before stop() and the destruction)."""

    state: str  # TaskState.report_name
    where: tuple | None  # (path, line, col, program)
    blocked_on: str | None
    loops: tuple = ()  # the loops it was in (Machine.loop_passes)


_TURN = Scheduler._turn.__code__  # where the scheduler resumes a task: no program runs below it


class Machine:
    def __init__(self, ws: Workspace, app: Application, registry: Registry, arm: Any, *,
                 budgets: Budgets | None = None, disk_roots: list[str] | None = None) -> None:
        self.ws = ws
        self.app = app
        self.registry = registry
        self.arm = arm  # the Arm port (arm_port.py), with or without an arm model
        self.budgets = budgets or Budgets()
        self.disk_roots = list(disk_roots or [])
        self.clock = Clock()
        self.scheduler = Scheduler(self, self.clock)
        self.wall_start = self.budgets.wall_clock()  # --max-wall covers loading and compiling too
        self.cell = Cell()
        self.cell.budget = MemoryBudget(self.budgets.max_memory_mb, clock=self._wall_check)
        # joint and config values have the fields of the arm's family (9.7.2; RX/TX without a model)
        self.cell.arm_family = getattr(arm, "type_family", "Rx") or "Rx"
        self.controller = Controller()
        self.controller.versions = default_versions(app.version, getattr(arm, "name", None))
        self.user_page = UserPage()
        self.recorder = Recorder(self.budgets.max_transcript, self.budgets.max_io_log, self._record_full)
        self.cell_subsystem = CellSubsystem(self.controller, self.log_io, self._cell_finding)
        self.scheduler.add_subsystem(self.cell_subsystem)
        self.diags: list[Diagnostic] = []
        self.compiled: dict[str, Compiled] = {}  # by the generated code's file name
        self.spaces: dict[str, TypeSpace] = {}
        self.units: dict[str, Unit] = {}  # loaded libraries by resolved path
        self.disk: dict[str, Any] = {}  # simulated disk overlay: normalised path -> snapshot or None
        self.main: Unit | None = None
        self.link_names: dict[tuple[str, str], list[str]] = {}
        self.system_io = SystemIO(self)
        self._system_io_seen: set[tuple[str, str]] = set()
        self.end_reason = ""
        self.end_time = 0
        self.stopping = False  # stop() has been started
        self.progress: Any = None  # called now and then with the simulated time (µs): a progress display
        self.stop_task: Task | None = None
        self.destroyed: list[str] = []
        self._libraries_reported: set[str] = set()
        self._legacy_arrays: dict[str, dict[str, dict[str, int]]] = {}  # app path -> compiler/legacy.py
        self.analysis_cache: dict[str, dict] = {}  # what the deadlock report computes from the code
        self._outside_seen: set[tuple] = set()  # the lines already reported R041
        self.files = VirtualDisk()  # the controller's disk of the system library's file instructions
        self._tcps: dict[int, tuple] = {}  # `tool_action`: id(tool) -> (its chain, held; its TCP's six values)
        self.base_namespace = self._base_namespace()
        # the condition of every wait for the end of motion (waitEndMove, open, close): one
        # function for the run, not one made at each wait
        self.motion_done = lambda: arm.motion_done(self.clock.now)
        self.motion_done.motion = True  # the deadlock report asks the arm why (deadlock.py)
        self.scheduler.pure_cond = self.motion_done  # (it reads the arm and the clock only)

    def add_subsystem(self, subsystem: Any) -> None:
        """A `Subsystem` (subsystem.py) the scheduler advances and asks for its next event,
        after the cell."""
        self.scheduler.add_subsystem(subsystem)

    # ---- set-up -------------------------------------------------------------------------------

    def _base_namespace(self) -> dict[str, Any]:
        ns: dict[str, Any] = {"__builtins__": __builtins__}
        ns.update(self.registry.namespace())
        ns["WORLD"] = self.cell.world  # the roots of the frame and tool trees (9.4.1, 9.5.1)
        ns["FLANGE"] = self.cell.flange
        ns["ROOTS"] = {"world": self.cell.world, "flange": self.cell.flange}  # passed by reference
        return ns

    def space_for(self, app: Application) -> TypeSpace:
        sp = self.spaces.get(app.path)
        if sp is None:
            sp = TypeSpace(self.ws, app, self.cell, self.spaces)
            self.spaces[app.path] = sp
        return sp

    def system_io_for(self, model: Application, alias: str) -> SystemIO:
        key = (model.path, alias)
        if key not in self._system_io_seen:
            self._system_io_seen.add(key)
            self.system_io.infer(model, alias)
        return self.system_io

    def library_model(self, app: Application, alias: str) -> Application | None:
        return self.ws.library(app, alias)

    def legacy_arrays(self, app: Application) -> dict[str, dict[str, int]]:
        """The s6 by-reference parameters an application's programs use as arrays
        (compiler/legacy.py), computed once per application."""
        found = self._legacy_arrays.get(app.path)
        if found is None:
            found = self._legacy_arrays[app.path] = array_parameters(app)
        return found

    def load_main(self) -> Unit:
        unit = Unit(self, self.app, "Disk://" + self.app.name)
        unit.init_globals()
        unit.build()
        self.main = unit
        for d_name, d in self.app.data.items():
            c = unit.globals[d_name]
            if d.type.lower() in ("dio", "aio", "sio") and type(c) is Arr:
                for i, io in enumerate(c.data):
                    if type(io) is IOPoint and io.link:
                        label = d_name if len(c.data) == 1 else f"{d_name}[{i}]"
                        self.link_names.setdefault((io.kind, io.link), []).append(label)
        autoload_libraries(self, unit)
        return unit

    # ---- what the run records -----------------------------------------------------------------

    def transcript_add(self, task: Task | None, kind: str, text: str, scr: Screen | None) -> None:
        if not self.recorder.transcript_room(task):
            return
        screen = None if scr is None or scr is self.user_page.default else scr.name
        self.recorder.transcript.append(TranscriptEntry(self.clock.time_of(task), task.name if task else "", kind, text,
                                                       screen))

    def log_io(self, at: int, io: IOPoint, value: Any, source: str) -> None:
        if self.recorder.io_room(self.clock.current):
            self.recorder.io_log.append(IOEvent(at, io.kind, io.link, value, source))

    def _record_full(self, message: str, task: Task | None) -> None:
        """A record budget is reached: said once (R006), the run goes on without recording."""
        self.diags.append(Diagnostic(codes.BUDGET_EXCEEDED, message, self.app.path, 0, 0,
                                     time_us=self.clock.time_of(task) if task is not None else self.clock.now,
                                     task=task.name if task is not None else "", program=""))

    def _cell_finding(self, diagnostic: Diagnostic) -> None:
        """A finding of the cell (R008), at the scenario file, else at the application."""
        if not diagnostic.path:
            diagnostic = Diagnostic(diagnostic.code, diagnostic.message, self.app.path, diagnostic.line, diagnostic.col,
                                    time_us=diagnostic.time_us, task=diagnostic.task, program=diagnostic.program)
        self.diags.append(diagnostic)

    def tool_action(self, task: Task, action: str, tool: Any, millimeter_unit: bool) -> None:
        """open()/close() of `tool` (9.5.4), recorded with the tool's centre point in the flange."""
        if len(self.recorder.tool_events) >= self.recorder.max_io_log:
            return
        x, y, z, rx, ry, rz = kept(self._tcps, tool, pose_values)  # (computed again only when the tool changed)
        s = app_mm(millimeter_unit)
        grip = getattr(tool.gripper, "link", "") or ""
        where = self.line_running()
        self.recorder.tool_events.append(ToolEvent(
            self.clock.time_of(task), task.name, action, tool.name or "", grip,
            (x * s, y * s, z * s, rx, ry, rz), where or (self.app.path, 0, 0, task.program)))

    def output_changed(self, task: Task, io: IOPoint) -> None:
        self.cell_subsystem.output_changed(io, self.clock.time_of(task), task.name)

    def sio_sent(self, task: Task, io: IOPoint, data: bytes) -> None:
        self.cell_subsystem.sio_sent(io, data, self.clock.time_of(task), task.name)

    # ---- diagnostics ----------------------------------------------------------------------------

    def add_diag(self, code: str, message: str, task: Task | None, pos, error: int | None) -> None:
        path, line, col, program = self.app.path, 0, 0, ""
        if pos is not None:
            compiled, lc = pos
            path = compiled.path
            program = compiled.name
            if lc is not None:
                line, col = lc
        if task is not None:
            task.errpos = (path, line, col, program)
        self.diags.append(Diagnostic(code, message, path, line, col,
                                     time_us=self.clock.time_of(task) if task is not None else self.clock.now,
                                     task=task.name if task is not None else "", program=program, error=error))

    def task_failed(self, task: Task, e: BaseException, skippable: bool) -> None:
        """A line raised: stop the task there (5.2) and record a runtime diagnostic."""
        tb = e.__traceback__
        pos = None
        if tb is not None:
            c = self.compiled.get(tb.tb_frame.f_code.co_filename)
            if c is not None:
                pos = (c, c.pos.get(tb.tb_lineno))
        task.skippable = skippable
        task.jump = 0
        if isinstance(e, SimLimit):
            task.state = HELD
            task.limit = e.kind
            code = limit_code(e.kind)
            if e.message:
                msg = e.message
            elif e.kind == ARM_LIMIT:
                msg = arm_message(e.what, self.arm.name)
            else:
                msg = f"not simulated: {e.what}"
            self.add_diag(code, msg, task, pos, None)
            task.errdetail = msg
            return
        code, detail = _error_code(e)
        task.state = ERROR
        task.error = code
        task.errdetail = detail
        text = RUNTIME_CODES.get(code, "runtime error")
        extra = f" ({detail})" if detail and detail not in text else ""
        rule = getattr(e, "rule", None)
        if rule:  # a motion instruction's error has the rule of its cause (R017 mdesc, R015 movec...)
            self.add_diag(rule, f"error {code}: {detail}", task, pos, code)
        else:
            self.runtime_error(task, pos, code, f"{text}{extra}")

    def runtime_error(self, task: Task | None, pos, code: int, message: str) -> None:
        """A task stopped by the runtime error `code` of 12.1 (R001)."""
        self.add_diag(codes.RUNTIME_ERROR, f"error {code}: {message}", task, pos, code)

    def library_failed(self, owner: Unit, alias: str, display: str, code: int, meaning: str, findings: list,
                       task: Task | None) -> None:
        """A library could not be loaded (6.6): why is kept for the error 80 of its uses; when
        its own files are invalid, their first finding is reported, once per library (R040)."""
        when = "at start" if task is None else f"by libLoad in task {task.name}"
        first = findings[0] if findings else None
        where = ""
        if first is not None:  # the path as from the folder that holds the applications (Disk://)
            disk = os.path.dirname(os.path.dirname(os.path.abspath(self.app.path)))
            where = f": {first.code} at {os.path.relpath(first.path, disk)}:{first.line}:{first.col}"
        owner.load_failures[alias] = f"loading {display} {when} returned {code}, {meaning}{where}"
        if first is None or display in self._libraries_reported:
            return
        self._libraries_reported.add(display)
        more = f" (and {len(findings) - 1} more finding(s) in the library)" if len(findings) > 1 else ""
        self.diags.append(
            Diagnostic(
                codes.LIBRARY_NOT_LOADED,
                f"library {display} (identifier {alias} of {owner.name}) cannot be loaded because of this "
                f"{first.code} finding: {first.message}{more}; libLoad returns {code} and the data and "
                f"programs of {alias}: are error 80 where they are used",
                first.path,
                first.line,
                first.col,
                time_us=self.clock.time_of(task) if task is not None else self.clock.now,
                task=task.name if task is not None else "",
                program="",
            )
        )

    def note_outside(self, task: Task, message: str) -> None:
        """R041 (info): the line running acts on something outside the simulation; said once per
        line of code."""
        where = self.line_running()
        path, line, col, program = where or (self.app.path, 0, 0, task.program)
        key = (path, line, col)
        if key in self._outside_seen:
            return
        self._outside_seen.add(key)
        self.diags.append(Diagnostic(codes.OUTSIDE_THE_SIMULATION, message, path, line, col, time_us=self.clock.time_of(task),
                                     task=task.name, program=program))

    def report_overrun(self, task: Task) -> None:
        """R005: a synchronous task used more than its period (5.6)."""
        w = self.where(task)
        path, line, col = (self.app.path, 0, 0) if w is None else w[:3]
        self.diags.append(Diagnostic(codes.SYNC_OVERRUN, f"synchronous task {task.name} overran its period of "
                                     f"{task.period / 1e6:g} s", path, line, col, time_us=self.clock.now,
                                     task=task.name, program=task.program))

    # ---- where a task is ------------------------------------------------------------------------

    def val3_frames(self, task: Task):
        """(compiled program, Python line) of each VAL 3 program the task is in, outermost first."""
        g = task.gen
        compiled = self.compiled
        while g is not None:
            code = getattr(g, "gi_code", None)
            frame = getattr(g, "gi_frame", None)
            if code is not None and frame is not None and code.co_filename in compiled:
                c = compiled[code.co_filename]
                yield c, c.line_of(frame)
            g = getattr(g, "gi_yieldfrom", None)

    def loop_passes(self, task: Task | None = None) -> tuple:
        """The loops the running line (or the suspended `task`) is in, outermost first, across the
        programs of its call stack: (compiled program, compiler.structures.LoopSite, the loop's
        pass counter: a list, new at each entry of the loop, whose [0] is the current pass)."""
        compiled = self.compiled
        if task is None and self.clock.current is not None:  # the running task's own list (Task.frames)
            frames = [(compiled[f.f_code.co_filename], f) for f in self.clock.current.frames]
        elif task is None:
            frames = []
            f = _getframe(1)
            while f is not None and f.f_code is not _TURN:  # (below a task's turn: the scheduler, no program)
                c = compiled.get(f.f_code.co_filename)
                if c is not None:
                    frames.append((c, f))
                f = f.f_back
            frames.reverse()
        else:
            frames = self._task_frames(task)
        out = []
        for c, f in frames:
            sites = c.at(f)[1]
            if sites:  # (only then are the frame's locals read: they are a dict made for the asking)
                local = f.f_locals
                out.extend((c, site, local[site.var]) for site in sites if site.var in local)
        return tuple(out)

    def _task_frames(self, task: Task):
        """(compiled program, frame) of each VAL 3 program a suspended task is in, outermost first."""
        g = task.gen
        compiled = self.compiled
        while g is not None:
            code = getattr(g, "gi_code", None)
            frame = getattr(g, "gi_frame", None)
            if code is not None and frame is not None and code.co_filename in compiled:
                yield compiled[code.co_filename], frame
            g = getattr(g, "gi_yieldfrom", None)

    def line_running(self) -> tuple[str, int, int, str] | None:
        """The file position of the VAL 3 line being executed now, for an instruction handler
        (the innermost program on the Python stack; `where` only sees suspended tasks)."""
        compiled = self.compiled
        running = self.clock.current
        if running is not None:  # its programs' frames (Task.frames): no walk up the Python stack
            for f in reversed(running.frames):
                w = compiled[f.f_code.co_filename].at(f)[0]
                if w is not None:
                    return w
            return None
        f = _getframe(1)
        while f is not None:
            c = compiled.get(f.f_code.co_filename)
            if c is not None:
                w = c.at(f)[0]
                if w is not None:
                    return w
            f = f.f_back
        return None

    def where(self, task: Task) -> tuple[str, int, int, str] | None:
        """The file position of the line a task is at (innermost VAL 3 program)."""
        found = None
        for c, lineno in self.val3_frames(task):
            lc = c.pos.get(lineno)
            if lc is not None:
                found = (c.path, lc[0], lc[1], c.name)
        return found

    def suspended_position(self, task: Task) -> tuple | None:
        """The sequence position (sequence, index, length) of the line a suspended task is at
        (innermost program), for taskResume's jumps."""
        found = None
        for c, lineno in self.val3_frames(task):
            found = c.bpos.get(lineno)
        return found

    @staticmethod
    def blocked_on(task: Task) -> str:
        return task.waiting_for or task.state.value

    # ---- the run (2.1.3) ----------------------------------------------------------------------

    def start(self) -> None:
        start = self.main.program("start")
        if start is None:
            raise EndRun("no-start")
        task = Task(self, f"{self.app.name}~", self.main, "start", START_PRIORITY)  # 5.2: start() in "APP~"
        task.gen = start.func(task)
        self.scheduler.add(task)

    def _wall_check(self) -> None:
        if self.budgets.wall_clock() > self.budgets.run_deadline(self.wall_start):
            raise EndRun("wall-clock")

    def check_load_budgets(self) -> None:
        """While the application is loaded and compiled: the wall-clock and memory budgets."""
        self._wall_check()
        why = self.cell.budget.over()
        if why:
            raise EndRun("budget:" + why)

    def run(self) -> None:
        self.start()
        try:
            self.scheduler.loop(self.budgets.duration_us)
            reason = "ended"
        except EndRun as stop:
            reason = stop.reason
        self.end_reason = reason
        # the run ends after the last line of the cycle it ended in (never before a time reported in it)
        self.end_time = self.clock.end_of_cycle() if reason in ("deadlock", "stalled", "cycles") else self.clock.now
        self._snapshot_tasks()
        if reason == "stop-timeout":
            # the application ended and its stop() was still running at --duration: the run
            # reached its duration (R007), and stop() did not end (R006)
            self.end_reason = reason = "duration"
            self._stop_did_not_end(f"still running at --duration {self.budgets.duration_us / 1e6:g} s")
        if reason == "deadlock":
            report_blocked(self)
        else:
            self._report_motion_waits()
        if reason not in ("ended", "wall-clock"):
            self._stop_after(reason)
        self._destroy_remaining()

    def _snapshot_tasks(self) -> None:
        """What each live task was doing when the run ended (before stop() and destruction)."""
        for task in self.scheduler.tasks:
            stopped = task.state is ERROR or task.state is HELD
            where = self.where(task) if not stopped else None
            if stopped and task.errpos:
                where = task.errpos
            task.final = FinalState(
                task.state.report_name,
                where,
                self.blocked_on(task) if task.state is WAIT else None,
                self.loop_passes(task),
            )

    def motion_reason(self, task: Task) -> tuple[str, str] | None:
        """(rule, why) when the task waits for the arm's motion and the arm cannot move."""
        if task.state is not WAIT or not getattr(task.cond, "motion", False):
            return None
        return self.arm.waiting_reason()

    def _report_motion_waits(self) -> None:
        """At the end of a run that did not end in a deadlock: the tasks still waiting for a
        motion that power never allows (R018)."""
        for task in self.scheduler.tasks:
            why = self.motion_reason(task)
            if why is None or why[0] != codes.MOTION_WITHOUT_POWER:
                continue
            w = self.where(task)
            path, line, col, prog = w if w else (self.app.path, 0, 0, task.program)
            self.diags.append(
                Diagnostic(
                    codes.MOTION_WITHOUT_POWER,
                    f"task {task.name} waits in {self.blocked_on(task)} for a motion that cannot happen: {why[1]}",
                    path,
                    line,
                    col,
                    time_us=self.clock.now,
                    task=task.name,
                    program=prog,
                )
            )

    def _stop_after(self, reason: str) -> None:
        """As when the application is stopped from the pendant (2.1.3, 5.2): the start task is
        destroyed, stop() runs, then the remaining tasks are destroyed."""
        if self.stopping:
            return
        for t in list(self.scheduler.tasks):
            if t.unit is self.main and t.name == f"{self.app.name}~":
                self.scheduler.kill(t)
                t.end_state = "destroyed"
        if reason in ("deadlock", "stalled", "cycles") and self.clock.cycle_lines:
            # the run ended in a cycle that ran lines: stop() starts at the next cycle, so that
            # its times follow those of the run
            self.clock.now += TICK_US
            self.clock.cycle_lines = 0
        self.start_stop_program()
        limit = self.clock.now + self.budgets.stop_us
        try:
            self.scheduler.loop(limit, stopping=True)
        except EndRun as extra:
            what = {
                "stop-timeout": f"still running {self.budgets.stop_us / 1e6:g} s after the run was stopped",
                "deadlock": "blocked",
            }.get(extra.reason, extra.reason)
            self._stop_did_not_end(what)

    def _stop_did_not_end(self, what: str) -> None:
        """R006 at the line where stop() is, when it is still alive (not stopped on an error)."""
        task = self.stop_task
        if task is not None and task in self.scheduler.tasks and task.state is not ERROR and task.state is not HELD:
            w = self.where(task)
            path, line, col, prog = w if w else (self.app.path, 0, 0, "stop")
            self.diags.append(
                Diagnostic(
                    codes.BUDGET_EXCEEDED,
                    f"stop() did not end: {what}",
                    path,
                    line,
                    col,
                    time_us=self.clock.now,
                    task=task.name,
                    program=prog,
                )
            )

    def start_stop_program(self) -> None:
        stop = self.main.program("stop")
        self.stopping = True
        if stop is None:
            return
        task = Task(self, f"~{self.app.name}", self.main, "stop", START_PRIORITY)  # 5.2: stop() in "~APP"
        task.created = self.clock.now
        task.gen = stop.func(task)
        self.scheduler.add(task)
        self.stop_task = task

    def _destroy_remaining(self) -> None:
        """2.1.3: remaining tasks are destroyed in the reverse order of their creation."""
        for t in sorted(self.scheduler.tasks, key=lambda x: x.seq, reverse=True):
            self.destroyed.append(t.name)
            t.end_state = t.end_state or "destroyed"
            self.scheduler.kill(t)
            t.end_state = "destroyed" if t.end_state == "killed" else t.end_state

    def stop_done(self) -> bool:
        task = self.stop_task
        return task is None or task not in self.scheduler.tasks or task.state is ERROR or task.state is HELD


def _error_code(e: BaseException) -> tuple[int, str]:
    if isinstance(e, Val3RuntimeError):
        return e.code, e.detail
    if isinstance(e, ZeroDivisionError):
        return 10, "division by zero"
    if isinstance(e, (ValueError, OverflowError)):
        return 11, str(e)
    if isinstance(e, RecursionError):
        return 41, "call depth"
    if isinstance(e, MemoryError):
        return 40, str(e)
    if isinstance(e, EndRun):
        raise e
    return 61, f"{e.__class__.__name__}: {e}"
