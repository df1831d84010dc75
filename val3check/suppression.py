"""Inline suppressions written as VAL 3 comments.

    // val3check: ignore[S101, T2]     codes or prefixes
    // val3check: ignore               every rule

A comment after code suppresses findings on its own line. The manual (2.2.5) wants `//` at the
start of a line, so a comment on a line of its own also covers the next line that holds code.
The code text is scanned directly, so suppressions work even in a program that does not parse.

Each directive remembers what it suppressed, so that the run can report a code that is no rule
of val3check (S020) and a directive, or a code in it, that suppressed nothing (S021, as ruff's
RUF100). A finding counts as suppressed whether or not its rule is selected, so that a directive
for a rule turned off in one configuration is not "unused" in it; a program that does not parse
gets no S021 (its semantic findings are unknown).
"""

from __future__ import annotations

import re

from .diagnostics import Diagnostic
from .light_dataclass import dataclass, field
from .loading.model import Application
from .rules import codes

_DIRECTIVE = re.compile(r"//\s*val3check\s*:\s*ignore\b(?:\s*\[([^\]]*)\])?", re.IGNORECASE)
ALL = "*"


@dataclass(slots=True, eq=False)
class Directive:
    path: str
    line: int  # file position of the comment
    col: int
    end_col: int
    codes: tuple[str, ...]  # codes or prefixes, upper case; (ALL,) for every rule
    covers: tuple[int, ...]  # the file lines it suppresses findings on
    used: set[str] = field(default_factory=set)  # the entries of `codes` that suppressed a finding


class Suppressions:
    """Every directive of the programs checked, by (path, file line) covered."""

    def __init__(self) -> None:
        self.directives: list[Directive] = []
        self._by_line: dict[tuple[str, int], list[Directive]] = {}

    def add(self, directive: Directive) -> None:
        self.directives.append(directive)
        for line in directive.covers:
            self._by_line.setdefault((directive.path, line), []).append(directive)

    def suppresses(self, code: str, path: str, line: int) -> bool:
        """Is a finding of `code` at `path`:`line` suppressed? Marks what suppressed it."""
        hit = False
        for directive in self._by_line.get((path, line), ()):
            for entry in directive.codes:
                if entry == ALL or code.startswith(entry):
                    directive.used.add(entry)
                    hit = True
        return hit

    def findings(self, known: list[str], unparsed: set[str]) -> list[Diagnostic]:
        """S020 for each code or prefix that matches no rule of `known`; S021 for a directive
        (or the codes of one) that suppressed nothing, except in the files of `unparsed`."""
        out = []
        for d in self.directives:
            unknown = [c for c in d.codes if c != ALL and not any(k.startswith(c) for k in known)]
            for code in unknown:
                out.append(Diagnostic(
                    codes.UNKNOWN_SUPPRESSION_CODE,
                    f"'{code}' in this suppression is no rule code or prefix of val3check (see `val3check rules`)",
                    d.path, d.line, d.col, d.line, d.end_col))
            if d.path in unparsed:
                continue
            unused = [c for c in d.codes if c not in d.used and c not in unknown]
            if not unused:
                continue
            if len(unused) == len(d.codes):
                what = "every rule" if unused == [ALL] else ", ".join(unused)
                lines = " and ".join(str(n) for n in d.covers)
                message = f"unused suppression: no finding of {what} on line {lines}; remove the comment"
            else:
                message = f"unused suppression code(s): {', '.join(unused)} suppress nothing here; remove them"
            out.append(Diagnostic(codes.UNUSED_SUPPRESSION, message, d.path, d.line, d.col, d.line, d.end_col))
        return out


def collect(app: Application, into: Suppressions | None = None) -> Suppressions:
    """The directives of `app`'s programs."""
    found = into if into is not None else Suppressions()
    for program in app.programs.values():
        if not program.code or "val3check" not in program.code:
            continue
        lines = program.code.split("\n")
        path = program.origin.path
        for k, text in enumerate(lines, start=1):
            m = _DIRECTIVE.search(text)
            if not m:
                continue
            listed = tuple(dict.fromkeys(c.strip().upper() for c in (m.group(1) or "").split(",") if c.strip()))
            listed = listed or (ALL,)
            targets = [k]
            if text[: m.start()].strip() == "":  # comment alone on its line: also the next code line
                nxt = k + 1
                while nxt <= len(lines) and (not lines[nxt - 1].strip() or lines[nxt - 1].lstrip().startswith("//")):
                    nxt += 1
                if nxt <= len(lines):
                    targets.append(nxt)
            start = program.code_map.to_file(k, m.start() + 1)
            end = program.code_map.to_file(k, m.end())
            covers = tuple(dict.fromkeys(program.code_map.to_file(t, 1).line for t in targets))
            found.add(Directive(path, start.line, start.col, end.col + 1, listed, covers))
    return found
