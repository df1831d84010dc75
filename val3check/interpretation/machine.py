"""The virtual controller: units (application and libraries), tasks, clock and scheduler.

Time (docs/sim.md): the controller's 4 ms cycle is the clock's tick. In a cycle, the
inputs are refreshed (scenario events, 5.7), the synchronous tasks that are due run (up to
3000 lines each, 5.5), then the asynchronous tasks take turns in creation order, each
running as many lines as its priority (5.4), round after round, until every task waits or the
cycle's line budget (`LINES_PER_CYCLE`, i.e. a simulated cost of 4 µs per line) is spent;
then the clock moves on. When every task waits (delay, wait, watch, get, sio, setMutex),
the clock jumps straight to the next event that could change something: the end of a delay or
a watch, a scenario event, a reaction, a synchronous task's period. When there is none, the
application is deadlocked and the run ends with every blocked task reported.
All times are integer microseconds: runs are deterministic.
"""

from __future__ import annotations

import heapq
import re
import time as _time
from dataclasses import dataclass, field
from typing import Any

from ..loading.model import Application, Container, Workspace
from ..parsing.parser import parse_program
from . import runtime as rt
from .compiler import Compiled, compile_program
from .errors import RUNTIME_CODES, Val3RuntimeError
from .instructions import TABLE
from .libraries import SystemIO, is_system_io
from .geom import NAMESPACE as GEOM_NAMESPACE
from .geom import NO_ARM, Arm
from .memory import Cell, TypeSpace, resolve_fathers
from .memory_budget import MemoryBudget
from .values import Arr, Coll, IOPoint, Screen, copy_globals, store

TICK_US = 4000  # the controller's cycle (4 ms)
LINES_PER_CYCLE = 1000  # simulated cost: 4 µs per VAL 3 line
LINE_US = TICK_US // LINES_PER_CYCLE
SYNC_LINES = 3000  # 5.5: up to 3000 lines per sequencing of a synchronous task
MAX_REACTIONS_PER_CYCLE = 10_000  # a scenario reaction firing more often within 4 ms is a loop (R008)
START_PRIORITY = 10  # 5.2
MAX_TASKS = 200
TASK_NAME = re.compile(r"^[A-Za-z0-9_]{1,15}$")


class EndRun(BaseException):
    def __init__(self, reason: str) -> None:
        super().__init__(reason)
        self.reason = reason


@dataclass
class Budgets:
    duration_us: int = 60_000_000
    wall_s: float = 60.0
    max_lines: int = 50_000_000
    max_transcript: int = 10_000
    max_io_log: int = 100_000
    stop_us: int = 2_000_000  # simulated time left to stop() after a run is cut short
    max_memory_mb: float = 512.0  # growth of the process (memory_budget.py), loading included


@dataclass
class Key:
    at: int
    code: int
    text: str | None = None
    hold: int = 200_000


@dataclass
class Controller:
    """Chapter 8 state, set by the scenario's [controller] table (docs/scenario.md)."""

    working_mode: int = 4
    working_state: int = 0
    es_status: int = 0
    powered: bool = False
    power_delay_us: int = 500_000
    calibrated: bool = True
    monitor_speed: float = 100.0
    operator_speed: bool = False
    safety_fault: str = ""
    profile: str = "default"
    profiles: dict[str, str] = field(default_factory=dict)
    language: str = "english"
    languages: tuple[str, ...] = ("francais", "english", "deutsch", "italiano", "espanol")
    date: Any = None
    versions: dict[str, str] = field(default_factory=lambda: {"VAL 3": "s7.11 - val3check simulator"})


class Task:
    __slots__ = ("name", "unit", "prio", "period", "gen", "state", "q", "stack", "smax", "wake", "tdep", "error",
                 "errdetail", "errpos", "program", "created", "ended", "order", "M", "jump", "skippable",
                 "overrun", "next_run", "overran", "limit", "end_state", "lines", "seq", "saved", "final",
                 "jumpctx", "pending", "cond")

    def __init__(self, M, name: str, unit, program: str, prio: int, period: int = 0) -> None:
        self.M = M
        self.name = name
        self.unit = unit
        self.program = program
        self.prio = prio
        self.period = period  # µs, > 0 for a synchronous task
        self.gen = None
        self.state = "ready"
        self.q = 0
        self.stack = 0
        self.smax = unit.model.stack_size or 5000
        self.wake: int | None = None
        self.tdep = False
        self.error = 0  # VAL 3 code while stopped on an error
        self.errdetail = ""
        self.errpos: tuple | None = None
        self.created = M.now
        self.ended: int | None = None
        self.order = 0
        self.jump = 0
        self.skippable = True
        self.overrun = None  # (container, key) of the sync task's bOverrun
        self.next_run = 0
        self.overran = False
        self.limit: str | None = None  # "arm"/"notsim" when held on a simulator limit
        self.end_state = ""
        self.lines = 0
        self.seq = 0
        self.saved: tuple | None = None
        self.final: dict | None = None
        self.jumpctx: tuple | None = None  # (sequence, index, length) of the line it stopped on
        self.pending: BaseException | None = None  # a taskResume jump to throw in at its next turn
        self.cond = None  # the condition of the wait/watch it is in (evaluated by the scheduler)


class Unit:
    """A loaded application: the started one or a library (chapter 6)."""

    _count = 0

    def __init__(self, machine: "Machine", model: Application, disk_path: str) -> None:
        Unit._count += 1
        self.uid = Unit._count
        self.machine = machine
        self.model = model
        self.disk_path = disk_path
        self.space = machine.space_for(model)
        self.aliases: dict[str, Any] = {a: None for a in model.libraries}
        for a in model.libraries:  # the controller's own I/O library is always there (io:...)
            if is_system_io(model, a, machine.ws):
                self.aliases[a] = machine.system_io_for(model, a)
        self.globals: dict[str, Any] = {}
        self.programs: dict[str, Compiled] = {}
        self.ns: dict[str, Any] = {}
        self.compile_errors: list = []

    @property
    def name(self) -> str:
        return self.model.name

    def init_globals(self, saved: dict[str, Any] | None = None) -> None:
        restored = copy_globals({n: saved[n] for n in self.model.data if n in saved}) if saved is not None else {}
        self.space.reserve_globals(d for n, d in self.model.data.items() if n not in restored)
        self.machine.cell.pending = []
        for name, d in self.model.data.items():
            if name in restored:
                self.globals[name] = restored[name]
            else:
                self.globals[name] = self.space.container(d)
        # frames, tools and points of the data file: linked to their fatherId (9.4.1)
        resolve_fathers(self.machine.cell, self.globals)
        for name in self.model.data:
            c = self.globals[name]
            if type(c) is Arr and c.t == "screen":  # the transcript names a screen by its variable
                for i, scr in enumerate(c.data):
                    if type(scr) is Screen and not scr.name:
                        scr.name = name if len(c.data) == 1 else f"{name}[{i}]"

    def build(self) -> None:
        M = self.machine
        ns = dict(M.base_ns)
        ns["A"] = self
        space = self.space
        # the compiled code's defaults are those of locals (no reference frame/tool, 9.4.1)
        ns["DEFAULT"] = lambda t, name="": space.default(t, True, name)
        ns["LOCAL"] = self._local
        ns["IODEF"] = lambda link: M.cell.io("dio", link)
        for name, c in self.globals.items():
            ns[f"g_{name}"] = c
            if type(c) is Arr:
                ns[f"d_{name}"] = c.data
        self.ns = ns
        for prog in self.model.programs.values():
            M.check_load_budgets()
            if prog.body is None and prog.code is not None:
                parse_program(prog)
            compiled = compile_program(self, prog, ns)
            self.programs[prog.name] = compiled
            M.compiled[compiled.filename] = compiled
            if compiled.error is not None:
                self.compile_errors.append(compiled)

    def _local(self, t: str, cont: str, sizes: tuple, name: str = "") -> Any:
        return self.space.local_container(t, Container.COLLECTION if cont == "COLLECTION" else Container.ARRAY, sizes,
                                          name)

    def program(self, name: str) -> Compiled | None:
        p = self.programs.get(name)
        if p is None:
            low = name.lower()
            p = next((c for n, c in self.programs.items() if n.lower() == low), None)
        return p

    def public_program(self, name: str) -> Compiled | None:
        p = self.program(name)
        if p is None:
            return None
        model = self.model.programs.get(p.name)
        return p if model is not None and model.access != "private" else None

    def public_global(self, name: str) -> Any:
        d = self.model.data.get(name)
        if d is None or d.access == "private":
            return None
        return self.globals.get(name)


@dataclass
class Diag:
    code: str
    message: str
    path: str
    line: int
    col: int
    time_us: int
    task: str
    program: str
    error: int | None = None


class Machine:
    def __init__(self, ws: Workspace, app: Application, *, budgets: Budgets | None = None, scenario=None,
                 disk_roots: list[str] | None = None, robot: Any = None) -> None:
        self.ws = ws
        self.app = app
        self.budgets = budgets or Budgets()
        self.disk_roots = list(disk_roots or [])
        self.cell = Cell()
        self.cell.budget = MemoryBudget(self.budgets.max_memory_mb, clock=self._wall_check)
        # the arm model (val3check.robot.RobotModel) and its commanded position, or None (geom.py)
        self.arm: Arm | None = Arm(robot) if robot is not None else None
        self.ctl = Controller()
        import datetime

        self.ctl.date = datetime.datetime(2000, 1, 1, 0, 0, 0)
        self.now = 0
        self.cycle_lines = 0
        self.turn_given = 0
        self.current: Task | None = None
        self.tasks: list[Task] = []  # live tasks, creation order
        self.history: list[Task] = []  # every task ever created
        self.events: list = []  # heap of (time, seq, kind, payload)
        self.seq = 0
        self.compiled: dict[str, Compiled] = {}
        self.spaces: dict[str, TypeSpace] = {}
        self.units: dict[str, Unit] = {}  # loaded libraries by resolved path
        self.disk: dict[str, Any] = {}  # simulated disk overlay: normalised path -> snapshot or None
        self.default_page = Screen("default")
        self.page = self.default_page
        self.transcript: list[tuple] = []
        self.io_log: list[tuple] = []
        self.diags: list[Diag] = []
        self.keys: list[Key] = []  # scripted key presses, in time order
        self.key_pos = 0
        self.key_last = -1
        self.key_seen = 0
        self.reactions: list = []  # (IOPoint, value, delay_us, [(IOPoint, value)])
        self.reaction_lines: list[int] = []  # the scenario line of each reaction (R008)
        self.scenario_path = ""
        self.sio_replies: list = []
        self.total_lines = 0
        self.end_reason = ""
        self.phase = "start"
        self.stop_task: Task | None = None
        self.wall_start = _time.monotonic()  # --max-wall covers loading and compiling too
        self.end_time = 0
        self.destroyed: list[str] = []
        self.base_ns = self._base_namespace()
        self.main: Unit | None = None
        self.link_names: dict[tuple[str, str], list[str]] = {}
        self.sync_periods: set[int] = set()
        self.full_logs: set[str] = set()
        self.system_io = SystemIO(self)
        self.system_io_seen: set[tuple[str, str]] = set()

    # ---- set-up -------------------------------------------------------------------------------

    def _base_namespace(self) -> dict[str, Any]:
        ns: dict[str, Any] = {"__builtins__": __builtins__}
        for name in ("E", "JUMP", "IX", "AI1", "AI2", "AI3", "CK", "CKW", "VIEW", "ELEMARR", "ASG", "CP", "MOD", "CAT", "DYN",
                     "IOR", "IOW", "FAIL", "YIELD", "DELAY", "WAIT", "WATCH",
                     "SETMUTEX", "PAGE", "GET", "SIOR", "SIOW", "SIZE", "SIZE2", "ISDEF", "INSERT", "DELETE", "APPEND",
                     "RESIZE", "CFIRST", "CLAST", "CNEXT", "CPREV", "BREF", "ARM", "NOTSIM"):
            ns[name] = getattr(rt, name)
        ns.update(TABLE)
        ns.update(GEOM_NAMESPACE)
        ns["WORLD"] = self.cell.world  # the roots of the frame and tool trees (9.4.1, 9.5.1)
        ns["FLANGE"] = self.cell.flange
        ns["LG"] = self.lib_global
        ns["LP"] = self.lib_program
        ns["LIBDEF"] = self.lib_defined
        ns["I_lib"] = self.lib_instruction
        ns["I_lib_now"] = self.lib_instruction_now
        ns["TASKCREATE"] = self.task_create
        ns["TASKCREATESYNC"] = self.task_create_sync
        ns["GETDATA"] = self.get_data
        return ns

    def space_for(self, app: Application) -> TypeSpace:
        sp = self.spaces.get(app.path)
        if sp is None:
            sp = TypeSpace(self.ws, app, self.cell, self.spaces)
            self.spaces[app.path] = sp
        return sp

    def system_io_for(self, model: Application, alias: str) -> SystemIO:
        key = (model.path, alias)
        if key not in self.system_io_seen:
            self.system_io_seen.add(key)
            self.system_io.infer(model, alias)
        return self.system_io

    def library_model(self, app: Application, alias: str) -> Application | None:
        return self.ws.library(app, alias)

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
        from .libraries import autoload_libraries

        autoload_libraries(self, unit)
        return unit

    # ---- time ---------------------------------------------------------------------------------

    def clock_us(self, T: Task | None = None) -> int:
        """Simulated time inside the cycle: cycle start + lines already run."""
        lines = self.cycle_lines
        if T is not None and T is self.current:
            lines += self.turn_given - max(T.q, 0)
        return self.now + min(lines, LINES_PER_CYCLE) * LINE_US

    def wake_time(self, T: Task, seconds: float) -> int:
        """The tick at which a wait of `seconds` started now ends (nearest tick, at least the next)."""
        target = self.clock_us(T) + int(round(seconds * 1_000_000))
        tick = (target + TICK_US // 2) // TICK_US
        return max(tick * TICK_US, self.now + TICK_US)

    def push_event(self, at: int, kind: str, payload: Any) -> None:
        self.seq += 1
        heapq.heappush(self.events, (at, self.seq, kind, payload))

    # ---- transcript and I/O log ---------------------------------------------------------------

    def transcript_add(self, T: Task | None, kind: str, text: str, scr: Screen | None) -> None:
        if len(self.transcript) >= self.budgets.max_transcript:
            self._log_full("transcript", f"the user page transcript is full ({self.budgets.max_transcript} entries): "
                           "later entries are not recorded (the page itself is still kept)", T)
            return
        screen = None if scr is None or scr is self.default_page else scr.name
        self.transcript.append((self.clock_us(T), T.name if T else "", kind, text, screen))

    def log_io(self, at: int, io: IOPoint, value: Any, source: str) -> None:
        if len(self.io_log) >= self.budgets.max_io_log:
            self._log_full("io_log", f"the I/O log is full ({self.budgets.max_io_log} events): later events are not "
                           "recorded", self.current)
            return
        self.io_log.append((at, io.kind, io.link, value, source))

    def output_changed(self, T: Task, io: IOPoint) -> None:
        now = self.clock_us(T)
        self.log_io(now, io, io.value, T.name)
        for watched, value, delay, actions in self.reactions:
            if watched is io and io.value == value:
                self.push_event(now + delay, "set", actions)

    def sio_sent(self, T: Task, io: IOPoint, data: bytes) -> None:
        if io.closed:
            raise Val3RuntimeError(125, f"{io.link} is closed")
        io.tx.extend(data)
        now = self.clock_us(T)
        self.log_io(now, io, sio_text(data), T.name)
        for target, pattern, delay, reply in self.sio_replies:
            if target is io and pattern.encode("utf-8") in bytes(io.tx):
                del io.tx[: bytes(io.tx).index(pattern.encode("utf-8")) + len(pattern.encode("utf-8"))]
                self.push_event(now + delay, "sio", (io, reply))

    def _log_full(self, which: str, message: str, T: Task | None) -> None:
        """A record budget is reached: said once (R006), the run goes on without recording."""
        if which in self.full_logs:
            return
        self.full_logs.add(which)
        self.diags.append(Diag("R006", message, self.app.path, 0, 0, self.clock_us(T) if T is not None else self.now,
                               T.name if T is not None else "", ""))

    def budget_exceeded(self, message: str) -> None:
        raise EndRun("budget:" + message)

    # ---- keys (4.3) ---------------------------------------------------------------------------

    def key_available(self) -> bool:
        return self.key_pos < len(self.keys) and self.keys[self.key_pos].at <= self.now

    def take_key(self) -> Key:
        k = self.keys[self.key_pos]
        self.key_pos += 1
        self.key_seen = max(self.key_seen, self.key_pos)
        return k

    def last_key(self) -> int:
        """getKey: the last key pressed since the previous call; keys read by get() count too."""
        code = -1
        while self.key_seen < len(self.keys) and self.keys[self.key_seen].at <= self.now:
            code = self.keys[self.key_seen].code
            self.key_seen += 1
        self.key_pos = max(self.key_pos, self.key_seen)
        return code

    def key_held(self, code: int) -> bool:
        now = self.now
        return any(k.code == code and k.at <= now < k.at + k.hold for k in self.keys)

    # ---- chapter 8 ----------------------------------------------------------------------------

    def set_power(self, T: Task, on: bool) -> None:
        if self.ctl.powered != on:
            self.ctl.powered = on
            self.transcript_add(T, "power", "on" if on else "off", None)

    def request_power(self, T: Task) -> None:
        """8.1 enablePower: no effect outside remote mode or with an emergency stop."""
        if self.ctl.working_mode != 4 or self.ctl.es_status != 0 or self.ctl.powered:
            self.transcript_add(T, "logMsg", "enablePower refused: not in remote mode or emergency stop", None)
            return
        self.push_event(self.clock_us(T) + self.ctl.power_delay_us, "power", True)

    # ---- tasks (chapter 5) --------------------------------------------------------------------

    def visible(self, unit: Unit) -> list[Task]:
        return [t for t in self.tasks if t.unit is unit]

    def find_task(self, unit: Unit, name: str) -> Task | None:
        """5.3: a task is only visible from the library or application that created it."""
        for t in self.tasks:
            if t.unit is unit and t.name == name:
                return t
        return None

    def status_code(self, T: Task) -> int:
        """taskStatus (5.10): 0 suspended, 1 running, or the runtime error code."""
        if T.state == "error":
            return T.error
        if T.state in ("stopped", "held"):
            return 0
        return 1

    def _new_task(self, creator: Task | None, unit: Unit, name: Any, program: Compiled, args: tuple,
                  prio: int, period: int, pname: str) -> Task:
        if type(name) is not str or not TASK_NAME.match(name):
            raise Val3RuntimeError(29, f"invalid task name {name!r}")
        if self.find_task(unit, name) is not None:
            raise Val3RuntimeError(31, f'a task "{name}" already exists')
        if len(self.tasks) >= MAX_TASKS:
            raise Val3RuntimeError(40, f"more than {MAX_TASKS} tasks")
        T = Task(self, name, unit, pname, prio, period)
        T.created = self.clock_us(creator)
        T.gen = program.func(T, *args)
        self.seq += 1
        T.seq = self.seq
        self.tasks.append(T)
        self.history.append(T)
        return T

    def task_create(self, creator: Task, unit: Unit, name: Any, prio: float, func, args: tuple, pname: str) -> None:
        """5.10 taskCreate: priority 1..100 (70 otherwise), name rules (29), unique (31)."""
        p = int(prio + 0.5) if prio >= 0 else -1
        if not 1 <= p <= 100:
            raise Val3RuntimeError(70, f"priority {prio!r} not in 1..100")
        program = self._compiled_of(func, pname)
        self._new_task(creator, unit, name, program, args, p, 0, pname)

    def task_create_sync(self, creator: Task, unit: Unit, name: Any, period: float, overrun, func, args: tuple,
                         pname: str) -> None:
        """5.10 taskCreateSync: the period is rounded down to a multiple of 4 ms; at most two
        different periods (32)."""
        ticks = int(period * 1_000_000 + 1e-6) // TICK_US
        if ticks < 1:
            raise Val3RuntimeError(70, f"period {period!r} is less than 4 ms")
        period_us = ticks * TICK_US
        live = {t.period for t in self.tasks if t.period}
        if period_us not in live and len(live) >= 2:
            raise Val3RuntimeError(32, "only two different periods of synchronous tasks")
        program = self._compiled_of(func, pname)
        T = self._new_task(creator, unit, name, program, args, SYNC_LINES, period_us, pname)
        T.overrun = overrun
        T.next_run = (self.clock_us(creator) // TICK_US + 1) * TICK_US

    def _compiled_of(self, func, pname: str) -> Compiled:
        c = self.compiled.get(func.__code__.co_filename)
        if c is None:  # pragma: no cover - every function comes from compile_program
            raise Val3RuntimeError(61, f"unknown program {pname}")
        return c

    def suspend(self, T: Task) -> None:
        if T.state in ("stopped", "error", "held", "killed"):
            return
        T.saved = (T.state if T.state != "run" else "ready", T.wake)
        T.state = "stopped"
        T.jump = 0

    def resume(self, T: Task, jump: int) -> None:
        """5.10 taskResume: no effect unless STOPPED (suspended, or stopped on a runtime error).
        The task resumes `jump` instructions before or after the line where it stopped, counted
        in the sequence that holds that line (a structure - if, while, for, do, switch - counts
        as one instruction of its sequence): 0 runs the line again, 1 goes on after it; the end
        of the sequence is a valid target. Error 90 when the target is outside the sequence or
        the line is in a sequence too deeply nested for the simulator's jumps (docs/sim.md)."""
        if T.state not in ("stopped", "error"):
            return
        if T.state == "error":
            if jump == 0 or jump == 1 and T.skippable and T.jumpctx is None:
                pass
            elif not self._jump_ok(T.jumpctx, jump):
                raise Val3RuntimeError(90, f"cannot resume {T.name} {jump} line(s) from where it stopped")
            T.jump = jump
            T.error = 0
            T.state = "ready"
            return
        if jump == 0:
            T.state, T.wake = T.saved or ("ready", None)
            return
        ctx = self._suspended_ctx(T)
        if not self._jump_ok(ctx, jump):
            raise Val3RuntimeError(90, f"cannot resume {T.name} {jump} line(s) from where it was suspended")
        T.pending = rt.JUMP(ctx[0], ctx[1] + jump)
        T.state, T.wake, T.tdep, T.cond = "ready", None, False, None

    @staticmethod
    def _jump_ok(ctx: tuple | None, jump: int) -> bool:
        return ctx is not None and 0 <= ctx[1] + jump <= ctx[2]

    def _val3_frames(self, T: Task):
        """(compiled program, Python line) of each VAL 3 program the task is in, outermost first."""
        g = T.gen
        while g is not None:
            code = getattr(g, "gi_code", None)
            frame = getattr(g, "gi_frame", None)
            if code is not None and frame is not None and code.co_filename in self.compiled:
                yield self.compiled[code.co_filename], frame.f_lineno
            g = getattr(g, "gi_yieldfrom", None)

    def _suspended_ctx(self, T: Task) -> tuple | None:
        """The sequence position of the line a suspended task is at (innermost program)."""
        found = None
        for c, lineno in self._val3_frames(T):
            found = c.bpos.get(lineno)
        return found

    def kill(self, T: Task, by: Task | None = None) -> None:
        if T.state == "killed":
            return
        T.state = "killed"
        T.end_state = "killed"
        T.ended = self.clock_us(by)
        if T in self.tasks:
            self.tasks.remove(T)
        if T is not self.current and T.gen is not None:
            T.gen.close()

    def task_failed(self, T: Task, e: BaseException, skippable: bool) -> None:
        """A line raised: stop the task there (5.2) and record a runtime diagnostic."""
        tb = e.__traceback__
        pos = None
        if tb is not None:
            c = self.compiled.get(tb.tb_frame.f_code.co_filename)
            if c is not None:
                pos = (c, c.pos.get(tb.tb_lineno))
        T.skippable = skippable
        T.jump = 0
        if isinstance(e, rt.SimLimit):
            T.state = "held"
            T.limit = e.kind
            code = "R002" if e.kind == "arm" else "R004"
            if e.message:
                msg = e.message
            elif e.kind == "arm":
                msg = self.arm_message(e.what)
            else:
                msg = f"not simulated: {e.what}"
            self.add_diag(code, msg, T, pos, None)
            T.errdetail = msg
            return
        code, detail = _error_code(e)
        T.state = "error"
        T.error = code
        T.errdetail = detail
        text = RUNTIME_CODES.get(code, "runtime error")
        extra = f" ({detail})" if detail and detail not in text else ""
        self.add_diag("R001", f"error {code}: {text}{extra}", T, pos, code)

    def arm_message(self, what: str) -> str:
        """R002: why the arm instruction stops the task, and (without an arm model) how to give one."""
        low = what.lower()
        if low in ("setlatch", "getlatch", "getdh", "getdefaultdh", "setdh"):
            return f"instruction {what} needs the arm's hardware (position capture, calibration), which this " \
                   f"version does not simulate"
        text = f"instruction {what} moves the arm or reads its motion, which this version does not simulate (chapter 10)"
        if self.arm is None:
            return f"{text}; the run has no arm model either (to have movej targets checked, " \
                   f"{NO_ARM[len('needs the arm model: '):]})"
        return f"{text}; the arm model {self.arm.name} stays at its initial joint position"

    def add_diag(self, code: str, message: str, T: Task | None, pos, error: int | None) -> None:
        path, line, col, program = self.app.path, 0, 0, ""
        if pos is not None:
            compiled, lc = pos
            path = compiled.path
            program = compiled.name
            if lc is not None:
                line, col = lc
        if T is not None:
            T.errpos = (path, line, col, program)
        self.diags.append(Diag(code, message, path, line, col, self.clock_us(T) if T is not None else self.now,
                               T.name if T is not None else "", program, error))

    def where(self, T: Task) -> tuple[str, int, int, str] | None:
        """The file position of the line a task is at (innermost VAL 3 program)."""
        found = None
        for c, lineno in self._val3_frames(T):
            lc = c.pos.get(lineno)
            if lc is not None:
                found = (c.path, lc[0], lc[1], c.name)
        return found

    # ---- libraries (chapter 6) ----------------------------------------------------------------

    def lib_unit(self, A: Unit, alias: str) -> Unit:
        if alias not in A.aliases:
            raise Val3RuntimeError(80, f"no library identifier {alias}")
        u = A.aliases[alias]
        if u is None:
            raise Val3RuntimeError(80, f"library {alias} is not loaded (libLoad)")
        return u

    def lib_global(self, A: Unit, alias: str, name: str) -> Any:
        u = self.lib_unit(A, alias)
        c = u.public_global(name)
        if c is None:
            raise Val3RuntimeError(80, f"{alias}:{name} is not in the loaded library")
        return c

    def lib_program(self, A: Unit, alias: str, name: str):
        u = self.lib_unit(A, alias)
        p = u.public_program(name)
        if p is None:
            raise Val3RuntimeError(80, f"{alias}:{name}() is not in the loaded library")
        return p.func

    def lib_defined(self, A: Unit, alias: str, name: str) -> bool:
        u = A.aliases.get(alias)
        return u is not None and u.public_global(name) is not None

    def lib_instruction(self, T: Task, A: Unit, alias: str, op: str, *args):
        return (yield from self.lib_op(T, A, alias, op, *args))

    def lib_instruction_now(self, T: Task, A: Unit, alias: str, op: str, *args):
        if op == "libpath":
            u = A.aliases.get(alias)
            if alias not in A.aliases:
                raise Val3RuntimeError(80, f"no library identifier {alias}")
            return u.disk_path if u is not None else ""
        if op == "libexist":
            u = A.aliases.get(alias)
            if u is None:
                return False
            sym = args[0] if args else ""
            if sym.endswith("()"):
                return u.public_program(sym[:-2]) is not None
            return u.public_global(sym) is not None
        raise Val3RuntimeError(70, op)

    def lib_op(self, T: Task, A: Unit, alias: str | None, op: str, *args):
        from .libraries import lib_operation

        result = lib_operation(self, T, A, alias, op, *args)
        yield from rt.YIELD(T)  # 5.4: disk access hands over to the next task
        return result

    def _load_library(self, A: Unit, alias: str, path: str, T: Task | None) -> int:
        from .libraries import load_library

        return load_library(self, A, alias, path, T)

    # ---- getData (2.5.4) ----------------------------------------------------------------------

    def get_data(self, T: Task, A: Unit, spec: str, c: Any, idx: Any, t: str) -> float:
        m = re.match(r"^\s*(?:([A-Za-z]\w*):)?([A-Za-z]\w*)\s*(?:\[\s*([^\]]*)\])?\s*$", spec)
        if not m:
            return -1.0
        alias, name, index = m.groups()
        unit = A
        if alias:
            if alias not in A.aliases or A.aliases[alias] is None:
                return -2.0
            unit = A.aliases[alias]
            src = unit.public_global(name)
        else:
            src = A.globals.get(name)
        if src is None:
            return -1.0
        if getattr(src, "t", None) != t:
            return -4.0
        if type(src) is Coll:
            if index is None or c is not None and type(c) is not Coll:
                return -4.0
            key = index.strip().strip('"')
            if key not in src.d:
                return -3.0
            vals = [src.d[key]]
        else:
            start = 0
            if index:
                try:
                    start = int(float(index))
                except ValueError:
                    return -3.0
                if not 0 <= start < len(src.data):
                    return -3.0
            vals = src.data[start:] if src.dims is None else src.data[start:start + 1]
            if c is None or type(c) is not Arr or (index is not None and src.dims is None and False):
                vals = vals[:1]
        if c is None:  # an element: idx is the (container, key) pair
            cc, kk = idx
            store(cc, kk, vals[0])
            return 1.0
        if type(c) is Coll:
            key = idx[0] if idx else None
            if key is None or key not in c.d:
                return -3.0
            store(c.d, key, vals[0])
            return 1.0
        dst_start = c.off
        if idx is not None:
            dst_start = rt.AI1(c, idx[0]) if c.dims is None else c.off
        room = len(c.data) - dst_start
        n = min(room, len(vals)) if c.dims is None else 1
        for i in range(n):
            store(c.data, dst_start + i, vals[i])
        return float(n)

    # ---- the run ------------------------------------------------------------------------------

    def start(self) -> None:
        unit = self.main
        start = unit.program("start")
        if start is None:
            raise EndRun("no-start")
        T = Task(self, f"{self.app.name}~", unit, "start", START_PRIORITY)  # 5.2: start() in "APP~"
        T.gen = start.func(T)
        self.seq += 1
        T.seq = self.seq
        self.tasks.append(T)
        self.history.append(T)

    def _wall_check(self) -> None:
        if _time.monotonic() > self.wall_start + self.budgets.wall_s:
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
            self._loop(self.budgets.duration_us)
            reason = "ended"
        except EndRun as stop:
            reason = stop.reason
        self.end_reason = reason
        self.end_time = self.now
        self._snapshot_tasks()
        if reason == "deadlock":
            self._report_blocked()
        if reason not in ("ended", "wall-clock"):
            self._stop_after(reason)
        self._destroy_remaining()

    def _snapshot_tasks(self) -> None:
        """What each live task was doing when the run ended (before stop() and destruction)."""
        for T in self.tasks:
            where = self.where(T) if T.state not in ("error", "held") else None
            if T.state in ("error", "held") and T.errpos:
                where = T.errpos
            state = {"ready": "running", "run": "running", "preempted": "running", "yield": "running",
                     "delay": "delay", "wait": "waiting", "stopped": "suspended", "error": "error",
                     "held": "stopped-unsimulated"}.get(T.state, T.state)
            T.final = {"state": state, "where": where,
                       "blocked_on": self.blocked_on(T) if T.state == "wait" else None}

    BLOCKERS = {"WAIT": "wait", "WATCH": "watch", "GET": "get", "SETMUTEX": "setMutex", "SIOR": "sio read",
                "I_sioget": "sioGet", "DELAY": "delay"}

    def blocked_on(self, T: Task) -> str:
        g = T.gen
        last = ""
        while g is not None:
            code = getattr(g, "gi_code", None)
            if code is not None and code.co_filename not in self.compiled:
                name = self.BLOCKERS.get(code.co_name)
                if name and not last:
                    last = name
            g = getattr(g, "gi_yieldfrom", None)
        return last or T.state

    def _report_blocked(self) -> None:
        """Deadlock: every task waits for something no scheduled event can change."""
        for T in self.tasks:
            if T.state in ("error", "held"):
                continue
            w = self.where(T)
            path, line, col, prog = w if w else (self.app.path, 0, 0, T.program)
            if T.state == "stopped":
                msg = f"task {T.name} is suspended and no task can resume it"
            else:
                msg = f"task {T.name} is blocked in {self.blocked_on(T)}: nothing scheduled can change what it waits for"
            T.errpos = (path, line, col, prog)
            self.diags.append(Diag("R003", msg, path, line, col, self.now, T.name, prog))

    def _stop_after(self, reason: str) -> None:
        """As when the application is stopped from the pendant (2.1.3, 5.2): the start task is
        destroyed, stop() runs, then the remaining tasks are destroyed."""
        if self.phase == "stopping":
            return
        for t in list(self.tasks):
            if t.unit is self.main and t.name == f"{self.app.name}~":
                self.kill(t)
                t.end_state = "destroyed"
        self._start_stop_program()
        limit = self.now + self.budgets.stop_us
        try:
            self._loop(limit, stopping=True)
        except EndRun as extra:
            what = {"stop-timeout": f"still running {self.budgets.stop_us / 1e6:g} s after the run was stopped",
                    "deadlock": "blocked"}.get(extra.reason, extra.reason)
            T = self.stop_task
            if T is not None and T in self.tasks and T.state not in ("error", "held"):
                w = self.where(T)
                path, line, col, prog = w if w else (self.app.path, 0, 0, "stop")
                self.diags.append(Diag("R006", f"stop() did not end: {what}", path, line, col, self.now, T.name, prog))

    def _start_stop_program(self) -> None:
        stop = self.main.program("stop")
        self.phase = "stopping"
        if stop is None:
            return
        T = Task(self, f"~{self.app.name}", self.main, "stop", START_PRIORITY)  # 5.2: stop() in "~APP"
        T.created = self.now
        T.gen = stop.func(T)
        self.seq += 1
        T.seq = self.seq
        self.tasks.append(T)
        self.history.append(T)
        self.stop_task = T

    def _destroy_remaining(self) -> None:
        """2.1.3: remaining tasks are destroyed in the reverse order of their creation."""
        for t in sorted(self.tasks, key=lambda x: x.seq, reverse=True):
            self.destroyed.append(t.name)
            t.end_state = t.end_state or "destroyed"
            self.kill(t)
            t.end_state = "destroyed" if t.end_state == "killed" else t.end_state

    def _stop_done(self) -> bool:
        T = self.stop_task
        return T is None or T not in self.tasks or T.state in ("error", "held")

    def _loop(self, limit_us: int, stopping: bool = False) -> None:
        budgets = self.budgets
        wall_deadline = self.wall_start + budgets.wall_s
        cycles = 0
        while True:
            if stopping and self._stop_done():
                return  # stop() has ended, or stopped on an error: the caller destroys the rest
            if not self.tasks:
                if self.phase == "stopping":
                    return
                # 2.1.3: the application ends when its last task ends; then stop() runs
                self._start_stop_program()
                stopping = True
                continue
            if self.now >= limit_us:
                raise EndRun("stop-timeout" if stopping else "duration")
            cycles += 1
            if _time.monotonic() > wall_deadline:
                raise EndRun("wall-clock")
            if cycles & 255 == 0:
                why = self.cell.budget.over()
                if why:
                    raise EndRun("budget:" + why)
            if self.total_lines > budgets.max_lines:
                raise EndRun("steps")
            busy = self._cycle()
            if stopping and self._stop_done():
                return  # at once, not after the clock jumps to the next event
            if busy or not self.tasks:
                self.now += TICK_US
                continue
            nxt = self._next_event()
            if nxt is None:
                waiting = any(t.state in ("wait", "delay", "stopped") for t in self.tasks)
                raise EndRun("deadlock" if waiting else "stalled")
            self.now = min(limit_us, max(self.now + TICK_US, -(-nxt // TICK_US) * TICK_US))

    def _apply_events(self) -> None:
        ev = self.events
        fired: dict[int, int] = {}  # reactions fired in this cycle, by index
        while ev and ev[0][0] <= self.now:
            at, _, kind, payload = heapq.heappop(ev)
            if kind == "set":
                for io, value in payload:
                    if io.value != value:
                        io.value = value
                        self.log_io(at, io, value, "scenario")
                        for k, (watched, v, delay, actions) in enumerate(self.reactions):
                            if watched is io and io.value == v:
                                fired[k] = fired.get(k, 0) + 1
                                if fired[k] > MAX_REACTIONS_PER_CYCLE:
                                    self._reaction_loop(at, fired)
                                self.push_event(at + delay, "set", actions)
            elif kind == "react":
                pass
            elif kind == "sio":
                io, data = payload
                io.rx.extend(data)
                self.log_io(at, io, sio_text(data), "scenario")
            elif kind == "power":
                if self.ctl.working_mode == 4 and self.ctl.es_status == 0:
                    self.ctl.powered = bool(payload)
            elif kind == "ctl":
                for k, v in payload.items():
                    setattr(self.ctl, k, v)
            # "key" events only wake the scheduler up

    def _reaction_loop(self, at: int, fired: dict[int, int]) -> None:
        """Scenario reactions that set each other's inputs without delay never let time move on:
        said once (R008) at the first reaction of the loop, and the run ends."""
        lines = [self.reaction_lines[k] if k < len(self.reaction_lines) else 0 for k in sorted(fired)
                 if fired[k] > MAX_REACTIONS_PER_CYCLE // 2]
        names = sorted({self.reactions[k][0].link for k in fired if fired[k] > MAX_REACTIONS_PER_CYCLE // 2})
        where = ", ".join(f"line {n}" for n in lines if n) or "see [[reactions]]"
        self.diags.append(Diag(
            "R008", f"the scenario's reactions to {', '.join(names)} set each other's inputs again and again at"
            f" {at / 1e6:g} s ({MAX_REACTIONS_PER_CYCLE} times within one 4 ms cycle; {where}): time cannot move on",
            self.scenario_path or self.app.path, min((n for n in lines if n), default=0), 1 if any(lines) else 0, at,
            "", ""))
        raise EndRun(f"budget:the scenario's reactions loop at {at / 1e6:g} s (R008)")

    def _cycle(self) -> bool:
        """One 4 ms cycle. Returns True when the line budget was spent (busy), False when every
        task ended up waiting."""
        self._apply_events()
        self.cycle_lines = 0
        now = self.now
        for T in list(self.tasks):
            if T.period and now >= T.next_run and T in self.tasks:
                self._sync_turn(T)
        while self.cycle_lines < LINES_PER_CYCLE:
            progress = False
            for T in list(self.tasks):
                if T.period or T not in self.tasks:
                    continue
                st = T.state
                if st in ("stopped", "error", "held", "killed"):
                    continue
                if st == "delay" and T.wake > now:
                    continue
                ok = None
                if st == "wait" and T.cond is not None:
                    # the wait/watch condition, evaluated once per turn here rather than by
                    # resuming the task: it is resumed when true (or at the watch timeout)
                    try:
                        ok = T.cond()
                    except Exception:  # noqa: BLE001 - raised again in the task, at its line
                        ok = None
                    else:
                        if not ok and (T.wake is None or now < T.wake):
                            continue
                left = LINES_PER_CYCLE - self.cycle_lines
                if left <= 0:
                    break
                ran = self._turn(T, min(T.prio, left), ok)
                if ran:
                    progress = True
            if not progress:
                break
        self.total_lines += self.cycle_lines
        return self.cycle_lines >= LINES_PER_CYCLE

    def _sync_turn(self, T: Task) -> None:
        """5.5/5.6: a synchronous task runs once per period; an overrun cancels the next one
        and sets its bOverrun flag, which tells at each start whether the last one overran."""
        if T.overrun is not None:
            c, k = T.overrun
            c[k] = T.overran
        st = T.state
        start_lines = self.cycle_lines
        if st not in ("stopped", "error", "held", "killed") and not (st == "delay" and T.wake > self.now):
            self._turn(T, SYNC_LINES)
        used = (self.cycle_lines - start_lines) * LINE_US
        T.overran = used > T.period
        T.next_run += T.period * (2 if T.overran else 1)
        if T.overran:
            self.diags.append(Diag("R005", f"synchronous task {T.name} overran its period of {T.period / 1e6:g} s",
                                   *(self._pos_or_app(T)), self.now, T.name, T.program))

    def _pos_or_app(self, T: Task) -> tuple:
        w = self.where(T)
        if w is None:
            return (self.app.path, 0, 0)
        return (w[0], w[1], w[2])

    def _turn(self, T: Task, quantum: int, value: Any = None) -> bool:
        """Run one turn of a task; True when it ran at least one line or changed state. `value`
        is sent to the task (True: the condition it waits for was found true)."""
        self.current = T
        self.turn_given = quantum
        before = T.state
        # a task preempted at the start of a line has already counted that line (T.q -= 1)
        T.q = quantum - 1 if before == "preempted" else quantum
        T.state = "run"
        try:
            if T.pending is not None:
                jump, T.pending = T.pending, None
                T.q = quantum
                T.gen.throw(jump)
            else:
                T.gen.send(value)
        except StopIteration:
            T.state = "ended"
        except EndRun:
            self.current = None
            raise
        except BaseException as exc:  # noqa: BLE001 - an error outside any line: internal
            self.current = None
            T.state = "error"
            T.error = 61
            self.add_diag("R001", f"error 61: {RUNTIME_CODES[61]} ({exc.__class__.__name__}: {exc})", T, None, 61)
        ran = quantum - max(T.q, 0)
        self.cycle_lines += ran
        T.lines += ran
        self.current = None
        if T.state == "run":
            T.state = "preempted"
        elif T.state == "ended":
            T.end_state = "ended"
            T.ended = self.now + min(self.cycle_lines, LINES_PER_CYCLE) * LINE_US
            if T in self.tasks:
                self.tasks.remove(T)
            return True
        elif T.state == "killed":
            if T.gen is not None:
                T.gen.close()
            return True
        return ran > 0 or T.state != before and T.state not in ("wait",)

    def _next_event(self) -> int | None:
        """The next time something can change, or None (deadlock)."""
        times = []
        if self.events:
            times.append(self.events[0][0])
        tdep = False
        for T in self.tasks:
            if T.period and T.state not in ("stopped", "error", "held", "killed"):
                times.append(T.next_run)
            if T.state == "delay" and T.wake is not None:
                times.append(T.wake)
            elif T.state == "wait":
                if T.wake is not None:
                    times.append(T.wake)
                if T.tdep:
                    tdep = True
            elif T.state in ("ready", "yield", "preempted"):
                tdep = True
        if tdep:
            times.append(self.now + TICK_US)
        return min(times) if times else None


def sio_text(data: bytes) -> Any:
    """How the I/O log shows bytes sent or received on a sio: the text when they are UTF-8,
    else the list of the byte values."""
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError:
        return list(data)


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
