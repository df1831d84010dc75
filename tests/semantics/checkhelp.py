"""Helpers for the compiler-check tests (N, T, L codes): lint a generated application and keep
the findings of those families."""

from __future__ import annotations

from pathlib import Path

from support import lint

from val3check.config import Settings
from val3check.rules.catalogue import OPT_IN
from val3check.testing import code_position, write_app, write_files

# what the checker finds, opt-in rules included (T025: off by default in `val3check lint`)
ALL = Settings(extend_select=sorted(OPT_IN))

MINE = ("N", "T", "L0", "L1")


def findings(tmp_path: Path, code: str, *, globals_=(), locals_=(), programs=None, version="s7.11",
             select: str | None = None) -> list[tuple[str, int, int]]:
    """(code, line, col) of the N/T/L findings of start() holding `code`; line/col as in the
    snippet (line 1 = begin) when the finding is in start.pgx, else the file's."""
    folder = write_app(tmp_path, code, globals_=globals_, locals_=locals_, programs=programs, version=version)
    return collect(folder, select)


def collect(folder: Path, select: str | None = None, with_path: bool = False) -> list:
    run = lint([folder], ALL, cwd=folder.parent)
    out = []
    for d in run.result.diagnostics:
        if not d.code.startswith(MINE) or d.code in ("L001", "L002", "L003", "L004", "L005"):
            continue
        if select is not None and not d.code.startswith(select):
            continue
        line, col = d.line, d.col
        if d.path.endswith("start.pgx") and not with_path:
            line, col = _snippet_position(d.line, d.col)
        out.append((d.code, Path(d.path).name, line, col) if with_path else (d.code, line, col))
    return out


def messages(folder: Path) -> list[str]:
    run = lint([folder], ALL, cwd=folder.parent)
    return [d.message for d in run.result.diagnostics if d.code.startswith(MINE)]


def codes(tmp_path: Path, code: str, **kw) -> list[str]:
    return [f[0] for f in findings(tmp_path, code, **kw)]


def _snippet_position(line: int, col: int) -> tuple[int, int]:
    first_line, _ = code_position(1, 1)
    return line - first_line + 1, col


__all__ = ["codes", "collect", "findings", "lint", "messages", "write_app", "write_files"]
