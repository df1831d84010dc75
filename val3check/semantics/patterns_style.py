"""S rules that look at one program at a time: control flow, comparisons, comments, strings,
waits and loops. Each function takes what `patterns.check_application` prepared and returns
its findings; none of them raises on a well-formed tree.
"""

from __future__ import annotations

import re
from functools import cache

from ..diagnostics import Diagnostic
from ..language.instructions import entries, yielding_instructions
from ..language.types import load_constants
from ..loading.model import Container, Program
from ..parsing import ast as A
from . import patterns_messages as M
from .patterns_usage import (
    IO_TYPES,
    VALUE_TYPES,
    ProgramFacts,
    Resolver,
    Scope,
    builtin_type,
    instruction_name,
    root_name,
)
from .program_nodes import ProgramNodes

STRING_MAX_BYTES = 128  # manual 3.4.1 (types.toml: string_max_bytes)

# Functions whose num result is, in general, not an integer (3.2.3, 9.x): comparing it with ==
# is what 3.2.1 warns about. distance() is a Euclidean distance (9.3.4, 9.6).
INEXACT_FUNCTIONS = frozenset({"sin", "cos", "tan", "asin", "acos", "atan", "sqrt", "exp", "ln", "log",
                               "power", "distance"})
ROUNDING_FUNCTIONS = frozenset({"round", "roundup", "rounddown"})
# Motion instructions record a move; when the motion memory is full, execution stops on the next
# one (10.2.1): a loop that issues them is paced by the arm, not a busy loop.
MOTION_INSTRUCTIONS = frozenset({"movej", "movel", "movec", "movejf", "movelf", "altermovej", "altermovel",
                                 "altermovec"})
_DIRECTIVE = re.compile(r"//\s*val3check\s*:", re.IGNORECASE)


@cache
def _yielding() -> frozenset[str]:
    """Instructions that may hand over to the next task (manual 5.4, `yields` in the catalogue)."""
    return yielding_instructions() | MOTION_INSTRUCTIONS


@cache
def _constants() -> frozenset[str]:
    return frozenset(name.lower() for name in load_constants())


def _diag(code: str, message: str, program: Program, node: object, end: bool = False) -> Diagnostic:
    end_line = getattr(node, "end_line", None) if end else None
    end_col = getattr(node, "end_col", None) if end else None
    return Diagnostic(code, message, program.origin.path, node.line, node.col, end_line, end_col)


# ------------------------------------------------------------------ statement structure


def check_blocks(program: Program) -> list[Diagnostic]:
    """S006 unreachable code, S009 case without break, S013 nested for loops sharing a counter."""
    out: list[Diagnostic] = []
    # (statements, enclosing for counters {name: line}, list is a case/default body)
    stack: list[tuple[list, dict[str, int], bool]] = [(program.body.statements, {}, False)]
    while stack:
        statements, counters, in_case = stack.pop()
        _unreachable(program, statements, in_case, out)
        for s in statements:
            t = type(s)
            if t is A.If:
                for branch in s.branches:
                    stack.append((branch.body, counters, False))
                if s.orelse:
                    stack.append((s.orelse, counters, False))
            elif t is A.While or t is A.DoUntil:
                stack.append((s.body, counters, False))
            elif t is A.For:
                inner = counters
                counter = s.counter
                if type(counter) is A.Name:
                    key = counter.name
                    if key in counters:
                        out.append(_diag(M.NESTED_FOR_SAME_COUNTER,
                                         M.nested_for_same_counter(counter.name, counters[key]), program, s))
                    else:
                        inner = dict(counters)
                        inner[key] = s.line
                stack.append((s.body, inner, False))
            elif t is A.Switch:
                for case in s.cases:
                    _case_break(program, case, "case", out)
                    stack.append((case.body, counters, True))
                if s.default is not None:
                    _case_break(program, s.default, "default", out)
                    stack.append((s.default.body, counters, True))
    return out


def _case_break(program: Program, case: object, keyword: str, out: list) -> None:
    if case.has_break:
        return
    if case.body and type(case.body[-1]) is A.Return:
        return  # cannot run on past its end
    out.append(_diag(M.CASE_WITHOUT_BREAK, M.case_without_break(keyword), program, case))


def _unreachable(program: Program, statements: list, in_case: bool, out: list) -> None:
    for i, s in enumerate(statements):
        t = type(s)
        if t is A.Return or (in_case and t is A.Break):
            rest = statements[i + 1:]
            if t is A.Return and in_case:
                rest = [x for x in rest if type(x) is not A.Break]  # the case's own closing break
            if rest:
                keyword = "break" if t is A.Break else "return"
                out.append(_diag(M.UNREACHABLE_CODE, M.unreachable_after(keyword), program, rest[0]))
            return


# ------------------------------------------------------------------ comparisons


def _contains_move_id(e: object) -> bool:
    stack = [e]
    while stack:
        n = stack.pop()
        t = type(n)
        if t is A.CallExpr:
            if instruction_name(n.func) == "getmoveid" and type(n.func) is A.Name:
                return True
        elif t is A.Binary and n.op in ("+", "-", "*", "/"):
            stack.append(n.left)
            stack.append(n.right)
        elif t is A.Unary and n.op == "-":
            stack.append(n.operand)
    return False


def _integral(x: float) -> bool:
    try:
        return float(x).is_integer()
    except (OverflowError, ValueError, TypeError):
        return False


def _inexact(e: object) -> str | None:
    """What makes this num expression a computed, non-integer value (None: nothing does)."""
    stack = [e]
    while stack:
        n = stack.pop()
        t = type(n)
        if t is A.Number:
            if not _integral(n.value):
                return f"the constant {n.text}"
        elif t is A.CallExpr:
            name = instruction_name(n.func)
            if type(n.func) is A.Name and name in INEXACT_FUNCTIONS:
                return f"the result of {n.func.name}()"
        elif t is A.Binary:
            if n.op == "/":
                if type(n.left) is A.Number and type(n.right) is A.Number and n.right.value \
                        and _integral(n.left.value / n.right.value):
                    continue
                return "the result of a division"
            if n.op in ("+", "-", "*"):
                stack.append(n.left)
                stack.append(n.right)
        elif t is A.Unary and n.op == "-":
            stack.append(n.operand)
    return None


def _is_rounding(e: object) -> bool:
    return type(e) is A.CallExpr and type(e.func) is A.Name and e.func.name.lower() in ROUNDING_FUNCTIONS


def check_comparisons(program: Program, facts: ProgramFacts) -> list[Diagnostic]:
    """S007 getMoveId() compared with == or != (10.6), S008 == / != on computed nums (3.2.1)."""
    out = []
    for b in facts.binaries:
        if b.op != "==" and b.op != "!=":
            continue
        if _contains_move_id(b.left) or _contains_move_id(b.right):
            out.append(_diag(M.MOVE_ID_EQUALITY, M.move_id_equality(b.op), program, b))
            continue
        left, right = b.left, b.right
        if type(left) in (A.String, A.Bool) or type(right) in (A.String, A.Bool):
            continue
        if type(left) is A.Number and type(right) is A.Number:
            continue
        if _is_rounding(left) or _is_rounding(right):
            continue  # `n / 3 == round(n / 3)`: a test for an integral value
        what = _inexact(left) or _inexact(right)
        if what:
            out.append(_diag(M.NUM_EQUALITY, M.num_equality(b.op, what), program, b))
    return out


# ------------------------------------------------------------------ comments and strings


def check_comments(program: Program) -> list[Diagnostic]:
    """S010: `//` after code on the same line (2.2.5). Suppression directives are allowed."""
    out = []
    for c in program.body.comments:
        if not c.starts_line and not _DIRECTIVE.match(c.text):
            out.append(Diagnostic(M.TRAILING_COMMENT, M.trailing_comment(), program.origin.path, c.line, c.col))
    return out


def _utf8_size(text: str) -> int:
    return len(text.encode("utf-8", errors="surrogatepass"))


def check_strings(program: Program, facts: ProgramFacts) -> list[Diagnostic]:
    """S011: a string constant over 128 bytes (3.4.1), or a `+` whose constant parts alone make
    more than 128 bytes: `+` keeps the first 128 bytes of its result (3.4.2)."""
    out = []
    long_literal = set()
    for s in facts.strings:
        size = _utf8_size(s.value)
        if size > STRING_MAX_BYTES:
            long_literal.add(id(s))
            out.append(_diag(M.STRING_TOO_LONG, M.string_too_long(size, False), program, s, end=True))
    covered: set[int] = set()
    for b in facts.binaries:  # pre-order: the outermost `+` of a chain comes first
        if b.op != "+" or id(b) in covered:
            continue
        total, others, skip = 0, 0, False
        stack = [b.right, b.left]
        while stack:
            n = stack.pop()
            t = type(n)
            if t is A.Binary and n.op == "+":
                covered.add(id(n))
                stack.append(n.right)
                stack.append(n.left)
            elif t is A.String:
                total += _utf8_size(n.value)
                skip = skip or id(n) in long_literal
            else:
                others += 1
        # over 128 bytes without a literal over 128 bytes: two constants at least
        if total > STRING_MAX_BYTES and not skip:
            out.append(_diag(M.STRING_TOO_LONG, M.string_too_long(total, True, others > 0), program, b))
    return out


# ------------------------------------------------------------------ waits and loops


def _frozen_names(e: object, scope: Scope) -> list[str] | None:
    """The locals/by-value parameters a condition reads when nothing else can change it while
    the task waits (no global, no call, no I/O); None when something else can."""
    names: list[str] = []
    stack = [e]
    while stack:
        n = stack.pop()
        t = type(n)
        if t is A.Number or t is A.String or t is A.Bool:
            continue
        if t is A.Name:
            key = n.name
            kind = scope.kind(key)
            if kind == "local":
                if builtin_type(scope.locals[key].type) not in VALUE_TYPES:
                    return None
            elif kind == "param":
                p = scope.params[key]
                if p.by_reference or p.container != Container.ELEMENT or builtin_type(p.type) not in VALUE_TYPES:
                    return None  # by reference: the caller's variable may be a global
            elif kind == "other" and key.lower() in _constants():
                continue
            else:
                return None
            if n.name not in names:
                names.append(n.name)
        elif t is A.Binary:
            stack.append(n.right)
            stack.append(n.left)
        elif t is A.Unary:
            stack.append(n.operand)
        elif t is A.Field:
            stack.append(n.base)
        elif t is A.Index:
            stack.append(n.base)
            stack.extend(n.indices)
        else:
            return None  # calls, library data, assignments, structures
    return names


def check_waits(program: Program, scope: Scope, facts: ProgramFacts) -> list[Diagnostic]:
    """S012: wait(cond) where cond only reads locals and by-value parameters (5.8, 5.10, 2.2.2).

    Locals and by-value parameters belong to this call of the program alone (2.2.2, 2.6.1) and
    a local cannot be passed by reference to a task (5.10): while the task waits, nothing can
    change them. A condition of constants only (`wait(false)`) is left alone: that is written
    on purpose.
    """
    out = []
    for s in facts.nodes.of(A.ExprStatement):
        call = s.call
        if type(call.func) is not A.Name or call.func.name.lower() != "wait" or len(call.args) != 1:
            continue
        names = _frozen_names(call.args[0], scope)
        if names:
            out.append(_diag(M.WAIT_NEVER_CHANGES, M.wait_never_changes(names), program, s))
    return out


def _loop_is_busy(loop: object, scope: Scope, nodes: ProgramNodes, stops: dict[str, bool]) -> bool:
    """Nothing in the loop can wait or yield, and the loop does not change its own condition.
    Each thing found is a reason for no, whatever the order: the walk ends at the first.
    `stops`: per name as written, whether it may wait or is unknown (shared by a program's loops)."""
    inside = nodes.under(loop)
    in_cond = {n.name.lower() for n in A.nodes(loop.cond) if type(n) is A.Name}  # small: walked, not searched
    yielding, instructions = _yielding(), entries()  # the catalogue's names (lower-case)
    for node in inside:
        t = type(node)
        if t is A.Return or t is A.Call or t is A.TaskCreate or t is A.TaskCreateSync:
            return False  # leaves the loop, or runs a program that may wait
        if t is A.CallExpr:
            if type(node.func) is not A.Name:
                return False  # library or system call: unknown
            name = node.func.name.lower()
            if name in yielding or name not in instructions:
                return False
            for arg, w in zip(node.args, Resolver.call_writes(node)):
                if w:
                    root = root_name(arg)
                    if root is not None and root.name.lower() in in_cond:
                        return False  # the loop changes its own condition: a computation, not a wait
        elif t is A.Assign or t is A.AssignExpr:
            root = root_name(node.target)
            if root is None or root.name.lower() in in_cond:
                return False
        elif t is A.For:
            root = root_name(node.counter)
            if root is not None and root.name.lower() in in_cond:
                return False
        elif t is A.Name:
            stop = stops.get(node.name)
            if stop is None:
                stop = stops[node.name] = _name_stops(node.name, scope, instructions)
            if stop:
                return False
    return True


def _name_stops(name: str, scope: Scope, instructions: dict) -> bool:
    """A name a busy loop may not read: a sio (reading or writing one waits, 5.4), or an unknown
    name (maybe a sio global of an application without data)."""
    typ = scope.type_of(name, ci=True)
    if typ is None:
        key = name.lower()
        return key not in _constants() and key not in instructions
    return builtin_type(typ) == "sio"


def check_loops(program: Program, scope: Scope, facts: ProgramFacts) -> list[Diagnostic]:
    """S014: a while/do loop that polls without ever yielding (5.4, delay() example of 5.10)."""
    out = []
    stops: dict[str, bool] = {}
    for loop in facts.loops:
        if _loop_is_busy(loop, scope, facts.nodes, stops):
            keyword = "while" if type(loop) is A.While else "do"
            out.append(_diag(M.BUSY_WAIT_LOOP, M.busy_wait_loop(keyword), program, loop))
    return out


# ------------------------------------------------------------------ self-assignment


def _same(a: object, b: object) -> bool:
    """Structurally equal lvalues whose evaluation has no side effect."""
    stack = [(a, b)]
    while stack:
        x, y = stack.pop()
        t = type(x)
        if t is not type(y):
            return False
        if t is A.Name:
            if x.name != y.name:
                return False
        elif t is A.Field:
            if x.name != y.name:
                return False
            stack.append((x.base, y.base))
        elif t is A.Index:
            if len(x.indices) != len(y.indices):
                return False
            stack.append((x.base, y.base))
            stack.extend(zip(x.indices, y.indices))
        elif t is A.Number or t is A.String:
            if x.value != y.value:
                return False
        elif t is A.Binary:
            if x.op != y.op:
                return False
            stack.append((x.left, y.left))
            stack.append((x.right, y.right))
        elif t is A.Unary:
            if x.op != y.op:
                return False
            stack.append((x.operand, y.operand))
        else:
            return False  # calls may have effects or differ from one evaluation to the next
    return True


def _text(e: object) -> str:
    t = type(e)
    if t is A.Name:
        return e.name
    if t is A.Field:
        return f"{_text(e.base)}.{e.name}"
    if t is A.Index:
        return f"{_text(e.base)}[...]"
    return "the variable"


def check_self_assignments(program: Program, scope: Scope, facts: ProgramFacts) -> list[Diagnostic]:
    """S015: `x = x` (also `p.trsf.x = p.trsf.x`, `a[i] = a[i]`)."""
    out = []
    for a in facts.assigns:
        root = root_name(a.target)
        if root is None or not _same(a.target, a.value):
            continue
        typ = scope.type_of(root.name)
        if typ is None or builtin_type(typ) in IO_TYPES:
            continue  # a sio read and write is an exchange, a dio may be an output: not a no-op
        out.append(_diag(M.SELF_ASSIGNMENT, M.self_assignment(_text(a.target)), program, a))
    return out
