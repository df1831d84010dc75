"""What every check of one program needs: the application, its symbol table, the program's
scope, and where findings go."""

from __future__ import annotations

from ..diagnostics import Diagnostic
from ..loading.model import Application, Program, Workspace
from .symbols import AppSymbols, Scope


class Context:
    """One program being checked.

    `strict_version`: the application is s6/s7 (or of unknown version): an unknown instruction
    name is an error there; s8 and later may have instructions the s7 catalogue lacks.
    `globals_known`: False for .pgx files without project (globals, libraries, user types and
    possibly programs unknown): undefined names are then not reported.
    """

    __slots__ = (
        "app",
        "diags",
        "dio_assign_removed",
        "globals_known",
        "major",
        "path",
        "program",
        "scope",
        "strict_version",
        "table",
        "workspace",
    )

    def __init__(self, workspace: Workspace, app: Application, table: AppSymbols, diags: list[Diagnostic]) -> None:
        self.workspace = workspace
        self.app = app
        self.table = table
        self.diags = diags
        self.major = app.version_major
        self.strict_version = self.major is None or self.major < 8
        self.globals_known = app.globals_known
        # 3.5.2: "L'opérateur '=' entre les deux variables dio n'existe plus avec VAL 3 s7".
        self.dio_assign_removed = self.major is None or self.major >= 7
        self.scope: Scope | None = None
        self.program: Program | None = None
        self.path = ""

    def names_complete(self, kind: str, app: Application | None = None) -> bool:
        """Every `kind` ("data"/"program") file of `app` (default: the checked one) was read:
        an unknown name is then really undefined. When a listed file could not be read, the
        loader reported it once and the name checks stay quiet."""
        app = app or self.app
        return app.layout != "pgx-only" and kind not in app.unread

    def enter(self, program: Program) -> None:
        self.program = program
        self.scope = self.table.scope(program)
        self.path = program.origin.path

    def report(self, code: str, message: str, line: int, col: int, end_line: int | None = None,
               end_col: int | None = None, path: str | None = None) -> None:
        self.diags.append(Diagnostic(code, message, path or self.path, line, col, end_line, end_col))

    def report_at(self, code: str, message: str, node: object) -> None:
        """At a node of the tree: its start, and its end when the node knows it."""
        end_line = getattr(node, "end_line", None)
        end_col = getattr(node, "end_col", None) if end_line is not None else None
        self.diags.append(Diagnostic(code, message, self.path, node.line, node.col, end_line, end_col))  # type: ignore[attr-defined]
