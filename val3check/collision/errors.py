"""Errors of the collision package."""

from __future__ import annotations


class CellError(ValueError):
    """A cell file that cannot be used. `problems` lists (path, line, column, message), one per
    problem found (the reader reports them all, not only the first); str() has one per line as
    `path:line:col: message`."""

    def __init__(self, problems: list[tuple[str, int, int, str]]) -> None:
        self.problems = list(problems)
        super().__init__("\n".join(_fmt(p) for p in self.problems))


def _fmt(p: tuple[str, int, int, str]) -> str:
    path, line, col, msg = p
    if line:
        return f"{path}:{line}:{col}: {msg}"
    return f"{path}: {msg}"


class MeshProblem(ValueError):
    """Why a mesh file cannot be used (the message names the file)."""
