"""Calls: instructions (the s7 catalogue), programs (`call`, taskCreate) and their arguments
(manual 2.2.5 call, 2.5.4-2.5.6, 2.6, 5.10, 6.7).

An instruction call chooses among the catalogue's overloads by the number, then the types of
its arguments; the chosen overload's parameters then say what each argument must be (a value, a
variable passed by reference, an array or a collection, with or without index). A program call
checks its arguments against the program's parameters as the project declares them.
"""

from __future__ import annotations

from ..rules import codes
from functools import cache, lru_cache

from ..language.instructions import (
    Instruction,
    Overload,
    Param,
    load_errata,
    load_instructions,
)
from ..language import s8
from ..language.instructions import lookup as lookup_instruction
from ..loading.model import Application, Container, Parameter, Program
from ..parsing import ast as A
from . import messages as M
from . import symbols as S
from . import vtypes as vt
from .expressions import (
    FROM_ARRAY,
    FROM_COLLECTION,
    ExprTyper,
    missing_index_code,
    missing_index_message,
    node_text,
    suggest,
)

ARRAY, COLLECTION, ELEMENT = vt.ARRAY, vt.COLLECTION, vt.ELEMENT
UNKNOWN, UNKNOWN_VAL = vt.UNKNOWN, vt.UNKNOWN_VAL

# Instructions that change the number of values of their variable (2.5.4, 2.5.5): not on
# local arrays; insert/delete/append not on 2-D/3-D arrays.
_RESIZERS = {"insert": True, "delete": True, "append": True, "resize": False}


class _Pending:
    """A diagnostic of an argument check, kept until an overload is chosen."""

    __slots__ = ("code", "message", "node")

    def __init__(self, code: str, message: str, node: object) -> None:
        self.code = code
        self.message = message
        self.node = node


# ------------------------------------------------------------------------------ instructions


@cache
def _param_type(name: str) -> vt.VType | None:
    """The VType of a catalogue parameter type; None for "*" (any type)."""
    if name == "*":
        return None
    return vt.BUILTINS.get(name, UNKNOWN)


def _type_ok(p: Param, v: vt.Val) -> bool:
    t = v.t
    if not t.known:
        return True
    pt = _param_type(p.type)
    if pt is None:
        return not p.accepts or t.name in p.accepts
    if t.kind == vt.LITERAL:
        return pt.structured
    if p.ref or p.variable or p.container != "element":
        return vt.same_type(t, pt)
    return vt.assignable(pt, t) is not False


def _describe_arg(v: vt.Val) -> str:
    return "{...} value" if v.t.kind == vt.LITERAL else vt.describe(v)


def check_call_expr(typer: ExprTyper, node: A.CallExpr, statement: bool) -> vt.Val:
    """A call written `f(args)`, `alias:f(args)` or `$f(args)` (an instruction, or a misused
    program)."""
    ctx = typer.ctx
    func = node.func
    ft = type(func)
    if ft is A.SystemName:  # undocumented system instruction: never reported
        for a in node.args:
            typer.typeof(a)
        return UNKNOWN_VAL
    if ft is A.LibraryName:
        ins = lookup_instruction(func.name)
        if ins is not None and ins.library_prefix != "none":
            typer.library(func, func.alias)  # the identifier must be declared
            return _instruction(typer, node, ins, statement)
        lib = typer.library(func, func.alias)
        _type_args(typer, node.args)
        if lib is None or func.name.startswith("$"):
            return UNKNOWN_VAL  # `alias:$name()`: an undocumented system instruction, like `$name()`
        prog, _ = lib.program(func.name)
        if prog is not None:
            ctx.report_at(codes.PROGRAM_INSTRUCTION_MISUSE, M.program_without_call(f"{func.alias}:{func.name}"), func)
            return UNKNOWN_VAL
        sym, _ = lib.data_symbol(func.name)
        if sym is not None:
            ctx.report_at(codes.LIBRARY_SYMBOL_KIND, M.library_symbol_not_program(func.alias, func.name), func)
            return UNKNOWN_VAL
        if ins is not None:
            ctx.report_at(codes.PROGRAM_INSTRUCTION_MISUSE, M.library_prefix_unexpected(func.alias, func.name), func)
            return UNKNOWN_VAL
        if ctx.names_complete("data", lib.app) and not ctx.program_may_exist(func.name, lib.app):
            publics = [n for n, p in lib.app.programs.items() if p.access == "public"]
            ctx.report_at(
                codes.UNDEFINED_LIBRARY_SYMBOL,
                M.undefined_library_symbol(func.alias, func.name, lib.app.name, suggest(func.name, publics)),
                func,
            )
        return UNKNOWN_VAL
    # A plain name.
    name = func.name
    ins = lookup_instruction(name)
    if ins is not None:
        if ins.library_prefix == "required":
            _type_args(typer, node.args)
            ctx.report_at(codes.PROGRAM_INSTRUCTION_MISUSE, M.library_prefix_needed(ins.name), func)
            return UNKNOWN_VAL
        return _instruction(typer, node, ins, statement)
    table = ctx.table
    new = s8.instruction(name)
    if new is not None and table.program(name) is None and table.program_ci(name) is None:
        ctx.s8_only(f"{new.name}()", func)
        if new.instruction is not None:
            return _instruction(typer, node, new.instruction, statement, s7=False)
        _type_args(typer, node.args)
        return UNKNOWN_VAL
    _type_args(typer, node.args)
    if table.program(name) is not None or table.program_ci(name) is not None:
        ctx.report_at(codes.PROGRAM_INSTRUCTION_MISUSE, M.program_without_call(name), func)
        return UNKNOWN_VAL
    sym = ctx.scope.lookup(name) or ctx.scope.lookup_ci(name)  # type: ignore[union-attr]
    if sym is not None:
        ctx.report_at(codes.UNDEFINED_INSTRUCTION, M.variable_called(name), func)
        return UNKNOWN_VAL
    if ctx.globals_known and ctx.program_may_exist(name):
        return UNKNOWN_VAL  # maybe the program of a file that could not be read, called without call
    erratum = load_errata().get(name.lower())
    close = erratum.canonical if erratum is not None else _close_instruction(name)
    if ctx.strict_version and close is not None:
        ctx.s7_only(
            codes.UNDEFINED_INSTRUCTION,
            M.undefined_instruction(name, close),
            func,
            codes.UNKNOWN_INSTRUCTION,
            M.unknown_instruction_s8(name, ctx.app.version),
        )
    elif ctx.strict_version:
        ctx.report_at(codes.UNKNOWN_INSTRUCTION, M.unknown_instruction_s7(name), func)
    else:
        ctx.report_at(codes.UNKNOWN_INSTRUCTION, M.unknown_instruction_s8(name, ctx.app.version), func)
    return UNKNOWN_VAL


def _close_instruction(name: str) -> str | None:
    """The catalogue instruction `name` is almost certainly a misspelling of, if any: one typing
    slip away (two for long names). A name further from every instruction may be one that the
    s7 manual does not list (a newer or optional instruction): not an error."""
    low = name.lower()
    limit = 2 if len(low) >= 8 else 1
    best, best_d = None, limit + 1
    for key, spelled in _instruction_names().items():
        if abs(len(key) - len(low)) > limit:
            continue
        d = _distance(low, key, limit)
        if d < best_d:
            best, best_d = spelled, d
    return best


def _distance(a: str, b: str, limit: int) -> int:
    """Edit distance with adjacent transpositions (optimal string alignment), capped at limit+1."""
    prev2: list[int] = []
    prev = list(range(len(b) + 1))
    for i in range(1, len(a) + 1):
        cur = [i] + [0] * len(b)
        for j in range(1, len(b) + 1):
            cost = 0 if a[i - 1] == b[j - 1] else 1
            v = min(prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + cost)
            if i > 1 and j > 1 and a[i - 1] == b[j - 2] and a[i - 2] == b[j - 1]:
                v = min(v, prev2[j - 2] + 1)
            cur[j] = v
        if min(cur) > limit:
            return limit + 1
        prev2, prev = prev, cur
    return prev[-1]


@lru_cache(maxsize=1)
def _instruction_names() -> dict[str, str]:
    return {k: ins.name for k, ins in load_instructions().items() if ins.kind != "special"}


def _type_args(typer: ExprTyper, args: list) -> list[vt.Val]:
    return [typer.typeof(a) for a in args]


def _s8_form(ins: Instruction, vals: list[vt.Val]) -> s8.S8Form | None:
    """The s8 form of `ins` (s8.toml) that these arguments select, if any."""
    n = len(vals)
    for form in s8.forms(ins.name):
        o = form.overload
        if o.accepts_arity(n) and all(_type_ok(p, v) for p, v in zip(o.params, vals)):
            return form
    return None


def _instruction(typer: ExprTyper, node: A.CallExpr, ins: Instruction, statement: bool, s7: bool = True) -> vt.Val:
    """A call of the catalogue instruction `ins`; `s7`: the signatures are the manual's (a
    mismatch is a sure error on s7), not the partly known ones of an s8 instruction."""
    ctx = typer.ctx
    args = node.args
    if ins.name == "isDefined":  # 2.5.4: the way to probe a library interface
        typer.probe = True
        try:
            vals = _type_args(typer, args)
        finally:
            typer.probe = False
    else:
        vals = _type_args(typer, args)
    n = len(vals)
    func = node.func
    label = f"{ins.name}()"
    cands = ins.overloads_with_arity(n)
    full = [o for o in cands if all(_type_ok(p, v) for p, v in zip(o.params, vals))]
    form = None
    if not full:
        form = _s8_form(ins, vals)
        if form is not None:  # an s8 form of an s7 instruction (s8.toml)
            shown = form.overload.signature(ins.name) if form.params_known else f"{ins.name}() with {n} arguments"
            ctx.s8_only(f"the form {shown}", func)
            cands = full = [form.overload]
    # A signature of the manual is certain; one read from s8 code (s8.toml) is not: a call that
    # disagrees with it is T024, a warning, never an error.
    certain = s7 and form is None
    if not cands:
        sigs = [o.signature(ins.name) for o in ins.overloads]
        counts = sorted({c for o in ins.overloads for c in range(o.min_arity, o.max_arity + 1)})
        msg = M.arity(label, _count_words(counts), n, sigs)
        _signature_finding(ctx, codes.WRONG_ARGUMENT_COUNT, msg, s7, func)
        return _common_return(ins.overloads, statement)
    if not full:
        best = max(cands, key=lambda o: sum(1 for p, v in zip(o.params, vals) if _type_ok(p, v)))
        i = next(i for i, (p, v) in enumerate(zip(best.params, vals)) if not _type_ok(p, v))
        got = _describe_arg(vals[i])
        if len(cands) == 1:
            p = best.params[i]
            expected = "value of any type" if p.type == "*" else p.type
            if p.type == "*" and p.accepts:
                expected = " or ".join(p.accepts)
            msg = M.argument_type(i + 1, label, p.name, expected, got)
        else:
            msg = M.argument_type_overloads(i + 1, label, got, [o.signature(ins.name) for o in cands])
        _signature_finding(ctx, codes.ARGUMENT_TYPE_MISMATCH, msg, s7, args[i])
        return _common_return(cands, statement)
    chosen = full[0] if form is not None and not form.params_known else None  # its arguments are not known
    first_errors: list[_Pending] = []
    for o in full if chosen is None else ():
        errors = _instruction_arg_errors(typer, ins, o, vals, args)
        if not errors:
            chosen = o
            break
        if chosen is None and not first_errors:
            first_errors = errors
    if chosen is None:
        for e in first_errors:
            if certain:
                ctx.report_at(e.code, e.message, e.node)
            else:
                ctx.report_at(codes.S8_SIGNATURE_UNVERIFIED, M.s8_reading(e.message), e.node)
        chosen = full[0]
    for p, a in zip(chosen.params, args):
        if type(a) is A.Struct:
            pt = _param_type(p.type)
            if pt is not None:
                typer.check_literal(a, pt)
    returns = {o.returns for o in full}
    if not statement and returns == {"void"}:
        if certain:
            ctx.report_at(codes.NO_RETURN_VALUE, M.no_value(ins.name), func)
        else:
            ctx.report_at(codes.S8_SIGNATURE_UNVERIFIED, M.s8_reading(M.no_value(ins.name)), func)
        return UNKNOWN_VAL
    if len(returns) == 1:
        ret = next(iter(returns))
        return vt.value(vt.BUILTINS.get(ret, UNKNOWN)) if ret != "void" else UNKNOWN_VAL
    return UNKNOWN_VAL


def _count_words(counts: list[int]) -> str:
    if len(counts) == 1:
        return f"{counts[0]} argument{'s' if counts[0] != 1 else ''}"
    if counts == list(range(counts[0], counts[-1] + 1)):
        return f"{counts[0]} to {counts[-1]} arguments"
    return ", ".join(str(c) for c in counts[:-1]) + f" or {counts[-1]} arguments"


def _common_return(overloads, statement: bool) -> vt.Val:
    returns = {o.returns for o in overloads}
    if len(returns) == 1:
        r = next(iter(returns))
        if r != "void":
            return vt.value(vt.BUILTINS.get(r, UNKNOWN))
    return UNKNOWN_VAL


def _instruction_arg_errors(
    typer: ExprTyper, ins: Instruction, o: Overload, vals: list[vt.Val], args: list
) -> list[_Pending]:
    out: list[_Pending] = []
    label = f"{ins.name}()"
    for i, (p, v, a) in enumerate(zip(o.params, vals, args)):
        idx = i + 1
        if p.container == "element" and not (p.ref or p.variable):
            if v.elem is False:
                out.append(_Pending(missing_index_code(v), missing_index_message(a, v), a))
            continue
        if v is UNKNOWN_VAL or v.dims < 0:
            continue  # an undefined name (reported), an unknowable value, an s6 variable
        if not v.var:
            word = {"array": "array", "collection": "collection"}.get(p.container, "")
            out.append(_Pending(codes.REFERENCE_NEEDS_VARIABLE, M.needs_variable(idx, label, p.name, word), a))
            continue
        cont = p.container
        if cont == "element":  # by reference or a variable the instruction changes
            if v.elem is False:
                out.append(_Pending(missing_index_code(v), missing_index_message(a, v), a))
            continue
        if cont == "array":
            e = _array_arg(idx, label, p, v, a, dims=None if p.type == "*" else 1, bare_only=p.index == "none")
            if e is not None:
                out.append(e)
            elif ins.name.lower() in _RESIZERS:
                e = _resize_error(ins.name, v, a)
                if e is not None:
                    out.append(e)
            continue
        if cont == "collection":
            if v.c == COLLECTION:
                if p.index == "required":
                    out.append(_Pending(codes.MISSING_INDEX, M.missing_index(node_text(a), "collection"), a))
            elif v.indexed == FROM_COLLECTION:
                if p.index != "required":
                    out.append(_Pending(codes.UNEXPECTED_INDEX, M.unexpected_index(idx, label, p.name, "key"), a))
            else:
                out.append(
                    _Pending(
                        codes.CONTAINER_MISMATCH,
                        M.container_mismatch(idx, label, p.name, "collection", vt.describe(v)),
                        a,
                    )
                )
            continue
        # container "any": size(*), isDefined(*), insert(*), delete(*), getData(..., *)
        rule = p.index or "any"
        if rule == "start":
            if v.indexed and not v.start:
                kind = "key" if v.indexed == FROM_COLLECTION else "indices"
                out.append(_Pending(codes.UNEXPECTED_INDEX, M.unexpected_index(idx, label, p.name, kind), a))
        elif rule == "required":
            if not v.indexed:
                what = (
                    "collection"
                    if v.c == COLLECTION
                    else (f"a {v.dims}-D array" if v.c == ARRAY and v.dims > 1 else "an array")
                )
                out.append(_Pending(codes.MISSING_INDEX, M.missing_index(node_text(a), what), a))
            elif ins.name.lower() in _RESIZERS:
                e = _resize_error(ins.name, v, a)
                if e is not None:
                    out.append(e)
    return out


def _array_arg(
    idx: int, label: str, p: Param | Parameter, v: vt.Val, a: object, dims: int | None, bare_only: bool
) -> _Pending | None:
    """An argument for an array parameter (2.6.3). `dims`: the dimensions required (None: any);
    `bare_only`: the variable must be given without index (size(*, n), append, resize)."""
    pname = p.name
    want = "array" if dims is None else ("1-D array" if dims == 1 else f"{dims}-D array")
    if v.c == COLLECTION or v.indexed == FROM_COLLECTION:
        return _Pending(codes.CONTAINER_MISMATCH, M.container_mismatch(idx, label, pname, want, vt.describe(v)), a)
    if v.c == ARRAY:
        if dims is not None and (v.dims or 1) != dims:
            return _Pending(codes.CONTAINER_MISMATCH, M.container_mismatch(idx, label, pname, want, vt.describe(v)), a)
        return None
    # An element: a[i], a2[i, j], or an element variable.
    if v.indexed == FROM_ARRAY or v.indexed == 1:
        if bare_only:
            return _Pending(
                codes.UNEXPECTED_INDEX, M.unexpected_index(idx, label, pname, "indices" if v.dims > 1 else "index"), a
            )
        if v.start:
            return None  # 2.6.3: a 1-D array from index i
        if dims is None or v.dims == dims:
            return _Pending(codes.UNEXPECTED_INDEX, M.unexpected_index(idx, label, pname, "indices"), a)
        return _Pending(codes.CONTAINER_MISMATCH, M.container_mismatch(idx, label, pname, want, vt.describe(v)), a)
    if dims is not None and dims > 1:
        return _Pending(codes.CONTAINER_MISMATCH, M.container_mismatch(idx, label, pname, want, vt.describe(v)), a)
    return None  # an element variable: a 1-value array (2.3.4)


def _resize_error(name: str, v: vt.Val, a: object) -> _Pending | None:
    low = name.lower()
    dims = v.dims if (v.c == ARRAY or v.indexed == FROM_ARRAY) else 0
    if _RESIZERS[low] and dims > 1:
        return _Pending(
            codes.ARRAY_RESIZE_NOT_ALLOWED,
            M.resize_not_allowed(node_text(a), name, f"it is a {dims}-D array (use resize)"),
            a,
        )
    root = v.root
    if root is not None and root.kind == S.LOCAL and not v.field and v.indexed != FROM_COLLECTION and v.c != COLLECTION:
        return _Pending(
            codes.ARRAY_RESIZE_NOT_ALLOWED, M.resize_not_allowed(node_text(a), name, "it is a local array"), a
        )
    return None


# ------------------------------------------------------------------------------ programs


class ProgramSignature:
    """A program's parameters with their types resolved in the program's own application."""

    __slots__ = ("params", "program", "s6", "types")

    def __init__(self, program: Program, types: list[vt.VType], s6: bool) -> None:
        self.program = program
        self.params = program.parameters
        self.types = types
        self.s6 = s6  # declared in s6 files: element parameters may be arrays


def signature(
    registry: S.TypeRegistry, owner: Application, program: Program, cache: dict[int, ProgramSignature]
) -> ProgramSignature:
    sig = cache.get(id(program))
    if sig is None:
        sig = ProgramSignature(
            program, [registry.resolve_type(owner, p.type) for p in program.parameters], owner.layout == "s6"
        )
        cache[id(program)] = sig
    return sig


def _param_text(p: Parameter) -> str:
    amp = "&" if p.by_reference or p.container is not Container.ELEMENT else ""
    tail = ""
    if p.container is Container.ARRAY:
        tail = "[" + "," * ((p.dimensions or 1) - 1) + "]"
    elif p.container is Container.COLLECTION:
        tail = '[""]'
    return f"{p.type}{amp} {p.name}{tail}"


def _signature_finding(ctx, code: str, message: str, s7: bool, node: object) -> None:
    """s8 adds overloads to s7 instructions (e.g. logMsg with a second argument on CS9, s8.toml):
    there a call that matches no s7 signature nor a known s8 form is T024, a warning, instead of a
    sure error; so in code saved as s7 that uses s8 forms (Context.settle). So is a call of an
    s8 instruction whose signature does not match what is known."""
    if ctx.strict_version and s7:
        ctx.s7_only(code, message, node, codes.S8_SIGNATURE_UNVERIFIED, M.s8_signature(message))
    else:
        ctx.report_at(codes.S8_SIGNATURE_UNVERIFIED, M.s8_signature(message), node)


def check_program_args(
    typer: ExprTyper, target: object, label: str, sig: ProgramSignature, args: list, vals: list[vt.Val], task: bool
) -> None:
    """Arguments of `call prog(...)` or of the program of taskCreate (2.6, 5.10)."""
    ctx = typer.ctx
    params = sig.params
    if len(args) != len(params):
        sigs = [f"{label[:-2]}({', '.join(_param_text(p) for p in params)})"]
        n = len(params)
        ctx.report_at(
            codes.WRONG_ARGUMENT_COUNT, M.arity(label, f"{n} argument{'s' if n != 1 else ''}", len(args), sigs), target
        )
        return
    s6 = sig.s6
    for i, (p, ptype, v, a) in enumerate(zip(params, sig.types, vals, args)):
        idx = i + 1
        cont = p.container
        by_ref = p.by_reference or cont is not Container.ELEMENT
        if v.dims < 0:
            continue  # an s6 parameter passed on: its container is not known
        if not by_ref:
            if type(a) is A.Struct:
                typer.check_literal(a, ptype)
                continue
            if s6:
                # s6 files may declare an array parameter without container: only the type
                if v.t.known and ptype.known and v.t is not ptype and vt.assignable(ptype, v.t) is False:
                    ctx.report_at(
                        codes.ARGUMENT_TYPE_MISMATCH,
                        M.argument_type(idx, label, p.name, ptype.name, _describe_arg(v)),
                        a,
                    )
                continue
            if v.elem is False:
                ctx.report_at(missing_index_code(v), missing_index_message(a, v), a)
                continue
            if vt.assignable(ptype, v.t) is False:
                ctx.report_at(
                    codes.ARGUMENT_TYPE_MISMATCH, M.argument_type(idx, label, p.name, ptype.name, _describe_arg(v)), a
                )
            continue
        if v is UNKNOWN_VAL:
            continue
        if not v.var:
            word = {Container.ARRAY: "array", Container.COLLECTION: "collection"}.get(cont, "")
            ctx.report_at(codes.REFERENCE_NEEDS_VARIABLE, M.needs_variable(idx, label, p.name, word), a)
            continue
        if not vt.same_type(v.t, ptype):
            ctx.report_at(
                codes.ARGUMENT_TYPE_MISMATCH, M.argument_type(idx, label, p.name, ptype.name + "&", vt.describe(v)), a
            )
            continue
        if cont is Container.ELEMENT:
            if v.elem is False and not s6:  # s6: maybe an array parameter declared by dimensions
                ctx.report_at(missing_index_code(v), missing_index_message(a, v), a)
                continue
        elif cont is Container.ARRAY:
            e = _array_arg(idx, label, p, v, a, dims=p.dimensions or 1, bare_only=False)
            if e is not None:
                ctx.report_at(e.code, e.message, e.node)
                continue
        else:
            if v.c != COLLECTION:
                if v.indexed == FROM_COLLECTION:
                    ctx.report_at(codes.UNEXPECTED_INDEX, M.unexpected_index(idx, label, p.name, "key"), a)
                else:
                    ctx.report_at(
                        codes.CONTAINER_MISMATCH,
                        M.container_mismatch(idx, label, p.name, "collection", vt.describe(v)),
                        a,
                    )
                continue
        if task and v.root is not None and v.root.kind == S.LOCAL:
            ctx.report_at(codes.TASK_REFERENCE_TO_LOCAL, M.task_local_reference(node_text(a), p.name), a)
