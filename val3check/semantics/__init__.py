"""Semantic analysis of a loaded and parsed application (manual chapters 2-11).

`analyse(workspace, app)` returns the findings of every semantic rule family:
- `checker`  : what the controller's compiler refuses: names, types, containers, parameters,
               libraries and user types (N, T and L codes);
- `patterns` : what compiles but is probably wrong (S codes);
- `limits`   : the manual's limits on sizes and numbers, and data-file references (T026,
               T027, F017, N014).
Programs whose code did not parse (`program.body is None`) are skipped.
"""

from __future__ import annotations

from ..diagnostics import Diagnostic
from ..language.target import Target
from ..loading.model import Application, Workspace


def analyse(workspace: Workspace, app: Application, target: Target | None = None) -> list[Diagnostic]:
    """`target`: the controller/version/arm `app` is checked for (language/target.py); by
    default the version its project file writes, arm unknown."""
    from . import checker, limits, patterns
    from .program_nodes import program_walks

    walks = program_walks(app)  # one walk of each program's tree, read by both families
    found = checker.check_application(workspace, app, target)
    found.extend(patterns.check_application(workspace, app, target, walks))
    found.extend(limits.check_application(workspace, app, target, walks))
    return found
