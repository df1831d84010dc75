"""Typing of expressions (manual 2.5.3, operator tables of chapters 3, 9, 10).

`ExprTyper(ctx, check_call).typeof(node)` gives the `Val` of an expression (vtypes.Val: type,
container, variable or value) and reports what the compiler refuses inside it: undefined names,
operators that do not exist for the operand types, wrong indices, unknown fields, `=` inside an
expression. `elem(node)` is the same for places that need one value (operands, conditions,
assigned values): a container used without index there is reported. A call inside an expression
goes to `check_call` (calls.check_call_expr, given by whoever makes the typer: calls.py types
its arguments with this typer, so neither module imports the other's entry point).

Every function is total: an undefined name or an unknown type gives UNKNOWN, which every later
check accepts (one diagnostic per root cause).
"""

from __future__ import annotations

from collections.abc import Callable

from ..language.instructions import lookup as lookup_instruction
from ..loading.model import Container
from ..parsing import ast as A
from ..rules import codes
from . import messages as M
from . import symbols as S
from . import vtypes as vt
from .context import Context

ARRAY, COLLECTION, ELEMENT = vt.ARRAY, vt.COLLECTION, vt.ELEMENT
UNKNOWN, UNKNOWN_VAL = vt.UNKNOWN, vt.UNKNOWN_VAL
# Val.indexed: what [] was applied to (0: nothing)
FROM_ELEMENT, FROM_ARRAY, FROM_COLLECTION = 1, 2, 3
# How a call is typed (calls.check_call_expr): (typer, call, used as a statement) -> its Val
CallChecker = Callable[["ExprTyper", A.CallExpr, bool], vt.Val]


def node_text(node: object, limit: int = 40) -> str:
    """A short source-like rendering of a name, element or field, for messages."""
    t = type(node)
    if t is A.Name:
        return node.name  # type: ignore[attr-defined]
    if t is A.LibraryName:
        return f"{node.alias}:{node.name}"  # type: ignore[attr-defined]
    if t is A.Field:
        return f"{node_text(node.base, limit)}.{node.name}"[:limit]  # type: ignore[attr-defined]
    if t is A.Index:
        inner = ", ".join(node_text(i, 12) for i in node.indices)  # type: ignore[attr-defined]
        return f"{node_text(node.base, limit)}[{inner}]"[:limit]  # type: ignore[attr-defined]
    if t is A.Number:
        return node.text  # type: ignore[attr-defined]
    if t is A.String:
        return f'"{node.value}"'[:limit]  # type: ignore[attr-defined]
    if t is A.CallExpr:
        return f"{node_text(node.func, limit)}(...)"  # type: ignore[attr-defined]
    if t is A.SystemName:
        return node.name  # type: ignore[attr-defined]
    return "this expression"


def missing_index_code(v: vt.Val) -> str:
    """T011 (error) for a collection or a 2-D/3-D array used where one value is needed; T025
    (warning) for a 1-D array of several values: 2.3.4 makes only a one-value array an element,
    but real s7 applications use such arrays bare (reading their first value) and run."""
    return codes.MISSING_INDEX if v.c == COLLECTION or (v.c == ARRAY and v.dims > 1) else codes.BARE_MULTI_VALUE_ARRAY


def missing_index_message(node: object, v: vt.Val) -> str:
    """T011: `node` (of Val `v`) is a container used where one value is needed."""
    if v.c == COLLECTION:
        what = "collection"
    elif v.c == ARRAY and v.dims > 1:
        what = f"a {v.dims}-D array"
    elif v.c == ARRAY and v.root is not None and v.root.sizes and not v.field:
        what = f"an array of {v.root.sizes[0]} values"
    else:
        what = "an array"
    return M.missing_index(node_text(node), what)


def suggest(name: str, candidates) -> str | None:
    import difflib  # only for a name not found: not at start-up (lint's import time)

    hits = difflib.get_close_matches(name, list(candidates), n=1, cutoff=0.75)
    return hits[0] if hits else None


class ExprTyper:
    """Types expressions of the program in `ctx` (see the module docstring)."""

    def __init__(self, ctx: Context, check_call: CallChecker) -> None:
        self.ctx = ctx
        self.check_call = check_call
        self.literal_vals: dict[int, list] = {}  # id(Struct) -> Vals of its fields
        self.probe = False  # typing the argument of isDefined(): unknown alias:x is fine (2.5.4)
        self._dispatch = {
            A.Number: self._number,
            A.String: self._string,
            A.Bool: self._bool,
            A.Name: self._name,
            A.LibraryName: self._library_name,
            A.SystemName: self._system_name,
            A.Index: self._index,
            A.Field: self._field,
            A.CallExpr: self._call,
            A.Unary: self._unary,
            A.Binary: self._binary,
            A.Struct: self._struct,
            A.AssignExpr: self._assign_expr,
            A.ErrorExpr: self._unknown,
        }

    # -- entry points ----------------------------------------------------------------------

    def typeof(self, node: object) -> vt.Val:
        """The Val of `node` as written (a bare array stays an array)."""
        f = self._dispatch.get(type(node))
        return f(node) if f is not None else UNKNOWN_VAL

    def elem(self, node: object) -> vt.Val:
        """The Val of `node` where one value is needed: a container without index is reported
        (2.3.4, 2.5.3) and read as one value of its type, still a variable when it is one: a bare
        1-D array of several values (a warning, T025) stands for its first value, so
        `pTarget.trsf.x = v` is the same warning as reading it, and no container gets a second
        finding ("must be a variable") after its missing index."""
        v = self.typeof(node)
        if v.elem is False:
            self._report_missing_index(node, v)
            if v.var:
                return vt.Val(v.t, ELEMENT, 1, True, True, v.root, False, FROM_ARRAY, v.field)
            return vt.value(v.t)
        return v

    def call(self, node: A.CallExpr, statement: bool) -> vt.Val:
        """A call of an instruction (or a misused program); `statement`: its value is unused."""
        return self.check_call(self, node, statement)

    # -- leaves ----------------------------------------------------------------------------

    def _number(self, node: A.Number) -> vt.Val:
        return vt.value(vt.NUM)

    def _string(self, node: A.String) -> vt.Val:
        return vt.value(vt.STRING)

    def _bool(self, node: A.Bool) -> vt.Val:
        return vt.value(vt.BOOL)

    def _unknown(self, node: object) -> vt.Val:
        return UNKNOWN_VAL

    def _system_name(self, node: A.SystemName) -> vt.Val:
        return UNKNOWN_VAL

    def _name(self, node: A.Name) -> vt.Val:
        ctx = self.ctx
        name = node.name
        sym = ctx.scope.lookup(name)  # type: ignore[union-attr]
        if sym is not None:
            if sym.type.kind == vt.USER and ctx.guessed_types:
                ctx.consulted_type(sym.type.key)
            return sym.val
        c = S.constant(name)
        if c is not None:
            return c.val
        sym = ctx.scope.lookup_ci(name)  # type: ignore[union-attr]
        if sym is not None:
            kind = "parameter" if sym.kind == S.PARAM else sym.kind
            ctx.report_at(codes.NAME_CASE_MISMATCH, M.case_mismatch(kind, name, sym.name), node,
                fix=("rename", name, sym.name))
            return sym.val
        if not ctx.globals_known or not ctx.names_complete("data"):
            return UNKNOWN_VAL  # maybe a global that could not be read
        table = ctx.table
        if table.program(name) is not None or table.program_ci(name) is not None:
            ctx.report_at(codes.PROGRAM_INSTRUCTION_MISUSE, M.program_as_value(name), node)
        elif lookup_instruction(name) is not None:
            ctx.report_at(codes.PROGRAM_INSTRUCTION_MISUSE, M.instruction_as_value(name), node)
        else:
            names = list(ctx.scope.own) + list(table.globals)  # type: ignore[union-attr]
            ctx.report_at(codes.UNDEFINED_VARIABLE, M.undefined_variable(name, suggest(name, names)), node)
        return UNKNOWN_VAL

    def library(self, node: A.LibraryName | A.Name, alias: str):
        """The LibraryInterface for `alias` at `node`, or None when its symbols are not to be
        checked (reported here when the alias is not declared)."""
        ctx = self.ctx
        lib = ctx.table.library(alias)
        if lib is S.MISSING:
            return None
        if lib is None:
            other = ctx.table.library_alias_ci(alias)
            if other is not None:
                ctx.report_at(codes.NAME_CASE_MISMATCH, M.case_mismatch("library identifier", alias, other), node,
                    fix=("rename", alias, other, "", ":"))
                lib = ctx.table.library(other)
                if lib is S.MISSING:
                    return None
                ctx.consulted_library(other)
                return lib
            if ctx.globals_known and alias.lower() != "io":
                ctx.report_at(codes.UNDEFINED_LIBRARY_ALIAS, M.undefined_alias(alias, suggest(alias, ctx.app.libraries)), node)
            return None
        ctx.consulted_library(alias)
        return lib

    def _library_name(self, node: A.LibraryName) -> vt.Val:
        ctx = self.ctx
        lib = self.library(node, node.alias)
        if lib is None:
            return UNKNOWN_VAL
        name = node.name
        sym, why = lib.data_symbol(name)
        if sym is not None:
            if why and not self.probe:
                ctx.report_at(
                    codes.PRIVATE_LIBRARY_SYMBOL,
                    M.private_library_symbol(node.alias, name, lib.app.name, "global"),
                    node,
                )
            return sym.val
        if self.probe:
            return UNKNOWN_VAL
        prog, _ = lib.program(name)
        if prog is not None:
            ctx.report_at(codes.LIBRARY_SYMBOL_KIND, M.library_symbol_not_data(node.alias, name), node)
            return UNKNOWN_VAL
        other = lib.lookup_ci(name)
        if other is not None:
            ctx.report_at(
                codes.NAME_CASE_MISMATCH,
                M.case_mismatch("library symbol", name, other),
                node,
                fix=("rename", name, other, ":", ""),
            )
            sym, _ = lib.data_symbol(other)
            return sym.val if sym is not None else UNKNOWN_VAL
        if ctx.names_complete("data", lib.app) and not ctx.program_may_exist(name, lib.app):
            publics = [n for n, d in lib.app.data.items() if d.access == "public"]
            ctx.report_at(
                codes.UNDEFINED_LIBRARY_SYMBOL,
                M.undefined_library_symbol(node.alias, name, lib.app.name, suggest(name, publics)),
                node,
            )
        return UNKNOWN_VAL

    # -- containers and fields -------------------------------------------------------------

    def _index(self, node: A.Index) -> vt.Val:
        ctx = self.ctx
        base = self.typeof(node.base)
        idx = [self.elem(i) for i in node.indices]
        if base is UNKNOWN_VAL:
            return UNKNOWN_VAL
        n = len(idx)
        t = base.t
        if base.c == COLLECTION:
            if n != 1:
                ctx.report(
                    codes.WRONG_INDEX_COUNT,
                    f"{node_text(node.base)} is a collection: it takes one string key, not {n} (2.5.3)",
                    node.indices[1].line,
                    node.indices[1].col,
                )  # type: ignore[union-attr]
            else:
                kt = idx[0].t
                if kt.known and kt is not vt.STRING and kt.kind != vt.LITERAL:
                    ctx.report_at(
                        codes.WRONG_INDEX_TYPE, M.key_not_string(node_text(node.base), kt.name), node.indices[0]
                    )
            return vt.Val(t, ELEMENT, 0, True, base.var, base.root, False, FROM_COLLECTION, base.field)
        if base.c == ARRAY:
            dims = base.dims or 1
            if n != dims:
                at = node.indices[dims] if n > dims else node.base
                ctx.report(codes.WRONG_INDEX_COUNT, M.index_count(node_text(node.base), dims, n), at.line, at.col)  # type: ignore[union-attr]
            else:
                self._numeric_indices(node, idx)
            return vt.Val(t, ELEMENT, dims, True, base.var, base.root, dims == 1 and n == 1, FROM_ARRAY, base.field)
        if base.dims < 0:  # container not known (s6 parameter or global)
            root = base.root
            if (
                root is not None
                and root.kind != S.PARAM
                and not base.field
                and getattr(root.decl, "container", None) is Container.ARRAY
            ):
                self._numeric_indices(node, idx)  # an s6 global is an array: its indices are numbers
            return vt.Val(t, ELEMENT, 0, True, base.var, base.root, True, FROM_ELEMENT, base.field)
        # An element: a single [0]-like index is accepted (a 1-value array is an element, 2.3.4).
        if not base.var:
            if t.known:
                ctx.report_at(codes.WRONG_INDEX_COUNT, M.not_indexable(node_text(node.base)), node)
            return vt.value(t)
        if n != 1:
            at = node.indices[1]
            ctx.report(codes.WRONG_INDEX_COUNT, M.index_count(node_text(node.base), 0, n), at.line, at.col)  # type: ignore[union-attr]
        else:
            self._numeric_indices(node, idx)
        return vt.Val(t, ELEMENT, 1, True, base.var, base.root, True, FROM_ELEMENT, base.field)

    def _numeric_indices(self, node: A.Index, idx: list[vt.Val]) -> None:
        for v, i in zip(idx, node.indices):
            it = v.t
            if it.known and it is not vt.NUM and it is not vt.AIO:
                self.ctx.report_at(codes.WRONG_INDEX_TYPE, M.index_not_num(node_text(node.base), it.name), i)
                return

    def _field(self, node: A.Field) -> vt.Val:
        ctx = self.ctx
        base = self.elem(node.base)
        t = base.t
        if not t.known:
            return vt.Val(UNKNOWN, var=base.var, root=base.root, field=True) if base.var else UNKNOWN_VAL
        name = node.name
        if t.kind == vt.USER:
            ctx.consulted_type(t.key)
            fields = S.user_fields(ctx.table.registry, t)
            sym = fields.get(name)
            if sym is None:
                low = name.lower()
                sym = next((s for n, s in fields.items() if n.lower() == low), None)
                if sym is not None:
                    ctx.report(
                        codes.NAME_CASE_MISMATCH,
                        M.case_mismatch("field", name, sym.name),
                        node.name_line,
                        node.name_col,
                        fix=("rename", name, sym.name),
                    )
            if sym is None and t.app is not None and not ctx.names_complete("data", t.app):
                return vt.Val(UNKNOWN, var=base.var, root=base.root, field=True) if base.var else UNKNOWN_VAL
            if sym is None or sym.decl.access != "public":
                publics = [n for n, s in fields.items() if s.decl.access == "public"]
                msg = (
                    M.private_user_field(t.name, name)
                    if sym is not None
                    else M.undefined_user_field(t.name, name, publics)
                )
                ctx.report(
                    codes.UNDEFINED_USER_TYPE_FIELD,
                    msg,
                    node.name_line,
                    node.name_col,
                    node.name_line,
                    node.name_col + len(name),
                )
                if sym is None:
                    return vt.Val(UNKNOWN, var=base.var, root=base.root, field=True) if base.var else UNKNOWN_VAL
            fv = sym.val
            return vt.Val(sym.type, fv.c, fv.dims, fv.elem, base.var, base.root, False, 0, True)
        if t.structured:
            hit = vt.field_of(t, name)
            if hit is None:
                known = [f.name for f in _builtin_type(t.name).fields] if t is not vt.JOINT else ["j1", "j2", "..."]
                ctx.report(
                    codes.UNKNOWN_FIELD,
                    M.no_field(t.name, name, known),
                    node.name_line,
                    node.name_col,
                    node.name_line,
                    node.name_col + len(name),
                )
                return vt.Val(UNKNOWN, var=base.var, root=base.root, field=True) if base.var else UNKNOWN_VAL
            canon, ft, exact = hit
            if not exact:
                ctx.report(
                    codes.NAME_CASE_MISMATCH,
                    M.case_mismatch("field", name, canon),
                    node.name_line,
                    node.name_col,
                    fix=("rename", name, canon),
                )
            return vt.Val(ft, ELEMENT, 0, True, base.var, base.root, False, 0, True)
        ctx.report(
            codes.UNKNOWN_FIELD,
            M.no_field(t.name, name),
            node.name_line,
            node.name_col,
            node.name_line,
            node.name_col + len(name),
        )
        return UNKNOWN_VAL

    # -- operators -------------------------------------------------------------------------

    def _unary(self, node: A.Unary) -> vt.Val:
        v = self.elem(node.operand)
        t = v.t
        if not t.known:
            return vt.value(vt.BOOL) if node.op == "!" else UNKNOWN_VAL
        res = vt.unary_result(node.op, t)
        if res is None:
            if node.op == "!" and t is vt.DIO:
                return vt.value(vt.BOOL)
            if node.op == "-" and t is vt.AIO:
                return vt.value(vt.NUM)
            self.ctx.report(codes.OPERATOR_NOT_DEFINED, M.operator_undefined(node.op, t.name), node.line, node.col)
            return UNKNOWN_VAL
        return vt.value(res)

    def _binary(self, node: A.Binary) -> vt.Val:
        left = self.elem(node.left)
        right = self.elem(node.right)
        op = node.op
        lt_, rt = left.t, right.t
        if lt_.kind == vt.LITERAL and rt.structured:
            self.check_literal(node.left, rt)
            lt_ = rt
        elif rt.kind == vt.LITERAL and lt_.structured:
            self.check_literal(node.right, lt_)
            rt = lt_
        res = vt.binary_result(op, lt_, rt)
        if res is not None:
            return vt.value(res)
        if op in _BOOL_RESULT:
            if not lt_.known or not rt.known:
                return vt.value(vt.BOOL)
            ok: bool | None
            if op in ("==", "!="):
                ok = vt.comparable(lt_, rt)
            elif op in ("and", "or", "xor"):
                ok = vt.condition_ok(lt_) and vt.condition_ok(rt)
                ok = bool(ok)
            else:  # < > <= >=
                ok = None if (vt.is_num_like(lt_) and vt.is_num_like(rt)) else False
            if ok is not False:
                return vt.value(vt.BOOL)
        else:
            if not lt_.known or not rt.known:
                return UNKNOWN_VAL  # one root cause, one finding
            if vt.is_num_like(lt_) and vt.is_num_like(rt):
                return vt.value(vt.NUM)  # aio read as a num
        self.ctx.report(
            codes.OPERATOR_NOT_DEFINED,
            M.operator_undefined(op, lt_.name, rt.name),
            node.op_line,
            node.op_col,
            node.op_line,
            node.op_col + len(op),
        )
        return UNKNOWN_VAL

    # -- structured values -----------------------------------------------------------------

    def _struct(self, node: A.Struct) -> vt.Val:
        vals = []
        for f in node.fields:
            vals.append(None if f is None else self.elem(f))
        self.literal_vals[id(node)] = vals
        return vt.value(vt.STRUCT_LITERAL)

    def check_literal(self, node: object, t: vt.VType) -> None:
        """A `{...}` value used where a `t` is expected (2.4.2): field count and field types."""
        if type(node) is not A.Struct or not t.known or t.kind == vt.USER:
            return
        ctx = self.ctx
        if not t.structured:
            ctx.report_at(codes.BAD_STRUCTURED_LITERAL, M.literal_not_structured(t.name), node)
            return
        n = len(node.fields)
        bounds = vt.literal_arity(t)
        if bounds is not None and not bounds[0] <= n <= bounds[1]:
            ctx.report_at(codes.BAD_STRUCTURED_LITERAL, M.literal_arity(t.name, bounds[0], bounds[1], n), node)
            return
        vals = self.literal_vals.get(id(node))
        if vals is None:
            self._struct(node)
            vals = self.literal_vals[id(node)]
        ftypes = vt.literal_field_types(t)
        for i, (f, v) in enumerate(zip(node.fields, vals)):
            if f is None or i >= len(ftypes):
                continue
            ft = ftypes[i]
            if type(f) is A.Struct:
                self.check_literal(f, ft)
                continue
            if v is not None and vt.assignable(ft, v.t) is False:
                ctx.report_at(codes.BAD_STRUCTURED_LITERAL, M.literal_field(t.name, i + 1, ft.name, v.t.name), f)

    # -- calls and misplaced assignments ---------------------------------------------------

    def _call(self, node: A.CallExpr) -> vt.Val:
        return self.call(node, False)

    def _assign_expr(self, node: A.AssignExpr) -> vt.Val:
        # 3.1.2, 3.2.2, 3.4.2: '=' is not allowed in an expression given as a parameter or a
        # condition; if(b1=b2) assigns b2 to b1 then tests b1.
        self.ctx.report(
            codes.ASSIGNMENT_IN_EXPRESSION,
            M.assign_in_expression(),
            node.op_line,
            node.op_col,
            node.op_line,
            node.op_col + 1,
        )
        return self.assignment(node.target, node.value, None)

    def assignment(self, target: object, value: object, op_pos: tuple[int, int] | None) -> vt.Val:
        """`target = value` (a statement, or inside an expression): checks the target is a
        variable and the value fits its type; returns the target's Val."""
        ctx = self.ctx
        tv = self.typeof(target)
        if type(value) is A.AssignExpr:  # x = y = 0: the value of y = 0
            vv = self.assignment(value.target, value.value, (value.op_line, value.op_col))
        else:
            vv = self.typeof(value)
        if tv is UNKNOWN_VAL:
            return tv
        if not tv.var:
            if tv.t.known:
                ctx.report_at(codes.NOT_ASSIGNABLE, M.not_assignable(node_text(target)), target)
            return tv
        if tv.elem is False:
            self._report_missing_index(target, tv)
            return vt.value(tv.t)
        if type(value) is A.Struct:
            self.check_literal(value, tv.t)
            return tv
        if vv.elem is False:
            self._report_missing_index(value, vv)
            return tv
        t, v = tv.t, vv.t
        if t is vt.DIO and v is vt.DIO and ctx.dio_assign_removed:
            line, col = op_pos or (value.line, value.col)  # type: ignore[attr-defined]
            ctx.report(codes.DIO_ASSIGNMENT_REMOVED, M.dio_assign(), line, col)
            return tv
        if vt.assignable(t, v) is False:
            ctx.report_at(codes.ASSIGNMENT_TYPE_MISMATCH, M.assign_mismatch(t.name, v.name), value)
        return tv

    def _report_missing_index(self, node: object, v: vt.Val) -> None:
        self.ctx.report_at(missing_index_code(v), missing_index_message(node, v), node)


_BOOL_RESULT = frozenset({"==", "!=", "<", ">", "<=", ">=", "and", "or", "xor"})


def _builtin_type(name: str):
    from ..language.types import load_types

    return load_types()[name]
