"""Chapter 6: libraries. `alias:libLoad(path)`, `alias:libSave()`, `libDelete(path)`,
`libList(path, array)`, `libPath()`, `alias:libExist(symbol)`, and the access to a library's
data and programs through its identifier (`alias:x`, `call alias:p()`), error 80 while the
library is not loaded (6.4). The loading itself (the simulated disk, 6.6) is libraries.py."""

from __future__ import annotations

from typing import Any

from ...language.runtime_errors import Val3RuntimeError
from ..libraries import lib_operation
from ..waiting import YIELD

E = Val3RuntimeError


def _library(unit, alias: str):
    if alias not in unit.aliases:
        raise E(80, f"no library identifier {alias}")
    lib = unit.aliases[alias]
    if lib is None:
        why = unit.load_failures.get(alias)
        raise E(80, f"library {alias} is not loaded ({why})" if why else f"library {alias} is not loaded (libLoad)")
    return lib


def LG(unit, alias: str, name: str) -> Any:
    """`alias:name`: the container of a public global of the loaded library."""
    c = _library(unit, alias).public_global(name)
    if c is None:
        raise E(80, f"{alias}:{name} is not in the loaded library")
    return c


def LP(unit, alias: str, name: str):
    """`call alias:name(...)`: the program function of the loaded library."""
    p = _library(unit, alias).public_program(name)
    if p is None:
        raise E(80, f"{alias}:{name}() is not in the loaded library")
    return p.func


def LIBDEF(unit, alias: str, name: str) -> bool:
    """isDefined(alias:name) (2.5.4): false while the library is not loaded."""
    lib = unit.aliases.get(alias)
    return lib is not None and lib.public_global(name) is not None


def _operation(task, unit, alias: str | None, op: str, *args):
    result = lib_operation(task.machine, task, unit, alias, op, *args)
    yield from YIELD(task)  # 5.4: disk access hands over to the next task
    return result


def I_lib(task, unit, alias: str, op: str, *args):
    """alias:libLoad / libSave / libDelete / libList (6.7)."""
    return (yield from _operation(task, unit, alias, op, *args))


def I_lib_now(task, unit, alias: str, op: str, *args):
    """alias:libPath() and alias:libExist(symbol): answered from memory, no hand-over."""
    if op == "libpath":
        lib = unit.aliases.get(alias)
        if alias not in unit.aliases:
            raise E(80, f"no library identifier {alias}")
        return lib.disk_path if lib is not None else ""
    if op == "libexist":
        lib = unit.aliases.get(alias)
        if lib is None:
            return False
        sym = args[0] if args else ""
        if sym.endswith("()"):
            return lib.public_program(sym[:-2]) is not None
        return lib.public_global(sym) is not None
    raise E(70, op)


def I_libsave(task, unit, *args):
    return (yield from _operation(task, unit, None, "libsave", *args))


def I_libdelete(task, unit, path: str):
    return (yield from _operation(task, unit, None, "libdelete", path))


def I_liblist(task, unit, path: str, arr):
    return (yield from _operation(task, unit, None, "liblist", path, arr))


def I_libpath(task, unit) -> str:
    return unit.disk_path


# ---- files of the controller's disk: the system library's `$file...` instructions ---------------
# (virtual_disk.py: a disk in memory that the scenario fills; a public description of the CS8
# "Expansion" add-on gives their signatures, quoted in docs/sim.md). The disk is the one chapter
# 6 names (6.6 "Chemin d'accès": `Disk://...`); an access to it hands over to the next task (5.4:
# "Les instructions accédant au contenu du disque"), as libLoad does.


def _disk_said(task, what: str) -> None:
    task.machine.transcript_add(task, "file", what, None)


def _shown(v) -> str:
    return f"{v:g}" if isinstance(v, float) else str(v)


def _count(n: float, room: int) -> int:
    return max(0, min(room, int(n) if abs(n) < 1e9 else 0))


def S_fileopen(task, unit, path: str, mode: str):
    """num $fileOpen(string sPath, string sMode): a handle from 0, -1 when it cannot be opened."""
    disk = task.machine.files
    handle = disk.open(path, mode)
    _disk_said(task, f"$fileOpen {path} {mode} -> {handle}")
    if handle < 0 and isinstance(mode, str) and mode.strip().lower() == "r" and not disk.exists(path):
        # the controller's disk is the cell's: the scenario gives its files (as R009 names the entry)
        task.machine.note_outside(task, f"$fileOpen: {path} is not on the simulated controller's disk (the scenario's "
                                        f'[[files]] entry with path = "{path}" gives it): -1')
    yield from YIELD(task)
    return float(handle)


def S_fileget(task, unit, handle: float, arr, count: float):
    """num $fileGet(num nHandle, string& sLine[], num nNbLines) / (num nHandle, num& nBytes[], num
    nNbBytes): reads lines (or bytes) into the array from its start; the number read: 0 at the
    end of the file, and 0 when the handle is not open for reading (nothing read: what public
    code that reads until 0 expects)."""
    disk = task.machine.files
    room = _count(count, arr.size())
    got = disk.read_lines(handle, room) if arr.t == "string" else disk.read_bytes(handle, room)
    yield from YIELD(task)
    if got is None:
        return 0.0
    for i, v in enumerate(got):
        arr.data[arr.off + i] = v if arr.t == "string" else float(v)
    return float(len(got))


def S_fileset(task, unit, handle: float, arr, count: float):
    """num $fileSet(num nHandle, string sLines[], num nNbLines) / (num nHandle, num nBytes[], num
    nNbBytes): writes lines (each followed by "\n") or bytes (nearest integer modulo 256); the
    number written, -1 when the handle is not open for writing."""
    n = _count(count, arr.size())
    values = arr.data[arr.off:arr.off + n]
    if arr.t == "string":
        data = "".join(f"{v}\n" for v in values).encode("utf-8")
    else:
        data = bytes(int(v + 0.5) % 256 if abs(v) < 1e15 else 0 for v in values)
    ok = task.machine.files.write(handle, data)
    yield from YIELD(task)
    return float(n) if ok else -1.0


def S_fileclose(task, unit, handle: float):
    """bool $fileClose(num nHandle): true when the handle was open."""
    done = task.machine.files.close(handle)
    _disk_said(task, f"$fileClose {_shown(handle)} -> {'true' if done else 'false'}")
    yield from YIELD(task)
    return done


def S_fileexists(task, unit, path: str):
    """bool $fileExists(string sPath): a file (or a folder) of the disk."""
    yield from YIELD(task)
    return task.machine.files.exists(path)


def S_delete(task, unit, path: str):
    """bool $delete(string sPath): removes a file or a folder; false when there is none, or it is
    open."""
    done = task.machine.files.delete(path)
    _disk_said(task, f"$delete {path} -> {'true' if done else 'false'}")
    yield from YIELD(task)
    return done


def S_ddel(task, unit, path: str):
    """bool $ddel(string sPath): met in real code, not described: read as the deletion of a folder
    and what it holds (R041 says so)."""
    task.machine.note_outside(task, "$ddel: not described in public material; the simulator deletes the folder (or "
                                    "file) of the disk it names and returns whether something was deleted")
    return (yield from S_delete(task, unit, path))


def S_copy(task, unit, src: str, dst: str):
    """bool $copy(string sFrom, string sTo)."""
    done = task.machine.files.copy(src, dst)
    _disk_said(task, f"$copy {src} {dst} -> {'true' if done else 'false'}")
    yield from YIELD(task)
    return done


def S_rename(task, unit, src: str, dst: str):
    """bool $rename(string sFrom, string sTo): moves the file."""
    done = task.machine.files.copy(src, dst, move=True)
    _disk_said(task, f"$rename {src} {dst} -> {'true' if done else 'false'}")
    yield from YIELD(task)
    return done


SYSTEM_FILES = (
    ("$fileOpen", S_fileopen, ("value", "value"), "num"), ("$fileGet", S_fileget, ("value", "array", "value"), "num"),
    ("$fileSet", S_fileset, ("value", "array", "value"), "num"), ("$fileClose", S_fileclose, ("value",), "bool"),
    ("$fileExists", S_fileexists, ("value",), "bool"), ("$delete", S_delete, ("value",), "bool"),
    ("$ddel", S_ddel, ("value",), "bool"), ("$copy", S_copy, ("value", "value"), "bool"),
    ("$rename", S_rename, ("value", "value"), "bool"),
)


def register(registry) -> None:
    for name, func, params, returns in SYSTEM_FILES:
        registry.system(name, func, params, returns, blocking=True)
    # alias:libLoad(), alias:libExist() and the alias forms of the others: compiler/calls.py
    registry.inline("libLoad", "libExist", chapter=__name__)
    registry.helpers(LG=LG, LP=LP, LIBDEF=LIBDEF, I_lib=I_lib, I_lib_now=I_lib_now)
    registry.instruction("libPath", I_libpath)
    for name, func in (("libSave", I_libsave), ("libDelete", I_libdelete), ("libList", I_liblist)):
        registry.instruction(name, func, blocking=True)
