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


def register(registry) -> None:
    # alias:libLoad(), alias:libExist() and the alias forms of the others: compiler/calls.py
    registry.inline("libLoad", "libExist", chapter=__name__)
    registry.helpers(LG=LG, LP=LP, LIBDEF=LIBDEF, I_lib=I_lib, I_lib_now=I_lib_now)
    registry.instruction("libPath", I_libpath)
    for name, func in (("libSave", I_libsave), ("libDelete", I_libdelete), ("libList", I_liblist)):
        registry.instruction(name, func, blocking=True)
