"""Names that s8 web user pages bind to: the `*.bindings.json` files of an application.

s8 (CS9) user pages are web pages kept with the application; their `*.bindings.json` files tie
page events to the application's programs and data. What their keys mean is not public, so
every string they hold that could be a VAL 3 name is kept: a program or global named there is
used by the page even if no program calls it (S003, S004 stay quiet for it), which can only make
those rules quieter.

Only files inside the application folder are read (a few levels down, no hidden folders,
symbolic links to elsewhere ignored), each within the size limit.
"""

from __future__ import annotations

import os
import re

SUFFIX = ".bindings.json"
_DEPTH = 3
_MAX_FOLDERS = 200  # an application folder that holds a whole repository is not searched further
_SKIP = frozenset({"node_modules", "__pycache__", "site-packages", "venv", "virtualenv", "bower_components"})
_NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")


def _files(folder: str) -> list[str]:
    out = []
    top = os.path.realpath(folder)
    for seen, (here, dirs, names) in enumerate(os.walk(folder)):
        if seen >= _MAX_FOLDERS:
            break
        depth = os.path.relpath(here, folder).count(os.sep) + (here != folder)
        dirs[:] = sorted(d for d in dirs if not d.startswith(".") and d not in _SKIP) if depth < _DEPTH else []
        for name in sorted(names):
            if name.lower().endswith(SUFFIX):
                path = os.path.join(here, name)
                real = os.path.realpath(path)
                if os.path.commonpath([real, top]) == top and os.path.isfile(real):
                    out.append(path)
    return out


def _strings(doc: object) -> list[str]:
    out: list[str] = []
    stack = [doc]
    while stack:
        v = stack.pop()
        if isinstance(v, str):
            out.append(v)
        elif isinstance(v, dict):
            out.extend(k for k in v if isinstance(k, str))
            stack.extend(v.values())
        elif isinstance(v, list):
            stack.extend(v)
    return out


def bound_names(folder: str, max_size: int) -> tuple[set[str], list[str]]:
    """(lower-case names found in the application's bindings files, the files read)."""
    from ..confine import Refused, Roots, read_bytes

    names: set[str] = set()
    read: list[str] = []
    roots = Roots([folder])
    files = _files(folder)
    if files:
        import json  # only for s8 applications that have user pages: lint starts without it
    for path in files:
        try:  # the one file gate (val3check.confine): inside the folder, a regular file, its size first
            doc = json.loads(read_bytes(path, roots, max_size).decode("utf-8-sig"))
        except (Refused, ValueError, RecursionError):
            continue  # not ours to report: the page editor owns these files
        read.append(path)
        for text in _strings(doc):
            # "pick", "App:pick", "pick()": any name the string holds
            names.update(m.group().lower() for m in _NAME.finditer(text))
    return names, read
