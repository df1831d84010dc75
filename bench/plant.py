"""Plant one known compiler error into a copy of a VAL 3 application (recall benchmark, issue 3).

    from plant import plant_workspace, KINDS
    ws, _ = load([app_folder])
    for m in plant_workspace(ws, ws.apps[ws.targets[0]], per_kind=5, seed=0):
        m.kind, m.code, m.path, m.line, m.col   # what was planted, what must be reported, where
        m.text                                  # the whole mutated .pgx text (m.encoding)

Nothing is ever written to the input: a mutant is the new text of ONE .pgx file of the
application, with ONE error of a known kind at a known place; `write(m, root, dest_root)` puts it
into a copy of the folder (bench_recall.py copies each root once, then writes and restores one
mutated file at a time).

Sites are chosen by walking the parsed tree of each program. Programs are re-parsed in CODE
coordinates (the extracted `<Code>` text, line/col 1-based), edits are made on the code text,
then mapped back into the file through the program's SourceMap, so that escaped text
(`&lt;`, `&quot;` in s6 files) stays well-formed: the replaced span is measured in the file and
the new text is escaped unless it lands inside a CDATA section. The expected position is where
the checker must report: the file position of the expected node (inside the new text when the
node is the new text). Two kinds edit a declaration of the .pgx instead (`<Local type=...>`,
`name=...`): the finding is then expected on the declaration's element. A mutated program must
still parse; sites that would not are dropped.

Names are only misspelt where they can be known to be undefined: not in .pgx files without a
project, nor in an application one of whose data (program) files could not be read. On s8
applications an arity or argument-type error is T024 and an unknown instruction N004 (warnings:
s8 adds forms the s7 catalogue lacks); the mutant's `code`/`severity` say so.

Deterministic: candidate sites are sorted, then sampled with a `random.Random` seeded by
(seed, application, kind); the choices made while finding sites use one seeded by
(seed, application, program).

Kinds (`KINDS`): the compiler errors of issue 3 (and a few more), each with the code it must
produce. Run `python bench/plant.py APP [N]` to see N mutants of each kind.
"""

from __future__ import annotations

import os
import random
import re
from dataclasses import dataclass, field

from val3check.language import s8
from val3check.language.instructions import lookup as lookup_instruction
from val3check.loading.model import Application, Container, Program, Workspace
from val3check.parsing import ast as A
from val3check.parsing.parser import parse_code
from val3check.parsing.tokens import KEYWORDS
from val3check.positions import SourceMap
from val3check.semantics import symbols as S
from val3check.semantics import vtypes as vt
from val3check.semantics.calls import _type_ok
from val3check.semantics.checker import program_typer

# kind -> (expected code, what is planted)
KINDS: dict[str, tuple[str, str]] = {
    "misspelt_variable": ("N001", "one letter of a used variable changed"),
    "misspelt_program": ("N002", "one letter of the program of a call changed"),
    "misspelt_instruction": ("N003", "one letter of an instruction name changed"),
    "misspelt_alias": ("N005", "one letter of a library identifier changed"),
    "assign_in_condition": ("T004", "== replaced by = in an if/elseIf/while/until condition"),
    "assign_in_argument": ("T004", "== replaced by = in an instruction argument (wait(a == b))"),
    "constant_by_reference": ("T007", "a constant passed for a by-reference element parameter of a program"),
    "constant_by_reference_instruction": ("T007", "a constant passed for a by-reference parameter of an instruction"),
    "collection_by_number": ("T010", "a collection indexed by a number"),
    "array_by_string": ("T010", "an array indexed by a string"),
    "missing_library_symbol": ("L010", "alias:known -> alias:unknown"),
    "program_arity": ("T005", "an argument added to or dropped from a call"),
    "instruction_arity": ("T005", "an argument added to or dropped from an instruction call"),
    "program_argument_type": ("T006", "a constant of another type passed by value to a program"),
    "instruction_argument_type": ("T006", "a constant of a type no form of the instruction takes"),
    "assign_type": ("T003", "a value of another type assigned to a variable"),
    "operator_type": ("T001", "an operand of a type the operator does not take (nX + \"x\", s + 1)"),
    "condition_not_bool": ("T002", "a num as the condition of if/elseIf/while/until"),
    "missing_index": ("T011", "the index of a 2-D/3-D array or the key of a collection dropped where one value is needed"),
    "undefined_field": ("T012", "a field that the structured type does not have"),
    "field_of_variable": ("T012", "a field added to a variable of a type without it (nX.q, pA.q)"),
    "undefined_user_field": ("L013", "a field that the user type does not have"),
    "reference_type": ("T006", "a variable of another type passed for a by-reference parameter of a program"),
    "index_count": ("T009", "one index too many on an array (nArr[i, 0])"),
    "missing_call": ("T018", "`call` dropped before a program: prog(args)"),
    "case_type": ("T014", "a case value of another type than the switch"),
    "for_bound": ("T015", "a for bound that is not a num"),
    "misspelt_local_type": ("N010", "the type of a local or parameter misspelt in the .pgx"),
    "duplicate_local": ("N007", "a local renamed like another local or parameter of its program"),
}
_DECLARATION_KINDS = ("misspelt_local_type", "duplicate_local")


@dataclass
class Mutant:
    kind: str
    code: str  # the code that must be reported
    severity: str  # "error" (or "warning": T024 on s8 applications)
    path: str  # absolute path of the ORIGINAL .pgx file
    line: int  # expected file position
    col: int
    program: str
    before: str  # the code line before and after the edit, for reports
    after: str
    text: str  # the whole mutated file
    encoding: str
    mutated_code: str  # the program's code once the file is read back (to check the edit)
    code_line: int = 0  # the expected position in the mutated code (to check the file position)
    code_col: int = 0
    app: str = ""  # the application's path (.pjx, or folder)

    @property
    def label(self) -> str:
        return f"{self.kind} {os.path.basename(self.path)}:{self.line}:{self.col}"


@dataclass
class _Site:
    kind: str
    program: Program
    line: int  # code coordinates of the edit
    c0: int
    c1: int  # exclusive
    new: str
    exp_line: int  # code coordinates of the expected finding
    exp_col: int
    code: str = ""
    severity: str = "error"
    key: tuple = field(default=())


# ------------------------------------------------------------------------------ text helpers


def _is_ident(c: str) -> bool:
    return c.isalnum() or c == "_"


def _balanced_span(lines: list[str], line: int, c0: int, c1: int) -> tuple[int, int] | None:
    """Widen [c0, c1) (code columns of `line`) so that its parentheses balance: the tree puts a
    parenthesised operand's start inside the parenthesis (`(a + b) * c` starts at `a`)."""
    text = lines[line - 1]
    while True:
        depth, low, in_str = 0, 0, False
        for ch in text[c0 - 1:c1 - 1]:
            if ch == '"':
                in_str = not in_str
            elif in_str:
                continue
            elif ch == "(":
                depth += 1
            elif ch == ")":
                depth -= 1
                low = min(low, depth)
        if in_str:
            return None
        if low < 0:  # a ')' closes a '(' before the span
            k = c0 - 2
            while k >= 0 and text[k] in " \t":
                k -= 1
            if k < 0 or text[k] != "(":
                return None
            c0 = k + 1
            continue
        if depth > 0:  # a '(' is closed after the span
            k = c1 - 1
            while k < len(text) and text[k] in " \t":
                k += 1
            if k >= len(text) or text[k] != ")":
                return None
            c1 = k + 2
            continue
        return c0, c1


def _close_after(lines: list[str], line: int, col: int, ch: str) -> int | None:
    """Column just after the `ch` that closes what ends at `col` (skipping blanks and `)`)."""
    text = lines[line - 1]
    k = col - 1
    while k < len(text) and text[k] in " \t)":
        if text[k] == ch:
            break
        k += 1
    if k < len(text) and text[k] == ch:
        return k + 2
    return None


def _end(node, lines: list[str]) -> tuple[int, int] | None:
    """(line, col) just after the last character of an expression (code coordinates), or None."""
    t = type(node)
    if t in (A.Number, A.String, A.Bool, A.Name, A.LibraryName, A.SystemName):
        return node.end_line, node.end_col
    if t is A.Field:
        return node.name_line, node.name_col + len(node.name)
    if t is A.Index:
        e = _end(node.indices[-1], lines)
        if e is None:
            return None
        c = _close_after(lines, e[0], e[1], "]")
        return None if c is None else (e[0], c)
    if t is A.CallExpr:
        if node.args:
            e = _end(node.args[-1], lines)
        else:
            e = _end(node.func, lines)
            if e is not None:
                text = lines[e[0] - 1]
                k = e[1] - 1
                while k < len(text) and text[k] in " \t":
                    k += 1
                if k >= len(text) or text[k] != "(":
                    return None
                e = (e[0], k + 2)
        if e is None:
            return None
        c = _close_after(lines, e[0], e[1], ")")
        return None if c is None else (e[0], c)
    if t is A.Unary:
        return _end(node.operand, lines)
    if t is A.Binary:
        return _end(node.right, lines)
    if t is A.AssignExpr:
        return _end(node.value, lines)
    if t is A.Struct:
        if node.fields and node.fields[-1] is not None:
            e = _end(node.fields[-1], lines)
        else:
            return None
        if e is None:
            return None
        c = _close_after(lines, e[0], e[1], "}")
        return None if c is None else (e[0], c)
    return None


def _span(node, lines: list[str]) -> tuple[int, int, int] | None:
    """(line, c0, c1) of a one-line expression, parentheses balanced; None when unknown."""
    e = _end(node, lines)
    if e is None or e[0] != node.line:
        return None
    sp = _balanced_span(lines, node.line, node.col, e[1])
    return None if sp is None else (node.line, sp[0], sp[1])


# ------------------------------------------------------------------------------ tree walking


_COND_OWNERS = (A.Branch, A.While, A.DoUntil)


def _walk(body: A.ProgramBody):
    """(node, parent, role) for every node; role: the parent's field holding the node."""
    stack: list[tuple[object, object, str]] = [(body, None, "")]
    while stack:
        node, parent, role = stack.pop()
        yield node, parent, role
        kids = []
        for name in A._CHILDREN.get(type(node), ()):
            value = getattr(node, name)
            if value is None:
                continue
            if type(value) is list:
                kids.extend((v, node, name) for v in value if v is not None)
            else:
                kids.append((value, node, name))
        stack.extend(reversed(kids))


def _misspell(name: str, rng: random.Random, taken) -> str | None:
    """`name` with one letter changed, not taken (taken(candidate) -> True when it resolves)."""
    positions = [i for i, c in enumerate(name) if c.isalpha()]
    rng.shuffle(positions)
    for i in positions[:6]:
        c = name[i]
        letters = [x for x in "abcdefghijklmnopqrstuvwxyz" if x != c.lower()]
        rng.shuffle(letters)
        for x in letters[:6]:
            x = x.upper() if c.isupper() else x
            cand = name[:i] + x + name[i + 1:]
            if cand.lower() in KEYWORDS or cand.lower() in ("to", "step"):
                continue
            if not taken(cand):
                return cand
    return None


# ------------------------------------------------------------------------------ site finders


# Constants written for a type: value -> its VType (to choose one of another type).
_CONSTANTS = (('"x"', vt.STRING), ("0", vt.NUM), ("true", vt.BOOL))
_ARITH = ("+", "-", "*", "/", "<", ">", "<=", ">=")


class _Finder:
    def __init__(self, ws: Workspace, app: Application, table: S.AppSymbols, program: Program,
                 body: A.ProgramBody, lines: list[str], rng: random.Random, s8_evidence: bool = False) -> None:
        self.ws, self.app, self.table, self.program = ws, app, table, program
        self.body, self.lines, self.rng = body, lines, rng
        self.scope = table.scope(program)
        self.typer = program_typer(ws, app, program, table)
        self.sites: dict[str, list[_Site]] = {k: [] for k in KINDS}
        # s8 code (by its project file, or because it already uses s8 forms, T030): a call that
        # matches no s7 signature is the T024 warning, not an error
        self.strict = (app.version_major is None or app.version_major < 8) and not s8_evidence
        self.names_data = app.globals_known and app.layout != "pgx-only" and "data" not in app.unread
        self.names_prog = app.globals_known and app.layout != "pgx-only" and "program" not in app.unread

    def add(self, kind: str, line: int, c0: int, c1: int, new: str, exp: tuple[int, int],
            code: str | None = None, severity: str = "error") -> None:
        self.sites[kind].append(_Site(kind, self.program, line, c0, c1, new, exp[0], exp[1],
                                      code or KINDS[kind][0], severity, (self.program.name, line, c0, c1)))

    def replace(self, kind: str, node, new: str, code: str | None = None, severity: str = "error") -> None:
        """Replace the whole expression `node` by `new`; the finding is expected at its start."""
        sp = _span(node, self.lines)
        if sp is not None:
            self.add(kind, sp[0], sp[1], sp[2], new, (sp[0], sp[1]), code, severity)

    def type_of(self, node) -> vt.Val:
        try:
            return self.typer.typeof(node)
        except Exception:  # noqa: BLE001 - a site finder must never stop the benchmark
            return vt.UNKNOWN_VAL

    # -- resolution helpers ----------------------------------------------------------------

    def name_taken(self, cand: str) -> bool:
        """The name designates something (variable, constant, program, instruction) in any case."""
        low = cand.lower()
        if self.scope.lookup_ci(cand) is not None or S.constant(cand) is not None:
            return True
        if self.table.program_ci(cand) is not None or lookup_instruction(cand) is not None:
            return True
        from val3check.language.instructions import load_errata

        if low in load_errata():
            return True
        return any(n.lower() == low for n in self.app.libraries)

    def callee(self, target) -> tuple[Program, Application] | None:
        """The program a call names, with the application that declares it."""
        if type(target) is A.Name:
            prog = self.table.program(target.name)
            return (prog, self.app) if prog is not None else None
        if type(target) is A.LibraryName:
            lib = self.table.library(target.alias)
            if not isinstance(lib, S.LibraryInterface):
                return None
            prog, why = lib.program(target.name)
            return (prog, lib.app) if prog is not None and not why else None
        return None

    def var_symbol(self, node) -> S.Symbol | None:
        if type(node) is not A.Name:
            return None
        return self.scope.lookup(node.name)

    def instruction_params(self, call: A.CallExpr):
        """The parameters (one list per overload of the call's arity) of an instruction call,
        or None when it is not a plain instruction call."""
        func = call.func
        if type(func) is not A.Name:
            return None
        ins = lookup_instruction(func.name)
        if ins is None or ins.library_prefix == "required" or ins.kind == "special":
            return None
        return ins, ins.overloads_with_arity(len(call.args))

    # -- the walk ------------------------------------------------------------------------

    def run(self) -> dict[str, list[_Site]]:
        for node, parent, role in _walk(self.body):
            t = type(node)
            try:
                if t is A.Name:
                    self.on_name(node, parent, role)
                elif t in (A.Call, A.TaskCreate, A.TaskCreateSync):
                    self.on_call(node)
                elif t in _COND_OWNERS:
                    self.on_condition(node.cond)
                elif t is A.Index:
                    self.on_index(node, parent, role)
                elif t is A.LibraryName:
                    self.on_library_name(node, parent, role)
                elif t is A.CallExpr:
                    self.on_call_expr(node)
                elif t is A.Assign:
                    self.on_assign(node)
                elif t is A.Field:
                    self.on_field(node, parent, role)
                elif t is A.Binary:
                    self.on_binary(node)
                elif t is A.Switch:
                    self.on_switch(node)
                elif t is A.For:
                    self.replace("for_bound", node.stop, '"x"')
            except Exception:  # noqa: BLE001 - a site finder must never stop the benchmark
                continue
        return self.sites

    def on_name(self, node: A.Name, parent, role: str) -> None:
        if role in ("func", "target"):
            return
        sym = self.scope.lookup(node.name)
        if sym is None:
            return
        if self.names_data:
            new = _misspell(node.name, self.rng, self.name_taken)
            if new is not None:
                self.add("misspelt_variable", node.line, node.col, node.end_col, new, (node.line, node.col))
        # field_of_variable: nX -> nX.q where the type has no field q
        if sym.val.elem is True and sym.type.known and sym.type.kind == vt.BUILTIN and type(parent) is not A.Index \
                and not (type(parent) is A.Field and role == "base"):
            if sym.type.structured and vt.field_of(sym.type, "q") is not None:
                return
            self.add("field_of_variable", node.end_line, node.end_col, node.end_col, ".q",
                     (node.end_line, node.end_col + 1))

    def on_switch(self, st: A.Switch) -> None:
        subject = self.type_of(st.subject).t
        new = {vt.NUM: '"x"', vt.STRING: "0", vt.BOOL: "0"}.get(subject)
        if new is None:
            return
        for case in st.cases:
            for value in case.values:
                self.replace("case_type", value, new)

    def on_call(self, st) -> None:
        target = st.target
        if type(st) is A.Call and self.callee(target) is not None and target.line == st.line:
            self.add("missing_call", st.line, st.col, target.col, "", (st.line, st.col))
        if type(target) is A.Name and self.names_prog and self.table.program(target.name) is not None:
            new = _misspell(target.name, self.rng, self.name_taken)
            if new is not None:
                self.add("misspelt_program", target.line, target.col, target.end_col, new, (target.line, target.col))
        found = self.callee(target)
        if found is None:
            return
        prog, owner = found
        params = prog.parameters
        args = st.args
        exp = (target.line, target.col)
        if len(args) != len(params):
            return  # already wrong: not a valid site
        # program_arity: add an argument, or drop the last one
        if args and self.rng.random() < 0.5:
            self._drop_last_argument("program_arity", args, exp)
        else:
            self._add_argument("program_arity", target, args, exp, "0")
        reg = self.table.registry
        for p, a in zip(params, args):
            ptype = reg.resolve_type(owner, p.type)
            if not ptype.known:
                continue
            by_ref = p.by_reference or p.container is not Container.ELEMENT
            if by_ref and p.container is Container.ELEMENT:
                const = {vt.NUM: "0", vt.BOOL: "false", vt.STRING: '"x"'}.get(ptype)
                v = self.type_of(a)
                if const is not None and v.var and v.t is ptype:
                    self.replace("constant_by_reference", a, const)
                if v.var and v.t is ptype and ptype.kind == vt.BUILTIN:
                    others = sorted(n for n, s in self.scope.own.items()
                                    if s.val.elem is True and s.type.kind == vt.BUILTIN and s.type is not ptype
                                    and not {s.type, ptype} <= {vt.DIO, vt.AIO, vt.BOOL, vt.NUM})
                    if others:
                        self.replace("reference_type", a, self.rng.choice(others))
            elif not by_ref:
                for const, ct in _CONSTANTS:
                    if vt.assignable(ptype, ct) is False:
                        self.replace("program_argument_type", a, const)
                        break

    def _drop_last_argument(self, kind: str, args: list, exp, code=None, severity="error") -> None:
        last = _span(args[-1], self.lines)
        if last is None:
            return
        if len(args) == 1:
            self.add(kind, last[0], last[1], last[2], "", exp, code, severity)
            return
        prev = _span(args[-2], self.lines)
        if prev is not None and prev[0] == last[0]:
            self.add(kind, last[0], prev[2], last[2], "", exp, code, severity)

    def _add_argument(self, kind: str, target, args: list, exp: tuple[int, int], value: str,
                      code: str | None = None, severity: str = "error") -> None:
        if args:
            last = _span(args[-1], self.lines)
            if last is None:
                return
            self.add(kind, last[0], last[2], last[2], f", {value}", exp, code, severity)
            return
        e = _end(target, self.lines)
        if e is None:
            return
        text = self.lines[e[0] - 1]
        k = e[1] - 1
        while k < len(text) and text[k] in " \t":
            k += 1
        if k < len(text) and text[k] == "(":
            self.add(kind, e[0], k + 2, k + 2, value, exp, code, severity)

    def _equal_signs(self, kind: str, expr) -> None:
        for node, _, _ in _walk_expr(expr):
            if type(node) is A.Binary and node.op == "==":
                text = self.lines[node.op_line - 1]
                if text[node.op_col - 1:node.op_col + 1] == "==":
                    self.add(kind, node.op_line, node.op_col, node.op_col + 2, "=", (node.op_line, node.op_col))

    def on_condition(self, cond) -> None:
        self._equal_signs("assign_in_condition", cond)
        # condition_not_bool: the whole condition replaced by a num
        want = vt.NUM if self.rng.random() < 0.7 else self.rng.choice([vt.STRING, vt.POINT, vt.JOINT, vt.TRSF])
        names = [s for s in self.scope.own.values() if s.type is want and s.val.elem is True]
        if not names and self.names_data:
            names = [s for s in self.table.globals.values() if s.type is want and s.val.elem is True]
        const = '"x"' if want is vt.STRING else "0"
        self.replace("condition_not_bool", cond, min(s.name for s in names) if names else const)

    def needs_one_value(self, parent, role: str, node) -> bool:
        """An expression at this place must be one value (2.3.4): a container there is T011."""
        pt = type(parent)
        if pt in (A.Binary, A.Unary, A.Assign, A.Struct, A.TaskCreate, A.TaskCreateSync) and role not in ("args", "target"):
            return not (pt in (A.TaskCreateSync,) and role == "overrun")
        if pt in _COND_OWNERS and role == "cond":
            return True
        if pt is A.For or pt is A.Switch or pt is A.Case and role == "values":
            return True
        if pt is A.Index and role == "indices":
            return True
        if pt is A.Field and role == "base":
            return True
        if pt is A.CallExpr and role == "args":
            found = self.instruction_params(parent)
            if found is None or not found[1]:
                return False
            i = next(k for k, a in enumerate(parent.args) if a is node)
            return all(o.params[i].container == "element" and o.params[i].type != "*" for o in found[1])
        if pt in (A.Call, A.TaskCreate, A.TaskCreateSync) and role == "args":
            callee = self.callee(parent.target)
            if callee is None or callee[1].layout == "s6" or len(parent.args) != len(callee[0].parameters):
                return False
            i = next(k for k, a in enumerate(parent.args) if a is node)
            return callee[0].parameters[i].container is Container.ELEMENT
        return False

    def on_index(self, node: A.Index, parent, role: str) -> None:
        sym = self.var_symbol(node.base)
        if sym is None:
            return
        first = node.indices[0]
        if sym.container == vt.COLLECTION and len(node.indices) == 1:
            nums = sorted(n for n, s in self.scope.own.items() if s.type is vt.NUM and s.val.elem is True)
            self.replace("collection_by_number", first, nums[0] if nums and self.rng.random() < 0.5 else "0")
        elif (sym.container == vt.ARRAY and sym.dims >= 1) or (
                sym.dims < 0 and sym.kind == S.GLOBAL and getattr(sym.decl, "container", None) is Container.ARRAY):
            # (an s6 global: its file writes no size, but it is an array, never a collection)
            if self.type_of(first).t is vt.NUM:
                self.replace("array_by_string", first, '"x"')
        if sym.container == vt.ARRAY and sym.dims >= 1 and len(node.indices) == sym.dims:
            last = _span(node.indices[-1], self.lines)
            if last is not None:
                self.add("index_count", last[0], last[2], last[2], ", 0", (last[0], last[2] + 2))
        # missing_index: where one value is needed
        if not _multi_value(sym) or not self.needs_one_value(parent, role, node):
            return
        e = _end(node, self.lines)
        base = node.base
        if e is None or e[0] != base.line:
            return
        self.add("missing_index", base.line, base.end_col, e[1], "", (base.line, base.col))

    def on_library_name(self, node: A.LibraryName, parent, role: str) -> None:
        # misspelt_alias (N005)
        declared = node.alias in self.app.libraries
        if declared and self.app.globals_known:
            new = _misspell(node.alias, self.rng, lambda c: any(a.lower() == c.lower() for a in self.app.libraries)
                            or c.lower() == "io")
            if new is not None:
                self.add("misspelt_alias", node.line, node.col, node.col + len(node.alias), new, (node.line, node.col))
        if role == "func":
            return  # instructions of libraries (lib:libLoad) or programs called without call
        lib = self.table.library(node.alias)
        if not isinstance(lib, S.LibraryInterface):
            return
        lapp = lib.app
        if lapp.layout == "pgx-only" or lapp.unread:
            return
        if role == "target":
            prog, why = lib.program(node.name)
            if prog is None or why:
                return
        else:
            sym, why = lib.data_symbol(node.name)
            if sym is None or why:
                return
        new = None
        for suffix in ("X", "Zz", "Qx", "Unk"):
            cand = node.name + suffix
            if lib.lookup_ci(cand) is None and not any(n.lower() == cand.lower() for n in lapp.data) \
                    and not any(n.lower() == cand.lower() for n in lapp.programs):
                new = cand
                break
        if new is None:
            return
        start = node.end_col - len(node.name)
        self.add("missing_library_symbol", node.end_line, start, node.end_col, new, (node.line, node.col))

    def on_call_expr(self, node: A.CallExpr) -> None:
        found = self.instruction_params(node)
        if found is None:
            return
        ins, overloads = found
        func = node.func
        n = len(node.args)
        if not overloads:
            return
        exp = (func.line, func.col)
        code, severity = ("T005", "error") if self.strict else ("T024", "warning")
        # instruction_arity (not into an s8 form: logMsg(s) -> logMsg(s, 1) is valid s8, T030)
        s8_arities = {k for f in s8.forms(ins.name) for k in range(f.overload.min_arity, f.overload.max_arity + 1)}
        if not ins.overloads_with_arity(n + 1) and n + 1 not in s8_arities:
            self._add_argument("instruction_arity", func, node.args, exp, "1", code, severity)
        if n and not ins.overloads_with_arity(n - 1) and n - 1 not in s8_arities:
            self._drop_last_argument("instruction_arity", node.args, exp, code, severity)
        # misspelt_instruction
        if not (self.app.globals_known and "program" in self.app.unread):
            new = _misspell(func.name, self.rng, self.name_taken)
            if new is not None:
                code_n, sev_n = ("N003", "error") if self.strict else ("N004", "warning")
                self.add("misspelt_instruction", func.line, func.col, func.end_col, new, exp, code_n, sev_n)
        vals = [self.type_of(a) for a in node.args]
        for i, (a, v) in enumerate(zip(node.args, vals)):
            params = [o.params[i] for o in overloads]
            # the call must match exactly one way for the argument to be judged alone
            if not all(_type_ok(o.params[k], vals[k]) for o in overloads for k in range(n) if k != i):
                continue
            # constant_by_reference_instruction
            if all(p.ref and p.container == "element" for p in params) and v.var:
                const = {vt.NUM: "0", vt.BOOL: "false", vt.STRING: '"x"'}.get(v.t)
                if const is not None and all(p.type == v.t.name for p in params):
                    self.replace("constant_by_reference_instruction", a, const)
            # instruction_argument_type (not into an s8 form: userPage("x") is valid s8, T030)
            s8_params = [f.overload.params[i] for f in s8.forms(ins.name) if f.overload.accepts_arity(n)]
            for const, ct in _CONSTANTS:
                if not any(_type_ok(p, vt.value(ct)) for p in params + s8_params):
                    self.replace("instruction_argument_type", a, const, "T006" if self.strict else "T024", severity)
                    break
        # assign_in_argument: wait(a == b) -> wait(a = b)
        for a in node.args:
            self._equal_signs("assign_in_argument", a)

    def on_assign(self, st: A.Assign) -> None:
        if type(st.value) is A.AssignExpr:
            return
        tv = self.type_of(st.target)
        if not tv.var or tv.elem is False or not tv.t.known or tv.t.kind not in (vt.BUILTIN, vt.USER):
            return
        for const, ct in _CONSTANTS:
            if vt.assignable(tv.t, ct) is False:
                self.replace("assign_type", st.value, const)
                return

    def on_binary(self, node: A.Binary) -> None:
        lt_, rt = self.type_of(node.left), self.type_of(node.right)
        if lt_.elem is False or rt.elem is False:
            return
        if node.op in _ARITH and lt_.t is vt.NUM and rt.t is vt.NUM:
            self.replace_operand(node, '"x"')
        elif node.op == "+" and lt_.t is vt.STRING and rt.t is vt.STRING:
            self.replace_operand(node, "1")
        elif node.op in ("and", "or", "xor") and lt_.t is vt.BOOL and rt.t is vt.BOOL:
            self.replace_operand(node, "1")

    def replace_operand(self, node: A.Binary, new: str) -> None:
        sp = _span(node.right, self.lines)
        if sp is not None and sp[0] == node.op_line:
            self.add("operator_type", sp[0], sp[1], sp[2], new, (node.op_line, node.op_col))

    def on_field(self, node: A.Field, parent, role: str) -> None:
        base = self.type_of(node.base)
        t = base.t
        if not t.known or base.elem is False:
            return
        if t.kind == vt.USER:
            fields = S.user_fields(self.table.registry, t)
            if not fields or t.app is None or t.app.unread:
                return
            cand = next(c for c in ("q", "qq", "zz", "qqq") if all(n.lower() != c for n in fields))
            self.add("undefined_user_field", node.name_line, node.name_col, node.name_col + len(node.name), cand,
                     (node.name_line, node.name_col))
            return
        if not t.structured or t.kind != vt.BUILTIN:
            return
        cand = next(c for c in ("q", "qq", "zz") if vt.field_of(t, c) is None)
        self.add("undefined_field", node.name_line, node.name_col, node.name_col + len(node.name), cand,
                 (node.name_line, node.name_col))


def _multi_value(sym: S.Symbol) -> bool:
    """Used bare where one value is needed, the variable is certainly refused (T011): a collection
    or a 2-D/3-D array. A 1-D array of several values is only a warning (T025), array parameters
    take the caller's size, and s6 files write no size: none of those is planted."""
    if sym.kind == S.PARAM or sym.kind == S.CONSTANT or sym.dims < 0:
        return False
    if sym.container == vt.COLLECTION:
        return True
    return len(getattr(sym.decl, "sizes", ()) or ()) > 1


def _walk_expr(node):
    stack = [(node, None, "")]
    while stack:
        n, p, r = stack.pop()
        yield n, p, r
        for name in A._CHILDREN.get(type(n), ()):
            value = getattr(n, name)
            if value is None:
                continue
            if type(value) is list:
                stack.extend((v, n, name) for v in value if v is not None)
            else:
                stack.append((value, n, name))


# ------------------------------------------------------------------------------ file editing


_ENCODING = re.compile(rb'^(?:\xef\xbb\xbf)?<\?xml[^>]*encoding=["\']([A-Za-z0-9._-]+)["\']')


def read_text(path: str) -> tuple[str, str]:
    """(text, encoding) of an XML file; a UTF-8 byte order mark stays in the text."""
    with open(path, "rb") as f:
        data = f.read()
    m = _ENCODING.match(data)
    enc = m.group(1).decode("ascii").lower() if m else "utf-8"
    if enc.replace("_", "-") in ("utf-8", "utf8"):
        enc = "utf-8"
    try:
        return data.decode(enc), enc
    except (LookupError, UnicodeDecodeError):
        return data.decode("utf-8", errors="surrogateescape"), "utf-8"


def _escape(text: str) -> str:
    return text.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")


def _file_width(line_text: str, col: int) -> int:
    """Width in the file of the character written at `col` (an entity counts whole)."""
    k = col - 1
    if k < len(line_text) and line_text[k] == "&":
        j = line_text.find(";", k)
        if 0 < j - k <= 10:
            return j - k + 1
    return 1


def _apply(text: str, program: Program, site: _Site) -> tuple[str, tuple[int, int]] | None:
    """The file text with `site`'s code edit applied and the file position of the expected
    finding, or None when the edit cannot be mapped."""
    sm: SourceMap = program.code_map
    code_lines = program.code.split("\n")  # type: ignore[union-attr]
    cl = code_lines[site.line - 1]
    file_lines = text.split("\n")
    p0 = sm.to_file(site.line, site.c0)
    if site.c1 > site.c0:
        pl = sm.to_file(site.line, site.c1 - 1)
        if pl.line != p0.line:
            return None
        ftext = file_lines[pl.line - 1]
        f1 = pl.col + _file_width(ftext, pl.col)
    elif site.c0 <= len(cl):
        f1 = p0.col
    else:
        pl = sm.to_file(site.line, site.c0 - 1)
        f1 = pl.col + _file_width(file_lines[pl.line - 1], pl.col)
        p0 = type(p0)(pl.line, f1)
    ln = p0.line
    ftext = file_lines[ln - 1]
    offset = sum(len(x) + 1 for x in file_lines[:ln - 1]) + p0.col - 1
    opened, closed = text.rfind("<![CDATA[", 0, offset), text.rfind("]]>", 0, offset)
    esc = (lambda x: x) if opened > closed else _escape
    file_lines[ln - 1] = ftext[:p0.col - 1] + esc(site.new) + ftext[f1 - 1:]
    # The expected position: before the edit, the file position it had; inside the new text,
    # counted from the start of the edit in the file.
    if (site.exp_line, site.exp_col) < (site.line, site.c0) or site.exp_line != site.line:
        exp = sm.to_file(site.exp_line, site.exp_col)
        where = (exp.line, exp.col)
    elif site.exp_col <= site.c0 + len(site.new):
        where = (ln, p0.col + len(esc(site.new[:site.exp_col - site.c0])))
    else:
        return None
    return "\n".join(file_lines), where


# ------------------------------------------------------------------------------ entry points


def _parse_in_code_coordinates(program: Program) -> A.ProgramBody | None:
    if program.code is None:
        return None
    body, diags = parse_code(program.code, SourceMap(), program.origin.path)
    return body if not diags else None


def plant_workspace(ws: Workspace, app: Application, *, per_kind: int | None = 5, seed: int = 0,
                    kinds: list[str] | None = None, skip_files=frozenset()) -> list[Mutant]:
    """Mutants of `app` (loaded in `ws`): at most `per_kind` per kind (None: every site),
    never in the files of `skip_files` (absolute paths)."""
    table = S.build(ws, app)
    from val3check.parsing.parser import parse_program
    from val3check.semantics.checker import check_application

    for program in app.programs.values():
        if program.body is None:
            parse_program(program)
    s8_evidence = any(d.code == "T030" for d in check_application(ws, app))
    by_kind: dict[str, list[_Site]] = {k: [] for k in KINDS}
    bodies: dict[str, A.ProgramBody] = {}
    for name in sorted(app.programs):
        program = app.programs[name]
        if os.path.abspath(program.origin.path) in skip_files or not program.origin.path.endswith(".pgx"):
            continue
        body = _parse_in_code_coordinates(program)
        if body is None:
            continue
        bodies[name] = body
        rng = random.Random(f"{seed}:{app.name}:{name}")
        finder = _Finder(ws, app, table, program, body, program.code.split("\n"), rng,  # type: ignore[union-attr]
                         s8_evidence)
        for kind, sites in finder.run().items():
            by_kind[kind].extend(sites)
        for kind, dsites in _declaration_sites(app, program, rng).items():
            by_kind.setdefault(kind, []).extend(dsites)  # type: ignore[arg-type]
    texts: dict[str, tuple[str, str]] = {}
    out: list[Mutant] = []
    for kind in sorted(by_kind):
        if kinds is not None and kind not in kinds:
            continue
        sites = sorted(by_kind[kind], key=lambda s: s.key)
        rng = random.Random(f"{seed}:{app.name}:{kind}")
        rng.shuffle(sites)
        taken = 0
        for site in sites:
            if per_kind is not None and taken >= per_kind:
                break
            m = _decl_mutant(site, app, texts) if isinstance(site, _DeclSite) else _mutant(site, app, texts)
            if m is not None:
                out.append(m)
                taken += 1
    return out


@dataclass
class _DeclSite:
    kind: str
    program: Program
    path: str
    line: int  # file line of the declaration (its element), where the finding is expected
    col: int
    attr: str  # attribute to change
    old: str
    new: str
    code: str = ""
    key: tuple = field(default=())


_VAL3_TYPES = ("num", "bool", "string", "point", "joint", "trsf", "frame", "tool", "config", "mdesc", "dio", "aio",
               "sio", "screen")


def _declaration_sites(app: Application, program: Program, rng: random.Random) -> dict[str, list[_DeclSite]]:
    out: dict[str, list[_DeclSite]] = {k: [] for k in _DECLARATION_KINDS}
    path = os.path.abspath(program.origin.path)
    s8 = app.version_major is not None and app.version_major >= 8
    decls = list(program.parameters) + list(program.locals)
    if app.globals_known and not s8:
        for d in decls:
            if d.type not in _VAL3_TYPES:
                continue
            taken = lambda c: vt.builtin(c) is not None or any(n.lower() == c.lower() for n in app.types)  # noqa: E731
            new = _misspell(d.type, rng, taken)
            if new is not None:
                out["misspelt_local_type"].append(_DeclSite("misspelt_local_type", program, path, d.origin.line,
                                                            d.origin.col, "type", d.type, new, "N010",
                                                            (program.name, d.origin.line)))
    names = [d.name for d in decls]
    for i, d in enumerate(program.locals):
        if i == 0 and not program.parameters:
            continue
        other = names[0] if program.parameters else program.locals[0].name
        if other != d.name and all(n != other for n in names[len(program.parameters) + i + 1:]):
            out["duplicate_local"].append(_DeclSite("duplicate_local", program, path, d.origin.line, d.origin.col,
                                                    "name", d.name, other, "N007", (program.name, d.origin.line)))
    return out


def _decl_mutant(site: _DeclSite, app: Application, texts: dict[str, tuple[str, str]]) -> Mutant | None:
    if site.path not in texts:
        texts[site.path] = read_text(site.path)
    text, enc = texts[site.path]
    lines = text.split("\n")
    ftext = lines[site.line - 1]
    m = re.compile(r"\b" + site.attr + r"""\s*=\s*(["'])""" + re.escape(site.old) + r"\1").search(ftext, site.col - 1)
    if m is None:
        return None
    q = m.group(1)
    new_attr = f"{site.attr}={q}{site.new}{q}"
    lines[site.line - 1] = ftext[:m.start()] + new_attr + ftext[m.end():]
    return Mutant(kind=site.kind, code=site.code, severity="error", path=site.path, line=site.line, col=site.col,
                  program=site.program.name, before=m.group(0), after=new_attr, text="\n".join(lines), encoding=enc,
                  mutated_code=site.program.code or "", app=app.path)


def _mutant(site: _Site, app: Application, texts: dict[str, tuple[str, str]]) -> Mutant | None:
    program = site.program
    path = os.path.abspath(program.origin.path)
    if path not in texts:
        texts[path] = read_text(path)
    text, enc = texts[path]
    code_lines = program.code.split("\n")  # type: ignore[union-attr]
    before = code_lines[site.line - 1]
    after = before[:site.c0 - 1] + site.new + before[site.c1 - 1:]
    code_lines[site.line - 1] = after
    mutated_code = "\n".join(code_lines)
    body, diags = parse_code(mutated_code, SourceMap(), path)
    if body is None or diags:
        return None  # the edit must keep the program parseable
    applied = _apply(text, program, site)
    if applied is None or applied[0] == text:
        return None
    new_text, (line, col) = applied
    return Mutant(kind=site.kind, code=site.code, severity=site.severity, path=path, line=line, col=col,
                  program=program.name, before=before.strip(), after=after.strip(), text=new_text, encoding=enc,
                  mutated_code=mutated_code, app=app.path, code_line=site.exp_line, code_col=site.exp_col)


def plant(app_path: str, *, per_kind: int | None = 5, seed: int = 0, kinds: list[str] | None = None) -> list[Mutant]:
    """Mutants of every application found at `app_path` (a folder, a .pjx)."""
    from val3check.loading import load

    ws, _ = load([app_path])
    out: list[Mutant] = []
    for key in ws.targets:
        out.extend(plant_workspace(ws, ws.apps[key], per_kind=per_kind, seed=seed, kinds=kinds))
    return out


def write(m: Mutant, original_root: str, dest_root: str) -> str:
    """Write the mutated file into `dest_root` (a copy of `original_root`); returns its path."""
    rel = os.path.relpath(m.path, original_root)
    dest = os.path.join(dest_root, rel)
    with open(dest, "w", encoding=m.encoding, errors="surrogateescape", newline="") as f:
        f.write(m.text)
    return dest


if __name__ == "__main__":  # pragma: no cover - quick look: python bench/plant.py APP
    import sys

    for m in plant(sys.argv[1], per_kind=int(sys.argv[2]) if len(sys.argv) > 2 else 3):
        print(f"{m.code} {m.label}: {m.before!r} -> {m.after!r}")
