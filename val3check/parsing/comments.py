"""The `//` comments of VAL 3 code, with file positions (also for code with syntax errors)."""

from __future__ import annotations

import re

from ..positions import SourceMap
from . import ast as A

_COMMENT_SCAN = re.compile(r'"[^"\n]*"?|//[^\n]*')


def scan_comments(code: str, source_map: SourceMap | None = None) -> list[A.Comment]:
    """Every `//` comment of `code` (outside strings), with file positions. Works on code with
    syntax errors too: the lint driver can read suppression comments there."""
    sm = source_map if source_map is not None else SourceMap()
    out: list[A.Comment] = []
    line = 1
    line_start = 0
    pos = 0
    for m in _COMMENT_SCAN.finditer(code):
        text = m.group()
        if text[0] == '"':
            continue
        start = m.start()
        nl = code.count("\n", pos, start)
        if nl:
            line += nl
            line_start = code.rindex("\n", 0, start) + 1
        pos = start
        col = start - line_start + 1
        starts_line = not code[line_start:start].strip()
        p = sm.to_file(line, col)
        out.append(A.Comment(text.rstrip("\r"), p.line, p.col, starts_line))
    return out

