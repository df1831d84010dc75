"""Inline suppressions written as VAL 3 comments.

    // val3check: ignore[S101, T2]     codes or prefixes
    // val3check: ignore               every rule

A comment after code suppresses findings on its own line. The manual (2.2.5) wants `//` at the
start of a line, so a comment on a line of its own also covers the next line that holds code.
The code text is scanned directly, so suppressions work even in a program that does not parse.
"""

from __future__ import annotations

import re

from .loading.model import Application

_DIRECTIVE = re.compile(r"//\s*val3check\s*:\s*ignore\b(?:\s*\[([^\]]*)\])?", re.IGNORECASE)
ALL = "*"


def collect(app: Application) -> dict[tuple[str, int], set[str]]:
    """(path, file line) -> suppressed codes or prefixes ({"*"} for every rule)."""
    found: dict[tuple[str, int], set[str]] = {}
    for program in app.programs.values():
        if not program.code or "val3check" not in program.code:
            continue
        lines = program.code.split("\n")
        path = program.origin.path
        for k, text in enumerate(lines, start=1):
            m = _DIRECTIVE.search(text)
            if not m:
                continue
            codes = {c.strip().upper() for c in (m.group(1) or "").split(",") if c.strip()} or {ALL}
            targets = [k]
            if text[: m.start()].strip() == "":  # comment alone on its line: also the next code line
                nxt = k + 1
                while nxt <= len(lines) and (not lines[nxt - 1].strip() or lines[nxt - 1].lstrip().startswith("//")):
                    nxt += 1
                if nxt <= len(lines):
                    targets.append(nxt)
            for t in targets:
                line = program.code_map.to_file(t, 1).line
                found.setdefault((path, line), set()).update(codes)
    return found


def is_suppressed(code: str, path: str, line: int, table: dict[tuple[str, int], set[str]]) -> bool:
    codes = table.get((path, line))
    if not codes:
        return False
    return ALL in codes or any(code.startswith(c) for c in codes)
