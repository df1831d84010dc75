"""What the HTML report quotes of the application: the lines around a diagnostic, from files
inside the given roots only (the application's folder by default)."""

from __future__ import annotations

import os

from .._common import SourceCache

SEVERITY_ORDER = {"info": 0, "warning": 1, "error": 2}  # for the verdict: at or above --fail-on fails
EXCERPT_AROUND = 2


def _inside(path: str, roots: list[str]) -> bool:
    """Whether `path` (its real path) is inside one of `roots`."""
    real = os.path.realpath(path)
    for root in roots:
        r = os.path.realpath(root)
        try:
            if os.path.commonpath([real, r]) == r:
                return True
        except ValueError:  # another drive
            continue
    return False


def excerpt(cache: SourceCache, path: str | None, line: int | None, roots: list[str]) -> dict | None:
    """The lines around `line` of `path` ({first_line, lines}), or None when the file is outside
    the roots, unreadable or shorter."""
    if not path or not line or not _inside(path, roots):
        return None
    lines = cache.lines(path)
    if lines and lines[-1] == "":  # the text after the last newline is not a line
        lines = lines[:-1]
    if lines is None or line > len(lines):
        return None
    first = max(1, line - EXCERPT_AROUND)
    return {"first_line": first, "lines": lines[first - 1:line + EXCERPT_AROUND]}
