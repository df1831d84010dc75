"""What the S rules need to know about names: a small resolver and the use/write facts.

Only local knowledge is used: a program's parameters and locals (from the model), the globals
of its application (`app.data`), program names (`app.programs`) and library aliases. A name
resolves like the controller does (manual 2.5.2): local or parameter first, then global.

Variables are resolved with their exact spelling, as the controller does, where a finding
depends on it; a mention or a write in any spelling counts as a use or a write, which can only
make the rules quieter. Programs and instructions are looked up without regard to case.

Rules here:
- S001 unused local, S002 unused parameter, S003 unused global, S004 unused private program;
- S005 a local read before any value is assigned to it, where that is certain.
"""

from __future__ import annotations

import re
from functools import cache

from ..diagnostics import Diagnostic
from ..language.instructions import lookup as lookup_instruction
from ..language.types import load_aliases, load_types
from ..light_dataclass import dataclass, field
from ..loading.model import Application, Container, Program, Workspace
from ..parsing import ast as A
from . import patterns_messages as M
from .program_nodes import ProgramNodes

# Types whose variables are linked to hardware or to the user interface (3.5-3.7, 4).
IO_TYPES = frozenset({"dio", "aio", "sio", "screen"})
# Built-in types of plain values: what a local of these types holds is only its own value.
VALUE_TYPES = frozenset({"bool", "num", "string", "trsf", "frame", "tool", "point", "joint", "config", "mdesc"})
# Reference frames and tools: the operator jogs and teaches in them from the pendant.
REFERENCE_TYPES = frozenset({"frame", "tool"})
# The system's root frame and tool: declared in the data of s6 applications, always defined.
SYSTEM_DATA = frozenset({"world", "flange"})

_DEFAULT_TEXT = {
    "bool": "false", "num": "0", "string": '""', "trsf": "{0,0,0,0,0,0}", "joint": "0 in every field",
    "mdesc": "the default motion descriptor", "config": "the default configuration",
    "point": "a point without reference frame", "frame": "a frame without reference frame",
    "tool": "a tool without base tool",
}
_IDENT = re.compile(r"[A-Za-z][A-Za-z0-9_]*")


@cache
def _type_table() -> dict[str, str]:
    table = {name.lower(): name for name in load_types()}
    for name, alias in load_aliases().items():
        table[name.lower()] = alias.type
    return table


def builtin_type(name: str) -> str | None:
    """The built-in type behind a type name as written (`pointRx` -> `point`); None for user types."""
    return _type_table().get((name or "").lower())


@cache
def _instruction_writes(key: str) -> tuple[bool, ...] | None:
    """Per argument position of the instruction `key` (lower-case): may the instruction write it?
    None: not an instruction.

    A parameter marked `&`, or that needs a variable, or that takes an array or a collection
    counts as written (manual 2.6.2, 2.6.3): `toNum(s, nVal, bOk)`, `get(sDay)`, `sioGet(si, nBuf)`.
    """
    ins = lookup_instruction(key)
    if ins is None:
        return None
    width = max((len(o.params) for o in ins.overloads), default=0)
    flags = []
    for k in range(width):
        flags.append(any(len(o.params) > k and o.params[k].needs_variable for o in ins.overloads))
    return tuple(flags)


def instruction_name(func: object) -> str | None:
    """Lower-case instruction name of a call's `func` (`alias:libLoad` gives `libload`)."""
    if type(func) is A.Name or type(func) is A.LibraryName:
        return func.name.lower()
    return None


def root_name(expr: object) -> A.Name | None:
    """The variable an lvalue designates: `a`, `a[i]`, `a.b.c`, `a[i].b` -> the Name `a`."""
    while True:
        t = type(expr)
        if t is A.Name:
            return expr
        if t is A.Index or t is A.Field:
            expr = expr.base
            continue
        return None


class Resolver:
    """Names of one application: programs, globals, libraries (built once per application)."""

    def __init__(self, workspace: Workspace, app: Application):
        self.workspace = workspace
        self.app = app
        self.programs = {name.lower(): p for name, p in app.programs.items()}
        self.globals = {name.lower(): d for name, d in app.data.items()}
        self._library_programs: dict[str, dict[str, Program]] = {}

    def program(self, target: object) -> Program | None:
        """The program a `call`/`taskCreate` names, when it is known."""
        if type(target) is A.Name:
            return self.programs.get(target.name.lower())
        if type(target) is A.LibraryName:
            alias = target.alias
            if alias not in self._library_programs:
                lib = self.workspace.library(self.app, alias)
                self._library_programs[alias] = {n.lower(): p for n, p in lib.programs.items()} if lib else {}
            return self._library_programs[alias].get(target.name.lower())
        return None

    def program_writes(self, target: object, count: int) -> list[bool]:
        """Per argument of a program call: may the callee write it (parameter by reference)?"""
        prog = self.program(target)
        if prog is None:
            return [True] * count
        params = prog.parameters
        return [k >= len(params) or params[k].by_reference or params[k].container != Container.ELEMENT
                for k in range(count)]

    @staticmethod
    def call_writes(call: A.CallExpr) -> list[bool]:
        """Per argument of an instruction call: may the instruction write it? Unknown: yes."""
        name = instruction_name(call.func) if type(call.func) is not A.SystemName else None
        flags = _instruction_writes(name) if name else None
        count = len(call.args)
        if flags is None:
            return [True] * count
        return [k >= len(flags) or flags[k] for k in range(count)]


class Scope:
    """What a name means inside one program (manual 2.5.2): local/parameter, then global.

    Variable names are matched with their exact spelling, as the controller does; the rules
    that only become quieter with a looser match (a use, a write) compare without case.
    """

    def __init__(self, resolver: Resolver, program: Program):
        self.resolver = resolver
        self.locals = {v.name: v for v in program.locals}
        self.params = {p.name: p for p in program.parameters}
        # without case: the first local, the first parameter of each lower-case name
        self._locals_ci: dict = {}
        for n, v in self.locals.items():
            self._locals_ci.setdefault(n.lower(), v)
        self._params_ci: dict = {}
        for n, v in self.params.items():
            self._params_ci.setdefault(n.lower(), v)

    def kind(self, name: str) -> str:
        """"local", "param", "global" or "other" for a name as written."""
        if name in self.locals:
            return "local"
        if name in self.params:
            return "param"
        if name in self.resolver.app.data:
            return "global"
        return "other"

    def type_of(self, name: str, ci: bool = False) -> str | None:
        """The declared type (as written) of a local, parameter or global; None otherwise.
        With `ci`, a variable whose name differs only by case also answers."""
        v = self.locals.get(name) or self.params.get(name) or self.resolver.app.data.get(name)
        if v is None and ci:
            key = name.lower()
            v = self._locals_ci.get(key) or self._params_ci.get(key) or self.resolver.globals.get(key)
        return v.type if v is not None else None


# ------------------------------------------------------------------ facts of one program


@dataclass(slots=True)
class ProgramFacts:
    """Everything the S rules read from one parsed program, from the walk of its tree the checks
    share (program_nodes.ProgramNodes, kept in `nodes` for the rules that need a loop's nodes)."""

    names: set[str] = field(default_factory=set)  # names mentioned anywhere, as written
    called: set[str] = field(default_factory=set)  # programs named by call/taskCreate(Sync)
    task_targets: set[str] = field(default_factory=set)  # programs named by taskCreate(Sync)
    strings: list | tuple = field(default_factory=list)  # String nodes
    binaries: list | tuple = field(default_factory=list)  # Binary nodes, in pre-order
    assigns: list | tuple = field(default_factory=list)  # Assign statements
    loops: list = field(default_factory=list)  # While and DoUntil nodes, in pre-order
    dynamic_data: bool = False  # getData() with a name that is not a constant string
    nodes: ProgramNodes | None = None

    def lower_names(self) -> set[str]:
        return {n.lower() for n in self.names}

    def string_tokens(self) -> set[str]:
        tokens: set[str] = set()
        for s in self.strings:
            tokens.update(t.lower() for t in _IDENT.findall(s.value))
        return tokens


def gather(nodes: ProgramNodes) -> ProgramFacts:
    """The facts of one program, read from the walk of its tree that the checks share."""
    called: set[str] = set()
    task_targets: set[str] = set()
    for kind in (A.Call, A.TaskCreate, A.TaskCreateSync):
        for node in nodes.of(kind):
            if type(node.target) is A.Name:
                target = node.target.name.lower()
                called.add(target)
                if kind is not A.Call:
                    task_targets.add(target)
    dynamic_data = any(type(c.func) is A.Name and c.func.name.lower() == "getdata"
                       and (not c.args or type(c.args[0]) is not A.String) for c in nodes.of(A.CallExpr))
    # while and do loops in source order (outer first): no two start at the same place
    loops = sorted([*nodes.of(A.While), *nodes.of(A.DoUntil)], key=_start)
    return ProgramFacts(names={n.name for n in nodes.of(A.Name)}, called=called, task_targets=task_targets,
                        strings=nodes.of(A.String), binaries=nodes.of(A.Binary), assigns=nodes.of(A.Assign),
                        loops=loops, dynamic_data=dynamic_data, nodes=nodes)


def _start(node: object) -> tuple[int, int]:
    return node.line, node.col


# ------------------------------------------------------------------ unused (S001-S004)


def application_is_library(workspace: Workspace, app: Application) -> bool:
    """A library or user type: no start() (manual 6.1), a start() that does nothing (SRS creates
    user types and libraries with empty start() and stop(): linted alone, nothing else says what
    they are), or used as one by another loaded application. Its public programs and globals are
    an interface (6.2, 7.2)."""
    start = next((p for name, p in app.programs.items() if name.lower() == "start"), None)
    if start is None or (start.body is not None and not start.body.statements):
        return True
    key = app.path
    for other in workspace.apps.values():
        if other is app:
            continue
        for ref in list(other.libraries.values()) + list(other.types.values()):
            if ref.resolved and ref.resolved == key:
                return True
    return False


def unused_in_program(program: Program, facts: ProgramFacts, interface: bool, is_task: bool) -> list[Diagnostic]:
    """S001 locals and S002 parameters that the program's code never mentions."""
    out = []
    path = program.origin.path
    mentioned = facts.lower_names()
    for local in program.locals:
        if local.name.lower() not in mentioned:
            o = local.origin
            out.append(Diagnostic(M.UNUSED_LOCAL, M.unused_local(local.name, program.name), o.path or path,
                                  o.line, o.col, fix=("remove-element", local.name)))
    if not interface and not is_task:
        for param in program.parameters:
            if param.name.lower() not in mentioned:
                o = param.origin
                out.append(Diagnostic(M.UNUSED_PARAMETER, M.unused_parameter(param.name, program.name),
                                      o.path or path, o.line, o.col))
    return out


def _father_names(app: Application) -> set[str]:
    """Globals named as the reference frame/tool of another global or value (fatherId)."""
    found: set[str] = set()
    stack = list(app.data.values())
    while stack:
        d = stack.pop()
        fathers = [d.father] + [v.father for v in d.values]
        for f in fathers:
            if f and ":" not in f:
                found.add(f.split("[", 1)[0].strip().lower())
        for v in d.values:
            stack.extend(v.members.values())
    return found


def unused_globals(app: Application, facts: dict[str, ProgramFacts], library: bool,
                   public_is_read: bool = False) -> list[Diagnostic]:
    """S003: globals no program of the application mentions, where that is certain.
    `public_is_read`: its public globals are read from outside (s8: OPC UA, web user pages)."""
    if not app.globals_known or not app.data:
        return []
    if "program" in app.unread or any(p.body is None for p in app.programs.values()):
        return []  # a program that is missing or did not parse may use any of them
    if any(f.dynamic_data for f in facts.values()):
        return []  # getData() with a computed name may read any of them (2.5.4)
    if library and not any(d.access == "public" for d in app.data.values()):
        return []  # a library without public data: access was probably not written
    used: set[str] = set()
    tokens: set[str] = set()
    for name, program in app.programs.items():
        f = facts.get(name)
        if f is None:
            continue
        own = {v.name for v in program.locals} | {p.name for p in program.parameters}
        used.update(n.lower() for n in f.names if n not in own)  # a local hides the global (2.5.2)
        tokens.update(f.string_tokens())
    used |= _father_names(app)
    used |= app.ui_names  # bound by an s8 web user page
    out = []
    for data in app.data.values():
        key = data.name.lower()
        if key in used or key in tokens or key in SYSTEM_DATA:
            continue
        if (library or public_is_read) and data.access != "private":
            continue  # the interface of a library or the fields of a user type (6.2, 7.2), or read over OPC UA
        base = builtin_type(data.type)
        if base in IO_TYPES:
            continue  # linked to hardware: declared for the I/O map, often on purpose
        if base in REFERENCE_TYPES:
            continue  # frames and tools also serve to jog and teach from the pendant (9.4, 9.5)
        o = data.origin
        out.append(Diagnostic(M.UNUSED_GLOBAL, M.unused_global(data.name, library), o.path, o.line, o.col))
    return out


def unused_programs(app: Application, facts: dict[str, ProgramFacts], library: bool) -> list[Diagnostic]:
    """S004: private programs that no other program of the application calls."""
    if "program" in app.unread or any(p.body is None for p in app.programs.values()):
        return []  # a program that is missing or did not parse may call any of them
    if library and not any(p.access == "public" for p in app.programs.values()):
        return []  # a library without public program: access was probably not written
    called_by: dict[str, set[str]] = {}
    for name, f in facts.items():
        for target in f.called:
            called_by.setdefault(target, set()).add(name.lower())
    out = []
    for name, program in app.programs.items():
        key = name.lower()
        if program.access != "private" or key in ("start", "stop"):
            continue
        if called_by.get(key, set()) - {key}:
            continue
        if key in app.ui_names:
            continue  # a callback of an s8 web user page (*.bindings.json)
        body = program.body
        if body is not None and not body.statements and body.comments:
            continue  # comments only (a `readme`): documentation, not dead code
        o = program.origin
        out.append(Diagnostic(M.UNUSED_PROGRAM, M.unused_program(program.name), o.path, o.line, o.col))
    return out


# ------------------------------------------------------------------ read before assignment (S005)


class _AllWritten(Exception):
    """Every tracked local is written: no later read can be certain to see the initial value,
    and a loop still open around an earlier read contains that read's first write (which came
    after it), so the rest of the walk cannot change the findings."""


def _certain_reads(statements: list, tracked: set[str], resolver: Resolver) -> list[tuple[str, A.Name]]:
    """Walks a program in evaluation order and records, per tracked local, the first write and
    the first read that comes before any write (with the outermost loop around that read); the
    reads certain to see the initial value.

    A read is certain to see the initial value when no write comes before it in the program
    text and no loop around it contains a write (the next iteration would see that write).
    VAL 3 has no goto: in structured code, every path to a statement only runs statements
    written before it, or statements of the loops around it.

    Closures over local state, not methods (S005 was the costliest S rule: a call and attribute
    writes per node); `pos` counts the same events in the same order as before.
    """
    pos = 0
    depth = 0
    outer: int | None = None
    unwritten = {name.lower() for name in tracked}
    first_write: dict[str, int] = {}  # tracked names are exact; writes match without case (quieter)
    first_read: dict[str, tuple[A.Name, int | None]] = {}
    loop_end: dict[int, int] = {}
    Name, Binary, CallExpr, Index, Field, Unary, Struct, AssignExpr = (
        A.Name, A.Binary, A.CallExpr, A.Index, A.Field, A.Unary, A.Struct, A.AssignExpr)
    call_writes, program_writes = Resolver.call_writes, resolver.program_writes

    def enter_loop() -> None:
        nonlocal pos, depth, outer
        depth += 1
        if depth == 1:
            outer = pos
        pos += 1

    def exit_loop() -> None:
        nonlocal pos, depth
        depth -= 1
        if depth == 0 and outer is not None:
            loop_end[outer] = pos
        pos += 1

    def read(e: object) -> None:
        nonlocal pos
        t = type(e)
        if t is Name:
            name = e.name
            if name in tracked and name not in first_read and name.lower() not in first_write:
                first_read[name] = (e, outer if depth else None)
            pos += 1
        elif t is Binary:
            read(e.left)
            read(e.right)
        elif t is CallExpr:
            args(e.args, call_writes(e))
        elif t is Index:
            read(e.base)
            for i in e.indices:
                read(i)
        elif t is Field:
            read(e.base)
        elif t is Unary:
            read(e.operand)
        elif t is Struct:
            for f in e.fields:
                if f is not None:
                    read(f)
        elif t is AssignExpr:
            read(e.value)
            write(e.target)

    def write(e: object) -> None:
        """`e` is assigned (or passed where it may be written): its indices are read."""
        nonlocal pos
        t = type(e)
        if t is Name:
            key = e.name.lower()
            if key not in first_write:
                first_write[key] = pos
                if key in unwritten:
                    unwritten.discard(key)
                    if not unwritten:
                        raise _AllWritten
            pos += 1
        elif t is Index:
            for i in e.indices:
                read(i)
            write(e.base)
        elif t is Field:
            write(e.base)
        else:
            read(e)

    def args(values: list, writes: list[bool]) -> None:
        for arg, w in zip(values, writes):
            if w:
                write(arg)
            else:
                read(arg)

    def block(body: list) -> None:
        for s in body:
            t = type(s)
            if t is A.Assign:
                read(s.value)
                write(s.target)
            elif t is A.ExprStatement:
                read(s.call)
            elif t is A.Call:
                args(s.args, program_writes(s.target, len(s.args)))
            elif t is A.If:
                for branch in s.branches:
                    read(branch.cond)
                    block(branch.body)
                if s.orelse:
                    block(s.orelse)
            elif t is A.While:
                enter_loop()
                read(s.cond)
                block(s.body)
                exit_loop()
            elif t is A.DoUntil:
                enter_loop()
                block(s.body)
                read(s.cond)
                exit_loop()
            elif t is A.For:
                read(s.start)
                enter_loop()
                write(s.counter)
                read(s.stop)
                if s.step is not None:
                    read(s.step)
                block(s.body)
                exit_loop()
            elif t is A.Switch:
                read(s.subject)
                for case in s.cases:
                    for v in case.values:
                        read(v)
                    block(case.body)
                if s.default is not None:
                    block(s.default.body)
            elif t is A.TaskCreate or t is A.TaskCreateSync:
                read(s.task)
                if t is A.TaskCreate:
                    read(s.priority)
                else:
                    read(s.period)
                    write(s.overrun)
                args(s.args, program_writes(s.target, len(s.args)))

    try:
        block(statements)
    except _AllWritten:
        pass
    out = []
    for name, (node, loop) in first_read.items():
        written = first_write.get(name.lower())
        if loop is not None and written is not None and written < loop_end.get(loop, written + 1):
            continue  # written later in a loop around the read: the next iteration sees it
        out.append((name, node))
    return out


def read_before_assignment(program: Program, resolver: Resolver) -> list[Diagnostic]:
    """S005: a local read where it can only hold its initial value (2.2.5 call, 2.4.1).

    Only locals of built-in value types (not I/O, not user types whose defaults are chosen by
    the type's author, 7.1). Writes include passing the local where it may be written: to a
    program parameter by reference, or an instruction parameter `&`/variable/container.
    """
    tracked: dict[str, str] = {}
    for local in program.locals:
        base = builtin_type(local.type)
        if base in VALUE_TYPES:
            tracked[local.name] = base
    params = {p.name.lower() for p in program.parameters}
    lowered: dict[str, int] = {}
    for name in tracked:
        lowered[name.lower()] = lowered.get(name.lower(), 0) + 1
    for name in list(tracked):
        if name.lower() in params or lowered[name.lower()] > 1:
            del tracked[name]  # a duplicate declaration: the other rules' business
    if not tracked:
        return []
    out = []
    for key, node in _certain_reads(program.body.statements, set(tracked), resolver):
        out.append(Diagnostic(M.READ_BEFORE_ASSIGNMENT, M.read_before_assignment(node.name, _DEFAULT_TEXT[tracked[key]]),
                              program.origin.path, node.line, node.col, node.end_line, node.end_col))
    return out
