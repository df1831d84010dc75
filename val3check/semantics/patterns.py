"""Suspicious patterns (S codes): code the controller accepts but that is probably wrong.

Entry point: `check_application(workspace, app) -> list[Diagnostic]`, called by
`semantics.analyse` for every target application. The rules (catalogue entries in `rules/S0xx.toml`,
messages in `patterns_messages.py`):

| code | rule | where |
|---|---|---|
| S001 | unused local | patterns_usage |
| S002 | unused parameter | patterns_usage |
| S003 | unused global | patterns_usage |
| S004 | unused private program | patterns_usage |
| S005 | local read before any assignment | patterns_usage |
| S006 | unreachable code after return / break | patterns_style |
| S007 | getMoveId() compared with == / != (10.6) | patterns_style |
| S008 | == / != on computed num values (3.2.1) | patterns_style |
| S009 | case / default without break (2.2.5) | patterns_style |
| S010 | `//` comment after code (2.2.5) | patterns_style |
| S011 | string constant over 128 bytes (3.4.1) | patterns_style |
| S012 | wait() whose condition nothing can change (5.4, 5.8) | patterns_style |
| S013 | nested for loops sharing a counter | patterns_style |
| S014 | busy loop that never yields (5.4) | patterns_style |
| S015 | self-assignment | patterns_style |

Programs whose code did not parse (`body is None`) are skipped; rules that need the whole
application (unused globals and programs) say nothing when one program did not parse. Every
check is linear in the size of the tree (loops: in the size of each loop).
"""

from __future__ import annotations

from ..diagnostics import Diagnostic
from ..language.target import Target, target_for
from ..loading.model import Application, Workspace
from . import patterns_style as style
from . import patterns_usage as usage
from .program_nodes import ProgramNodes, program_walks

# Tests set this to see exceptions; in use, a check that fails on an unexpected tree is skipped
# for that program (the other checks and programs still run).
STRICT = False


def _run(out: list[Diagnostic], check, *args) -> None:
    try:
        out.extend(check(*args))
    except Exception:
        if STRICT:
            raise


def check_application(workspace: Workspace, app: Application, target: Target | None = None,
                      walks: dict[str, ProgramNodes] | None = None) -> list[Diagnostic]:
    """`target`: what `app` is checked for (its project file's version by default); `walks`: the
    walk of each parsed program (program_nodes.program_walks), shared with the other checks."""
    target = target if target is not None else target_for(app.version, None)
    out: list[Diagnostic] = []
    try:
        resolver = usage.Resolver(workspace, app)
        library = usage.application_is_library(workspace, app)
    except Exception:
        if STRICT:
            raise
        return out

    facts: dict[str, usage.ProgramFacts] = {}
    try:
        walks = walks if walks is not None else program_walks(app)
    except Exception:
        if STRICT:
            raise
        return out
    for name, program in app.programs.items():
        if program.body is None:
            continue
        try:
            facts[name] = usage.gather(walks[name])
        except Exception:
            if STRICT:
                raise
    task_targets: set[str] = set()
    for f in facts.values():
        task_targets |= f.task_targets

    # a library's public programs are its interface (6.2); when none is public, the access
    # attribute was probably left out of the files: treat them all as interface
    all_interface = library and not any(p.access == "public" for p in app.programs.values())
    for name, program in app.programs.items():
        f = facts.get(name)
        if f is None:
            continue
        scope = usage.Scope(resolver, program)
        interface = all_interface or (library and program.access == "public")
        _run(out, usage.unused_in_program, program, f, interface, name.lower() in task_targets)
        _run(out, usage.read_before_assignment, program, resolver)
        _run(out, style.check_blocks, program)
        _run(out, style.check_comparisons, program, f)
        _run(out, style.check_comments, program)
        _run(out, style.check_strings, program, f)
        _run(out, style.check_waits, program, scope, f)
        _run(out, style.check_loops, program, scope, f)
        _run(out, style.check_self_assignments, program, scope, f)

    if len(facts) == len(app.programs):  # every program parsed
        # s8 (CS9): the OPC UA server and the web user pages read the public globals of an
        # application; no program needs to mention them
        _run(out, usage.unused_globals, app, facts, library, target.s8 or target.cs9 or bool(app.ui_names))
        _run(out, usage.unused_programs, app, facts, library)
    return out
