"""Compile a VAL 3 program into a Python generator function, once, before the run.

Walking the syntax tree at every evaluation would be far too slow (the goal is 200,000 VAL 3
lines per second), so each program becomes Python source, compiled with `compile()`. The
work is split as semantic analysis splits it: variables.py (where each variable lives),
expressions.py, calls.py (what the registry says about each instruction), statements.py (lines,
retries, taskResume's jumps); this module puts them together and compiles the source.

The generated function is `P_<name>(T, <parameters>)`: `T` is the running task (`T.q` its
line count), `A` (in the unit's namespace) the unit whose program it is. The Python line
numbers map back to VAL 3 file positions (`Compiled.pos`) for runtime diagnostics and for
reporting where a blocked task waits.
"""

from __future__ import annotations

from ...loading.model import Application, Container, Program
from ...loading.types import base_type
from ..memory import TypeSpace
from .calls import CallCompiler
from .expressions import ExpressionCompiler
from .legacy import effective_parameters
from .statements import StatementCompiler
from .structures import Compiled, CompileError, VarInfo
from .variables import CALL_BYTES, VariableCompiler


class ProgramCompiler(StatementCompiler, CallCompiler, ExpressionCompiler, VariableCompiler):
    """Compiles one program of a unit (units.Unit: an application or a library)."""

    def __init__(self, unit, program: Program, max_level: int = 1000) -> None:
        self.unit = unit
        self.registry = unit.machine.registry
        self.types = unit.expression_types  # id(node) -> semantics' Val
        self.app: Application = unit.model
        self.space: TypeSpace = unit.space
        self.program = program
        self.out: list[str] = []
        self.pos: dict[int, tuple[int, int]] = {}
        self.cur = (program.origin.line, program.origin.col)
        self.ind = 1
        self.tmp = 0
        self.vars: dict[str, VarInfo] = {}
        self.loop_depth = 0
        self.in_switch = 0
        self.arrayed: set[str] = set()
        # taskResume jumps (5.10): each sequence of instructions (block) up to `max_level`
        # nesting levels is a dispatch loop `_bK`; `ctx` is (K, index, length) of the
        # instruction being compiled, `bpos` maps Python lines to it
        self.max_level = max_level
        self.level = 0
        self.nblocks = 0
        self.deepest = 0
        self.ctx: tuple[int, int, int] | None = None
        self.bpos: dict[int, tuple[int, int, int] | None] = {}
        self.sw_flags: list[str] = []
        self.statement_call = None  # the call of the statement being compiled, when it is one
        self.loops: list = []  # structures.LoopSite (statements.py: loop_start, loop_end)

    # ---- output -------------------------------------------------------------------------------

    def emit(self, text: str) -> None:
        self.out.append("    " * self.ind + text)
        self.pos[len(self.out) + 1] = self.cur  # +1: the "def" line comes first
        self.bpos[len(self.out) + 1] = self.ctx

    def fresh(self, stem: str = "t") -> str:
        self.tmp += 1
        return f"_{stem}{self.tmp}"

    def at(self, node) -> None:
        self.cur = (node.line, node.col)

    def err(self, message: str, node=None) -> CompileError:
        line, col = (node.line, node.col) if node is not None and hasattr(node, "line") else self.cur
        return CompileError(message, line, col)

    def compile(self) -> Compiled:
        prog = self.program
        self.setup_vars()
        fb = self.frame_bytes()
        params = []
        for p in prog.parameters:
            v = self.vars[p.name]
            if v.store == "ref":
                params += [f"c_{p.name}", f"k_{p.name}"]
            elif v.store == "box":
                params.append(f"a_{p.name}")
            else:
                params.append(f"v_{p.name}")
        body = prog.body
        # 2.1.4.2: a task's execution memory holds the parameters and locals of every program of
        # its call stack; a call that does not fit stops the task at the program's declaration
        # (error 41), as does local data the simulator has no memory for (error 40).
        self.cur = (prog.origin.line, prog.origin.col)
        self.emit("while 1:")
        self.ind += 1
        self.emit("try:")
        self.ind += 1
        self.emit(f"T.stack += {fb}")
        self.emit(f"if T.stack > T.smax: T.stack -= {fb}; raise E(41, 'the parameters and locals of {prog.name}()"
                  f" need {fb} bytes, the task has ' + str(T.smax - T.stack) + ' left of its ' + str(T.smax))")
        self.ind -= 1
        self.emit("except Exception as _e:")
        self.ind += 1
        self.emit("yield from FAIL(T, _e, False, None)")
        self.emit("continue")
        self.ind -= 1
        self.emit("break")
        self.ind -= 1
        prologue_at = len(self.out)
        boxinit = ["None"] * self.nbox
        for p in prog.parameters:
            v = self.vars[p.name]
            if v.store == "box":
                boxinit[v.slot] = f"a_{p.name}"
        for loc in prog.locals:
            v = self.vars[loc.name]
            if v.store == "box":
                boxinit[v.slot] = f"DEFAULT({v.t!r}, {loc.name!r})"
        if self.nbox:
            self.emit(f"L = [{', '.join(boxinit)}]")
        for loc in prog.locals:
            v = self.vars[loc.name]
            if v.store == "py":
                self.emit(f"v_{loc.name} = {self.default_code(v.t, loc.name)}")
            elif v.store == "obj":
                cont = "COLLECTION" if v.cont == "collection" else "ARRAY"
                self.emit(f"v_{loc.name} = LOCAL({v.t!r}, {cont!r}, {tuple(loc.sizes or (1,))!r}, {loc.name!r})")
        if len(self.out) > prologue_at:  # the locals' values: allocated at the declaration too
            init = self.out[prologue_at:]
            del self.out[prologue_at:]
            self.guarded([line.strip() for line in init], False)
        if body is not None:
            self.cur = (body.line, body.col)
        self.emit("T.frames.append(FRAME())")  # (popped by the `finally` below, however the program ends)
        self.emit("try:")
        self.ind += 1

        def end_line() -> None:
            if body is not None:
                self.cur = (body.end_line, max(1, body.end_col - 3))
            self.line()  # `end` (2.2.5: return and end have the same effect)
            self.emit("pass")

        self.block(body.statements if body is not None else [], end=end_line)
        self.ind -= 1
        self.emit("finally:")
        self.ind += 1
        self.emit(f"T.stack -= {fb}")
        self.emit("T.frames.pop()")
        self.ind -= 1
        self.emit("if 0: yield")
        head = f"def P_{prog.name}(T{''.join(', ' + x for x in params)}):"
        source = head + "\n" + "\n".join(self.out) + "\n"
        filename = f"<val3 {self.unit.uid}:{prog.name}>"
        return Compiled(prog.name, None, prog.parameters, self.pos, prog.origin.path, filename, fb, source,
                        bpos=self.bpos, loops=self.loops)

    def default_code(self, t: str, name: str = "") -> str:
        b = base_type(t)
        if b == "num":
            return "0.0"
        if b == "bool":
            return "False"
        if b == "string":
            return "''"
        return f"DEFAULT({t!r}, {name!r})" if name else f"DEFAULT({t!r})"


def compile_program(unit, program: Program, namespace: dict) -> Compiled:
    """Compile `program` of `unit` into `namespace` (shared by the unit's programs)."""
    if program.code is not None and program.body is None:  # syntax errors (F101): it cannot run
        err = CompileError(f"program {program.name}() has syntax errors", program.origin.line, program.origin.col)
        return _failing(unit, program, err, namespace)
    max_level = 1000
    while True:
        pc = ProgramCompiler(unit, program, max_level)
        try:
            result = pc.compile()
        except CompileError as exc:  # the whole program cannot run: calling it fails with R004
            return _failing(unit, program, exc, namespace)
        try:
            code = compile(result.source, result.filename, "exec")
            break
        except MemoryError:
            err = CompileError(f"program {program.name}() is too large for the simulator (out of memory while"
                               " compiling it)", program.origin.line, program.origin.col)
            return _failing(unit, program, err, namespace)
        except (SyntaxError, RecursionError) as exc:
            # Python allows 20 nested blocks: fewer sequences get a taskResume dispatch loop
            if max_level > 0 and isinstance(exc, SyntaxError):
                max_level = min(max_level, pc.deepest) - 1
                continue
            err = CompileError(f"program too deeply nested for the simulator ({exc.__class__.__name__})",
                               program.origin.line, program.origin.col)
            return _failing(unit, program, err, namespace)
    exec(code, namespace)
    result.func = namespace[f"P_{program.name}"]
    return result


def _failing(unit, program: Program, exc: CompileError, namespace: dict) -> Compiled:
    params = []
    for p in effective_parameters(unit.model, program, unit.machine.legacy_arrays(unit.model)):
        if p.container is Container.ELEMENT and p.by_reference:
            params += [f"c_{p.name}", f"k_{p.name}"]
        else:
            params.append(f"v_{p.name}")
    # the task (or the caller's line) stops with R004 where the program starts
    src = (f"def P_{program.name}(T{''.join(', ' + x for x in params)}):\n"
           f"    T.frames.append(FRAME())\n    try:\n"
           f"        while 1:\n            try:\n                NOTSIM({str(exc)!r})\n"
           f"            except Exception as _e:\n                yield from FAIL(T, _e, False, None)\n"
           f"                continue\n    finally:\n        T.frames.pop()\n"
           f"    if 0: yield\n")
    filename = f"<val3 {unit.uid}:{program.name}>"
    exec(compile(src, filename, "exec"), namespace)
    return Compiled(program.name, namespace[f"P_{program.name}"], program.parameters,
                    {i: (exc.line, exc.col) for i in range(2, 13)}, program.origin.path, filename, CALL_BYTES, src, exc)
