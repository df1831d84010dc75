"""Tree building: the callback of each grammar rule makes its `ast` node, with file positions."""

from __future__ import annotations

from ..positions import SourceMap
from . import ast as A

_WORD_OPS = frozenset({"AND", "OR", "XOR"})


class Builder:
    """Tree-building callbacks, one per grammar rule or alias (Lark calls them through its
    child filters with the list of the rule's kept children: tokens and nodes).

    Positions: `setup()` gives, for each code line, the file line and the column offset, so
    that the common case (code copied verbatim from a CDATA block) maps with two list reads;
    lines with a column map (escaped XML text) go through `SourceMap.to_file`.
    """

    def __init__(self) -> None:
        self.setup("", SourceMap())

    def setup(self, code: str, source_map: SourceMap) -> None:
        n_lines = code.count("\n") + 1
        starts = source_map.line_starts
        if starts:
            lines = [p.line for p in starts[:n_lines]]
            offs = [p.col - 1 for p in starts[:n_lines]]
            if len(lines) < n_lines:  # past the map: SourceMap.to_file keeps the last line start
                lines.extend([lines[-1]] * (n_lines - len(lines)))
                offs.extend([offs[-1]] * (n_lines - len(offs)))
        else:
            lines = list(range(1, n_lines + 1))
            offs = [0] * n_lines
        self.lines = lines
        self.offs = offs
        self.col_maps = source_map.col_maps
        self.sm = source_map

    def fpos(self, line: int, col: int) -> tuple[int, int]:
        """Code (line, col) -> file (line, col)."""
        k = line - 1
        if k in self.col_maps or not 0 <= k < len(self.lines):
            p = self.sm.to_file(line, col)
            return p.line, p.col
        return self.lines[k], self.offs[k] + col

    def tend(self, t) -> tuple[int, int]:
        """The file (line, col) just after a token."""
        return self.fpos(t[2], t[3] + len(t[1]))

    def tpos(self, t) -> tuple[int, int]:
        """The file (line, col) of a token (tokens are tuples: type, value, line, column)."""
        k = t[2] - 1
        if k in self.col_maps:
            return self.fpos(t[2], t[3])
        return self.lines[k], self.offs[k] + t[3]

    def _span(self, t) -> tuple[int, int, int, int]:
        line, column, n = t[2], t[3], len(t[1])
        k = line - 1
        if k in self.col_maps:
            ln, c = self.fpos(line, column)
            el, ec = self.fpos(line, column + n)
            return ln, c, el, ec
        ln = self.lines[k]
        c = self.offs[k] + column
        return ln, c, ln, c + n

    # leaves ----------------------------------------------------------

    def name(self, c):
        t = c[0]
        v = t[1]
        k = t[2] - 1
        if k in self.col_maps:
            return A.Name(v, *self._span(t))
        ln = self.lines[k]
        col = self.offs[k] + t[3]
        return A.Name(v, ln, col, ln, col + len(v))

    def lib_name(self, c):
        a, n = c
        ln, k, _, _ = self._span(a)
        _, _, el, ec = self._span(n)
        return A.LibraryName(a[1], n[1], ln, k, el, ec)

    def sys_name(self, c):
        t = c[0]
        return A.SystemName(t[1], *self._span(t))

    def number(self, c):
        t = c[0]
        text = t[1]
        try:
            value = float(text)
        except ValueError:  # BADNUMBER, already reported
            value = float("nan")
        return A.Number(value, text, *self._span(t))

    def string(self, c):
        t = c[0]
        v = t[1]
        return A.String(v[1:-1] if t[0] == "STRING" else v[1:], *self._span(t))

    def true(self, c):
        return A.Bool(True, *self._span(c[0]))

    def false(self, c):
        return A.Bool(False, *self._span(c[0]))

    def error_expr(self, c):
        t = c[0]
        return A.ErrorExpr(*self.tpos(t))

    # expressions -----------------------------------------------------

    def struct(self, c):
        t = c[0]
        fields = c[1:]
        if len(fields) == 1 and fields[0] is None:
            fields = []
        return A.Struct(fields, *self.tpos(t))

    def args(self, c):
        return c

    def call(self, c):
        f, args = c
        return A.CallExpr(f, args if args is not None else [], f.line, f.col)

    def index(self, c):
        base, args = c
        return A.Index(base, args, base.line, base.col)

    def field(self, c):
        base, t = c
        return A.Field(base, t[1], base.line, base.col, *self.tpos(t))

    def unary(self, c):
        t, operand = c
        ln, k = self.tpos(t)
        if t[1] == "-" and type(operand) is A.Number and not operand.text.startswith("-"):
            # fold `-3` into a constant (3.2.1: `[-]<digits>...`)
            return A.Number(-operand.value, "-" + operand.text, ln, k, operand.end_line, operand.end_col)
        return A.Unary(t[1], operand, ln, k)

    def binary(self, c):
        left, t, right = c
        op = t[1]
        if t[0] in _WORD_OPS:
            op = op.lower()
        return A.Binary(op, left, right, left.line, left.col, *self.tpos(t))

    def assign_expr(self, c):
        target, t, value = c
        return A.AssignExpr(target, value, target.line, target.col, *self.tpos(t))

    # statements ------------------------------------------------------

    def block(self, c):
        return c

    def assign(self, c):
        target, t, value = c
        return A.Assign(target, value, target.line, target.col, *self.tpos(t))

    def expr_stmt(self, c):
        call = c[0]
        return A.ExprStatement(call, call.line, call.col)

    def call_stmt(self, c):
        t, target, args = c
        return A.Call(target, args if args is not None else [], *self.tpos(t))

    def task_create(self, c):
        t, task, priority, target, args = c
        return A.TaskCreate(task, priority, target, args if args is not None else [],
                            *self.tpos(t))

    def task_create_sync(self, c):
        t, task, period, overrun, target, args = c
        return A.TaskCreateSync(task, period, overrun, target, args if args is not None else [],
                                *self.tpos(t))

    def print_stmt(self, c):
        t, values = c
        return A.Print(values, *self.tpos(t))

    def return_stmt(self, c):
        t = c[0]
        return A.Return(*self.tpos(t))

    def break_stmt(self, c):
        t = c[0]
        return A.Break(*self.tpos(t))

    def error_stmt(self, c):
        t = c[0]
        return A.ErrorStatement(*self.tpos(t))

    def if_stmt(self, c):
        t, cond, body = c[0], c[1], c[2]
        end = c[-1]
        orelse = c[-2]
        ln, k = self.tpos(t)
        branches = [A.Branch(cond, body, ln, k)]
        branches.extend(c[3:-2])
        el, ec = self.tend(end)
        if orelse is None:
            return A.If(branches, None, ln, k, 0, 0, el, ec)
        ol, oc, obody = orelse
        return A.If(branches, obody, ln, k, ol, oc, el, ec)

    def elseif_clause(self, c):
        t, cond, body = c
        return A.Branch(cond, body, *self.tpos(t))

    def else_clause(self, c):
        t, body = c
        ln, k = self.tpos(t)
        return (ln, k, body)

    def while_stmt(self, c):
        t, cond, body, end = c
        ln, k = self.tpos(t)
        el, ec = self.tend(end)
        return A.While(cond, body, ln, k, el, ec)

    def do_stmt(self, c):
        t, body, u, cond = c
        ln, k = self.tpos(t)
        ul, uc = self.tpos(u)
        return A.DoUntil(body, cond, ln, k, ul, uc)

    def for_header(self, c):
        if len(c) == 1:  # ERROR (recovery)
            e = A.ErrorExpr(*self.tpos(c[0]))
            return (e, e, e, None)
        counter, _eq, start, _to, stop, _step, step = c
        return (counter, start, stop, step)

    def for_stmt(self, c):
        t, (counter, start, stop, step), body, end = c
        ln, k = self.tpos(t)
        el, ec = self.tend(end)
        return A.For(counter, start, stop, step, body, ln, k, el, ec)

    def case_clause(self, c):
        t = c[0]
        return A.Case(c[1:-1], c[-1], *self.tpos(t))

    def default_clause(self, c):
        t, body = c
        return A.Default(body, *self.tpos(t))

    def switch_stmt(self, c):
        t, subject = c[0], c[1]
        end = c[-1]
        default = c[-2]
        ln, k = self.tpos(t)
        el, ec = self.tend(end)
        return A.Switch(subject, c[2:-2], default, ln, k, el, ec)

    def start(self, c):
        b, stmts, e = c
        ln, k = self.tpos(b)
        el, ec = self.tend(e)
        return A.ProgramBody(stmts, [], ln, k, el, ec)

