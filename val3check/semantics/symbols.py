"""Symbol tables: what each name of a VAL 3 application refers to (manual 2.5.2, 6, 7).

    table = symbols.build(workspace, app)         # one per application
    scope = table.scope(program)                  # parameters and locals of one program
    sym = scope.lookup("nCount")                  # Symbol or None (exact spelling)
    sym = scope.lookup_ci("ncount")               # case-insensitive fallback, or None
    prog = table.program("pick")                  # Program or None
    lib = table.library("lib")                    # LibraryInterface; MISSING (declared, not loaded); None
    decl = symbols.resolve(scope, name_node)      # AST Name/LibraryName -> Symbol, Program or None
    sym, why = lib.data_symbol("nX")              # (Symbol, "") public; (Symbol, "private"); (None, "")
    fields = symbols.user_fields(table.registry, part_vtype)   # name -> Symbol: a user type's fields
    vtype = table.resolve_type("pointRx")         # VType of a type name written in the app's files

Names resolve in this order (2.5.2): the program's parameters and locals, then the
application's globals, then the language's constants (`world`, `flange`, `true`, `righty`,
`off`...). Programs, instructions and library identifiers live in their own name spaces
(`call x()`, `x()`, `alias:x`).

A `Symbol` describes one declared variable: its kind (global, local, param, constant, library
data, user-type field), its VType, its container and the declaration it comes from (`decl`: a
loading.model Data, Local or Parameter; None for constants). `Symbol.val` is the `Val` of the
bare name, shared (treat it as read-only).

Types are resolved in the application that declares them: a library's data of type "Part" is
the "Part" of the library's own project file.
"""

from __future__ import annotations


from ..loading.model import (
    Application,
    Container,
    Data,
    Local,
    Parameter,
    Program,
    Workspace,
)
from . import vtypes as vt

TYPE_CHECKING = False  # not typing's: importing typing costs 3 ms at lint's start-up
if TYPE_CHECKING:
    from typing import Any

GLOBAL = "global"
LOCAL = "local"
PARAM = "param"
CONSTANT = "constant"
LIBDATA = "library data"
FIELD = "field"


class Symbol:
    __slots__ = ("by_ref", "container", "decl", "dims", "kind", "name", "owner", "sizes", "type", "val")

    def __init__(self, name: str, kind: str, vtype: vt.VType, container: int, dims: int, sizes: tuple[int, ...],
                 decl: Any, owner: Application | None, by_ref: bool = False, elem: bool | None = True) -> None:
        self.name = name
        self.kind = kind
        self.type = vtype
        self.container = container
        self.dims = dims
        self.sizes = sizes
        self.decl = decl
        self.owner = owner  # the application that declares it
        self.by_ref = by_ref
        var = kind != CONSTANT or name.lower() in vt.CONSTANT_VARIABLES
        self.val = vt.Val(vtype, container, dims, elem, var, self if var else None)

    @property
    def is_local(self) -> bool:
        return self.kind == LOCAL

    def __repr__(self) -> str:
        return f"Symbol({self.kind} {self.name}: {vt.describe(self.val)})"


class TypeRegistry:
    """User types and library interfaces of one workspace, built once and shared."""

    def __init__(self, workspace: Workspace) -> None:
        self.workspace = workspace
        self.user_types: dict[str, vt.VType] = {}
        self.interfaces: dict[str, LibraryInterface] = {}
        self.globals: dict[str, dict[str, Symbol]] = {}

    def resolve_type(self, app: Application, name: str) -> vt.VType:
        """The VType of a type name written in `app`'s files; UNKNOWN when it cannot be known
        (a user type that is not declared, or whose application was not found)."""
        t = vt.builtin(name)
        if t is not None:
            return t
        ref = app.types.get(name)
        if ref is None:
            low = name.lower()
            ref = next((r for n, r in app.types.items() if n.lower() == low), None)
        if ref is None or not ref.resolved:
            return vt.UNKNOWN
        tapp = self.workspace.apps.get(ref.resolved)
        if tapp is None:
            return vt.UNKNOWN
        t = self.user_types.get(tapp.path)
        if t is None:
            t = vt.VType(ref.name, vt.USER, tapp.path, tapp)
            self.user_types[tapp.path] = t
        return t

    def globals_of(self, app: Application) -> dict[str, Symbol]:
        """Every global of `app` (public and private), as Symbols."""
        table = self.globals.get(app.path)
        if table is None:
            kind = GLOBAL
            table = {name: data_symbol(self, app, d, kind) for name, d in app.data.items()}
            self.globals[app.path] = table
        return table

    def interface(self, lib: Application) -> LibraryInterface:
        it = self.interfaces.get(lib.path)
        if it is None:
            it = LibraryInterface(self, lib)
            self.interfaces[lib.path] = it
        return it


def data_symbol(reg: TypeRegistry, app: Application, d: Data, kind: str) -> Symbol:
    vtype = reg.resolve_type(app, d.type)
    if d.container is Container.COLLECTION:
        return Symbol(d.name, kind, vtype, vt.COLLECTION, 0, (), d, app, elem=False)
    if d.container is Container.ELEMENT:
        return Symbol(d.name, kind, vtype, vt.ELEMENT, 0, (1,), d, app)
    if app.layout == "s6" and kind != FIELD:
        # s6 data files write no size: the loader counts the values of one dimension; the
        # dimensions are not known (dims -1: any index is accepted, 2.3.4 element or array).
        # Nor is it known whether a bare name of a global written with several values stands
        # for its first value: real s6 applications pass such arrays bare to movej/movel by
        # the dozen, so a missing index is not reported there.
        return Symbol(d.name, kind, vtype, vt.ELEMENT, -1, d.sizes, d, app, elem=None)
    sizes = d.sizes or (1,)
    dims = len(sizes)
    if dims > 1:
        elem: bool | None = False
    elif sizes == (1,):
        elem = True  # 2.3.4: a 1-D array with one value is an element
    elif kind == FIELD or app.layout != "s7":
        elem = None  # field sizes change per variable (7.1); s6 sizes are counted from values
    else:
        elem = False
    return Symbol(d.name, kind, vtype, vt.ARRAY, dims, sizes, d, app, elem=elem)


def local_symbol(reg: TypeRegistry, app: Application, loc: Local) -> Symbol:
    vtype = reg.resolve_type(app, loc.type)
    if loc.container is Container.COLLECTION:
        return Symbol(loc.name, LOCAL, vtype, vt.COLLECTION, 0, (), loc, app, elem=False)
    sizes = loc.sizes or (1,)
    # The loader reads a size-1 local as an element (2.3.4); it is still a 1-D array.
    dims = len(sizes)
    elem = sizes == (1,)
    return Symbol(loc.name, LOCAL, vtype, vt.ARRAY, dims, sizes, loc, app, elem=elem)


def param_symbol(reg: TypeRegistry, app: Application, p: Parameter) -> Symbol:
    vtype = reg.resolve_type(app, p.type)
    if p.container is Container.COLLECTION:
        return Symbol(p.name, PARAM, vtype, vt.COLLECTION, 0, (), p, app, True, elem=False)
    if p.container is Container.ARRAY:
        dims = p.dimensions or 1
        # 1-D: the caller's array from some index, of unknown size (2.6.3)
        return Symbol(p.name, PARAM, vtype, vt.ARRAY, dims, (), p, app, True, elem=None if dims == 1 else False)
    if app.layout == "s6":
        # s6 files may describe an array parameter by `dimensions` alone, and a reference by
        # `byVal`; the loader reads neither for elements: the container is not known (dims -1).
        return Symbol(p.name, PARAM, vtype, vt.ELEMENT, -1, (1,), p, app, p.by_reference, elem=None)
    return Symbol(p.name, PARAM, vtype, vt.ELEMENT, 0, (1,), p, app, p.by_reference)


class LibraryInterface:
    """The public programs and data of a library (manual 6.2), and its private names."""

    def __init__(self, reg: TypeRegistry, lib: Application) -> None:
        self.app = lib
        self.reg = reg
        self._data: dict[str, Symbol] | None = None

    def _all_data(self) -> dict[str, Symbol]:
        if self._data is None:
            self._data = {n: data_symbol(self.reg, self.app, d, LIBDATA) for n, d in self.app.data.items()}
        return self._data

    def data_symbol(self, name: str) -> tuple[Symbol | None, str]:
        """(symbol, "") for public data; (symbol, "private") for private data; (None, "")."""
        sym = self._all_data().get(name)
        if sym is None:
            return None, ""
        return (sym, "") if sym.decl.access == "public" else (sym, "private")

    def program(self, name: str) -> tuple[Program | None, str]:
        prog = self.app.programs.get(name)
        if prog is None:
            return None, ""
        return (prog, "") if prog.access == "public" else (prog, "private")

    def lookup_ci(self, name: str) -> str | None:
        """The spelling of a public symbol that differs from `name` only by case."""
        low = name.lower()
        for n, d in self.app.data.items():
            if n.lower() == low and d.access == "public":
                return n
        for n, p in self.app.programs.items():
            if n.lower() == low and p.access == "public":
                return n
        return None


# Marker for a library alias that is declared but whose application was not loaded (L001,
# L003 already reported): its symbols are not checked.
MISSING = object()


def user_fields(reg: TypeRegistry, t: vt.VType) -> dict[str, Symbol]:
    """Fields of a user type: every global of the type's application (7.2), public or not;
    `decl.access` tells the private ones apart."""
    fields = t._fields
    if fields is None:
        app = t.app
        fields = {} if app is None else {n: data_symbol(reg, app, d, FIELD) for n, d in app.data.items()}
        t._fields = fields
    return fields


class AppSymbols:
    """The symbol table of one application."""

    def __init__(self, workspace: Workspace, app: Application, registry: TypeRegistry | None = None) -> None:
        self.workspace = workspace
        self.app = app
        self.registry = registry or TypeRegistry(workspace)
        self.globals: dict[str, Symbol] = self.registry.globals_of(app)
        self._globals_ci: dict[str, list[Symbol]] | None = None
        self._programs_ci: dict[str, list[Program]] | None = None
        self._libs: dict[str, Any] = {}

    # -- programs ------------------------------------------------------------------------------

    def program(self, name: str) -> Program | None:
        return self.app.programs.get(name)

    def program_ci(self, name: str) -> Program | None:
        if self._programs_ci is None:
            self._programs_ci = {}
            for n, p in self.app.programs.items():
                self._programs_ci.setdefault(n.lower(), []).append(p)
        hits = self._programs_ci.get(name.lower())
        return hits[0] if hits else None

    # -- globals -------------------------------------------------------------------------------

    def global_ci(self, name: str) -> Symbol | None:
        if self._globals_ci is None:
            self._globals_ci = {}
            for n, s in self.globals.items():
                self._globals_ci.setdefault(n.lower(), []).append(s)
        hits = self._globals_ci.get(name.lower())
        return hits[0] if hits else None

    # -- libraries -----------------------------------------------------------------------------

    def library(self, alias: str) -> Any:
        """LibraryInterface; MISSING when declared but not loaded; None when not declared."""
        if alias in self._libs:
            return self._libs[alias]
        ref = self.app.libraries.get(alias)
        result: Any
        if ref is None:
            result = None
        else:
            lib = self.workspace.library(self.app, alias)
            result = MISSING if lib is None else self.registry.interface(lib)
        self._libs[alias] = result
        return result

    def library_alias_ci(self, alias: str) -> str | None:
        low = alias.lower()
        return next((a for a in self.app.libraries if a.lower() == low), None)

    # -- scopes --------------------------------------------------------------------------------

    def scope(self, program: Program) -> Scope:
        return Scope(self, program)

    def resolve_type(self, name: str) -> vt.VType:
        return self.registry.resolve_type(self.app, name)


class Scope:
    """Names visible in one program: its parameters and locals hide the globals (2.5.2)."""

    def __init__(self, table: AppSymbols, program: Program) -> None:
        self.table = table
        self.program = program
        reg, app = table.registry, table.app
        own: dict[str, Symbol] = {}
        for p in program.parameters:
            own.setdefault(p.name, param_symbol(reg, app, p))
        for loc in program.locals:
            own.setdefault(loc.name, local_symbol(reg, app, loc))
        self.own = own
        self._own_ci: dict[str, Symbol] | None = None

    def lookup(self, name: str) -> Symbol | None:
        """The variable `name` designates in this program (exact spelling), or None."""
        s = self.own.get(name)
        if s is not None:
            return s
        return self.table.globals.get(name)

    def lookup_ci(self, name: str) -> Symbol | None:
        """A variable whose name differs from `name` only by case, or None."""
        if self._own_ci is None:
            self._own_ci = {}
            for n, s in self.own.items():
                self._own_ci.setdefault(n.lower(), s)
        s = self._own_ci.get(name.lower())
        return s if s is not None else self.table.global_ci(name)


_CONSTANT_SYMBOLS: dict[str, Symbol] = {}


def constant(name: str) -> Symbol | None:
    """The language constant `name` (any case): true, world, flange, righty, off..."""
    low = name.lower()
    s = _CONSTANT_SYMBOLS.get(low)
    if s is None:
        t = vt.constants().get(low)
        if t is None:
            return None
        s = Symbol(name, CONSTANT, t, vt.ELEMENT, 0, (1,), None, None)
        _CONSTANT_SYMBOLS[low] = s
    return s


def build(workspace: Workspace, app: Application, registry: TypeRegistry | None = None) -> AppSymbols:
    """The symbol table of `app` (see the module docstring)."""
    return AppSymbols(workspace, app, registry)


def resolve_name(scope: Scope, name: str) -> Symbol | None:
    """What a bare name designates in an expression: a variable of the scope, else a constant;
    exact spelling only (see Scope.lookup_ci for the case-insensitive fallback)."""
    return scope.lookup(name) or constant(name)


def resolve(scope: Scope, node: Any) -> Symbol | Program | None:
    """What an AST `Name` or `LibraryName` designates where it is written in `scope`'s program:
    a variable or constant Symbol (`.decl` is its declaration), a Program (a `call` target, or a
    program of a library), or None (undefined, an instruction, or a library not loaded). Exact
    spelling first, then ignoring case, as the checker does."""
    from ..parsing import ast as A

    t = type(node)
    table = scope.table
    if t is A.Name:
        name = node.name
        return (scope.lookup(name) or constant(name) or scope.lookup_ci(name) or table.program(name)
                or table.program_ci(name))
    if t is A.LibraryName:
        lib = table.library(node.alias)
        if lib is None:
            other = table.library_alias_ci(node.alias)
            lib = table.library(other) if other is not None else None
        if not isinstance(lib, LibraryInterface):
            return None
        sym, _ = lib.data_symbol(node.name)
        if sym is not None:
            return sym
        prog, _ = lib.program(node.name)
        return prog
    return None
