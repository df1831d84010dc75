"""Statements of a program body (manual 2.2.5, 5.10): assignments, calls, control structures.

`StatementChecker(ctx).check(body)` walks the statements once, in order, typing every
expression through ExprTyper and checking what each statement requires of them.
"""

from __future__ import annotations

from ..language.instructions import lookup as lookup_instruction
from ..language.version_facts import task_name_problem
from ..parsing import ast as A
from ..rules import codes
from . import messages as M
from . import symbols as S
from . import vtypes as vt
from .calls import ProgramSignature, check_call_expr, check_program_args, signature
from .expressions import ExprTyper, node_text, suggest

UNKNOWN_VAL = vt.UNKNOWN_VAL


class StatementChecker(ExprTyper):
    def __init__(self, ctx, signatures: dict[int, ProgramSignature]) -> None:
        super().__init__(ctx, check_call_expr)
        self.signatures = signatures
        self._stmt = {
            A.Assign: self._assign,
            A.ExprStatement: self._expr_statement,
            A.Call: self._call_statement,
            A.TaskCreate: self._task_create,
            A.TaskCreateSync: self._task_create_sync,
            A.Print: self._print,
            A.If: self._if,
            A.While: self._while,
            A.DoUntil: self._do,
            A.For: self._for,
            A.Switch: self._switch,
        }

    def check(self, body: A.ProgramBody) -> None:
        self.block(body.statements)

    def block(self, statements: list) -> None:
        get = self._stmt.get
        ctx = self.ctx
        outer = ctx.guess  # a statement's findings depend on the guesses it consults, not its neighbours'
        for st in statements:
            f = get(type(st))
            if f is not None:
                ctx.guess = ""
                f(st)
        ctx.guess = outer

    # -- simple statements -----------------------------------------------------------------

    def _assign(self, st: A.Assign) -> None:
        self.assignment(st.target, st.value, (st.op_line, st.op_col))

    def _expr_statement(self, st: A.ExprStatement) -> None:
        self.call(st.call, True)

    def _print(self, st: A.Print) -> None:
        for v in st.values:
            self.typeof(v)  # any value, containers included: what the emulator prints is not documented
        self.ctx.s8_only("the print statement '? expr'", st)

    def _condition(self, cond: object, keyword: str) -> None:
        v = self.elem(cond)
        if type(cond) is A.AssignExpr:
            return  # `if x = y`: the misplaced `=` is the one error reported (T004)
        if not vt.condition_ok(v.t):
            self.ctx.report_at(
                codes.CONDITION_NOT_BOOL,
                M.condition_not_bool(keyword, v.t.name if v.t.kind != vt.LITERAL else "{...} value"),
                cond,
            )

    # -- control structures ----------------------------------------------------------------

    def _if(self, st: A.If) -> None:
        for i, br in enumerate(st.branches):
            self._condition(br.cond, "if" if i == 0 else "elseIf")
            self.block(br.body)
        if st.orelse is not None:
            self.block(st.orelse)

    def _while(self, st: A.While) -> None:
        self._condition(st.cond, "while")
        self.block(st.body)

    def _do(self, st: A.DoUntil) -> None:
        self.block(st.body)
        self._condition(st.cond, "until")

    def _for(self, st: A.For) -> None:
        ctx = self.ctx
        counter = st.counter
        if type(counter) is not A.ErrorExpr:
            v = self.typeof(counter)
            if v is not UNKNOWN_VAL:
                if not v.var and v.t.known:
                    ctx.report_at(codes.BAD_FOR_HEADER, M.for_counter(node_text(counter)), counter)
                elif v.elem is False:
                    self._report_missing_index(counter, v)
                elif v.t.known and v.t is not vt.NUM:
                    ctx.report_at(codes.BAD_FOR_HEADER, M.for_counter(f"a {v.t.name}"), counter)
        for which, e in (("start value", st.start), ("end value", st.stop), ("step", st.step)):
            if e is None or type(e) is A.ErrorExpr:
                continue
            b = self.elem(e)
            if not vt.is_num_like(b.t):
                ctx.report_at(
                    codes.BAD_FOR_HEADER, M.for_bound(which, b.t.name if b.t.kind != vt.LITERAL else "{...} value"), e
                )
        self.block(st.body)

    def _switch(self, st: A.Switch) -> None:
        s = self.elem(st.subject)
        for case in st.cases:
            for value in case.values:
                c = self.elem(value)
                if vt.comparable(s.t, c.t) is False:
                    self.ctx.report_at(codes.CASE_TYPE_MISMATCH, M.case_type(c.t.name, s.t.name), value)
            self.block(case.body)
        if st.default is not None:
            self.block(st.default.body)

    # -- programs and tasks ----------------------------------------------------------------

    def _program_target(self, target: object, args: list) -> tuple[ProgramSignature | None, str, list[vt.Val]]:
        """The program a `call`/taskCreate names, its label for messages, and the typed
        arguments (typed even when the program is unknown, to check the names they use)."""
        ctx = self.ctx
        vals = [self.typeof(a) for a in args]
        if type(target) is A.LibraryName:
            label = f"{target.alias}:{target.name}()"
            lib = self.library(target, target.alias)
            if lib is None:
                return None, label, vals
            prog, why = lib.program(target.name)
            if prog is None:
                sym, _ = lib.data_symbol(target.name)
                if sym is not None:
                    ctx.report_at(
                        codes.LIBRARY_SYMBOL_KIND, M.library_symbol_not_program(target.alias, target.name), target
                    )
                    return None, label, vals
                other = lib.lookup_ci(target.name)
                if other is not None and lib.app.programs.get(other) is not None:
                    ctx.report_at(
                        codes.NAME_CASE_MISMATCH,
                        M.case_mismatch("library program", target.name, other),
                        target,
                        fix=("rename", target.name, other, ":", ""),
                    )
                    prog, why = lib.program(other)
                else:
                    if not ctx.program_may_exist(target.name, lib.app) and ctx.names_complete("data", lib.app):
                        publics = [n for n, p in lib.app.programs.items() if p.access == "public"]
                        ctx.report_at(
                            codes.UNDEFINED_LIBRARY_SYMBOL,
                            M.undefined_library_symbol(
                                target.alias, target.name, lib.app.name, suggest(target.name, publics)
                            ),
                            target,
                        )
                    return None, label, vals
            if why:
                ctx.report_at(
                    codes.PRIVATE_LIBRARY_SYMBOL,
                    M.private_library_symbol(target.alias, target.name, lib.app.name, "program"),
                    target,
                )
            return signature(ctx.table.registry, lib.app, prog, self.signatures), label, vals
        name = target.name  # type: ignore[attr-defined]
        label = f"{name}()"
        table = ctx.table
        prog = table.program(name)
        if prog is None:
            prog = table.program_ci(name)
            if prog is not None:
                ctx.report_at(
                    codes.NAME_CASE_MISMATCH,
                    M.case_mismatch("program", name, prog.name),
                    target,
                    fix=("rename", name, prog.name),
                )
        if prog is None:
            ins = lookup_instruction(name)
            if ins is not None:
                ctx.report_at(codes.PROGRAM_INSTRUCTION_MISUSE, M.call_of_instruction(ins.name), target)
            elif ctx.globals_known and not ctx.program_may_exist(name):
                ctx.report_at(
                    codes.UNDEFINED_PROGRAM, M.undefined_program(name, suggest(name, table.app.programs)), target
                )
            return None, label, vals
        return signature(table.registry, ctx.app, prog, self.signatures), label, vals

    def _call_statement(self, st: A.Call) -> None:
        sig, label, vals = self._program_target(st.target, st.args)
        if sig is not None:
            check_program_args(self, st.target, label, sig, st.args, vals, task=False)

    def _task_common(self, keyword: str, name: object, target: object, args: list) -> None:
        v = self.elem(name)
        if vt.assignable(vt.STRING, v.t) is False:
            self.ctx.report_at(
                codes.ARGUMENT_TYPE_MISMATCH, M.argument_type(1, keyword, "sNom", "string", vt.describe(v)), name
            )
        elif type(name) is A.String:
            # 5.10: "sNom doit avoir 1 à 15 caractères parmi a..zA..Z0..9_" (runtime error 29); s8
            # code uses longer names: the rule of the version, shared with the simulator
            problem = task_name_problem(name.value, self.ctx.major)
            if problem is not None:
                self.ctx.report_at(
                    codes.INVALID_TASK_CONSTANT, M.task_name(keyword, name.value, problem.why, problem.certain), name
                )
        sig, label, vals = self._program_target(target, args)
        if sig is not None:
            check_program_args(self, target, label, sig, args, vals, task=True)

    def _task_create(self, st: A.TaskCreate) -> None:
        p = self.elem(st.priority)
        if not vt.is_num_like(p.t):
            self.ctx.report_at(
                codes.ARGUMENT_TYPE_MISMATCH,
                M.argument_type(2, "taskCreate", "nPriorité", "num", vt.describe(p)),
                st.priority,
            )
        elif type(st.priority) is A.Number and not 1 <= st.priority.value <= 100:
            # 5.10: "nPriorité doit être compris entre 1 et 100" (runtime error 70)
            self.ctx.report_at(codes.INVALID_TASK_CONSTANT, M.task_priority(st.priority.text), st.priority)
        self._task_common("taskCreate", st.task, st.target, st.args)

    def _task_create_sync(self, st: A.TaskCreateSync) -> None:
        ctx = self.ctx
        p = self.elem(st.period)
        if not vt.is_num_like(p.t):
            ctx.report_at(
                codes.ARGUMENT_TYPE_MISMATCH,
                M.argument_type(2, "taskCreateSync", "nPériode", "num", vt.describe(p)),
                st.period,
            )
        o = self.typeof(st.overrun)
        if o is not UNKNOWN_VAL:
            if not o.var:
                ctx.report_at(
                    codes.REFERENCE_NEEDS_VARIABLE, M.needs_variable(3, "taskCreateSync", "bOverrun"), st.overrun
                )
            elif o.t.known and o.t is not vt.BOOL:
                ctx.report_at(
                    codes.ARGUMENT_TYPE_MISMATCH,
                    M.argument_type(3, "taskCreateSync", "bOverrun", "bool&", vt.describe(o)),
                    st.overrun,
                )
            elif o.elem is False:
                self._report_missing_index(st.overrun, o)
            elif o.root is not None and o.root.kind == S.LOCAL:
                ctx.report_at(codes.TASK_REFERENCE_TO_LOCAL, M.task_overrun_local(node_text(st.overrun)), st.overrun)
        self._task_common("taskCreateSync", st.task, st.target, st.args)
