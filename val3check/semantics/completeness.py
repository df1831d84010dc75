"""Whether an application's declarations are complete: every data (or program) file its project
lists could be read.

When a listed `.dtx` is missing, malformed or refused (F001-F005), the application's globals
are only partly known, and "undefined variable" would be reported for every use of the missing
ones; likewise for programs and missing `.pgx` files. The loader reports the file once; the
name checks then stay quiet. The model has no flag for this, so the project is read again, only
when a check is about to report an undefined name (rare), and the answer is cached.
"""

from __future__ import annotations

import os

from ..loading import reader as rd
from ..loading import resolve as rs
from ..loading.model import Application
from ..loading.xmlread import read_xml

MAX_SIZE = 16 * 1024 * 1024  # the loader's default limit (LoadOptions.max_file_size)

def files_complete(app: Application, kind: str, cache: dict[tuple[str, str], bool]) -> bool:
    """True when every `kind` ("data" or "program") file listed by `app`'s project was read.
    `cache` keeps the answers of one run (files may change between runs)."""
    if app.layout == "pgx-only":
        return False
    key = (app.path, kind)
    hit = cache.get(key)
    if hit is None:
        hit = cache[key] = _complete(app, kind)
    return hit


def _complete(app: Application, kind: str) -> bool:
    res = read_xml(app.path, MAX_SIZE)
    if res.root is None:
        return False
    try:
        project = rd.read_project(res.root, rd.Sink(app.path))
    except (ValueError, AttributeError, TypeError):  # pragma: no cover - a project the loader read
        return False
    entries = project.data if kind == "data" else project.programs
    folder = os.path.dirname(app.path)
    for rel, _node in entries:
        path = rs.find_path(folder, rel)
        if path is None or not os.path.isfile(path):
            return False
        root = read_xml(path, MAX_SIZE).root
        if root is None or rd.check_root(root, "data" if kind == "data" else "programs", path)[0] is None:
            return False
    return True
