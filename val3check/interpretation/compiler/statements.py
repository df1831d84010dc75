"""Statements in the generated code (2.2.5): one VAL 3 line at a time.

- every VAL 3 line starts with the scheduler's line count (`T.q`, 5.4: as many lines per turn
  as the priority) and hands over with `yield` when the turn is used up;
- each line that may fail is wrapped in a retry loop: a runtime error stops the task at that
  line (12.1, 5.2) and `taskResume(name, 0)` runs the line again, `taskResume(name, 1)` skips
  it;
- each sequence of instructions is a small dispatch loop, so that `taskResume` can resume at
  any of its instructions (`block`);
- calls of programs pass references as (container, key) pairs and copies of values (2.6).
"""

from __future__ import annotations

from typing import NamedTuple

from ...loading.model import Container
from ...loading.types import base_type
from ...parsing import ast
from ..values import NODE_TYPES
from .structures import Code, CompileError, LoopSite


# A budget on the Python the compiler writes: 150,000 lines (about 15,000 VAL 3 lines in one
# program) compile in about 2 s and 700 MB; a 100,000-line program would need many GB.
MAX_SOURCE_LINES = 150_000


class _Mark(NamedTuple):
    """The compiler's state before a statement, to drop what it wrote if it cannot compile."""

    out: int
    ind: int
    loop_depth: int
    in_switch: int
    ctx: tuple | None
    level: int
    sw_flags: int
    loops: int


class StatementCompiler:
    """The statements part of `ProgramCompiler` (program.py)."""

    def line(self) -> None:
        """Count one VAL 3 line (5.4) and hand over when the turn is used up."""
        if len(self.out) > MAX_SOURCE_LINES:
            origin = self.program.origin
            raise CompileError(f"program {self.program.name}() is too large for the simulator (more than"
                               f" {MAX_SOURCE_LINES} lines of generated code)", origin.line, origin.col)
        self.emit("T.q -= 1")
        self.emit("if T.q < 0: yield")

    def guarded(self, code_lines: list[str], skippable: bool) -> None:
        """One VAL 3 line that may fail: stop the task there (5.2); on taskResume (5.10) run it
        again (jump 0), go on after it (1) or resume `jump` instructions away in its sequence."""
        self.emit("while 1:")
        self.ind += 1
        self.emit("try:")
        self.ind += 1
        for c in code_lines:
            self.emit(c)
        self.ind -= 1
        self.emit("except Exception as _e:")
        self.ind += 1
        ctx = self.ctx
        self.emit(f"_j = yield from FAIL(T, _e, {skippable}, {ctx!r})")
        self.emit("if _j == 0: continue")
        if ctx is not None:
            b, i, _ = ctx
            if skippable:
                self.emit(f"if _j != 1: raise JUMP({b}, {i} + _j)")
            else:
                self.emit(f"raise JUMP({b}, {i} + _j)")
        self.ind -= 1
        self.emit("break")
        self.ind -= 1

    def block(self, stmts, end=None) -> None:
        """A sequence of instructions. Up to `max_level` nesting levels it is a dispatch loop, so
        that taskResume can resume at any of its instructions (5.10):

            _bK = 0
            while 1:
                try:
                    if _bK <= 0: <instruction 0>
                    if _bK <= 1: <instruction 1>
                except JUMP as _x:          # resume at instruction _x.t of this sequence
                    if _x.b != K: raise
                    _bK = _x.t
                    continue
                break

        Deeper sequences are plain code (Python allows 20 nested blocks): there, only jumps 0 and
        1 are possible. `end` emits the program's `end` line as the sequence's last position."""
        saved_ctx, saved_level = self.ctx, self.level
        self.level += 1
        self.deepest = max(self.deepest, self.level)
        try:
            if self.level > self.max_level:
                self.ctx = None
                if not stmts and end is None:
                    self.emit("pass")
                for st in stmts:
                    self.stmt(st)
                if end is not None:
                    end()
                return
            self.nblocks += 1
            K = self.nblocks
            n = len(stmts)
            self.emit(f"_b{K} = 0")
            self.emit("while 1:")
            self.ind += 1
            self.emit("try:")
            self.ind += 1
            if not stmts and end is None:
                self.emit("pass")
            for i, st in enumerate(stmts):
                self.ctx = (K, i, n)
                self.emit(f"if _b{K} <= {i}:")
                self.ind += 1
                self.stmt(st)
                self.ind -= 1
            if end is not None:
                self.ctx = (K, n, n)
                self.emit(f"if _b{K} <= {n}:")
                self.ind += 1
                end()
                self.ind -= 1
            self.ind -= 1
            self.ctx = saved_ctx
            self.emit("except JUMP as _x:")
            self.ind += 1
            self.emit(f"if _x.b != {K}: raise")
            self.emit(f"_b{K} = _x.t")
            self.emit("continue")
            self.ind -= 1
            self.emit("break")
            self.ind -= 1
            if self.sw_flags and self.in_switch and not self.loop_depth:
                self.emit(f"if {self.sw_flags[-1]}: break")  # a `break` of the switch left this loop
        finally:
            self.ctx, self.level = saved_ctx, saved_level

    def stmt(self, s) -> None:
        self.at(s)
        ts = type(s)
        mark = _Mark(len(self.out), self.ind, self.loop_depth, self.in_switch, self.ctx, self.level,
                     len(self.sw_flags), len(self.loops))
        try:
            if ts is ast.Assign:
                self.line()
                code, _ = self.assign_code(s.target, s.value, as_expr=False)
                self.guarded(code.split("\n"), True)
            elif ts is ast.ExprStatement:
                self.line()
                self.statement_call = s.call  # its value is not used (a `$` call, a raw handler)
                try:
                    code, _ = self.expr(s.call)
                finally:
                    self.statement_call = None
                self.guarded([code], True)
            elif ts is ast.Call:
                self.line()
                self.guarded([self.call_stmt(s)], True)
            elif ts is ast.TaskCreate or ts is ast.TaskCreateSync:
                self.line()
                self.guarded([self.task_create(s)], True)
            elif ts is ast.Print:  # s8 `? expr`: the emulator prints the value; here, a user page line
                self.line()
                parts = [self.coerce(*self.expr(v), "?") for v in s.values]
                calls = [f"PAGE(T, {'putln' if k == len(parts) - 1 else 'put'!r}, {p})" for k, p in enumerate(parts)]
                self.guarded(["; ".join(calls)], True)
            elif ts is ast.Return:
                self.line()
                self.emit("return")
            elif ts is ast.Break:
                if not self.in_switch or self.loop_depth:
                    self.line()
                    self.guarded(["NOTSIM('break outside a switch case')"], True)
                else:
                    self.emit(f"{self.sw_flags[-1]} = 1")
                    self.emit("break")
            elif ts is ast.If:
                self.if_stmt(s)
            elif ts is ast.While:
                self.while_stmt(s)
            elif ts is ast.DoUntil:
                self.do_stmt(s)
            elif ts is ast.For:
                self.for_stmt(s)
            elif ts is ast.Switch:
                self.switch_stmt(s)
            else:
                raise self.err(f"unsupported statement {ts.__name__}", s)
        except CompileError as exc:
            # The line cannot run here: the task stops on it with R004 when it gets there.
            del self.out[mark.out:]
            self.ind, self.loop_depth, self.in_switch = mark.ind, mark.loop_depth, mark.in_switch
            self.ctx, self.level = mark.ctx, mark.level
            del self.sw_flags[mark.sw_flags:]
            del self.loops[mark.loops:]
            self.at(s)
            self.line()
            self.guarded([f"NOTSIM({str(exc)!r})"], True)

    def assign_code(self, target, value, as_expr: bool) -> Code:
        if type(target) is ast.Name and target.name.lower() in ("world", "flange") and self.lookup_var(target.name) is None:
            # the roots may be written (9.4.1, 9.5.1): the next computation through them fails
            c, k, t = None, "WORLD" if target.name.lower() == "world" else "FLANGE", (
                "frame" if target.name.lower() == "world" else "tool")
        else:
            c, k, t, _ = self.lvalue(target)
        vcode, vt = self.expr(value, want=t)
        if t in NODE_TYPES:
            # `=` copies INTO the variable's node (it keeps its identity: what is linked to it
            # follows, 9.4.2); a {...} literal only writes the fields (the reference stays)
            place = k if c is None else f"{c}[{k}]"
            return Code(f"{'NSET' if type(value) is ast.Struct else 'NASG'}({place}, {vcode})", t)
        if t == "dio" and vt in ("bool", "dio", "?"):
            # 3.5.2: `dio = bool` writes the output and returns the value
            tgt = f"{c}[{k}]" if c is not None else k
            v = f"IOR({vcode})" if vt == "dio" else vcode
            return Code(f"IOW(T, {tgt}, {v})", "bool")
        if t == "sio" and vt in ("num", "string"):
            tgt = f"{c}[{k}]" if c is not None else k
            return Code(f"(yield from SIOW(T, {tgt}, {vcode}, {vt!r}))", vt)
        if vt == "sio" and t in ("num", "string"):
            vcode = f"(yield from SIOR(T, {vcode}, {t!r}))"
        elif t == "bool" and vt == "dio":
            vcode = f"IOR({vcode})"
        elif t == "num" and vt == "aio":
            vcode = self.coerce(vcode, vt, t)
        elif t not in ("num", "bool", "string") and vt not in ("num", "bool", "string") and type(value) is not ast.Struct:
            vcode = f"CP({vcode})"  # 7.3: `=` copies (deep copy) structured and user-type values
        if as_expr:
            if c is None:
                return Code(f"({k} := {vcode})", t)
            return Code(f"ASG({c}, {k}, {vcode})", t)
        if c is None:
            return Code(f"{k} = {vcode}", t)
        return Code(f"{c}[{k}] = {vcode}", t)

    def call_args(self, target, args, params) -> list[str]:
        if params is None and type(target) is ast.LibraryName:
            # the library's interface is not known here (not found when loading): values only;
            # the call itself raises 80 until the library is loaded (6.4)
            return [self.expr(a).text for a in args]
        if params is None:
            raise self.err(f"unknown program '{getattr(target, 'name', '?')}'", target)
        if len(args) != len(params):
            raise self.err(f"program '{target.name}' takes {len(params)} argument(s), not {len(args)}", target)
        out = []
        for a, p in zip(args, params):
            if p.container is not Container.ELEMENT:
                out.append(self.container_arg(a))
            elif p.by_reference:
                c, k, _, _ = self.lvalue(a)
                if c is None:
                    raise self.err("internal: local not boxed", a)
                out.append(c)
                out.append(k)
            else:
                code, t = self.expr(a, want=base_type(p.type))
                code = self.coerce(code, t, base_type(p.type))
                if base_type(p.type) in NODE_TYPES:
                    code = f"CPL({code})"  # 2.6.1: the callee gets a copy, a local of its own
                elif t not in ("num", "bool", "string", "dio", "aio", "sio"):
                    code = f"CP({code})"  # 2.6.1: the callee gets a copy
                out.append(code)
        return out

    def prog_ref(self, target) -> str:
        if type(target) is ast.Name:
            prog = self._program(target.name)
            if prog is None:
                raise self.err(f"unknown program '{target.name}'", target)
            return f"P_{prog.name}"
        return f"LP(A, {target.alias!r}, {target.name!r})"

    def call_stmt(self, s: ast.Call) -> str:
        params = self._callee_params(s.target)
        args = self.call_args(s.target, s.args, params)
        return f"yield from {self.prog_ref(s.target)}(T{''.join(', ' + x for x in args)})"

    def task_create(self, s) -> str:
        params = self._callee_params(s.target)
        args = self.call_args(s.target, s.args, params)
        name = self.coerce(*self.expr(s.task), "string")
        fn = self.prog_ref(s.target)
        pname = s.target.name if type(s.target) is ast.Name else f"{s.target.alias}:{s.target.name}"
        argt = "(" + "".join(x + ", " for x in args) + ")"
        if type(s) is ast.TaskCreate:
            prio = self.expr(s.priority).text
            return f"TASKCREATE(T, A, {name}, {prio}, {fn}, {argt}, {pname!r})"
        period = self.expr(s.period).text
        over = self.ref_arg(s.overrun)
        return f"TASKCREATESYNC(T, A, {name}, {period}, {over}, {fn}, {argt}, {pname!r})"

    def if_stmt(self, s: ast.If) -> None:
        depth = 0
        for i, br in enumerate(s.branches):
            self.at(br)
            self.line()
            self.guarded([f"_c = {self.cond(br.cond)}"], False)
            self.emit("if _c:")
            self.ind += 1
            self.block(br.body)
            self.ind -= 1
            self.emit("else:")
            self.ind += 1
            depth += 1
        if s.orelse is not None:
            self.block(s.orelse)
        else:
            self.emit("pass")
        self.ind -= depth

    # A loop counts its passes in a local list (`_lN = [0]`, new at each entry, `_lN[0] += 1` at
    # each pass): a motion instruction reads which pass of which loops records it (the cycle of
    # docs/motion.md). The site spans the Python lines of the loop (structures.LoopSite).

    def loop_start(self, s, kind: str) -> int:
        """The loop's counter, before its first line: the index of its site."""
        k = len(self.loops)
        self.emit(f"_l{k} = [0]")
        self.loops.append(LoopSite(kind, s.line, s.col, len(self.out) + 2, 0, f"_l{k}"))
        return k

    def loop_pass(self, k: int) -> None:
        """One more pass of loop `k`."""
        self.emit(f"_l{k}[0] += 1")

    def loop_end(self, k: int) -> None:
        """The last Python line of loop `k`."""
        self.loops[k] = self.loops[k]._replace(py_last=len(self.out) + 1)

    def while_stmt(self, s: ast.While) -> None:
        k = self.loop_start(s, "while")
        self.emit("while 1:")
        self.ind += 1
        self.at(s)
        self.line()
        self.guarded([f"_c = {self.cond(s.cond)}"], False)
        self.emit("if not _c: break")
        self.loop_pass(k)
        self.loop_depth += 1
        self.block(s.body)
        self.loop_depth -= 1
        self.ind -= 1
        self.loop_end(k)

    def do_stmt(self, s: ast.DoUntil) -> None:
        k = self.loop_start(s, "do")
        self.emit("while 1:")
        self.ind += 1
        self.loop_pass(k)
        self.loop_depth += 1
        self.block(s.body)
        self.loop_depth -= 1
        self.cur = (s.until_line, s.until_col)
        self.line()
        self.guarded([f"_c = {self.cond(s.cond)}"], False)
        self.emit("if _c: break")
        self.ind -= 1
        self.loop_end(k)

    def for_stmt(self, s: ast.For) -> None:
        n = self.fresh("f")
        c, k, t, _ = self.lvalue(s.counter)
        place = k if c is None else f"{c}[{k}]"
        self.line()
        start = self.num(s.start)
        stop = self.num(s.stop)
        step = self.num(s.step) if s.step is not None else "1.0"
        self.guarded([f"{n}b = {stop}", f"{n}s = {step}", f"{place} = {start}"], False)
        site = self.loop_start(s, "for")
        self.emit("while 1:")
        self.ind += 1
        # 2.2.5: positive step: stop when the counter is above nFin; negative: below
        self.guarded([f"_c = ({place} > {n}b) if {n}s >= 0 else ({place} < {n}b)"], False)
        self.emit("if _c: break")
        self.loop_pass(site)
        self.loop_depth += 1
        self.block(s.body)
        self.loop_depth -= 1
        self.cur = (s.end_line, max(1, s.end_col - 6))
        self.line()
        self.guarded([f"{place} = {place} + {n}s"], False)
        self.ind -= 1
        self.loop_end(site)

    def switch_stmt(self, s: ast.Switch) -> None:
        n = self.fresh("k")
        subj, st = self.expr(s.subject)
        if st == "dio":
            subj = f"IOR({subj})"
            st = "bool"
        elif st == "aio":
            subj, st = self.coerce(subj, st, "num"), "num"
        self.line()
        lines = [f"_s = {subj}", f"{n} = -1"]
        tests = []
        for i, case in enumerate(s.cases):
            vals = [self.coerce(*self.expr(v, want=st), st) for v in case.values]
            tests.append((i, " or ".join(f"_s == {v}" for v in vals) or "False"))
        code = lines
        # flat tests, not an elif chain: Python's compiler nests elif, and thousands of cases
        # would exhaust its recursion
        for i, test in tests:
            code.append(f"if {n} < 0 and ({test}): {n} = {i}")
        if s.default is not None:
            code.append(f"if {n} < 0: {n} = {len(s.cases)}")
        self.guarded(code, False)
        flag = f"{n}x"
        self.emit(f"{flag} = 0")
        self.emit("while 1:")
        self.ind += 1
        self.in_switch += 1
        self.sw_flags.append(flag)
        saved_loops = self.loop_depth
        self.loop_depth = 0
        bodies = [c.body for c in s.cases] + ([s.default.body] if s.default is not None else [])
        for i, body in enumerate(bodies):
            self.emit(f"if {n} == {i}:")
            self.ind += 1
            self.block(body)
            # no break: the next case's instructions follow (2.2.5 runs "jusqu'au mot-clé break")
            self.emit(f"{n} = {i + 1}")
            self.ind -= 1
        self.emit("break")
        self.loop_depth = saved_loops
        self.sw_flags.pop()
        self.in_switch -= 1
        self.ind -= 1

    # ---- the program --------------------------------------------------------------------------
