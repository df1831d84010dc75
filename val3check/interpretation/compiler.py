"""Compile a VAL 3 program into a Python generator function, once, before the run.

Walking the syntax tree at every evaluation would be far too slow (the goal is 200,000 VAL 3
lines per second), so each program becomes Python source, compiled with `compile()`:

- VAL 3 locals and by-value parameters are Python locals (`v_name`); a local whose address is
  taken (passed by reference, 2.6.2) lives in a list `L` so that a callee can write it;
  a by-reference element parameter is a (container, key) pair `c_name`/`k_name`; array and
  collection parameters are `Arr`/`Coll` objects (2.6.3); globals are bound in the module
  namespace (`g_name` container, `d_name` its list of values);
- every VAL 3 line starts with the scheduler's line count (`T.q`, 5.4: as many lines per turn as
  the priority) and hands over with `yield` when the turn is used up;
- blocking instructions (`wait`, `delay`, `watch`, `get`, sio reads, ... 5.4) are `yield from`
  helpers, usable in the middle of an expression, so a task can block anywhere;
- each line is wrapped in a retry loop: a runtime error stops the task at that line (12.1,
  5.2) and `taskResume(name, 0)` runs the line again, `taskResume(name, 1)` skips it.

The Python line numbers of the generated code map back to VAL 3 file positions (`Compiled.pos`)
for runtime diagnostics and for reporting where a blocked task waits.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

from ..language import lookup
from ..loading.model import Application, Container, Program
from ..loading.types import base_type
from ..parsing import ast as A
from .builtins_bridge import builtin
from .memory import TypeSpace
from .values import (
    ENUM_CONSTANTS,
    ENUM_SPELLING,
    STRUCT_FIELDS,
    STRUCT_ORDER,
    clip_string,
)

# Instructions that move the arm or need more of it than its kinematics (chapters 9-11): they
# stop the task with R002 (motion is the next issue). Chapter 9 itself is in geom.py; movej
# is there too (it reports targets out of reach, then stops with R002).
ARM_INSTRUCTIONS = frozenset(n.lower() for n in (
    "setLatch getLatch movel movec stopMove resetMotion restartMove "
    "waitEndMove isEmpty isSettled autoConnectMove getSpeed getPositionErr getJointForce getMoveId setMoveId "
    "movejf movelf isCompliant alterMovej alterMovel alterMovec alterBegin alterEnd alter alterStopTime getDH "
    "getDefaultDH setDH resetTurn"
).split())
GEOMETRY_TYPES = frozenset({"trsf", "frame", "tool", "point", "joint"})
# values that are geometry objects (fields read as attributes, values.py) / nodes (`=` copies into)
OBJECT_TYPES = frozenset({"trsf", "frame", "tool", "point"})
NODE_TYPES = frozenset({"frame", "tool", "point"})

# Functions whose value changes with time alone: a wait on them cannot be skipped over by
# jumping to the next event (the clock is stepped instead).
TIME_DEPENDENT = frozenset({"clock", "getdate", "watch"})


class CompileError(Exception):
    """The program uses something the simulator cannot run (reported as R004 at run time)."""

    def __init__(self, message: str, line: int, col: int) -> None:
        super().__init__(message)
        self.line, self.col = line, col


@dataclass
class VarInfo:
    name: str
    t: str  # base type ("num", "point"...) or a user type name
    cont: str  # "element" | "array" | "collection"
    ndim: int = 1
    store: str = "py"  # py | box | ref | obj | g | lib
    slot: int = 0  # index in L for "box"
    alias: str = ""  # for "lib"
    space: TypeSpace | None = None  # where the type's name is resolved


@dataclass
class Compiled:
    """One program, ready to run."""

    name: str
    func: Any  # generator function (T, *args)
    params: list  # model Parameters
    pos: dict[int, tuple[int, int]]  # python line -> (file line, col)
    path: str
    filename: str
    frame_bytes: int
    source: str = ""
    error: CompileError | None = None
    # python line -> (sequence, index, length) of the VAL 3 instruction (taskResume jumps)
    bpos: dict = field(default_factory=dict)


# Estimated execution memory (2.1.4.2: 5000 bytes per task by default). The manual gives no
# sizes; these are ours, documented in docs/sim.md.
CALL_BYTES = 48
_SIZES = {"num": 8, "bool": 8, "string": 128, "dio": 8, "aio": 8, "sio": 8, "screen": 2048, "trsf": 48,
          "frame": 56, "tool": 80, "point": 80, "joint": 48, "config": 24, "mdesc": 64}


def value_bytes(t: str, space: TypeSpace | None, depth: int = 0) -> int:
    b = base_type(t)
    if b in _SIZES:
        return _SIZES[b]
    if space is None or depth > 8:
        return 64
    fields = space.field_info(t)
    if not fields:
        return 64
    total = 0
    ut = space.user_type(t)
    sp = space.space_of(ut.app) if ut else space
    for d in fields.values():
        n = 1
        for s in d.sizes or (1,):
            n *= max(1, int(s))
        total += n * value_bytes(d.type, sp, depth + 1)
    return total


def _lower_map(names) -> dict[str, str]:
    return {n.lower(): n for n in names}


class ProgramCompiler:
    def __init__(self, unit, program: Program, max_level: int = 1000) -> None:
        self.unit = unit  # runtime.Unit
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

    # ---- variables ----------------------------------------------------------------------------

    def _boxed_names(self, body: A.ProgramBody) -> set[str]:
        """Locals whose address is taken: passed where a reference is expected. Locals passed
        where an array is expected are collected in `self.arrayed`."""
        boxed: set[str] = set()
        self.arrayed = arrayed = set()
        for node in A.walk(body):
            args = None
            ref_flags: list[bool] = []
            if isinstance(node, (A.Call, A.TaskCreate, A.TaskCreateSync)):
                args = node.args
                callee = self._callee_params(node.target)
                ref_flags = [bool(p.by_reference) for p in callee] if callee is not None else [True] * len(args)
                if callee is not None:
                    arrayed.update(a.name for a, p in zip(args, callee)
                                   if isinstance(a, A.Name) and p.container is not Container.ELEMENT)
                if isinstance(node, A.TaskCreateSync) and isinstance(node.overrun, A.Name):
                    boxed.add(node.overrun.name)
            elif isinstance(node, A.CallExpr) and isinstance(node.func, A.Name):
                args = node.args
                ins = lookup(node.func.name)
                if ins is not None:
                    ov = [o for o in ins.overloads if o.accepts_arity(len(args))]
                    ref_flags = [any(i < len(o.params) and (o.params[i].ref or o.params[i].variable) for o in ov)
                                 for i in range(len(args))]
                    arrayed.update(a.name for i, a in enumerate(args) if isinstance(a, A.Name) and any(
                        i < len(o.params) and o.params[i].container == "array" for o in ov))
            elif isinstance(node, (A.For,)):
                continue
            if args:
                for a, ref in zip(args, ref_flags):
                    if ref and isinstance(a, A.Name):
                        boxed.add(a.name)
        return boxed

    def _callee_params(self, target) -> list | None:
        if isinstance(target, A.Name):
            prog = self._program(target.name)
            return prog.parameters if prog else None
        if isinstance(target, A.LibraryName):
            lib = self._lib_model(target.alias)
            if lib is None:
                return None
            prog = lib.programs.get(target.name)
            return prog.parameters if prog else None
        return None

    def _program(self, name: str) -> Program | None:
        p = self.app.programs.get(name)
        if p is None:
            low = name.lower()
            p = next((q for n, q in self.app.programs.items() if n.lower() == low), None)
        return p

    def _lib_model(self, alias: str) -> Application | None:
        return self.unit.machine.library_model(self.app, alias)

    def setup_vars(self) -> None:
        prog = self.program
        boxed = self._boxed_names(prog.body) if prog.body else set()
        indexed = {n.base.name for n in A.walk(prog.body) if isinstance(n, A.Index) and isinstance(n.base, A.Name)} if prog.body else set()
        indexed |= self.arrayed
        slot = 0
        for p in prog.parameters:
            t = base_type(p.type)
            if p.container is Container.ELEMENT:
                if p.by_reference:
                    self.vars[p.name] = VarInfo(p.name, t, "element", store="ref", space=self.space)
                elif p.name in boxed or p.name in self.arrayed:  # arrayed: passed on as a 1-value array
                    self.vars[p.name] = VarInfo(p.name, t, "element", store="box", slot=slot, space=self.space)
                    slot += 1
                else:
                    self.vars[p.name] = VarInfo(p.name, t, "element", store="py", space=self.space)
            else:
                cont = "collection" if p.container is Container.COLLECTION else "array"
                self.vars[p.name] = VarInfo(p.name, t, cont, ndim=p.dimensions or 1, store="obj", space=self.space)
        for loc in prog.locals:
            t = base_type(loc.type)
            if loc.container is Container.COLLECTION:
                self.vars[loc.name] = VarInfo(loc.name, t, "collection", store="obj", space=self.space)
            elif tuple(loc.sizes or (1,)) != (1,) or loc.name in indexed:
                self.vars[loc.name] = VarInfo(loc.name, t, "array", ndim=len(loc.sizes or (1,)), store="obj",
                                              space=self.space)
            elif loc.name in boxed:
                self.vars[loc.name] = VarInfo(loc.name, t, "element", store="box", slot=slot, space=self.space)
                slot += 1
            else:
                self.vars[loc.name] = VarInfo(loc.name, t, "element", store="py", space=self.space)
        self.nbox = slot

    def frame_bytes(self) -> int:
        total = CALL_BYTES
        for p in self.program.parameters:
            if p.by_reference or p.container is not Container.ELEMENT:
                total += 8
            else:
                total += value_bytes(p.type, self.space)
        for loc in self.program.locals:
            n = 1
            for s in loc.sizes or (1,):
                n *= max(1, int(s))
            total += n * value_bytes(loc.type, self.space)
        return total

    def lookup_var(self, name: str) -> VarInfo | None:
        v = self.vars.get(name)
        if v is not None:
            return v
        d = self.app.data.get(name)
        if d is None:
            return None
        t = base_type(d.type)
        if d.container is Container.COLLECTION:
            return VarInfo(name, t, "collection", store="g", space=self.space)
        dims = d.sizes or (1,)
        return VarInfo(name, t, "array", ndim=len(dims), store="g", space=self.space)

    def lib_var(self, node: A.LibraryName) -> VarInfo:
        lib = self._lib_model(node.alias)
        d = lib.data.get(node.name) if lib is not None else None
        sysio = self.unit.aliases.get(node.alias) if lib is None else None
        if sysio is not None and sysio is self.unit.machine.system_io:  # the controller's io: library
            return VarInfo(node.name, sysio.kind_of(node.name), "array", store="lib", alias=node.alias,
                           space=self.space)
        if d is None:
            # unknown at compile time: the library may be loaded with another interface (6.3)
            return VarInfo(node.name, "?", "array", store="lib", alias=node.alias, space=self.space)
        sp = self.space.space_of(lib)
        t = base_type(d.type)
        cont = "collection" if d.container is Container.COLLECTION else "array"
        return VarInfo(node.name, t, cont, ndim=len(d.sizes or (1,)), store="lib", alias=node.alias, space=sp)

    # ---- variable access code -----------------------------------------------------------------

    def cont_code(self, v: VarInfo) -> str:
        """Code of the container object (Arr/Coll) of an array/collection variable."""
        if v.store == "g":
            return f"g_{v.name}"
        if v.store == "obj":
            return f"v_{v.name}"
        if v.store == "lib":
            return f"LG(A, {v.alias!r}, {v.name!r})"
        raise self.err(f"'{v.name}' is not an array or a collection")

    def elem_pair(self, v: VarInfo) -> tuple[str, str]:
        """(container, key) code of the element named by a variable without index."""
        if v.store == "box":
            return "L", str(v.slot)
        if v.store == "ref":
            return f"c_{v.name}", f"k_{v.name}"
        if v.store == "g":
            if v.cont == "collection":
                raise self.err(f"collection '{v.name}' used without a key")
            return f"d_{v.name}", "0"
        if v.store == "obj":
            if v.cont == "collection":
                raise self.err(f"collection '{v.name}' used without a key")
            return f"v_{v.name}.data", f"v_{v.name}.off"
        if v.store == "lib":
            return f"LG(A, {v.alias!r}, {v.name!r}).data", "0"
        raise self.err(f"cannot take the address of '{v.name}'")

    def elem_read(self, v: VarInfo) -> str:
        if v.store == "py":
            return f"v_{v.name}"
        if v.store == "g" and v.cont == "array":
            return f"d_{v.name}[0]"
        c, k = self.elem_pair(v)
        return f"{c}[{k}]"

    # ---- types of expressions -----------------------------------------------------------------

    def field_type(self, t: str, name: str, space: TypeSpace, node) -> tuple[str, str, TypeSpace, int]:
        """(type, container, space, ndim) of field `name` of a value of type `t`."""
        b = base_type(t)
        if b in STRUCT_FIELDS:
            ft = STRUCT_FIELDS[b].get(name)
            if ft is None and b == "mdesc" and name in ("tmax", "rmax"):
                ft = "num"
            if ft is None and b == "joint" and name[:1] == "j" and name[1:].isdigit():
                ft = "num"
            if ft is None:
                raise self.err(f"type {b} has no field '{name}'", node)
            return ft, "element", space, 1
        fields = space.field_info(t)
        if fields is None:
            raise self.err(f"unknown type '{t}' for field '{name}'", node)
        d = fields.get(name)
        if d is None:
            raise self.err(f"user type '{t}' has no public field '{name}'", node)
        ut = space.user_type(t)
        sp = space.space_of(ut.app)
        cont = "collection" if d.container is Container.COLLECTION else "array"
        return base_type(d.type), cont, sp, len(d.sizes or (1,))

    # ---- expressions --------------------------------------------------------------------------

    def expr(self, node, want: str | None = None) -> tuple[str, str]:
        """(python code, VAL 3 type) of an rvalue. `want` is the expected type (for `{...}`)."""
        tn = type(node)
        if tn is A.Number:
            if not math.isfinite(node.value):  # F017 in lint; a library is not linted for sim
                raise self.err(f"numeric constant {node.text[:40]} is beyond the range of a num (F017)", node)
            return repr(float(node.value)), "num"
        if tn is A.String:
            return repr(clip_string(node.value)), "string"  # 3.4.1: at most 128 bytes
        if tn is A.Bool:
            return ("True" if node.value else "False"), "bool"
        if tn is A.Name:
            return self.name_expr(node)
        if tn is A.LibraryName:
            v = self.lib_var(node)
            return self.elem_read(v), v.t
        if tn is A.Index:
            c, k, t, _ = self.index_pair(node)
            return f"{c}[{k}]", t
        if tn is A.Field:
            return self.field_expr(node)
        if tn is A.CallExpr:
            return self.call_expr(node)
        if tn is A.Unary:
            code, t = self.expr(node.operand)
            if node.op == "-":
                if t not in ("num", "?"):
                    raise self.err(f"unary - on {t}", node)
                return f"(-{code})", "num"
            if t == "dio":
                return f"(not IOR({code}))", "bool"
            if t in ("bool", "?"):
                return f"(not {code})", "bool"
            if t == "trsf":
                return f"TINV({code})", "trsf"
            raise self.err(f"operator ! on {t}", node)
        if tn is A.Binary:
            return self.binary(node)
        if tn is A.Struct:
            return self.struct(node, want)
        if tn is A.AssignExpr:
            code, t = self.assign_code(node.target, node.value, as_expr=True)
            return code, t
        if tn is A.SystemName:
            raise self.err(f"system instruction {node.name} is not simulated", node)
        raise self.err(f"unsupported expression {tn.__name__}", node)

    def name_expr(self, node: A.Name) -> tuple[str, str]:
        v = self.lookup_var(node.name)
        if v is not None:
            if v.cont != "element" and v.store in ("obj",) and v.cont == "collection":
                raise self.err(f"collection '{node.name}' used without a key", node)
            return self.elem_read(v), v.t
        low = node.name.lower()
        if low in ENUM_CONSTANTS:
            return repr(ENUM_SPELLING[low]), ENUM_CONSTANTS[low]
        if low == "world":
            return "WORLD", "frame"
        if low == "flange":
            return "FLANGE", "tool"
        prog = self._program(node.name)
        if prog is not None:
            raise self.err(f"program '{node.name}' used as a value", node)
        raise self.err(f"unknown name '{node.name}'", node)

    def var_of(self, node) -> VarInfo | None:
        if type(node) is A.Name:
            return self.lookup_var(node.name)
        if type(node) is A.LibraryName:
            return self.lib_var(node)
        return None

    def container_of(self, node) -> tuple[str, str, str, int, TypeSpace]:
        """(container code, type, cont kind, ndim, space) for the base of an Index or a
        container argument: a variable, a library variable, or a user-type field."""
        tn = type(node)
        if tn is A.Name or tn is A.LibraryName:
            v = self.var_of(node)
            if v is None:
                raise self.err(f"unknown name '{node.name}'", node)
            if v.cont == "element":
                raise self.err(f"'{node.name}' is not an array or a collection", node)
            return self.cont_code(v), v.t, v.cont, v.ndim, v.space or self.space
        if tn is A.Field:
            bcode, bt, bsp = self.value_with_space(node.base)
            ft, cont, sp, ndim = self.field_type(bt, node.name, bsp, node)
            if cont == "element":
                raise self.err(f"field '{node.name}' is not a container", node)
            return f"{bcode}[{node.name!r}]", ft, cont, ndim, sp
        raise self.err("expected a variable", node)

    def value_with_space(self, node) -> tuple[str, str, TypeSpace]:
        """rvalue code, type and the TypeSpace resolving the type's name."""
        tn = type(node)
        if tn is A.Name or tn is A.LibraryName:
            v = self.var_of(node)
            if v is not None:
                return self.elem_read(v), v.t, v.space or self.space
        if tn is A.Index:
            c, k, t, sp = self.index_pair(node)
            return f"{c}[{k}]", t, sp
        if tn is A.Field:
            bcode, bt, bsp = self.value_with_space(node.base)
            ft, cont, sp, _ = self.field_type(bt, node.name, bsp, node)
            if base_type(bt) in OBJECT_TYPES:  # a geometry object: its fields are attributes
                return f"{bcode}.{node.name}", ft, sp
            code = f"{bcode}[{node.name!r}]"
            if cont == "array":
                code += ".data[0]"
            elif cont == "collection":
                raise self.err(f"collection field '{node.name}' used without a key", node)
            return code, ft, sp
        code, t = self.expr(node)
        return code, t, self.space

    def index_pair(self, node: A.Index, write: bool = False) -> tuple[str, str, str, TypeSpace]:
        """(container code, key code, type, space) for `base[i...]`. Writing to a collection
        key that does not exist creates it (2.5.3 example); reading it is error 20."""
        c, t, cont, ndim, sp = self.container_of(node.base)
        n = len(node.indices)
        if cont == "collection":
            if n != 1:
                raise self.err("a collection takes one key", node)
            key, kt = self.expr(node.indices[0])
            return f"{c}.d", f"{'CKW(A, ' if write else 'CK('}{c}, {key})", t, sp
        idx = [self.expr(i)[0] for i in node.indices]
        if n == 1:
            if type(node.base) is A.Name:
                v = self.lookup_var(node.base.name)
                if v is not None and v.store == "g" and v.ndim == 1:
                    return f"d_{v.name}", f"IX({idx[0]}, len(d_{v.name}))", t, sp
            return f"{c}.data", f"AI1({c}, {idx[0]})", t, sp
        if n == 2:
            return f"{c}.data", f"AI2({c}, {idx[0]}, {idx[1]})", t, sp
        if n == 3:
            return f"{c}.data", f"AI3({c}, {idx[0]}, {idx[1]}, {idx[2]})", t, sp
        raise self.err("too many indices", node)

    def field_expr(self, node: A.Field) -> tuple[str, str]:
        code, t, _ = self.value_with_space(node)
        return code, t

    def lvalue(self, node) -> tuple[str | None, str, str, TypeSpace]:
        """(container, key, type, space) of an assignable place; container None means the
        Python local `key`."""
        tn = type(node)
        if tn is A.Name:
            v = self.lookup_var(node.name)
            if v is None:
                raise self.err(f"unknown variable '{node.name}'", node)
            if v.store == "py":
                return None, f"v_{v.name}", v.t, v.space or self.space
            c, k = self.elem_pair(v)
            return c, k, v.t, v.space or self.space
        if tn is A.LibraryName:
            v = self.lib_var(node)
            c, k = self.elem_pair(v)
            return c, k, v.t, v.space or self.space
        if tn is A.Index:
            c, k, t, sp = self.index_pair(node, write=True)
            return c, k, t, sp
        if tn is A.Field:
            bcode, bt, bsp = self.value_with_space(node.base)
            ft, cont, sp, _ = self.field_type(bt, node.name, bsp, node)
            if cont == "array":
                return f"{bcode}[{node.name!r}].data", "0", ft, sp
            if cont == "collection":
                raise self.err(f"collection field '{node.name}' used without a key", node)
            return bcode, repr(node.name), ft, sp
        raise self.err("expected a variable", node)

    def ref_arg(self, node) -> str:
        """A by-reference element argument (2.6.2): code of a (container, key) pair."""
        c, k, _, _ = self.lvalue(node)
        if c is None:
            raise self.err("internal: local not boxed", node)
        return f"({c}, {k})"

    def coerce(self, code: str, have: str, want: str | None) -> str:
        if want == "bool" and have == "dio":
            return f"IOR({code})"
        if want == "num" and have == "aio":  # an aio read as a num, as lint accepts it (3.6.2 aioGet)
            return f"I_aioget(T, A, {code})"
        if want in ("num", "string") and have == "sio":
            return f"(yield from SIOR(T, {code}, {want!r}))"
        return code

    def cond(self, node) -> str:
        code, t = self.expr(node)
        if t == "dio":
            return f"IOR({code})"
        return code

    def binary(self, node: A.Binary) -> tuple[str, str]:
        op = node.op
        if op in ("and", "or"):
            lc, lt = self.expr(node.left)
            rc, rt = self.expr(node.right)
            return f"({self.coerce(lc, lt, 'bool')} {op} {self.coerce(rc, rt, 'bool')})", "bool"
        if type(node.left) is A.Struct:
            rc, rt = self.expr(node.right)
            lc, lt = self.expr(node.left, want=rt)
        else:
            lc, lt = self.expr(node.left)
            rc, rt = self.expr(node.right, want=lt if lt != "?" else None)
        if op == "xor":
            return f"({self.coerce(lc, lt, 'bool')} != {self.coerce(rc, rt, 'bool')})", "bool"
        if lt == "dio" or rt == "dio":
            if op in ("==", "!="):
                lc2 = f"IOR({lc})" if lt == "dio" else lc
                rc2 = f"IOR({rc})" if rt == "dio" else rc
                return f"({lc2} {op} {rc2})", "bool"
            raise self.err(f"operator {op} on dio", node)
        if lt == "num" and rt == "num":
            if op in ("+", "-", "*", "/"):
                return f"({lc} {op} {rc})", "num"
            if op == "%":
                return f"MOD({lc}, {rc})", "num"
            return f"({lc} {op} {rc})", "bool"
        if lt == "string" and rt == "string":
            if op == "+":
                return f"CAT({lc}, {rc})", "string"
            if op in ("==", "!="):
                return f"({lc} {op} {rc})", "bool"
        if lt == "bool" and rt == "bool" and op in ("==", "!="):
            return f"({lc} {op} {rc})", "bool"
        if lt == rt and lt in ENUM_VALUES_TYPES and op in ("==", "!="):
            return f"({lc} {op} {rc})", "bool"
        if lt == rt == "joint":  # 9.2.2
            fn = {"+": "JADD", "-": "JSUB", ">": "JGT", "<": "JLT", "==": "JEQ", "!=": "JNE"}.get(op)
            if fn is not None:
                return f"{fn}({lc}, {rc})", "joint" if op in ("+", "-") else "bool"
        if lt == rt and lt in ("config", "mdesc") and op in ("==", "!="):
            return f"({lc} {op} {rc})", "bool"
        if lt == rt and lt in OBJECT_TYPES and op in ("==", "!="):  # 9.3.3, 9.4.3, 9.5.3, 9.6.2
            return f"({lc} {op} {rc})", "bool"
        if lt == rt == "trsf" and op == "*":  # 9.3.3: geometric composition
            return f"({lc} * {rc})", "trsf"
        if "?" in (lt, rt):
            res = "bool" if op in ("==", "!=", "<", ">", "<=", ">=") else (lt if lt != "?" else rt)
            return f"DYN({op!r}, {lc}, {rc})", res
        if lt in GEOMETRY_TYPES or rt in GEOMETRY_TYPES:
            raise self.err(f"operator {op} between {lt} and {rt}", node)
        raise self.err(f"operator {op} between {lt} and {rt}", node)

    def struct(self, node: A.Struct, want: str | None) -> tuple[str, str]:
        if want is None or want == "?":
            raise self.err("structured value {...} whose type cannot be determined", node)
        b = base_type(want)
        if b == "frame":  # {x,y,z,rx,ry,rz} for a frame means its trsf
            inner, _ = self.struct(node, "trsf") if not (node.fields and type(node.fields[0]) is A.Struct) else self.struct(node.fields[0], "trsf")
            return f"FRAMELIT({inner})", "frame"
        order = STRUCT_ORDER.get(b)
        if order is None:
            raise self.err(f"structured value {{...}} for type {want}", node)
        if len(node.fields) > len(order):
            raise self.err(f"too many fields for {b}", node)
        parts = []
        codes = []
        defaults = {"config": {"shoulder": "ssame", "elbow": "esame", "wrist": "wsame"}}.get(b, {})
        for i, name in enumerate(order):
            ft = STRUCT_FIELDS[b][name]
            f = node.fields[i] if i < len(node.fields) else None
            if f is None:
                if ft == "num":
                    code = "0.0"  # 2.4.2: empty fields are 0
                elif ft in STRUCT_FIELDS:
                    code = f"DEFAULT({ft!r})"
                elif ft == "dio":
                    code = "IODEF('valve1')"
                else:
                    code = repr(defaults.get(name, {"blend": "joint"}.get(name, "")))
            else:
                code, t = self.expr(f, want=ft)
                if ft != "num" and ft not in STRUCT_FIELDS and t in ("num",):
                    raise self.err(f"field {name} of {b} expects {ft}", f)
                code = self.coerce(code, t, ft)
            parts.append(f"{name!r}: {code}")
            codes.append(code)
        if b in OBJECT_TYPES:  # geometry objects (values.py): TRSF(x, ...), POINTLIT(trsf, config)...
            ctor = {"trsf": "TRSF", "point": "POINTLIT", "tool": "TOOLLIT"}[b]
            return f"{ctor}({', '.join(codes)})", b
        return "{" + ", ".join(parts) + "}", b

    # ---- calls --------------------------------------------------------------------------------

    def call_expr(self, node: A.CallExpr) -> tuple[str, str]:
        func = node.func
        if type(func) is A.SystemName:
            return f"NOTSIM({func.name!r})", "?"
        if type(func) is A.LibraryName:
            return self.lib_instruction(node)
        name = func.name
        low = name.lower()
        if low in ARM_INSTRUCTIONS:
            args = [self._arm_arg(a) for a in node.args]
            return f"ARM({name!r}, {', '.join(args)})" if args else f"ARM({name!r})", self._ret_type(name, node.args)
        handler = getattr(self, f"i_{low}", None)
        if handler is not None:
            return handler(node)
        from . import instructions as I

        if low == "abs" and node.args and self._arg_type(node.args[0]) == "joint":
            return f"JABS({self.expr(node.args[0])[0]})", "joint"
        if low in I.ASYNC or low in I.SYNC:
            return self.generic_instruction(node, low)
        if builtin(low) is not None:
            return self.builtin_call(node, low)
        ins = lookup(name)
        if ins is not None:
            return f"NOTSIM({ins.name!r})", self._ret_type(name, node.args)
        raise self.err(f"unknown instruction '{name}'", node)

    def _arm_arg(self, a) -> str:
        return "None"  # arm instructions are not evaluated (their arguments could block)

    def _ret_type(self, name: str, args) -> str:
        ins = lookup(name)
        if ins is None:
            return "?"
        ovs = ins.overloads_with_arity(len(args)) or list(ins.overloads)
        rets = {o.returns for o in ovs}
        return rets.pop() if len(rets) == 1 else "?"

    def _overload(self, name: str, node):
        ins = lookup(name)
        ovs = ins.overloads_with_arity(len(node.args)) if ins else []
        if not ovs:
            raise self.err(f"{name}: no form takes {len(node.args)} argument(s)", node)
        if len(ovs) == 1:
            return ovs[0]
        types = [self._arg_type(a) for a in node.args]
        for o in ovs:
            if all(p.type in ("*", t) or t == "?" or (p.type == "bool" and t == "dio") for p, t in zip(o.params, types)):
                return o
        return ovs[0]

    def _arg_type(self, a) -> str:
        try:
            tn = type(a)
            if tn in (A.Name, A.LibraryName):
                v = self.var_of(a)
                if v is not None:
                    return v.t
                low = a.name.lower()
                if low in ENUM_CONSTANTS:
                    return ENUM_CONSTANTS[low]
                return "?"
            if tn is A.Struct:
                return "?"
            return self.expr(a)[1]
        except CompileError:
            return "?"

    def args_for(self, node, params) -> list[str]:
        """Arguments compiled for catalogue parameters: values, (container, key) pairs for
        references, Arr/Coll objects for containers."""
        out = []
        for a, p in zip(node.args, params):
            if p.container in ("array", "collection"):
                out.append(self.container_arg(a))
            elif p.ref:
                out.append(self.ref_arg(a))
            else:
                code, t = self.expr(a, want=p.type if p.type != "*" else None)
                out.append(self.coerce(code, t, p.type))
        return out

    def container_arg(self, a) -> str:
        """An array/collection argument; `a[i]` of a 1-D array passes the part from i (2.6.3)."""
        if type(a) is A.Index:
            c, t, cont, ndim, _ = self.container_of(a.base)
            if cont == "array" and len(a.indices) == 1:
                return f"VIEW({c}, {self.expr(a.indices[0])[0]})"
            raise self.err("only a 1-D array can be passed from an index", a)
        tn = type(a)
        if tn in (A.Name, A.LibraryName):
            v = self.var_of(a)
            if v is not None and v.cont == "element":
                c, k = self.elem_pair(v) if v.store != "py" else (None, None)
                if c is None:
                    raise self.err(f"'{a.name}' is not an array", a)
                return f"ELEMARR({c}, {k}, {v.t!r})"
        c, t, cont, ndim, _ = self.container_of(a)
        return c

    def generic_instruction(self, node, low: str) -> tuple[str, str]:
        from . import instructions as I

        ov = self._overload(low, node)
        args = self.args_for(node, ov.params)
        fn = f"I_{low}"
        call = f"{fn}(T, A{''.join(', ' + x for x in args)})"
        if low in I.ASYNC:
            call = f"(yield from {call})"
        return call, ov.returns if ov.returns != "void" else "void"

    def builtin_call(self, node, low: str) -> tuple[str, str]:
        b = builtin(low)
        if len(node.args) != len(b.params):
            raise self.err(f"{b.name} takes {len(b.params)} argument(s)", node)
        args = []
        for i, (a, p) in enumerate(zip(node.args, b.params)):
            if p.endswith("[]"):
                args.append(self.container_arg(a))
            elif i in b.outputs:
                args.append(self.ref_arg(a))
            else:
                code, t = self.expr(a, want=p)
                args.append(self.coerce(code, t, p))
        self.unit.ns[f"B_{low}"] = b.func if not b.outputs and not any(p.endswith("[]") for p in b.params) else b
        if not b.outputs and not any(p.endswith("[]") for p in b.params):
            return f"B_{low}({', '.join(args)})", b.returns
        return f"BREF(B_{low}{''.join(', ' + x for x in args)})", b.returns

    def lib_instruction(self, node: A.CallExpr) -> tuple[str, str]:
        alias, name = node.func.alias, node.func.name
        low = name.lower()
        args = [self.expr(a)[0] for a in node.args]
        if low in ("libload", "libsave", "libdelete", "liblist"):
            return f"(yield from I_lib(T, A, {alias!r}, {low!r}{''.join(', ' + x for x in args)}))", "num"
        if low in ("libpath", "libexist"):
            return f"I_lib_now(T, A, {alias!r}, {low!r}{''.join(', ' + x for x in args)})", "string" if low == "libpath" else "bool"
        raise self.err(f"{alias}:{name}() is not a library instruction", node)

    # -- instructions with special argument forms (2.5.4 - 2.5.6: any variable) ------------------

    def var_arg(self, a) -> tuple[str, str, str]:
        """(container code, index tuple code or 'None', cont) for instructions on any variable."""
        if type(a) is A.Index:
            c, t, cont, ndim, _ = self.container_of(a.base)
            idx = ", ".join(self.expr(i)[0] for i in a.indices)
            return c, f"({idx},)", cont
        tn = type(a)
        if tn in (A.Name, A.LibraryName):
            v = self.var_of(a)
            if v is None:
                raise self.err(f"unknown variable '{a.name}'", a)
            if v.cont == "element":
                if v.store == "py":
                    return "None", "None", "element"
                c, k = self.elem_pair(v)
                return f"({c}, {k})", "None", "element"
            return self.cont_code(v), "None", v.cont
        if tn is A.Field:
            try:
                c, t, cont, ndim, _ = self.container_of(a)
                return c, "None", cont
            except CompileError:
                return "None", "None", "element"
        raise self.err("expected a variable", a)

    def i_size(self, node):
        if len(node.args) == 2:
            c, idx, cont = self.var_arg(node.args[0])
            return f"SIZE2({c}, {self.expr(node.args[1])[0]})", "num"
        c, idx, cont = self.var_arg(node.args[0])
        return f"SIZE({c}, {idx})", "num"

    def i_isdefined(self, node):
        a = node.args[0]
        if type(a) is A.LibraryName:
            return f"LIBDEF(A, {a.alias!r}, {a.name!r})", "bool"
        if type(a) is A.Index and type(a.base) is A.LibraryName:
            c, idx, cont = self.var_arg(a)
            return f"(LIBDEF(A, {a.base.alias!r}, {a.base.name!r}) and ISDEF({c}, {idx}))", "bool"
        c, idx, cont = self.var_arg(a)
        return f"ISDEF({c}, {idx})", "bool"

    def i_insert(self, node):
        if len(node.args) == 3:
            return self.builtin_or_missing(node, "insert")
        c, idx, cont = self.var_arg(node.args[0])
        return f"INSERT(T, A, {c}, {idx})", "bool"

    def i_delete(self, node):
        if len(node.args) == 3:
            return self.builtin_or_missing(node, "delete")
        c, idx, cont = self.var_arg(node.args[0])
        return f"DELETE(T, {c}, {idx})", "bool"

    def builtin_or_missing(self, node, low):
        if builtin(low) is not None:
            return self.builtin_call(node, low)
        return f"NOTSIM({low!r})", "string"

    def i_append(self, node):
        c, idx, cont = self.var_arg(node.args[0])
        return f"APPEND(T, A, {c})", "void"

    def i_resize(self, node):
        c, idx, cont = self.var_arg(node.args[0])
        return f"RESIZE(T, A, {c}, {self.expr(node.args[1])[0]}, {self.expr(node.args[2])[0]})", "void"

    def _coll_key_fn(self, node, fn):
        a = node.args[0]
        if type(a) is A.Index:
            c, t, cont, ndim, _ = self.container_of(a.base)
            return f"{fn}({c}, {self.expr(a.indices[0])[0]})", "string"
        c, idx, cont = self.var_arg(a)
        return f"{fn}({c}, None)", "string"

    def i_first(self, node):
        return self._coll_key_fn(node, "CFIRST")

    def i_last(self, node):
        return self._coll_key_fn(node, "CLAST")

    def i_next(self, node):
        return self._coll_key_fn(node, "CNEXT")

    def i_prev(self, node):
        return self._coll_key_fn(node, "CPREV")

    def i_getdata(self, node):
        name = self.expr(node.args[0])[0]
        a = node.args[1]
        if type(a) is A.Index:
            c, t, cont, ndim, _ = self.container_of(a.base)
            return f"GETDATA(T, A, {name}, {c}, ({', '.join(self.expr(i)[0] for i in a.indices)},), {t!r})", "num"
        v = self.var_of(a) if type(a) in (A.Name, A.LibraryName) else None
        if v is not None and v.cont == "element":
            return f"GETDATA(T, A, {name}, None, {self.ref_arg(a)}, {v.t!r})", "num"
        c, t, cont, ndim, _ = self.container_of(a)
        return f"GETDATA(T, A, {name}, {c}, None, {t!r})", "num"

    def _cond_lambda(self, node) -> tuple[str, bool]:
        code = self.cond(node)
        if "yield" in code:
            raise self.err("a blocking instruction inside a wait condition is not simulated", node)
        tdep = any(type(n) is A.CallExpr and type(n.func) is A.Name and n.func.name.lower() in TIME_DEPENDENT
                   for n in A.walk(node))
        return f"lambda: {code}", tdep

    def i_wait(self, node):
        fn, tdep = self._cond_lambda(node.args[0])
        return f"(yield from WAIT(T, {fn}, {tdep}))", "void"

    def i_watch(self, node):
        fn, tdep = self._cond_lambda(node.args[0])
        secs = self.expr(node.args[1])[0]
        return f"(yield from WATCH(T, {fn}, {secs}, {tdep}))", "bool"

    def i_setmutex(self, node):
        return f"(yield from SETMUTEX(T, {self.ref_arg(node.args[0])}))", "void"

    def i_put(self, node):
        return self._page(node, "put")

    def i_putln(self, node):
        return self._page(node, "putln")

    def i_title(self, node):
        return self._page(node, "title")

    def _page(self, node, kind):
        args = [self.coerce(*self.expr(a), "?") for a in node.args]
        return f"PAGE(T, {kind!r}{''.join(', ' + x for x in args)})", "void"

    def i_get(self, node):
        args = []
        for a in node.args:
            t = self._arg_type(a)
            if t == "screen":
                args.append(self.expr(a)[0])
            else:
                args.append(self.ref_arg(a) + f", {t!r}")
        return f"(yield from GET(T{''.join(', ' + x for x in args)}))", "num"

    # ---- statements ---------------------------------------------------------------------------

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
        mark = (len(self.out), self.ind, self.loop_depth, self.in_switch, self.ctx, self.level, len(self.sw_flags))
        try:
            if ts is A.Assign:
                self.line()
                code, _ = self.assign_code(s.target, s.value, as_expr=False)
                self.guarded(code.split("\n"), True)
            elif ts is A.ExprStatement:
                self.line()
                code, _ = self.expr(s.call)
                self.guarded([code], True)
            elif ts is A.Call:
                self.line()
                self.guarded([self.call_stmt(s)], True)
            elif ts is A.TaskCreate or ts is A.TaskCreateSync:
                self.line()
                self.guarded([self.task_create(s)], True)
            elif ts is A.Print:  # s8 `? expr`: the emulator prints the value; here, a user page line
                self.line()
                parts = [self.coerce(*self.expr(v), "?") for v in s.values]
                calls = [f"PAGE(T, {'putln' if k == len(parts) - 1 else 'put'!r}, {p})" for k, p in enumerate(parts)]
                self.guarded(["; ".join(calls)], True)
            elif ts is A.Return:
                self.line()
                self.emit("return")
            elif ts is A.Break:
                if not self.in_switch or self.loop_depth:
                    self.line()
                    self.guarded(["NOTSIM('break outside a switch case')"], True)
                else:
                    self.emit(f"{self.sw_flags[-1]} = 1")
                    self.emit("break")
            elif ts is A.If:
                self.if_stmt(s)
            elif ts is A.While:
                self.while_stmt(s)
            elif ts is A.DoUntil:
                self.do_stmt(s)
            elif ts is A.For:
                self.for_stmt(s)
            elif ts is A.Switch:
                self.switch_stmt(s)
            else:
                raise self.err(f"unsupported statement {ts.__name__}", s)
        except CompileError as exc:
            # The line cannot run here: the task stops on it with R004 when it gets there.
            del self.out[mark[0]:]
            self.ind, self.loop_depth, self.in_switch = mark[1], mark[2], mark[3]
            self.ctx, self.level = mark[4], mark[5]
            del self.sw_flags[mark[6]:]
            self.at(s)
            self.line()
            self.guarded([f"NOTSIM({str(exc)!r})"], True)

    def assign_code(self, target, value, as_expr: bool) -> tuple[str, str]:
        if type(target) is A.Name and target.name.lower() in ("world", "flange") and self.lookup_var(target.name) is None:
            # the roots may be written (9.4.1, 9.5.1): the next computation through them fails
            c, k, t = None, "WORLD" if target.name.lower() == "world" else "FLANGE", (
                "frame" if target.name.lower() == "world" else "tool")
        else:
            c, k, t, sp = self.lvalue(target)
        vcode, vt = self.expr(value, want=t)
        if t in NODE_TYPES:
            # `=` copies INTO the variable's node (it keeps its identity: what is linked to it
            # follows, 9.4.2); a {...} literal only writes the fields (the reference stays)
            place = k if c is None else f"{c}[{k}]"
            return f"{'NSET' if type(value) is A.Struct else 'NASG'}({place}, {vcode})", t
        if t == "dio" and vt in ("bool", "dio", "?"):
            # 3.5.2: `dio = bool` writes the output and returns the value
            tgt = f"{c}[{k}]" if c is not None else k
            v = f"IOR({vcode})" if vt == "dio" else vcode
            return f"IOW(T, {tgt}, {v})", "bool"
        if t == "sio" and vt in ("num", "string"):
            tgt = f"{c}[{k}]" if c is not None else k
            return f"(yield from SIOW(T, {tgt}, {vcode}, {vt!r}))", vt
        if vt == "sio" and t in ("num", "string"):
            vcode = f"(yield from SIOR(T, {vcode}, {t!r}))"
        elif t == "bool" and vt == "dio":
            vcode = f"IOR({vcode})"
        elif t == "num" and vt == "aio":
            vcode = self.coerce(vcode, vt, t)
        elif t not in ("num", "bool", "string") and vt not in ("num", "bool", "string") and type(value) is not A.Struct:
            vcode = f"CP({vcode})"  # 7.3: `=` copies (deep copy) structured and user-type values
        if as_expr:
            if c is None:
                return f"({k} := {vcode})", t
            return f"ASG({c}, {k}, {vcode})", t
        if c is None:
            return f"{k} = {vcode}", t
        return f"{c}[{k}] = {vcode}", t

    def call_args(self, target, args, params) -> list[str]:
        if params is None and type(target) is A.LibraryName:
            # the library's interface is not known here (not found when loading): values only;
            # the call itself raises 80 until the library is loaded (6.4)
            return [self.expr(a)[0] for a in args]
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
        if type(target) is A.Name:
            prog = self._program(target.name)
            if prog is None:
                raise self.err(f"unknown program '{target.name}'", target)
            return f"P_{prog.name}"
        return f"LP(A, {target.alias!r}, {target.name!r})"

    def call_stmt(self, s: A.Call) -> str:
        params = self._callee_params(s.target)
        args = self.call_args(s.target, s.args, params)
        return f"yield from {self.prog_ref(s.target)}(T{''.join(', ' + x for x in args)})"

    def task_create(self, s) -> str:
        params = self._callee_params(s.target)
        args = self.call_args(s.target, s.args, params)
        name = self.coerce(*self.expr(s.task), "string")
        fn = self.prog_ref(s.target)
        pname = s.target.name if type(s.target) is A.Name else f"{s.target.alias}:{s.target.name}"
        argt = "(" + "".join(x + ", " for x in args) + ")"
        if type(s) is A.TaskCreate:
            prio = self.expr(s.priority)[0]
            return f"TASKCREATE(T, A, {name}, {prio}, {fn}, {argt}, {pname!r})"
        period = self.expr(s.period)[0]
        over = self.ref_arg(s.overrun)
        return f"TASKCREATESYNC(T, A, {name}, {period}, {over}, {fn}, {argt}, {pname!r})"

    def if_stmt(self, s: A.If) -> None:
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

    def while_stmt(self, s: A.While) -> None:
        self.emit("while 1:")
        self.ind += 1
        self.at(s)
        self.line()
        self.guarded([f"_c = {self.cond(s.cond)}"], False)
        self.emit("if not _c: break")
        self.loop_depth += 1
        self.block(s.body)
        self.loop_depth -= 1
        self.ind -= 1

    def do_stmt(self, s: A.DoUntil) -> None:
        self.emit("while 1:")
        self.ind += 1
        self.loop_depth += 1
        self.block(s.body)
        self.loop_depth -= 1
        self.cur = (s.until_line, s.until_col)
        self.line()
        self.guarded([f"_c = {self.cond(s.cond)}"], False)
        self.emit("if _c: break")
        self.ind -= 1

    def for_stmt(self, s: A.For) -> None:
        n = self.fresh("f")
        c, k, t, _ = self.lvalue(s.counter)
        place = k if c is None else f"{c}[{k}]"
        self.line()
        start = self.expr(s.start)[0]
        stop = self.expr(s.stop)[0]
        step = self.expr(s.step)[0] if s.step is not None else "1.0"
        self.guarded([f"{n}b = {stop}", f"{n}s = {step}", f"{place} = {start}"], False)
        self.emit("while 1:")
        self.ind += 1
        # 2.2.5: positive step: stop when the counter is above nFin; negative: below
        self.guarded([f"_c = ({place} > {n}b) if {n}s >= 0 else ({place} < {n}b)"], False)
        self.emit("if _c: break")
        self.loop_depth += 1
        self.block(s.body)
        self.loop_depth -= 1
        self.cur = (s.end_line, max(1, s.end_col - 6))
        self.line()
        self.guarded([f"{place} = {place} + {n}s"], False)
        self.ind -= 1

    def switch_stmt(self, s: A.Switch) -> None:
        n = self.fresh("k")
        subj, st = self.expr(s.subject)
        if st == "dio":
            subj = f"IOR({subj})"
            st = "bool"
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
        self.ind -= 1
        self.emit("if 0: yield")
        head = f"def P_{prog.name}(T{''.join(', ' + x for x in params)}):"
        source = head + "\n" + "\n".join(self.out) + "\n"
        filename = f"<val3 {self.unit.uid}:{prog.name}>"
        return Compiled(prog.name, None, prog.parameters, self.pos, prog.origin.path, filename, fb, source,
                        bpos=self.bpos)

    def default_code(self, t: str, name: str = "") -> str:
        b = base_type(t)
        if b == "num":
            return "0.0"
        if b == "bool":
            return "False"
        if b == "string":
            return "''"
        return f"DEFAULT({t!r}, {name!r})" if name else f"DEFAULT({t!r})"


# A budget on the Python the compiler writes: 150,000 lines (about 15,000 VAL 3 lines in one
# program) compile in about 2 s and 700 MB; a 100,000-line program would need many GB.
MAX_SOURCE_LINES = 150_000

ENUM_VALUES_TYPES = frozenset({"shoulder", "elbow", "wrist", "blend"})


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
    for p in program.parameters:
        if p.container is Container.ELEMENT and p.by_reference:
            params += [f"c_{p.name}", f"k_{p.name}"]
        else:
            params.append(f"v_{p.name}")
    # the task (or the caller's line) stops with R004 where the program starts
    src = (f"def P_{program.name}(T{''.join(', ' + x for x in params)}):\n"
           f"    while 1:\n        try:\n            NOTSIM({str(exc)!r})\n"
           f"        except Exception as _e:\n            yield from FAIL(T, _e, False, None)\n            continue\n"
           f"    if 0: yield\n")
    filename = f"<val3 {unit.uid}:{program.name}>"
    exec(compile(src, filename, "exec"), namespace)
    return Compiled(program.name, namespace[f"P_{program.name}"], program.parameters,
                    {i: (exc.line, exc.col) for i in range(2, 8)}, program.origin.path, filename, CALL_BYTES, src, exc)
