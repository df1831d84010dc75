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

from ..loading.libraries import find_library
from ..loading.resolve import listdir
from .system_io import SystemIO
from .units import Unit
from .values import Arr, copy_globals

_ROOT = re.compile(r"^([A-Za-z][A-Za-z0-9_\-]*):/+(.*)$")
ROOTS = ("disk", "usb0", "floppy")
_NAME = re.compile(r"^[A-Za-z0-9_.\-]{1,64}$")


class Snapshot:
    def __init__(self, model, values: dict[str, Any], display: str) -> None:
        self.model = model
        self.values = values
        self.display = display


def normalise(path: str, owner) -> tuple[int, str, str]:
    """(code, key, display path) for a library path (6.6 "Chemin d'accès"); code 0 when valid."""
    text = path.strip().replace("\\", "/")
    m = _ROOT.match(text)
    if m:
        root, rest = m.group(1), m.group(2)
    elif text.startswith(("./", "../")):
        root, rest = "Disk", owner.disk_path.split("://", 1)[-1] + "/" + text
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


def _roots(machine):
    """The lint run's roots (val3check.confine): a path never leads outside them at run time either."""
    roots = machine.ws.roots
    if roots is None:
        from ..confine import Roots

        roots = machine.ws.roots = Roots([*machine.disk_roots, os.path.dirname(machine.app.folder)])
    return roots


def _real_path(machine, owner, path: str, task=None, by_name: bool = True) -> str | None:
    """The library a path leads to, found as lint finds a project's libraries (one resolution:
    loading.libraries.find_library): the Disk:// folder, --disk-root, the controller tree, else
    the only application of that name in the repository (said in the transcript: a guess)."""
    text = path.strip()
    if text.lower().startswith("disk://"):
        text = "Disk://" + text[7:]
    ws = machine.ws
    for ref in (*owner.model.libraries.values(), *owner.model.types.values()):
        # the path of a Library entry: where the loader resolved it (and said so: F016)
        if ref.resolved and ref.path.strip().replace("\\", "/").lower() == text.replace("\\", "/").lower():
            return ref.resolved
    found = find_library(text, owner.model.path, machine.disk_roots, _roots(machine), ws.repos,
                         ws.repository_index, by_name=by_name)
    if found.guessed and task is not None:
        shown = os.path.relpath(found.path, os.path.dirname(owner.model.folder)).replace(os.sep, "/")
        machine.transcript_add(task, "disk", f"libLoad {path}: not at its Disk:// place; the application of "
                                             f"that name in the repository is used, {shown} (a guess, as lint's F016)",
                               None)
    return found.path


def _model_for(machine, resolved: str) -> tuple[Any, list]:
    """The library's model, and the loader's findings when it could not be read."""
    app = machine.ws.apps.get(resolved)
    if app is not None:
        return app, []
    from ..loading import LoadOptions, load

    ws2, found = load([resolved], LoadOptions(disk_roots=list(machine.disk_roots),
                                              extra_roots=_roots(machine).folders))
    for k, v in ws2.apps.items():
        machine.ws.apps.setdefault(k, v)
    return machine.ws.apps.get(resolved), found


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


def _in_use(machine, unit) -> int:
    """13: a program of the library is running in a task; 14: the library created a task."""
    if unit is None:
        return 0
    for t in machine.scheduler.tasks:
        if t.unit is unit:
            return 14
    for t in machine.scheduler.tasks:
        g = t.gen
        while g is not None:
            code = getattr(g, "gi_code", None)
            c = machine.compiled.get(code.co_filename) if code is not None else None
            if c is not None and c.filename.startswith(f"<val3 {unit.uid}:"):
                return 13
            g = getattr(g, "gi_yieldfrom", None)
    return 0


# 6.6: what libLoad's codes mean
LOAD_CODES = {
    10: "the library identifier is not declared", 11: "loaded, but its public interface does not match",
    12: "the library holds invalid data or programs", 13: "the previous library is running in a task",
    14: "the previous library created a task that still runs", 20: "invalid root of the path",
    21: "invalid path", 22: "invalid library name", 39: "library not found",
}


def load_library(machine, owner, alias: str, path: Any, task) -> int:
    """6.7 libLoad: 0 loaded, 11 interface does not match, 12 invalid content, 13/14 the
    previous library cannot be unloaded, 20-22 bad path, 39 not found. When the identifier
    is left without a library, why is kept for the error 80 of its uses, and a library whose
    own files are invalid is reported with its findings (R040)."""
    code, display, findings = _load(machine, owner, alias, path, task)
    if owner.aliases.get(alias) is not None:
        owner.load_failures.pop(alias, None)
    elif code:
        machine.library_failed(owner, alias, display or str(path), code, LOAD_CODES.get(code, "file error"),
                               findings, task)
    return code


def _load(machine, owner, alias: str, path: Any, task=None) -> tuple[int, str, list]:
    """(libLoad's code, the library's display path, the findings that make it invalid)."""
    if not isinstance(path, str):
        return 22, "", []
    if alias not in owner.aliases:
        return 10, "", []
    code, key, display = normalise(path, owner)
    if code:
        return code, "", []
    old = owner.aliases.get(alias)
    busy = _in_use(machine, old)
    if busy:
        return busy, display, []
    snap = machine.disk.get(key, False)
    if snap is None:
        return 39, display, []
    if snap is not False:
        unit = machine.units.get("snap:" + key)
        if unit is None:
            unit = Unit(machine, snap.model, snap.display)
            unit.init_globals(snap.values)
            unit.build()
            machine.units["snap:" + key] = unit
    else:
        resolved = _real_path(machine, owner, path if path.strip() else display, task)
        if resolved is None:
            return 39, display, []
        unit = machine.units.get(resolved)
        if unit is None:
            model, found = _model_for(machine, resolved)
            if model is None:
                return 12, display, [d for d in found if d.code.startswith("F")]
            unit = Unit(machine, model, display)
            unit.init_globals()
            unit.build()
            if any(model.programs[c.name].code is not None and model.programs[c.name].body is None
                   for c in unit.compile_errors):
                return 12, display, unit.parse_findings  # 6.6: invalid programs (syntax errors)
            machine.units[resolved] = unit
            autoload_libraries(machine, unit)  # a library brings the libraries it loads at start
    owner.aliases[alias] = unit
    interface = machine.library_model(owner.model, alias)
    return (0 if _interface_ok(interface, unit) else 11), display, []


def autoload_libraries(machine, unit) -> None:
    """Load the libraries `unit`'s project declares with autoload (a missing attribute counts
    as autoload: files that do not want a library loaded write autoload="false"). owner library
    already in memory is shared (6.6)."""
    for alias, ref in unit.model.libraries.items():
        if ref.autoload and unit.aliases.get(alias) is None:
            load_library(machine, unit, alias, ref.path, None)


def _exists(machine, owner, key: str, path: str) -> bool:
    snap = machine.disk.get(key, False)
    if snap is None:
        return False
    if snap is not False:
        return True
    return _real_path(machine, owner, path, by_name=False) is not None


def lib_operation(machine, task, owner, alias: str | None, op: str, *args: Any) -> Any:
    if op == "libload":
        code = load_library(machine, owner, alias, args[0] if args else "", task)
        return float(code)
    if op in ("libsave",):
        if alias is None:
            unit = owner
        else:
            if alias not in owner.aliases or owner.aliases[alias] is None:
                return 10.0
            unit = owner.aliases[alias]
            if isinstance(unit, SystemIO):
                return 35.0  # the controller's I/O library cannot be saved ("write-protected")
        if args:
            code, key, display = normalise(args[0], owner)
            if code:
                return float(code)
            if _exists(machine, owner, key, args[0]):
                return 31.0  # 6.6: remove it first with libDelete()
        else:
            code, key, display = normalise(unit.disk_path, owner)
            if code:
                return float(code)
        machine.disk[key] = Snapshot(unit.model, copy_globals(unit.globals), display)
        machine.transcript_add(task, "disk", f"libSave {display}", None)
        return 0.0
    if op == "libdelete":
        code, key, display = normalise(args[0] if args else "", owner)
        if code:
            return float(code)
        if _exists(machine, owner, key, args[0]):
            machine.disk[key] = None
            machine.transcript_add(task, "disk", f"libDelete {display}", None)
        return 0.0
    if op == "liblist":
        path, arr = args[0], args[1]
        return _lib_list(machine, owner, path, arr)
    if op == "libpath":
        return owner.disk_path if alias is None else (owner.aliases.get(alias).disk_path if owner.aliases.get(alias) else "")
    raise ValueError(op)


def _lib_list(machine, owner, path: str, arr: Arr) -> bool:
    """6.7 libList: the names found at the path; a global array grows as needed."""
    code, key, display = normalise(path + "/x", owner) if path.strip() else (0, "disk://x", "Disk://x")
    names: set[str] = set()
    prefix = key[:-1] if not code else ""
    for k, snap in machine.disk.items():
        if snap is not None and k.startswith(prefix):
            names.add(snap.display[len(display) - 1:].split("/")[0])
    folder = None
    real = _real_path(machine, owner, (path.rstrip("/") + "/") if path.strip() else "Disk://", by_name=False)
    if real is None:
        base = os.path.dirname(os.path.dirname(os.path.abspath(owner.model.path)))
        rest = path.split("://", 1)[-1].strip("/")
        cand = os.path.normpath(os.path.join(base, rest)) if rest else base
        roots = _roots(machine)  # never list a folder outside the run's roots (val3check.confine)
        folder = cand if roots.holds(cand) and roots.allows(cand) and os.path.isdir(cand) else None
    else:
        folder = os.path.dirname(os.path.dirname(real))
    if folder:
        for n in listdir(folder):
            if os.path.isdir(os.path.join(folder, n)) and not n.startswith("."):
                names.add(n)
    for k, snap in machine.disk.items():
        if snap is None:
            names.discard(k.rsplit("/", 1)[-1])
    out = sorted(names, key=str.lower)
    return len(out) <= arr.fill_strings(out)
