"""Libraries at run time (chapter 6): libLoad, libSave, libDelete, libList, libPath, libExist.

The simulated disk is the folder tree the application was loaded from (read only: the
loader's `Disk://` resolution, docs/sim.md) with an in-memory overlay: `libSave` writes a
snapshot of the library's programs and current global values there and `libDelete` hides a
library; nothing is ever written to the user's files. Return codes are those of 6.6.
"""

from __future__ import annotations

import os
import re
from typing import Any

from ..loading.resolve import listdir, resolve_library
from .values import Arr, copy_globals

_ROOT = re.compile(r"^([A-Za-z][A-Za-z0-9_\-]*):/+(.*)$")
ROOTS = ("disk", "usb0", "floppy")
_NAME = re.compile(r"^[A-Za-z0-9_.\-]{1,64}$")


class Snapshot:
    def __init__(self, model, values: dict[str, Any], display: str) -> None:
        self.model = model
        self.values = values
        self.display = display


def normalise(path: str, A) -> tuple[int, str, str]:
    """(code, key, display path) for a library path (6.6 "Chemin d'accès"); code 0 when valid."""
    text = path.strip().replace("\\", "/")
    m = _ROOT.match(text)
    if m:
        root, rest = m.group(1), m.group(2)
    elif text.startswith(("./", "../")):
        root, rest = "Disk", A.disk_path.split("://", 1)[-1] + "/" + text
    else:
        root, rest = "Disk", text
    if root.lower() not in ROOTS:
        return 20, "", ""
    parts = []
    for comp in rest.split("/"):
        if comp in ("", "."):
            continue
        if comp == "..":
            if not parts:
                return 21, "", ""
            parts.pop()
            continue
        parts.append(comp)
    if not parts:
        return 22, "", ""
    name = parts[-1]
    if name.lower().endswith(".pjx"):
        parts = parts[:-1] if len(parts) > 1 and parts[-2].lower() == name[:-4].lower() else parts[:-1] + [name[:-4]]
        name = parts[-1]
    if not _NAME.match(name):
        return 22, "", ""
    if any(not _NAME.match(p) for p in parts):
        return 21, "", ""
    canon = root[0].upper() + root[1:].lower() if root.lower() != "usb0" else "USB0"
    display = f"{canon}://" + "/".join(parts)
    return 0, display.lower(), display


def _roots(M):
    """The lint run's roots (val3check.confine): a path never leads outside them at run time either."""
    roots = M.ws.roots
    if roots is None:
        from ..confine import Roots

        roots = M.ws.roots = Roots([*M.disk_roots, os.path.dirname(M.app.folder)])
    return roots


def _real_path(M, A, path: str) -> str | None:
    text = path.strip()
    if text.lower().startswith("disk://"):
        text = "Disk://" + text[7:]
    found = resolve_library(text, A.model.path, M.disk_roots, _roots(M))
    if found is None:
        # a library the loader found by name in the repository (issue 11 item 5)
        for ref in (*A.model.libraries.values(), *A.model.types.values()):
            if ref.resolved and ref.path.strip().replace("\\", "/").lower() == text.replace("\\", "/").lower():
                return ref.resolved
    return found


def _model_for(M, resolved: str):
    app = M.ws.apps.get(resolved)
    if app is not None:
        return app
    from ..loading import LoadOptions, load

    ws2, _ = load([resolved], LoadOptions(disk_roots=list(M.disk_roots), extra_roots=_roots(M).folders))
    for k, v in ws2.apps.items():
        M.ws.apps.setdefault(k, v)
    return M.ws.apps.get(resolved)


def _interface_ok(interface, unit) -> bool:
    """6.3: the library loaded must have the public symbols of the declared interface."""
    if interface is None:
        return True
    for n, d in interface.data.items():
        if d.access != "private" and unit.public_global(n) is None:
            return False
    for n, p in interface.programs.items():
        if p.access != "private" and unit.public_program(n) is None:
            return False
    return True


def _in_use(M, unit) -> int:
    """13: a program of the library is running in a task; 14: the library created a task."""
    if unit is None:
        return 0
    for t in M.tasks:
        if t.unit is unit:
            return 14
    for t in M.tasks:
        g = t.gen
        while g is not None:
            code = getattr(g, "gi_code", None)
            c = M.compiled.get(code.co_filename) if code is not None else None
            if c is not None and c.filename.startswith(f"<val3 {unit.uid}:"):
                return 13
            g = getattr(g, "gi_yieldfrom", None)
    return 0


def load_library(M, A, alias: str, path: Any, T) -> int:
    """6.7 libLoad: 0 loaded, 11 interface does not match, 12 invalid content, 13/14 the
    previous library cannot be unloaded, 20-22 bad path, 39 not found."""
    from .machine import Unit

    if not isinstance(path, str):
        return 22
    if alias not in A.aliases:
        return 10
    code, key, display = normalise(path, A)
    if code:
        return code
    old = A.aliases.get(alias)
    busy = _in_use(M, old)
    if busy:
        return busy
    snap = M.disk.get(key, False)
    if snap is None:
        return 39
    if snap is not False:
        unit = M.units.get("snap:" + key)
        if unit is None:
            unit = Unit(M, snap.model, snap.display)
            unit.init_globals(snap.values)
            unit.build()
            M.units["snap:" + key] = unit
    else:
        resolved = _real_path(M, A, path if path.strip() else display)
        if resolved is None:
            return 39
        unit = M.units.get(resolved)
        if unit is None:
            model = _model_for(M, resolved)
            if model is None:
                return 12
            unit = Unit(M, model, display)
            unit.init_globals()
            unit.build()
            if any(model.programs[c.name].code is not None and model.programs[c.name].body is None
                   for c in unit.compile_errors):
                return 12  # 6.6: the library holds invalid programs (syntax errors)
            M.units[resolved] = unit
            autoload_libraries(M, unit)  # a library brings the libraries it loads at start
    A.aliases[alias] = unit
    interface = M.library_model(A.model, alias)
    return 0 if _interface_ok(interface, unit) else 11


def autoload_libraries(M, unit) -> None:
    """Load the libraries `unit`'s project declares with autoload (a missing attribute counts
    as autoload: files that do not want a library loaded write autoload="false"). A library
    already in memory is shared (6.6)."""
    for alias, ref in unit.model.libraries.items():
        if ref.autoload and unit.aliases.get(alias) is None:
            load_library(M, unit, alias, ref.path, None)


def _exists(M, A, key: str, path: str) -> bool:
    snap = M.disk.get(key, False)
    if snap is None:
        return False
    if snap is not False:
        return True
    return _real_path(M, A, path) is not None


def lib_operation(M, T, A, alias: str | None, op: str, *args: Any) -> Any:
    if op == "libload":
        code = load_library(M, A, alias, args[0] if args else "", T)
        return float(code)
    if op in ("libsave",):
        if alias is None:
            unit = A
        else:
            if alias not in A.aliases or A.aliases[alias] is None:
                return 10.0
            unit = A.aliases[alias]
            if isinstance(unit, SystemIO):
                return 35.0  # the controller's I/O library cannot be saved ("write-protected")
        if args:
            code, key, display = normalise(args[0], A)
            if code:
                return float(code)
            if _exists(M, A, key, args[0]):
                return 31.0  # 6.6: remove it first with libDelete()
        else:
            code, key, display = normalise(unit.disk_path, A)
            if code:
                return float(code)
        M.disk[key] = Snapshot(unit.model, copy_globals(unit.globals), display)
        M.transcript_add(T, "disk", f"libSave {display}", None)
        return 0.0
    if op == "libdelete":
        code, key, display = normalise(args[0] if args else "", A)
        if code:
            return float(code)
        if _exists(M, A, key, args[0]):
            M.disk[key] = None
            M.transcript_add(T, "disk", f"libDelete {display}", None)
        return 0.0
    if op == "liblist":
        path, arr = args[0], args[1]
        return _lib_list(M, A, path, arr)
    if op == "libpath":
        return A.disk_path if alias is None else (A.aliases.get(alias).disk_path if A.aliases.get(alias) else "")
    raise ValueError(op)


def _lib_list(M, A, path: str, arr: Arr) -> bool:
    """6.7 libList: the names found at the path; a global array grows as needed."""
    code, key, display = normalise(path + "/x", A) if path.strip() else (0, "disk://x", "Disk://x")
    names: set[str] = set()
    prefix = key[:-1] if not code else ""
    for k, snap in M.disk.items():
        if snap is not None and k.startswith(prefix):
            names.add(snap.display[len(display) - 1:].split("/")[0])
    folder = None
    real = _real_path(M, A, (path.rstrip("/") + "/") if path.strip() else "Disk://")
    if real is None:
        base = os.path.dirname(os.path.dirname(os.path.abspath(A.model.path)))
        rest = path.split("://", 1)[-1].strip("/")
        cand = os.path.normpath(os.path.join(base, rest)) if rest else base
        roots = _roots(M)  # never list a folder outside the run's roots (val3check.confine)
        folder = cand if roots.holds(cand) and roots.allows(cand) and os.path.isdir(cand) else None
    else:
        folder = os.path.dirname(os.path.dirname(real))
    if folder:
        for n in listdir(folder):
            if os.path.isdir(os.path.join(folder, n)) and not n.startswith("."):
                names.add(n)
    for k, snap in M.disk.items():
        if snap is None:
            names.discard(k.rsplit("/", 1)[-1])
    out = sorted(names, key=str.lower)
    return len(out) <= arr.fill_strings(out)


# ---- the controller's I/O library (`io:`) ---------------------------------------------------------


def is_system_io(model, alias: str, ws) -> bool:
    """An alias that names the controller's own I/O library (an s6 `<alias interface="io">` or
    a `Disk://io` library that is not in the project): its symbols are the controller's
    inputs/outputs (`io:bIn0`, `io:valve1`, `io:tcp_server`), as lint's L003 says."""
    ref = model.libraries.get(alias)
    if ref is None or ws.library(model, alias) is not None:
        return False
    tail = ref.path.replace("\\", "/").rstrip("/").rsplit("/", 1)[-1]
    stem = tail[:-4] if tail.lower().endswith(".pjx") else tail
    return alias.lower() == "io" or stem.lower() == "io"


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
        self.M = machine
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
            c = self.globals[name] = Arr(kind, [self.M.cell.io(kind, f"io:{name}")])
        return c

    def public_program(self, name: str):
        return None

    def infer(self, app, alias: str) -> None:
        """Kinds of the `alias:NAME` symbols from their uses in `app`'s programs."""
        from ..language import lookup
        from ..loading.types import base_type
        from ..parsing import ast as A

        def io_name(node) -> str | None:
            return node.name if type(node) is A.LibraryName and node.alias == alias else None

        def note(node, kind: str | None) -> None:
            n = io_name(node)
            if n is not None and kind in ("dio", "aio", "sio") and n not in self.kinds:
                self.kinds[n] = kind

        def kind_of_value(node, prog) -> str | None:
            t = type(node)
            if t is A.String or t is A.Binary and node.op == "+" and (type(node.left) is A.String or
                                                                      type(node.right) is A.String):
                return "sio"
            if t is A.Bool or t is A.Unary and node.op == "!" or t is A.Binary and node.op in (
                    "==", "!=", "<", ">", "<=", ">=", "and", "or", "xor"):
                return "dio"
            if t is A.Number:
                return "aio"
            if t in (A.Name, A.Index):
                base = node if t is A.Name else node.base
                if type(base) is A.Name:
                    vt = var_type(base.name, prog)
                    return {"string": "sio", "bool": "dio", "num": "aio", "dio": "dio", "aio": "aio",
                            "sio": "sio"}.get(vt or "")
            return None

        def var_type(name: str, prog) -> str | None:
            for d in list(prog.parameters) + list(prog.locals):
                if d.name == name:
                    return base_type(d.type)
            d = app.data.get(name)
            return base_type(d.type) if d is not None else None

        for prog in app.programs.values():
            if prog.body is None:
                continue
            for node in A.walk(prog.body):
                t = type(node)
                if t is A.CallExpr and type(node.func) is A.Name:
                    ins = lookup(node.func.name)
                    if ins is not None:
                        for i, a in enumerate(node.args):
                            if io_name(a) is not None:
                                types = {o.params[i].type for o in ins.overloads
                                         if o.accepts_arity(len(node.args)) and i < len(o.params)}
                                kinds = types & {"dio", "aio", "sio"}
                                note(a, kinds.pop() if len(kinds) == 1 else ("dio" if "bool" in types else None))
                elif t in (A.Assign, A.AssignExpr):
                    if io_name(node.target) is not None:
                        note(node.target, kind_of_value(node.value, prog))
                    elif io_name(node.value) is not None:
                        note(node.value, kind_of_value(node.target, prog))
                elif t is A.Binary:
                    for a, b in ((node.left, node.right), (node.right, node.left)):
                        if io_name(a) is not None:
                            note(a, "dio" if node.op in ("and", "or", "xor") else kind_of_value(b, prog))
                elif t is A.Unary and node.op == "!":
                    note(node.operand, "dio")
                elif t in (A.While, A.DoUntil):
                    note(node.cond, "dio")
                elif t is A.If:
                    for br in node.branches:
                        note(br.cond, "dio")
        for name in sorted(self.kinds):
            self.public_global(name)
