"""Where a task is scheduled: tasks, their states, and the sequencing of chapter 5.

Each 4 ms cycle (docs/sim.md, manual 5.4 - 5.7): the subsystems are brought up to date (the
cell's inputs refreshed, 5.7; the arm's motion...), each synchronous task that is due runs up
to 3000 lines (5.5), then the asynchronous tasks take turns in creation order, each running
as many lines as its priority (5.4), round after round, until every task waits or the cycle's
line budget (a simulated cost of 4 µs per line) is spent; then the clock moves on. When every
task waits, the clock jumps straight to the next time anything can change: the end of a
delay or a watch, a synchronous task's period, or the next event of a subsystem
(`Subsystem.next_time`). When nothing can change any more, the run ends: deadlock (tasks wait)
or stalled (every task is stopped).

A task is a Python generator (the compiled program, `compiler/`): a turn is `send()` until it
yields, either because its quantum `task.q` is spent (preempted) or because it blocks
(`waiting.py`) or stopped on a line (`machine.task_failed`).
"""

from __future__ import annotations

from enum import StrEnum
from typing import Any

from ..language.runtime_errors import RUNTIME_CODES, Val3RuntimeError
from ..language.version_facts import task_name_problem
from .clock import LINE_US, LINES_PER_CYCLE, TICK_US, Clock
from .recorder import task_state_of

SYNC_LINES = 3000  # 5.5: up to 3000 lines per sequencing of a synchronous task
START_PRIORITY = 10  # 5.2
MAX_TASKS = 200


class TaskState(StrEnum):
    READY = "ready"  # created, or resumed: runs at its next turn
    RUNNING = "run"  # in its turn
    PREEMPTED = "preempted"  # its turn's lines are spent
    YIELD = "yield"  # handed over (delay(0), a disk access...)
    DELAY = "delay"  # in delay() until `wake`
    WAIT = "wait"  # waits for `cond` (wait, watch, get, setMutex, sio, end of motion...)
    SUSPENDED = "stopped"  # taskSuspend() (5.10)
    ERROR = "error"  # stopped on a runtime error (12.1)
    HELD = "held"  # stopped on something the simulator does not simulate (R002/R004)
    KILLED = "killed"
    ENDED = "ended"

    @property
    def report_name(self) -> str:
        """How the report names the state of a task alive at the end of the run."""
        return _REPORT_NAMES.get(self, self.value)


_REPORT_NAMES = {TaskState.READY: "running", TaskState.RUNNING: "running", TaskState.PREEMPTED: "running",
                 TaskState.YIELD: "running", TaskState.DELAY: "delay", TaskState.WAIT: "waiting",
                 TaskState.SUSPENDED: "suspended", TaskState.ERROR: "error",
                 TaskState.HELD: "stopped-unsimulated"}

READY, RUNNING, PREEMPTED, YIELD = TaskState.READY, TaskState.RUNNING, TaskState.PREEMPTED, TaskState.YIELD
DELAY, WAIT, SUSPENDED, ERROR = TaskState.DELAY, TaskState.WAIT, TaskState.SUSPENDED, TaskState.ERROR
HELD, KILLED, ENDED = TaskState.HELD, TaskState.KILLED, TaskState.ENDED
# a task in one of these states does not run until another task (or taskResume) changes it
STOPPED_STATES = (SUSPENDED, ERROR, HELD, KILLED)


class EndRun(BaseException):
    """The run ends (`reason`: duration, deadlock, stalled, wall-clock, steps, budget:...)."""

    def __init__(self, reason: str) -> None:
        super().__init__(reason)
        self.reason = reason


class JUMP(BaseException):
    """taskResume(name, n) (5.10): resume at instruction `t` of sequence `b` of the program the
    task stopped in (caught by that sequence's dispatch loop, compiler/statements.py). A
    BaseException, so that the `except Exception` of the lines it goes through does not take
    it for an error."""

    __slots__ = ("b", "t")

    def __init__(self, b: int, t: int) -> None:
        super().__init__(b, t)
        self.b = b
        self.t = t


class Task:
    __slots__ = ("name", "unit", "prio", "period", "gen", "state", "q", "stack", "smax", "wake", "tdep", "error",
                 "errdetail", "errpos", "program", "created", "ended", "machine", "jump", "skippable",
                 "overrun", "next_run", "overran", "limit", "end_state", "lines", "seq", "saved", "final",
                 "jumpctx", "pending", "cond", "waiting_for", "clock", "frames")

    def __init__(self, machine, name: str, unit, program: str, prio: int, period: int = 0) -> None:
        self.machine = machine
        self.clock = machine.clock
        self.name = name
        self.unit = unit
        self.program = program
        self.prio = prio
        self.period = period  # µs, > 0 for a synchronous task
        self.gen = None
        self.state = READY
        self.q = 0  # lines left in its turn (the generated code counts them down)
        self.stack = 0  # execution memory used (2.1.4.2)
        self.smax = unit.model.stack_size or 5000
        self.wake: int | None = None  # end of its delay / watch
        self.tdep = False  # waits for a condition that changes with time alone
        self.error = 0  # VAL 3 code while stopped on an error
        self.errdetail = ""
        self.errpos: tuple | None = None
        self.created = machine.clock.now
        self.ended: int | None = None
        self.jump = 0
        self.skippable = True
        self.overrun = None  # (container, key) of the sync task's bOverrun
        self.next_run = 0
        self.overran = False
        self.limit: str | None = None  # "arm"/"notsim" when held on a simulator limit
        self.end_state = ""
        self.lines = 0
        self.seq = 0  # creation order
        self.saved: tuple | None = None  # (state, wake) before taskSuspend
        self.final: dict | None = None
        self.jumpctx: tuple | None = None  # (sequence, index, length) of the line it stopped on
        self.pending: BaseException | None = None  # a taskResume jump to throw in at its next turn
        self.cond = None  # the condition of the wait it is in (evaluated by the scheduler)
        self.waiting_for = ""  # what it waits for, in words (waiting.py)
        # the frames of the VAL 3 programs it is in, outermost first: each program pushes its own
        # at its start and pops it at its end (compiler/program.py), so that the running line
        # and its loops are read without walking the Python stack (machine.py)
        self.frames: list = []


class Scheduler:
    """The live tasks in creation order, the sequencing loop, and the task instructions'
    effects (create, suspend, resume, kill: 5.10)."""

    def __init__(self, machine, clock: Clock) -> None:
        self.machine = machine
        self.clock = clock
        self.tasks: list[Task] = []  # live tasks, creation order
        self.history: list[Task] = []  # every task ever created
        self.subsystems: list[Any] = []  # Subsystem objects, in registration order
        self._advance: list[Any] = []  # their bound `advance` and `next_time` (asked every cycle)
        self._next_time: list[Any] = []
        self.total_lines = 0
        self._seq = 0
        self._created: list[Task] = []  # tasks created since the round's order was taken (5.4)
        self._ran: set[Task] = set()  # tasks that ran a line in this cycle (the task timelines)
        self._alive: dict[Task, tuple] = {}  # the tasks alive at the end of the last cycle, their state
        self._removed = False  # a task left `tasks` since the states were last noted
        # a task was added or took a turn since the states were last noted: only then can a
        # state have changed (a wait's condition, evaluated by the cycle, changes none)
        self._changed = False
        self._periodic = False  # a synchronous task was ever added (else each cycle skips their turns)
        # changes whenever VAL 3 code may have run (a turn, a wait's condition other than
        # `pure_cond`, a task closed): what reads the program's values between cycles
        # (simulation/value_watch.py) skips its check while it has not changed
        self.runs = 0
        self.pure_cond: Any = None  # a wait's condition known to change no value (Machine.motion_done)

    def add_subsystem(self, subsystem: Any) -> None:
        self.subsystems.append(subsystem)
        self._advance.append(subsystem.advance)
        self._next_time.append(subsystem.next_time)

    # ---- task life (5.10) -----------------------------------------------------------------------

    def add(self, task: Task) -> Task:
        self._seq += 1
        task.seq = self._seq
        if task.period:
            self._periodic = True
        self._changed = True
        self.tasks.append(task)
        self.history.append(task)
        return task

    def find(self, unit, name: str) -> Task | None:
        """5.3: a task is only visible from the library or application that created it."""
        for t in self.tasks:
            if t.unit is unit and t.name == name:
                return t
        return None

    @staticmethod
    def status_code(task: Task) -> int:
        """taskStatus (5.10): 0 suspended, 1 running, or the runtime error code."""
        if task.state is ERROR:
            return task.error
        if task.state is SUSPENDED or task.state is HELD:
            return 0
        return 1

    def create(self, creator: Task | None, unit, name: Any, func, args: tuple, prio: int, period: int,
               pname: str) -> Task:
        # 5.10 (error 29); the rule of the application's version, shared with lint (T023): a limit
        # the manual does not state for this version does not stop the task
        problem = task_name_problem(name, self.machine.app.version_major) if type(name) is str else None
        if type(name) is not str or (problem is not None and problem.certain):
            raise Val3RuntimeError(29, f"invalid task name {name!r}" + (f": {problem.why}" if problem else ""))
        if self.find(unit, name) is not None:
            raise Val3RuntimeError(31, f'a task "{name}" already exists')
        if len(self.tasks) >= MAX_TASKS:
            raise Val3RuntimeError(40, f"more than {MAX_TASKS} tasks")
        task = Task(self.machine, name, unit, pname, prio, period)
        task.created = self.clock.time_of(creator)
        task.gen = func(task, *args)
        self._created.append(task)
        return self.add(task)

    def suspend(self, task: Task) -> None:
        if task.state in STOPPED_STATES:
            return
        task.saved = (task.state if task.state is not RUNNING else READY, task.wake)
        task.state = SUSPENDED
        task.jump = 0

    def resume(self, task: Task, jump: int) -> None:
        """5.10 taskResume: no effect unless STOPPED (suspended, or stopped on a runtime error).
        The task resumes `jump` instructions before or after the line where it stopped, counted
        in the sequence that holds that line (a structure - if, while, for, do, switch - counts
        as one instruction of its sequence): 0 runs the line again, 1 goes on after it; the end
        of the sequence is a valid target. Error 90 when the target is outside the sequence or
        the line is in a sequence too deeply nested for the simulator's jumps (docs/sim.md)."""
        if task.state is not SUSPENDED and task.state is not ERROR:
            return
        if task.state is ERROR:
            if jump == 0 or jump == 1 and task.skippable and task.jumpctx is None:
                pass
            elif not _jump_ok(task.jumpctx, jump):
                raise Val3RuntimeError(90, f"cannot resume {task.name} {jump} line(s) from where it stopped")
            task.jump = jump
            task.error = 0
            task.state = READY
            return
        if jump == 0:
            task.state, task.wake = task.saved or (READY, None)
            return
        ctx = self.machine.suspended_position(task)
        if not _jump_ok(ctx, jump):
            raise Val3RuntimeError(90, f"cannot resume {task.name} {jump} line(s) from where it was suspended")
        task.pending = JUMP(ctx[0], ctx[1] + jump)
        task.state, task.wake, task.tdep, task.cond, task.waiting_for = READY, None, False, None, ""

    def kill(self, task: Task, by: Task | None = None) -> None:
        if task.state is KILLED:
            return
        task.state = KILLED
        task.end_state = "killed"
        self.runs += 1
        task.ended = self.clock.time_of(by)
        if task in self.tasks:
            self.tasks.remove(task)
            self._removed = True
        if task is not self.clock.current and task.gen is not None:
            task.gen.close()

    # ---- the sequencing loop --------------------------------------------------------------------

    def loop(self, limit_us: int, stopping: bool = False) -> None:
        """Run cycles until the application ends (or, `stopping`, until stop() ends), or
        raise EndRun (duration reached, deadlock, budgets)."""
        machine = self.machine
        clock = self.clock
        tasks = self.tasks  # (one list for the run: tasks leave it by remove())
        cycle, next_event = self.cycle, self.next_event
        budgets = machine.budgets
        wall_deadline = budgets.run_deadline(machine.wall_start)
        wall_clock = budgets.wall_clock
        memory = machine.cell.budget
        cycles = 0
        while True:
            if stopping and machine.stop_done():
                return  # stop() has ended, or stopped on an error: the caller destroys the rest
            if not tasks:
                if machine.stopping:
                    return
                # 2.1.3: the application ends when its last task ends; then stop() runs
                machine.start_stop_program()
                stopping = True
                continue
            now = clock.now
            if now >= limit_us:
                raise EndRun("stop-timeout" if stopping else "duration")
            cycles += 1
            if wall_clock() > wall_deadline:
                raise EndRun("wall-clock")
            if cycles & 63 == 0:
                if cycles & 255 == 0:
                    why = memory.over()
                    if why:
                        raise EndRun("budget:" + why)
                if machine.progress is not None:
                    machine.progress(now)
            if self.total_lines > budgets.max_lines:
                raise EndRun("steps")
            busy = cycle()
            if stopping and machine.stop_done():
                return  # at once, not after the clock jumps to the next event
            if busy or not tasks:
                clock.now = now + TICK_US
                continue
            nxt = next_event()
            if nxt is None:
                waiting = any(t.state is WAIT or t.state is DELAY or t.state is SUSPENDED for t in tasks)
                raise EndRun("deadlock" if waiting else "stalled")
            # the tick of the next event, at least the next one, at most the limit
            nxt = -(-nxt // TICK_US) * TICK_US
            if nxt < now + TICK_US:
                nxt = now + TICK_US
            clock.now = nxt if nxt < limit_us else limit_us

    def cycle(self) -> bool:
        """One 4 ms cycle. Returns True when the line budget was spent (busy), False when every
        task ended up waiting."""
        clock = self.clock
        now = clock.now
        for advance in self._advance:
            advance(now)
        clock.cycle_lines = 0
        tasks = self.tasks
        if self._periodic:
            for task in list(tasks):
                if task.period and now >= task.next_run and task in tasks:
                    self._sync_turn(task)
        created = self._created
        pure = self.pure_cond
        while clock.cycle_lines < LINES_PER_CYCLE:
            progress = False
            if created:
                created.clear()
            order = list(tasks)
            # (a list iterator sees the items appended while it runs: the tasks created below)
            for task in order:
                if task.period or task not in tasks:
                    continue
                st = task.state
                ok = None
                if st is WAIT:
                    cond = task.cond
                    if cond is not None:
                        if cond is not pure:
                            self.runs += 1
                        # the wait's condition, evaluated once per turn here rather than by
                        # resuming the task: it is resumed when true (or at the watch timeout)
                        try:
                            ok = cond()
                        except Exception:  # noqa: BLE001 - raised again in the task, at its line
                            ok = None
                        else:
                            if not ok and (task.wake is None or now < task.wake):
                                continue
                elif st is DELAY:
                    if task.wake > now:
                        continue
                elif st in STOPPED_STATES:
                    continue
                left = LINES_PER_CYCLE - clock.cycle_lines
                if left <= 0:
                    break
                if self._turn(task, task.prio if task.prio < left else left, ok):
                    progress = True
                if created:
                    # 5.4: tasks take turns in creation order; one created in this turn takes
                    # its turn in this round, after the tasks created before it
                    order.extend(created)
                    created.clear()
            if not progress:
                break
        lines = clock.cycle_lines
        if lines:
            self.total_lines += lines
        if self._changed or self._removed:
            self._changed = False
            self._note_states(now)
        return lines >= LINES_PER_CYCLE

    def _note_states(self, now: int) -> None:
        """The task timelines (recorder.TaskStateChange): over this cycle, running for a task that
        ran a line in it; from the next cycle on, the state it was left in. Called only after a
        turn or a change of the task list (`cycle`); a task that did not run and whose state
        did not change costs one dict lookup."""
        ran = self._ran
        alive = self._alive  # task -> (state, waiting_for) last noted
        tasks = self.tasks
        note = None
        after = now + TICK_US
        if self._removed:  # (only then is a task gone: the other cycles skip the search)
            self._removed = False
            note = self.machine.recorder.task_state
            live = set(tasks)
            gone = [t for t in ran if t not in live] + [t for t in alive if t not in live and t not in ran]
            for task in sorted(gone, key=lambda t: t.seq):  # ended or killed in this cycle
                if task in ran:
                    note(now, task.name, "running", "", task)
                note(after, task.name, "ended", "", task)
                alive.pop(task, None)
        for task in tasks:
            st = task.state
            wf = task.waiting_for
            last = alive.get(task)
            if last is not None and last[0] is st and last[1] == wf and task not in ran:
                continue
            if note is None:
                note = self.machine.recorder.task_state
            if task in ran:
                note(now, task.name, "running", "", task)
            elif last is None:
                note(now, task.name, "running" if st is READY else task_state_of(st.value, wf), "", task)
            state, detail = _shown(st, wf, task.period != 0)
            note(after, task.name, state, detail, task)
            alive[task] = (st, wf)
        if ran:
            ran.clear()

    def _sync_turn(self, task: Task) -> None:
        """5.5/5.6: a synchronous task runs once per period; an overrun cancels the next one
        and sets its bOverrun flag, which tells at each start whether the last one overran."""
        if task.overrun is not None:
            c, k = task.overrun
            c[k] = task.overran
        clock = self.clock
        st = task.state
        start_lines = clock.cycle_lines
        if st not in STOPPED_STATES and not (st is DELAY and task.wake > clock.now):
            self._turn(task, SYNC_LINES)
        used = (clock.cycle_lines - start_lines) * LINE_US
        task.overran = used > task.period
        task.next_run += task.period * (2 if task.overran else 1)
        if task.overran:
            self.machine.report_overrun(task)

    def _turn(self, task: Task, quantum: int, value: Any = None) -> bool:
        """Run one turn of a task; True when it ran at least one line or changed state. `value`
        is sent to the task (True: the condition it waits for was found true)."""
        clock = self.clock
        clock.current = task
        clock.turn_given = quantum
        self._changed = True
        self.runs += 1
        before = task.state
        # a task preempted at the start of a line has already counted that line (task.q -= 1)
        task.q = quantum - 1 if before is PREEMPTED else quantum
        task.state = RUNNING
        try:
            if task.pending is not None:
                jump, task.pending = task.pending, None
                task.q = quantum
                task.gen.throw(jump)
            else:
                task.gen.send(value)
        except StopIteration:
            task.state = ENDED
        except EndRun:
            clock.current = None
            raise
        except BaseException as exc:  # noqa: BLE001 - an error outside any line: internal
            clock.current = None
            task.state = ERROR
            task.error = 61
            self.machine.runtime_error(task, None, 61, f"{RUNTIME_CODES[61]} ({exc.__class__.__name__}: {exc})")
        q = task.q
        ran = quantum - q if q > 0 else quantum
        clock.cycle_lines += ran
        task.lines += ran
        if ran > 0:
            self._ran.add(task)
        clock.current = None
        st = task.state
        if st is RUNNING:
            st = task.state = PREEMPTED
        elif st is ENDED:
            task.end_state = "ended"
            task.ended = clock.end_of_cycle()
            if task in self.tasks:
                self.tasks.remove(task)
                self._removed = True
            return True
        elif st is KILLED:
            if task.gen is not None:
                task.gen.close()
            return True
        return ran > 0 or st is not before and st is not WAIT

    def next_event(self) -> int | None:
        """The next time something can change, or None (deadlock). (A running minimum: this is
        asked at every cycle where every task waits.)"""
        now = self.clock.now
        best = None
        for next_time in self._next_time:
            t = next_time(now)
            if t is not None and (best is None or t < best):
                best = t
        tdep = False
        for task in self.tasks:
            st = task.state
            if task.period and st not in STOPPED_STATES:
                t = task.next_run
                if best is None or t < best:
                    best = t
            if st is DELAY or st is WAIT:
                t = task.wake
                if t is not None and (best is None or t < best):
                    best = t
                if task.tdep and st is WAIT:
                    tdep = True
            elif st is READY or st is YIELD or st is PREEMPTED:
                tdep = True
        if tdep and (best is None or now + TICK_US < best):
            best = now + TICK_US
        return best


def _shown(st: TaskState, waiting_for: str, periodic: bool) -> tuple[str, str]:
    """(timeline state, detail) of a task left in state `st`, from the next cycle on."""
    state = task_state_of(st.value, waiting_for)
    if periodic and state == "running":  # a synchronous task between its periods (5.5)
        return "waiting", "period"
    return state, (waiting_for if state in ("waiting", "blocked") else (st.report_name if state == "stopped" else ""))


def _jump_ok(ctx: tuple | None, jump: int) -> bool:
    return ctx is not None and 0 <= ctx[1] + jump <= ctx[2]
