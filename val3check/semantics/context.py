"""What every check of one program needs: the application, its symbol table, the program's
scope, and where findings go."""

from __future__ import annotations

from ..diagnostics import Diagnostic, Severity
from ..language.target import Target, target_for
from ..loading.model import Application, Program, Workspace
from ..rules import codes
from . import messages as M
from .symbols import AppSymbols, Scope


class Context:
    """One program being checked.

    `strict_version`: the application is s6/s7 (or of unknown version): an unknown instruction
    name is an error there; s8 and later may have instructions the s7 catalogue lacks.
    `globals_known`: False for .pgx files without project (globals, libraries, user types and
    possibly programs unknown): undefined names are then not reported.
    `target`: the controller/version/arm the application is checked for (language/target.py);
    by default the version of its project file.
    """

    __slots__ = (
        "_s7_only",
        "app",
        "diags",
        "dio_assign_removed",
        "globals_known",
        "guess",
        "guessed_libraries",
        "guessed_types",
        "major",
        "path",
        "program",
        "s8_evidence",
        "scope",
        "strict_version",
        "table",
        "target",
        "workspace",
    )

    def __init__(self, workspace: Workspace, app: Application, table: AppSymbols, diags: list[Diagnostic],
                 target: Target | None = None) -> None:
        self.workspace = workspace
        self.app = app
        self.table = table
        self.diags = diags
        self.target = target if target is not None else target_for(app.version, None)
        self.major = self.target.major
        self.strict_version = self.major is None or self.major < 8
        self.globals_known = app.globals_known
        # 3.5.2: "L'opérateur '=' entre les deux variables dio n'existe plus avec VAL 3 s7".
        self.dio_assign_removed = self.major is None or self.major >= 7
        self.scope: Scope | None = None
        self.program: Program | None = None
        self.path = ""
        # The code uses s8 forms although the project file says s7 (T030), or the application
        # has s8 web user pages (*.bindings.json): it is CS9 code, and the findings that only
        # hold on s7 (`_s7_only`) are turned into their s8 warning.
        self.s8_evidence = bool(app.ui_names) or self.target.cs9
        self._s7_only: list[tuple[int, str, str]] = []
        # Libraries and user types found by name in the repository (F016): a guess. A finding of
        # a statement that consulted one depends on the guess: at most a warning, and it says so
        # (`guess`: the note of the statement being checked, "" when it consulted none).
        self.guessed_libraries = {alias: M.guessed("library", alias, ref.path, ref.guessed)
                                  for alias, ref in app.libraries.items() if ref.guessed}
        self.guessed_types = {ref.resolved: M.guessed("user type", ref.name, ref.path, ref.guessed)
                              for a in workspace.apps.values() for ref in a.types.values()
                              if ref.guessed and ref.resolved}
        self.guess = ""

    def consulted_library(self, alias: str) -> None:
        """The statement being checked uses the library `alias`."""
        note = self.guessed_libraries.get(alias)
        if note and not self.guess:
            self.guess = note

    def consulted_type(self, app_path: str | None) -> None:
        """The statement being checked uses a value of the user type of application `app_path`."""
        note = self.guessed_types.get(app_path) if app_path else None
        if note and not self.guess:
            self.guess = note

    def names_complete(self, kind: str, app: Application | None = None) -> bool:
        """Every `kind` ("data"/"program") file of `app` (default: the checked one) was read:
        an unknown name is then really undefined. When a listed file could not be read, the
        loader reported it once and the name checks stay quiet."""
        app = app or self.app
        return app.layout != "pgx-only" and kind not in app.unread

    def program_may_exist(self, name: str, app: Application | None = None) -> bool:
        """A program `name` may exist although it is not loaded: a listed program file that
        could not be read is named after it (files are named after their program), or the
        application has no project file (its other programs are not known)."""
        app = app or self.app
        return app.layout == "pgx-only" or name.lower() in app.unread_programs

    def s8_only(self, what: str, node: object) -> None:
        """`what` (a form, an instruction, a statement) exists from s8 on: fine on an s8 target,
        T031 (error) on an s7 target the configuration names, T030 (warning) when the project
        file says s7 (or no version): real CS9 code is often saved that way."""
        t = self.target
        if t.s8 or t.cs9:
            return
        if t.explicit:
            self.report_at(codes.S8_ON_S7_TARGET, M.s8_on_s7_target(what, t.label), node)
        else:
            self.s8_evidence = True
            self.report_at(codes.S8_ONLY, M.s8_only(what, t.label), node)

    def s7_only(self, code: str, message: str, node: object, s8_code: str, s8_message: str) -> None:
        """A finding that is sure on s7 but not on s8 (a call matching no s7 signature may be an
        s8 form val3check does not know): reported as `code`, and turned into `s8_code` by
        `settle()` when the application turns out to use s8 forms."""
        note = f" [{self.guess}]" if self.guess else ""
        self._s7_only.append((len(self.diags), s8_code, s8_message + note))
        self.report_at(code, message, node)

    def settle(self) -> None:
        """After every program is checked: code that uses s8 forms (T030) is CS9 code whatever its
        project file says, so its s7-only findings become the s8 warnings (unless the
        configuration names the target)."""
        if self.s8_evidence and not self.target.explicit:
            for i, code, message in self._s7_only:
                d = self.diags[i]
                self.diags[i] = Diagnostic(code, message, d.path, d.line, d.col, d.end_line, d.end_col,
                                           at_most=d.at_most)
        self._s7_only.clear()

    def enter(self, program: Program) -> None:
        self.guess = ""
        self.program = program
        self.scope = self.table.scope(program)
        self.path = program.origin.path

    def report(self, code: str, message: str, line: int, col: int, end_line: int | None = None,
               end_col: int | None = None, path: str | None = None, fix: tuple | None = None) -> None:
        if self.guess:  # it depends on a guess: at most a warning, and no certain fix
            self.diags.append(Diagnostic(code, f"{message} [{self.guess}]", path or self.path, line, col, end_line,
                                         end_col, at_most=Severity.WARNING))
            return
        self.diags.append(Diagnostic(code, message, path or self.path, line, col, end_line, end_col, fix=fix))

    def report_at(self, code: str, message: str, node: object, fix: tuple | None = None) -> None:
        """At a node of the tree: its start, and its end when the node knows it. `fix`: what
        `lint --fix` may do (diagnostics.Diagnostic.fix)."""
        end_line = getattr(node, "end_line", None)
        end_col = getattr(node, "end_col", None) if end_line is not None else None
        self.report(code, message, node.line, node.col, end_line, end_col, fix=fix)  # type: ignore[attr-defined]
