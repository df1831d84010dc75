"""The controller's own I/O library (`io:`), as applications see it: always loaded, its
symbols are the controller's inputs/outputs (docs/sim.md, "The cell")."""

from __future__ import annotations

from ..language import lookup
from ..loading.types import base_type
from ..parsing import ast
from .values import Arr


IO_TYPES = ("dio", "aio", "sio")


def is_system_io(model, alias: str, ws) -> bool:
    """An alias that names the controller's own I/O library: its symbols are the controller's
    inputs/outputs (`io:bIn0`, `io:valve1`, `io:tcp_server`), as lint's L003 says. Either an s6
    `<alias interface="io">` or a `Disk://io` library that is not in the project, or the
    controller's io library exported with the application (`usr/usrapp/io/io.pjx`: a library
    named io that declares only inputs/outputs)."""
    ref = model.libraries.get(alias)
    if ref is None:
        return False
    lib = ws.library(model, alias)
    if lib is not None:
        return exported_io(lib)
    tail = ref.path.replace("\\", "/").rstrip("/").rsplit("/", 1)[-1]
    stem = tail[:-4] if tail.lower().endswith(".pjx") else tail
    return alias.lower() == "io" or stem.lower() == "io"


def exported_io(lib) -> bool:
    """The controller's io library as exported in a controller tree: named io, no program, its
    globals only dio, aio and sio (their links are the controller's, not in the file)."""
    return (lib.name.lower() == "io" and not lib.programs and bool(lib.data)
            and all(base_type(d.type) in IO_TYPES for d in lib.data.values()))


class SystemIO:
    """The controller's I/O library, always loaded: `io:NAME` is a dio, aio or sio linked to
    "io:NAME" (the scenario names it so). Its kind is inferred from how the application uses
    it (`dioLink(x, io:NAME)`, `io:NAME = "text"`, `if io:NAME`...), else from the name
    (b.../d... dio, a... aio)."""

    uid = 0
    name = "io"
    model = None
    disk_path = "io"

    def __init__(self, machine) -> None:
        self.machine = machine
        self.kinds: dict[str, str] = {}
        self.globals: dict[str, Arr] = {}

    def kind_of(self, name: str) -> str:
        k = self.kinds.get(name)
        if k is None:
            low = name.lower()
            k = "aio" if low.startswith("a") else "dio"
        return k

    def public_global(self, name: str) -> Arr:
        c = self.globals.get(name)
        if c is None:
            kind = self.kind_of(name)
            c = self.globals[name] = Arr(kind, [self.machine.cell.io(kind, f"io:{name}")])
        return c

    def public_program(self, name: str):
        return None

    def infer(self, app, alias: str) -> None:
        """Kinds of the `alias:NAME` symbols: as the exported io library declares them, else
        from their uses in `app`'s programs."""
        exported = self.machine.ws.library(app, alias)
        if exported is not None:
            for name, d in exported.data.items():
                self.kinds.setdefault(name, base_type(d.type))

        def io_name(node) -> str | None:
            return node.name if type(node) is ast.LibraryName and node.alias == alias else None

        def note(node, kind: str | None) -> None:
            n = io_name(node)
            if n is not None and kind in ("dio", "aio", "sio") and n not in self.kinds:
                self.kinds[n] = kind

        def kind_of_value(node, prog) -> str | None:
            t = type(node)
            if t is ast.String or t is ast.Binary and node.op == "+" and (type(node.left) is ast.String or
                                                                      type(node.right) is ast.String):
                return "sio"
            if t is ast.Bool or t is ast.Unary and node.op == "!" or t is ast.Binary and node.op in (
                    "==", "!=", "<", ">", "<=", ">=", "and", "or", "xor"):
                return "dio"
            if t is ast.Number:
                return "aio"
            if t in (ast.Name, ast.Index):
                base = node if t is ast.Name else node.base
                if type(base) is ast.Name:
                    vt = var_type(base.name, prog)
                    return {"string": "sio", "bool": "dio", "num": "aio", "dio": "dio", "aio": "aio",
                            "sio": "sio"}.get(vt or "")
            return None

        def callee_params(target) -> list | None:
            if type(target) is ast.Name:
                low = target.name.lower()
                prog = next((p for n, p in app.programs.items() if n.lower() == low), None)
            elif type(target) is ast.LibraryName:
                lib = self.machine.ws.library(app, target.alias)
                prog = lib.programs.get(target.name) if lib is not None else None
            else:
                prog = None
            return prog.parameters if prog is not None else None

        def var_type(name: str, prog) -> str | None:
            for d in list(prog.parameters) + list(prog.locals):
                if d.name == name:
                    return base_type(d.type)
            d = app.data.get(name)
            return base_type(d.type) if d is not None else None

        for prog in app.programs.values():
            if prog.body is None:
                continue
            for node in ast.walk(prog.body):
                t = type(node)
                if t is ast.CallExpr and type(node.func) is ast.Name:
                    ins = lookup(node.func.name)
                    if ins is not None:
                        for i, a in enumerate(node.args):
                            if io_name(a) is not None:
                                types = {o.params[i].type for o in ins.overloads
                                         if o.accepts_arity(len(node.args)) and i < len(o.params)}
                                kinds = types & {"dio", "aio", "sio"}
                                note(a, kinds.pop() if len(kinds) == 1 else ("dio" if "bool" in types else None))
                elif t in (ast.Call, ast.TaskCreate, ast.TaskCreateSync):
                    # a parameter of a program: `call openLine(io:tcp_server)` with `sio x_siLine`
                    params = callee_params(node.target)
                    for a, p in zip(node.args, params or ()):
                        note(a, base_type(p.type))
                elif t in (ast.Assign, ast.AssignExpr):
                    if io_name(node.target) is not None:
                        note(node.target, kind_of_value(node.value, prog))
                    elif io_name(node.value) is not None:
                        note(node.value, kind_of_value(node.target, prog))
                elif t is ast.Binary:
                    for a, b in ((node.left, node.right), (node.right, node.left)):
                        if io_name(a) is not None:
                            note(a, "dio" if node.op in ("and", "or", "xor") else kind_of_value(b, prog))
                elif t is ast.Unary and node.op == "!":
                    note(node.operand, "dio")
                elif t in (ast.While, ast.DoUntil):
                    note(node.cond, "dio")
                elif t is ast.If:
                    for br in node.branches:
                        note(br.cond, "dio")
        for name in sorted(self.kinds):
            self.public_global(name)
