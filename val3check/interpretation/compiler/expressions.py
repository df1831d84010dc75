"""Expressions in the generated code (2.5.3, operators of chapters 3, 9, 10).

Each expression compiles to a `Code`: Python source and the VAL 3 type ("num", "point"... a
user type's name, or UNKNOWN when the compiler cannot know it, e.g. a symbol of a library
loaded with another interface: then the operator is chosen at run time, `DYN`).
"""

from __future__ import annotations

import math

from ...loading.types import base_type
from ...parsing import ast
from ...semantics import vtypes as vt
from ..values import (
    ENUM_CONSTANTS,
    ENUM_SPELLING,
    FAMILY_FIELDS,
    FIELD_DEFAULTS,
    OBJECT_TYPES,
    STRUCT_FIELDS,
    STRUCT_ORDER,
    clip_string,
)
from .structures import (
    ENUM_VALUES_TYPES,
    GEOMETRY_TYPES,
    UNKNOWN,
    Code,
    ContainerRef,
    Place,
    TypedCode,
    VarInfo,
)


# The roots of the frame and tool trees, places in the generated code's ROOTS (machine.py).
ROOTS = {"world": "frame", "flange": "tool"}
# Expressions whose type the compiler takes from semantic analysis (see `expr`).
_TYPED_BY_SEMANTICS = frozenset({ast.Name, ast.LibraryName, ast.Index, ast.Field, ast.CallExpr, ast.Unary, ast.Binary,
                                 ast.Number, ast.String, ast.Bool})
_KNOWN_KINDS = frozenset({vt.BUILTIN, vt.ENUM, vt.USER})


class ExpressionCompiler:
    """The expressions part of `ProgramCompiler` (program.py)."""

    def semantic_type(self, node) -> str | None:
        """The type semantic analysis gave `node` (semantics.checker.expression_types), or None
        when it could not tell (an unknown name, the controller's `io:` symbols...)."""
        v = self.types.get(id(node))
        if v is None or v.t.kind not in _KNOWN_KINDS:
            return None
        return v.t.name

    def expr(self, node, want: str | None = None) -> Code:
        """The Python code and VAL 3 type of an rvalue. `want` is the expected type (for
        `{...}`). The type is semantic analysis's when it typed the node; the compiler's own
        for what only the context types (`{...}`), for the value of an `=` inside an
        expression (the value written, not the variable: `n = (si = 5)` reads no sio), and
        for what semantic analysis cannot know."""
        code = self.derive(node, want)
        if type(node) in _TYPED_BY_SEMANTICS:
            t = self.semantic_type(node)
            if t is not None and t != code.t:
                return Code(code.text, t)
        return code

    def derive(self, node, want: str | None = None) -> Code:
        """Code and type of an rvalue, the type as the compiler derives it."""
        tn = type(node)
        if tn is ast.Number:
            if not math.isfinite(node.value):  # F017 in lint; a library is not linted for sim
                raise self.err(f"numeric constant {node.text[:40]} is beyond the range of a num (F017)", node)
            return Code(repr(float(node.value)), "num")
        if tn is ast.String:
            return Code(repr(clip_string(node.value)), "string")  # 3.4.1: at most 128 bytes
        if tn is ast.Bool:
            return Code("True" if node.value else "False", "bool")
        if tn is ast.Name:
            return self.name_expr(node)
        if tn is ast.LibraryName:
            v = self.lib_var(node)
            return Code(self.elem_read(v), v.t)
        if tn is ast.Index:
            p = self.index_pair(node)
            return Code(f"{p.container}[{p.key}]", p.t)
        if tn is ast.Field:
            return self.field_expr(node)
        if tn is ast.CallExpr:
            return self.call_expr(node, want)
        if tn is ast.Unary:
            code, t = self.expr(node.operand)
            if t == "aio":  # an aio read as a num (3.6.2)
                code, t = self.coerce(code, t, "num"), "num"
            if node.op == "-":
                if t not in ("num", UNKNOWN):
                    raise self.err(f"unary - on {t}", node)
                return Code(f"(-{code})", "num")
            if t == "dio":
                return Code(f"(not IOR({code}))", "bool")
            if t in ("bool", UNKNOWN):
                return Code(f"(not {code})", "bool")
            if t == "trsf":
                return Code(f"TINV({code})", "trsf")
            raise self.err(f"operator ! on {t}", node)
        if tn is ast.Binary:
            return self.binary(node)
        if tn is ast.Struct:
            return self.struct(node, want)
        if tn is ast.AssignExpr:
            return self.assign_code(node.target, node.value, as_expr=True)
        if tn is ast.SystemName:
            raise self.err(f"system instruction {node.name} is not simulated", node)
        raise self.err(f"unsupported expression {tn.__name__}", node)

    def name_expr(self, node: ast.Name) -> Code:
        v = self.lookup_var(node.name)
        if v is not None:
            if v.store == "obj" and v.cont == "collection":
                raise self.err(f"collection '{node.name}' used without a key", node)
            return Code(self.elem_read(v), v.t)
        low = node.name.lower()
        if low in ENUM_CONSTANTS:
            return Code(repr(ENUM_SPELLING[low]), ENUM_CONSTANTS[low])
        if low == "world":
            return Code("WORLD", "frame")
        if low == "flange":
            return Code("FLANGE", "tool")
        prog = self._program(node.name)
        if prog is not None:
            raise self.err(f"program '{node.name}' used as a value", node)
        raise self.err(f"unknown name '{node.name}'", node)

    def var_of(self, node) -> VarInfo | None:
        if type(node) is ast.Name:
            return self.lookup_var(node.name)
        if type(node) is ast.LibraryName:
            return self.lib_var(node)
        return None

    def container_of(self, node) -> ContainerRef:
        """The container object for the base of an Index or a container argument: a variable,
        a library variable, or a user-type field."""
        tn = type(node)
        if tn is ast.Name or tn is ast.LibraryName:
            v = self.var_of(node)
            if v is None:
                raise self.err(f"unknown name '{node.name}'", node)
            if v.cont == "element":
                raise self.err(f"'{node.name}' is not an array or a collection", node)
            return ContainerRef(self.cont_code(v), v.t, v.cont, v.ndim, v.space or self.space)
        if tn is ast.Field:
            base = self.value_with_space(node.base)
            f = self.field_type(base.t, node.name, base.space, node)
            if f.cont == "element":
                raise self.err(f"field '{node.name}' is not a container", node)
            return ContainerRef(f"{base.text}[{f.name!r}]", f.t, f.cont, f.ndim, f.space)
        raise self.err("expected a variable", node)

    def value_with_space(self, node) -> TypedCode:
        """rvalue code, type and the TypeSpace resolving the type's name."""
        tn = type(node)
        if tn is ast.Name or tn is ast.LibraryName:
            v = self.var_of(node)
            if v is not None:
                return TypedCode(self.elem_read(v), v.t, v.space or self.space)
        if tn is ast.Index:
            p = self.index_pair(node)
            return TypedCode(f"{p.container}[{p.key}]", p.t, p.space)
        if tn is ast.Field:
            base = self.value_with_space(node.base)
            f = self.field_type(base.t, node.name, base.space, node)
            if base_type(base.t) in OBJECT_TYPES:  # a geometry object: its fields are attributes
                return TypedCode(f"{base.text}.{f.name}", f.t, f.space)
            code = f"{base.text}[{f.name!r}]"
            if f.cont == "array":
                code += ".data[0]"
            elif f.cont == "collection":
                raise self.err(f"collection field '{node.name}' used without a key", node)
            return TypedCode(code, f.t, f.space)
        code, t = self.expr(node)
        return TypedCode(code, t, self.space)

    def index_pair(self, node: ast.Index, write: bool = False) -> Place:
        """The place `base[i...]`. Writing to a collection key that does not exist creates it
        (2.5.3 example); reading it is error 20."""
        c, t, cont, ndim, sp = self.container_of(node.base)
        n = len(node.indices)
        if cont == "collection":
            if n != 1:
                raise self.err("a collection takes one key", node)
            key = self.expr(node.indices[0]).text
            return Place(f"{c}.d", f"{'CKW(A, ' if write else 'CK('}{c}, {key})", t, sp)
        idx = [self.num(i) for i in node.indices]
        if n == 1:
            if type(node.base) is ast.Name:
                v = self.lookup_var(node.base.name)
                if v is not None and v.store == "g" and v.ndim == 1:
                    return Place(f"d_{v.name}", f"IX({idx[0]}, len(d_{v.name}))", t, sp)
            return Place(f"{c}.data", f"AI1({c}, {idx[0]})", t, sp)
        if n == 2:
            return Place(f"{c}.data", f"AI2({c}, {idx[0]}, {idx[1]})", t, sp)
        if n == 3:
            return Place(f"{c}.data", f"AI3({c}, {idx[0]}, {idx[1]}, {idx[2]})", t, sp)
        raise self.err("too many indices", node)

    def field_expr(self, node: ast.Field) -> Code:
        v = self.value_with_space(node)
        return Code(v.text, v.t)

    def lvalue(self, node) -> Place:
        """An assignable place; its container is None for the Python local `key`."""
        tn = type(node)
        if tn is ast.Name:
            v = self.lookup_var(node.name)
            if v is None:
                low = node.name.lower()
                if low in ROOTS:  # world and flange (9.4.1, 9.5.1) passed by reference
                    return Place("ROOTS", repr(low), ROOTS[low], self.space)
                raise self.err(f"unknown variable '{node.name}'", node)
            if v.store == "py":
                return Place(None, f"v_{v.name}", v.t, v.space or self.space)
            c, k = self.elem_pair(v)
            return Place(c, k, v.t, v.space or self.space)
        if tn is ast.LibraryName:
            v = self.lib_var(node)
            c, k = self.elem_pair(v)
            return Place(c, k, v.t, v.space or self.space)
        if tn is ast.Index:
            return self.index_pair(node, write=True)
        if tn is ast.Field:
            base = self.value_with_space(node.base)
            f = self.field_type(base.t, node.name, base.space, node)
            if f.cont == "array":
                return Place(f"{base.text}[{f.name!r}].data", "0", f.t, f.space)
            if f.cont == "collection":
                raise self.err(f"collection field '{node.name}' used without a key", node)
            return Place(base.text, repr(f.name), f.t, f.space)
        raise self.err("expected a variable", node)

    def ref_arg(self, node) -> str:
        """A by-reference element argument (2.6.2): code of a (container, key) pair."""
        p = self.lvalue(node)
        if p.container is None:
            raise self.err("internal: local not boxed", node)
        return f"({p.container}, {p.key})"

    def coerce(self, code: str, have: str, want: str | None) -> str:
        if want == "bool" and have == "dio":
            return f"IOR({code})"
        if want == "num" and have == "aio":  # an aio read as a num, as lint accepts it (3.6.2 aioGet)
            return f"I_aioget(T, A, {code})"
        if want in ("num", "string") and have == "sio":
            return f"(yield from SIOR(T, {code}, {want!r}))"
        return code

    def num(self, node) -> str:
        """Code of an expression where a num is needed (an aio or a sio is read)."""
        return self.coerce(*self.expr(node), "num")

    def cond(self, node) -> str:
        code, t = self.expr(node)
        if t == "dio":
            return f"IOR({code})"
        return code

    def binary(self, node: ast.Binary) -> Code:
        op = node.op
        if op in ("and", "or"):
            lc, lt = self.expr(node.left)
            rc, rt = self.expr(node.right)
            return Code(f"({self.coerce(lc, lt, 'bool')} {op} {self.coerce(rc, rt, 'bool')})", "bool")
        if type(node.left) is ast.Struct:
            rc, rt = self.expr(node.right)
            lc, lt = self.expr(node.left, want=rt)
        else:
            lc, lt = self.expr(node.left)
            rc, rt = self.expr(node.right, want=lt if lt != UNKNOWN else None)
        if lt == "aio":  # an aio read as a num (3.6.2), as lint accepts it
            lc, lt = self.coerce(lc, lt, "num"), "num"
        if rt == "aio":
            rc, rt = self.coerce(rc, rt, "num"), "num"
        if op == "xor":
            return Code(f"({self.coerce(lc, lt, 'bool')} != {self.coerce(rc, rt, 'bool')})", "bool")
        if lt == "dio" or rt == "dio":
            if op in ("==", "!="):
                lc2 = f"IOR({lc})" if lt == "dio" else lc
                rc2 = f"IOR({rc})" if rt == "dio" else rc
                return Code(f"({lc2} {op} {rc2})", "bool")
            raise self.err(f"operator {op} on dio", node)
        if lt == "num" and rt == "num":
            if op in ("+", "-", "*", "/"):
                return Code(f"({lc} {op} {rc})", "num")
            if op == "%":
                return Code(f"MOD({lc}, {rc})", "num")
            return Code(f"({lc} {op} {rc})", "bool")
        if lt == "string" and rt == "string":
            if op == "+":
                return Code(f"CAT({lc}, {rc})", "string")
            if op in ("==", "!="):
                return Code(f"({lc} {op} {rc})", "bool")
        if lt == "bool" and rt == "bool" and op in ("==", "!="):
            return Code(f"({lc} {op} {rc})", "bool")
        if lt == rt and lt in ENUM_VALUES_TYPES and op in ("==", "!="):
            return Code(f"({lc} {op} {rc})", "bool")
        if lt == rt == "joint":  # 9.2.2
            fn = {"+": "JADD", "-": "JSUB", ">": "JGT", "<": "JLT", "==": "JEQ", "!=": "JNE"}.get(op)
            if fn is not None:
                return Code(f"{fn}({lc}, {rc})", "joint" if op in ("+", "-") else "bool")
        if lt == rt and lt in ("config", "mdesc") and op in ("==", "!="):
            return Code(f"({lc} {op} {rc})", "bool")
        if lt == rt and lt in OBJECT_TYPES and op in ("==", "!="):  # 9.3.3, 9.4.3, 9.5.3, 9.6.2
            return Code(f"({lc} {op} {rc})", "bool")
        if lt == rt == "trsf" and op == "*":  # 9.3.3: geometric composition
            return Code(f"({lc} * {rc})", "trsf")
        if UNKNOWN in (lt, rt):
            res = "bool" if op in ("==", "!=", "<", ">", "<=", ">=") else (lt if lt != UNKNOWN else rt)
            return Code(f"DYN({op!r}, {lc}, {rc})", res)
        if lt in GEOMETRY_TYPES or rt in GEOMETRY_TYPES:
            raise self.err(f"operator {op} between {lt} and {rt}", node)
        raise self.err(f"operator {op} between {lt} and {rt}", node)

    def struct(self, node: ast.Struct, want: str | None) -> Code:
        if want is None or want == UNKNOWN:
            raise self.err("structured value {...} whose type cannot be determined", node)
        b = base_type(want)
        if b == "frame":  # {x,y,z,rx,ry,rz} for a frame means its trsf
            inner, _ = self.struct(node, "trsf") if not (node.fields and type(node.fields[0]) is ast.Struct) else self.struct(node.fields[0], "trsf")
            return Code(f"FRAMELIT({inner})", "frame")
        order = STRUCT_ORDER.get(b)
        if order is None:
            raise self.err(f"structured value {{...}} for type {want}", node)
        if len(node.fields) > len(order):
            raise self.err(f"too many fields for {b}", node)
        if b in ("joint", "config"):
            # one field per axis of the arm of the run, the shoulder only on RS/TS arms (9.7.2);
            # a literal written with more keeps them (then error 81 where the arm uses it)
            own = FAMILY_FIELDS[getattr(self.unit.machine.cell, "arm_family", "Rx")][b]
            order = order[:max(len(own), len(node.fields))]
        parts = []
        codes = []
        defaults = FIELD_DEFAULTS[b]
        for i, name in enumerate(order):
            ft = STRUCT_FIELDS[b][name]
            f = node.fields[i] if i < len(node.fields) else None
            if f is None:
                if ft == "num":
                    code = "0.0"  # 2.4.2: empty fields are 0
                elif ft in STRUCT_FIELDS:
                    code = f"DEFAULT({ft!r})"
                elif ft == "dio":
                    code = f"IODEF({defaults[name]!r})"  # 9.5.1: valve1
                else:
                    code = repr(defaults.get(name, ""))  # an enum field: its default value
            else:
                code, t = self.expr(f, want=ft)
                if ft != "num" and ft not in STRUCT_FIELDS and t in ("num",):
                    raise self.err(f"field {name} of {b} expects {ft}", f)
                code = self.coerce(code, t, ft)
            parts.append(f"{name!r}: {code}")
            codes.append(code)
        if b in OBJECT_TYPES:  # geometry objects (values.py): TRSF(x, ...), POINTLIT(trsf, config)...
            ctor = {"trsf": "TRSF", "point": "POINTLIT", "tool": "TOOLLIT"}[b]
            return Code(f"{ctor}({', '.join(codes)})", b)
        return Code("{" + ", ".join(parts) + "}", b)
