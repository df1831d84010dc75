"""Checks of what the project files declare (no code needed): names (2.5.1), duplicate
parameters and locals, start()/stop() without parameters (2.2.3, 2.2.4), unknown types, and
positions for the arm (9.7.2, SRS files: Rx types for six-axis arms, Rs types for SCARA).

Duplicate programs and globals of one application are reported by the loader (F011).
"""

from __future__ import annotations

import re

from ..diagnostics import Diagnostic
from ..language.target import Target, target_for
from ..loading.model import Application, Origin, Program
from ..rules import codes
from . import messages as M
from . import vtypes as vt
from .symbols import AppSymbols

_NAME = re.compile(r"[A-Za-z][A-Za-z0-9_]*\Z")
# Program names may also start with '_': Stäubli's own sample applications have `_globals`;
# 2.5.1's "starting with a letter" is written for variables.
_PROGRAM_NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_]*\Z")
_CHARS = re.compile(r"[A-Za-z0-9_]*\Z")


def name_problem(name: str, max_len: int | None = 15, pattern: re.Pattern = _NAME) -> tuple[str, str] | None:
    """(code, why) when `name` breaks 2.5.1, or None.

    A name that is only too long is N012, a warning: real applications loaded by controllers
    carry longer names (notably type projects saved by newer tools), so the length alone is not
    a sure compile error. Bad characters are N008."""
    if pattern.match(name):
        if max_len is not None and len(name) > max_len:
            return codes.NAME_TOO_LONG, f"{len(name)} characters, more than {max_len}"
        return None
    if not name:
        return codes.INVALID_NAME, "empty"
    if _PROGRAM_NAME.match(name):
        # Starts with '_': 2.5.1 wants a letter, but files saved by Stäubli's editor carry such
        # locals and load; a warning, not an error.
        return codes.NAME_STARTS_WITH_UNDERSCORE, "it starts with '_' instead of a letter"
    if not _CHARS.match(name):
        bad = next(c for c in name if not (c.isascii() and (c.isalnum() or c == "_")))
        return codes.INVALID_NAME, f"the character {bad!r} is not allowed"
    return codes.INVALID_NAME, "it must start with a letter"


def _diag(code: str, message: str, origin: Origin) -> Diagnostic:
    return Diagnostic(code, message, origin.path, origin.line, origin.col)


def check_declarations(table: AppSymbols, target: Target | None = None) -> list[Diagnostic]:
    app = table.app
    target = target if target is not None else target_for(app.version, None)
    out: list[Diagnostic] = []
    # s8 may allow longer names: only the characters are checked there.
    max_len = None if target.s8 else 15
    families: list[tuple[str, str, str, Origin]] = []  # (family, kind, name, origin)

    for d in app.data.values():
        problem = name_problem(d.name, max_len)
        if problem:
            out.append(_diag(problem[0], M.invalid_name("global", d.name, problem[1]), d.origin))
        _type_check(table, target, "global", d.name, d.type, d.origin, out, families)

    for prog in app.programs.values():
        problem = name_problem(prog.name, max_len, _PROGRAM_NAME)
        if problem:
            out.append(_diag(problem[0], M.invalid_name("program", prog.name, problem[1]), prog.origin))
        if prog.name in ("start", "stop") and prog.parameters:
            out.append(
                _diag(
                    codes.START_STOP_WITH_PARAMETERS, M.start_stop_params(prog.name, len(prog.parameters)), prog.origin
                )
            )
        _program_declarations(table, target, prog, max_len, out, families)

    out.extend(_families(families, target))
    return out


def _program_declarations(
    table: AppSymbols, target: Target, prog: Program, max_len: int | None, out: list[Diagnostic], families: list
) -> None:
    seen: dict[str, tuple[str, int]] = {}
    for kind, decls in (("parameter", prog.parameters), ("local", prog.locals)):
        for d in decls:
            problem = name_problem(d.name, max_len)
            if problem:
                out.append(_diag(problem[0], M.invalid_name(kind, d.name, problem[1]), d.origin))
            first = seen.get(d.name)
            if first is not None:
                out.append(_diag(codes.DUPLICATE_LOCAL, M.duplicate_local(kind, d.name, first[0], first[1]), d.origin))
            else:
                seen[d.name] = (kind, d.origin.line)
            _type_check(table, target, kind, d.name, d.type, d.origin, out, families)


def _type_check(
    table: AppSymbols,
    target: Target,
    kind: str,
    name: str,
    type_name: str,
    origin: Origin,
    out: list[Diagnostic],
    families: list,
) -> None:
    app: Application = table.app
    if vt.builtin(type_name) is None:
        low = type_name.lower()
        declared = any(n.lower() == low for n in app.types)
        if not declared and app.globals_known and not target.s8:  # s8 may have types s7 lacks
            out.append(_diag(codes.UNDEFINED_TYPE, M.undefined_type(kind, name, type_name), origin))
        return
    fam = vt.family_of(type_name)
    if fam is not None:
        families.append((fam, kind, name, type_name, origin))


_ARM_KIND = {"Rx": "six-axis", "Rs": "SCARA"}


def _families(families: list, target: Target) -> list[Diagnostic]:
    """Positions of the other arm family (9.7.2). When the controller tree says which arm the
    application runs on, each declaration of the other family is N011 (an error), at its line;
    when the arm is not known, an application that declares both families gets one N016 (a
    warning): a library may offer both forms, and which side is right is not known."""
    if not families:
        return []
    arm = target.family
    if arm is not None:
        where = f"{target.arm} in {target.arm_source}" if target.arm_source else str(target.arm)
        return [
            _diag(
                codes.WRONG_ARM_FAMILY,
                M.wrong_arm_family(kind, name, type_name, fam, arm, _ARM_KIND[arm], where),
                origin,
            )
            for fam, kind, name, type_name, origin in families
            if fam != arm
        ]
    counts: dict[str, int] = {}
    for f in families:
        counts[f[0]] = counts.get(f[0], 0) + 1
    if len(counts) < 2:
        return []
    order = [f[0] for f in families]
    main = max(counts, key=lambda k: (counts[k], -order.index(k)))
    fam, kind, name, type_name, origin = next(f for f in families if f[0] != main)
    return [
        _diag(codes.MIXED_ARM_FAMILIES_UNKNOWN_ARM, M.mixed_families_unknown_arm(kind, name, type_name, counts), origin)
    ]
