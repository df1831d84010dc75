"""Variables in the generated code (2.5, 2.6): where each one lives, and the code that reads
or addresses it.

- VAL 3 locals and by-value parameters are Python locals (`v_name`, store "py"); a local
  whose address is taken (passed by reference, 2.6.2) lives in a list `L` ("box") so that a
  callee can write it;
- a by-reference element parameter is a (container, key) pair `c_name`/`k_name` ("ref");
- array and collection parameters and locals are `Arr`/`Coll` objects (`v_name`, "obj");
- globals are bound in the module namespace (`g_name` container, `d_name` its list of values,
  "g"); a library's through `LG(A, alias, name)` ("lib").
"""

from __future__ import annotations

from ...loading.model import Application, Container, Program
from ...loading.types import base_type
from ...parsing import ast
from ..memory import TypeSpace
from ..values import FIELD_NAMES, STRUCT_FIELDS
from .legacy import effective_parameters
from .overloads import overloads_with_arity
from .structures import FieldInfo, VarInfo

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


class VariableCompiler:
    """The variables part of `ProgramCompiler` (program.py)."""

    def _boxed_names(self, body: ast.ProgramBody) -> set[str]:
        """Locals whose address is taken: passed where a reference is expected. Locals passed
        where an array is expected are collected in `self.arrayed`."""
        boxed: set[str] = set()
        self.arrayed = arrayed = set()
        for node in ast.walk(body):
            args = None
            ref_flags: list[bool] = []
            if isinstance(node, (ast.Call, ast.TaskCreate, ast.TaskCreateSync)):
                args = node.args
                callee = self._callee_params(node.target)
                ref_flags = [bool(p.by_reference) for p in callee] if callee is not None else [True] * len(args)
                if callee is not None:
                    arrayed.update(a.name for a, p in zip(args, callee)
                                   if isinstance(a, ast.Name) and p.container is not Container.ELEMENT)
                if isinstance(node, ast.TaskCreateSync) and isinstance(node.overrun, ast.Name):
                    boxed.add(node.overrun.name)
            elif isinstance(node, ast.CallExpr) and isinstance(node.func, ast.Name):
                args = node.args
                ov = overloads_with_arity(node.func.name, len(args))
                if ov:
                    ref_flags = [any(i < len(o.params) and (o.params[i].ref or o.params[i].variable) for o in ov)
                                 for i in range(len(args))]
                    arrayed.update(a.name for i, a in enumerate(args) if isinstance(a, ast.Name) and any(
                        i < len(o.params) and o.params[i].container == "array" for o in ov))
            elif isinstance(node, ast.CallExpr) and isinstance(node.func, ast.SystemName):
                args = node.args
                h = self.registry.system_handler(node.func.name)
                if h is not None and len(h.params) == len(args):
                    ref_flags = [how == "ref" for how in h.params]
                    arrayed.update(a.name for a, how in zip(args, h.params) if isinstance(a, ast.Name) and how == "array")
            elif isinstance(node, (ast.For,)):
                continue
            if args:
                for a, ref in zip(args, ref_flags):
                    if ref and isinstance(a, ast.Name):
                        boxed.add(a.name)
        return boxed

    def _callee_params(self, target) -> list | None:
        """The parameters of a called program as the simulator binds them (an s6 reference
        parameter used as an array is an array reference: legacy.py)."""
        if isinstance(target, ast.Name):
            prog = self._program(target.name)
            return self._params_of(self.app, prog) if prog else None
        if isinstance(target, ast.LibraryName):
            lib = self._lib_model(target.alias)
            if lib is None:
                return None
            prog = lib.programs.get(target.name)
            return self._params_of(lib, prog) if prog else None
        return None

    def _params_of(self, app: Application, prog: Program) -> list:
        return effective_parameters(app, prog, self.unit.machine.legacy_arrays(app))

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
        indexed = {n.base.name for n in ast.walk(prog.body) if isinstance(n, ast.Index) and isinstance(n.base, ast.Name)} if prog.body else set()
        indexed |= self.arrayed
        slot = 0
        for p in self._params_of(self.app, prog):
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

    def lib_var(self, node: ast.LibraryName) -> VarInfo:
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

    # ---- fields -------------------------------------------------------------------------------

    def field_type(self, t: str, name: str, space: TypeSpace, node) -> FieldInfo:
        """Type, container, space, ndim and canonical name of field `name` of a value of type
        `t` (a file alias of a built-in field, `mDesc.tmax`, is the field `tvel`)."""
        b = base_type(t)
        if b in STRUCT_FIELDS:
            canonical = FIELD_NAMES[b].get(name)
            if canonical is None and b == "joint" and name[:1] == "j" and name[1:].isdigit():
                canonical = name  # one field per axis (9.2.1): j7, j8 on extra axes
            if canonical is None:
                raise self.err(f"type {b} has no field '{name}'", node)
            return FieldInfo(STRUCT_FIELDS[b].get(canonical, "num"), "element", space, 1, canonical)
        fields = space.field_info(t)
        if fields is None:
            raise self.err(f"unknown type '{t}' for field '{name}'", node)
        d = fields.get(name)
        if d is None:
            raise self.err(f"user type '{t}' has no public field '{name}'", node)
        ut = space.user_type(t)
        sp = space.space_of(ut.app)
        cont = "collection" if d.container is Container.COLLECTION else "array"
        return FieldInfo(base_type(d.type), cont, sp, len(d.sizes or (1,)), name)
