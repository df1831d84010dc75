"""The report of a run that ends because every task waits (scheduler.py: no event can come).

Waiting for something nothing in the run will change is not always a fault of the program. On a
controller the cell ends many waits: an input a sensor sets (`wait(diPart)`), a serial or socket
peer that sends data (`sioGet`, `sText = siIn`), an operator who presses a key (`get()`,
`getKey()`), the controller's state that the operator or the safety changes (`esStatus()`,
`getMonitorSpeed()`...). A task waiting for one of these gets R009, a warning naming the
scenario entry that would end the wait (`[inputs]`, `[[serial]]`, `[[keys]]`, `[controller]
changes`: docs/scenario.md). The words come from the wait itself (`waiting.WAIT(..., hint=...)`,
set by the compiler for `wait()` conditions and by the instructions that read the cell).

A task that waits for program variables is deadlocked (R003, an error) only when no task that
waits on the cell could change them once released: the globals the condition reads
(`WAIT(..., reads=...)`) are compared with the globals the programs of those tasks can write
(`writes_of`, a deliberate over-estimate: every variable handed to a call may be written). Tasks
that wait on each other, or on variables nothing can write, stay R003.
"""

from __future__ import annotations

from typing import Any

from ..diagnostics import Diagnostic
from ..language import lookup
from ..loading.model import Application, Container
from ..parsing import ast
from ..rules import codes
from .scheduler import ERROR, HELD, SUSPENDED, WAIT


def report_blocked(machine) -> None:
    """Every task waits for something no scheduled event can change: R009 for the waits only the
    cell can end (and for the waits those tasks may end once released), R018 for a motion power
    never allows, R003 for the rest."""
    tasks = [t for t in machine.scheduler.tasks if t.state is not ERROR and t.state is not HELD]
    on_cell = {t: _reachable_writes(machine, t) for t in tasks
               if t.state is WAIT and getattr(t.cond, "hint", "") and machine.motion_reason(t) is None}
    for task in tasks:
        w = machine.where(task)
        path, line, col, prog = w if w else (machine.app.path, 0, 0, task.program)
        code, msg = _finding(machine, task, on_cell)
        task.errpos = (path, line, col, prog)
        machine.diags.append(Diagnostic(code, msg, path, line, col, time_us=machine.clock.now, task=task.name,
                                        program=prog))


def _finding(machine, task, on_cell: dict) -> tuple[str, str]:
    blocked = machine.blocked_on(task)
    if task.state is SUSPENDED:
        resumers = [t.name for t, (_w, resumes) in on_cell.items() if resumes]
        if resumers:
            return codes.INPUT_NEVER_DRIVEN, (f"task {task.name} is suspended; only a task that waits on the cell "
                            f"({', '.join(resumers)}) may resume it once released")
        return codes.DEADLOCK, f"task {task.name} is suspended and no task can resume it"
    why = machine.motion_reason(task)
    if why is not None:
        code, text = why
        return code, f"task {task.name} waits in {blocked} for a motion that cannot happen: {text}"
    if task in on_cell:
        # the condition reads the cell: on the controller the outside world can release it; only
        # the simulation has nobody to (R009, a warning)
        return codes.INPUT_NEVER_DRIVEN, f"task {task.name} waits in {blocked}, which only the cell can end ({task.cond.hint})"
    reads = getattr(task.cond, "reads", None) if task.state is WAIT else None
    writers = [t.name for t, (writes, _r) in on_cell.items() if reads and _may_change(reads, writes)]
    if writers:
        return codes.INPUT_NEVER_DRIVEN, (f"task {task.name} waits in {blocked}, which only a task that waits on the cell "
                        f"({', '.join(writers)}) may change once released")
    if reads and _may_change(reads, _web_page_writes(machine, task)):
        # a CS9 web user page binds the application's data and calls its programs (its
        # *.bindings.json): the operator's clicks are the cell's, which the scenario cannot play
        return codes.INPUT_NEVER_DRIVEN, (f"task {task.name} waits in {blocked}, which only the operator can end through the web user "
                        "page (its bindings write that data or call a program that does); the simulation has no "
                        "web page")
    return codes.DEADLOCK, f"task {task.name} waits in {blocked}, which nothing scheduled can change"


def _web_page_writes(machine, task) -> set[str]:
    """The globals the application's web user pages may write: the names their bindings files
    hold (data bound, read or written) and what the programs they call (callbacks) may write."""
    model = task.unit.model
    bound = getattr(model, "ui_names", None) or set()
    if not bound:
        return set()
    table = _write_table(machine, model)
    out = {name for name in model.data if name.lower() in bound}
    for prog in model.programs:
        if prog.lower() in bound:
            w, _c, _r = table.get(prog.lower(), (set(), set(), False))
            out |= w
    return out


def _may_change(reads: frozenset[str], writes: set[str]) -> bool:
    """`?` in reads: the condition reads a parameter by reference (a global not known here)."""
    if "?" in reads:
        return bool(writes)
    return any(r in writes or (":" in r and r.split(":", 1)[0] + ":*" in writes) for r in reads)


def _reachable_writes(machine, task) -> tuple[set[str], bool]:
    """(globals the task's program and everything it calls or starts may write, whether that
    code calls taskResume)."""
    model = task.unit.model
    table = _write_table(machine, model)
    seen: set[str] = set()
    todo = [task.program.lower()]
    out: set[str] = set()
    resumes = False
    while todo:
        name = todo.pop()
        if name in seen or name not in table:
            continue
        seen.add(name)
        written, called, resume = table[name]
        out |= written
        resumes = resumes or resume
        todo.extend(called)
    return out, resumes


def _write_table(machine, model: Application) -> dict[str, tuple[set[str], set[str], bool]]:
    cache = machine.analysis_cache.setdefault("writes", {})
    table = cache.get(model.path)
    if table is None:
        table = cache[model.path] = {name.lower(): writes_of(prog, model) for name, prog in model.programs.items()}
    return table


def writes_of(prog, app: Application) -> tuple[set[str], set[str], bool]:
    """(globals a program may write, lower-case names of the programs it calls or starts, whether
    it calls taskResume). Library globals are `alias:name`; a call of a library program adds
    `alias:*`. Parameters and locals are not globals. An over-estimate: a variable given to a
    by-reference parameter, to an instruction whose signature is not known, or to a program not
    found, may be written."""
    own = {p.name for p in prog.parameters} | {x.name for x in prog.locals}
    written: set[str] = set()
    called: set[str] = set()
    resume = False
    if prog.body is None:
        return written, called, resume

    def target(e: Any) -> None:
        while type(e) in (ast.Index, ast.Field):
            e = e.base
        if type(e) is ast.Name and e.name not in own:
            written.add(e.name)
        elif type(e) is ast.LibraryName:
            written.add(f"{e.alias}:{e.name}")

    for node in ast.walk(prog.body):
        tn = type(node)
        if tn is ast.Assign or tn is ast.AssignExpr:
            target(node.target)
        elif tn in (ast.Call, ast.TaskCreate, ast.TaskCreateSync):
            if tn is ast.TaskCreateSync:
                target(node.overrun)
            callee = None
            if type(node.target) is ast.Name:
                called.add(node.target.name.lower())
                callee = app.programs.get(node.target.name) or next(
                    (q for n, q in app.programs.items() if n.lower() == node.target.name.lower()), None)
            elif type(node.target) is ast.LibraryName:
                written.add(f"{node.target.alias}:*")
            params = callee.parameters if callee is not None else None
            for i, a in enumerate(node.args):
                if params is None or i >= len(params) or params[i].by_reference or \
                        params[i].container is not Container.ELEMENT:
                    target(a)
        elif tn is ast.CallExpr:
            written_args = _written_arguments(node)
            for i, a in enumerate(node.args):
                if written_args is None or i in written_args:
                    target(a)
            if type(node.func) is ast.Name and node.func.name.lower() == "taskresume":
                resume = True
    return written, called, resume


def _written_arguments(node) -> set[int] | None:
    """The arguments an instruction call may write (by reference, 2.6.2/2.6.3), None when its
    signature is not known (a `$` system call, an s8 instruction, a library's)."""
    if type(node.func) is not ast.Name:
        return None
    ins = lookup(node.func.name)
    if ins is None:
        return None
    n = len(node.args)
    overloads = [o for o in ins.overloads if o.accepts_arity(n)] or list(ins.overloads)
    return {i for i in range(n) if any(i < len(o.params) and (o.params[i].ref or o.params[i].variable
                                                               or o.params[i].container == "any")
                                        for o in overloads)}
