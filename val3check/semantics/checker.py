"""What the controller's compiler refuses when it loads an application (N, T and L codes).

`check_application(workspace, app)` checks the declarations of the project (declarations.py),
then the code of every program that parsed (statements.py, expressions.py, calls.py), against
the application's symbol table (symbols.py). Programs whose code has syntax errors
(`body is None`) are skipped; their declarations still serve the other programs' calls.

For reuse (suspicious-pattern rules, an interpreter): `symbols.build(workspace, app)` gives the
symbol table, `program_typer(workspace, app, program)` an ExprTyper whose `typeof(node)`
types any expression of that program (diagnostics go to its `ctx.diags`), and
`expression_types(workspace, app)` the type of every expression the checks typed (the
simulator's compiler reads it).
"""

from __future__ import annotations

from ..diagnostics import Diagnostic
from ..language.target import Target
from ..loading.model import Application, Program, Workspace
from . import symbols
from .calls import check_call_expr
from .context import Context
from .declarations import check_declarations
from .expressions import ExprTyper
from .statements import StatementChecker
from .vtypes import Val


def check_application(workspace: Workspace, app: Application, target: Target | None = None) -> list[Diagnostic]:
    """`target`: what the application is checked for (default: its project file's version)."""
    table = symbols.build(workspace, app)
    ctx = Context(workspace, app, table, [], target)
    diags: list[Diagnostic] = check_declarations(table, ctx.target)
    ctx.diags = diags
    checker = StatementChecker(ctx, {})
    for program in app.programs.values():
        body = program.body
        if body is None:
            continue
        ctx.enter(program)
        checker.literal_vals.clear()
        checker.check(body)
    ctx.settle()
    return diags


def program_typer(workspace: Workspace, app: Application, program: Program,
                  table: symbols.AppSymbols | None = None, target: Target | None = None) -> ExprTyper:
    """An expression typer for `program` (its diagnostics collect in `typer.ctx.diags`)."""
    ctx = Context(workspace, app, table or symbols.build(workspace, app), [], target)
    ctx.enter(program)
    return ExprTyper(ctx, check_call_expr)


class _RecordingChecker(StatementChecker):
    def __init__(self, ctx: Context, types: dict[int, Val]) -> None:
        super().__init__(ctx, {})
        self.types = types

    def typeof(self, node: object) -> Val:
        v = super().typeof(node)
        self.types[id(node)] = v
        return v


def expression_types(workspace: Workspace, app: Application,
                     table: symbols.AppSymbols | None = None) -> dict[int, Val]:
    """The Val of every expression of every program of `app` that parsed, by `id(node)`, as
    the checks type it (the findings are dropped: lint reports them)."""
    types: dict[int, Val] = {}
    ctx = Context(workspace, app, table or symbols.build(workspace, app), [])
    checker = _RecordingChecker(ctx, types)
    for program in app.programs.values():
        if program.body is None:
            continue
        ctx.enter(program)
        checker.literal_vals.clear()
        checker.check(program.body)
    return types
