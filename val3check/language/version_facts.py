"""Limits that depend on the VAL 3 version, decided in one place for `lint` and `sim`.

The s7 manual states limits (9999 values per variable, 2.5.4; task names of 1 to 15 characters,
5.10) that real s8 code exceeds (`s8.toml`, `[limits]`). Up to s7, or when the version is not
known, the manual's limit is certain. On s8 what real code uses is accepted; beyond it the s8 limit
is not known: a finding says so and is a warning, and the simulator does not stop for it.

    values_problem(10_000, 7)  -> Problem("...9999 values (manual 2.5.4)", certain=True)
    values_problem(10_000, 8)  -> None
    task_name_problem("socketServerTask", 8) -> None
"""

from __future__ import annotations

from functools import cache

from ..light_dataclass import dataclass


@dataclass(frozen=True, slots=True)
class Limit:
    what: str
    s7: int
    s7_source: str
    s8_seen: int
    s8_source: str


@dataclass(frozen=True, slots=True)
class Problem:
    """Why a value breaks a limit; `certain`: the manual states it for this version."""

    why: str
    certain: bool


@cache
def limit(name: str) -> Limit:
    from .compiled import load_toml

    raw = load_toml("s8.toml")["limits"][name]
    return Limit(raw["what"], raw["s7"], raw["s7_source"], raw["s8_seen"], raw["s8_source"])


def over(name: str, n: int, major: int | None, shown: str | None = None) -> Problem | None:
    """`n` against the limit `name` ("values", "task_name") for VAL 3 major version `major`."""
    lim = limit(name)
    shown = shown or str(n)
    if major is None or major < 8:
        if n > lim.s7:
            return Problem(f"{shown}, more than {lim.s7} (the most the s7 manual allows)", True)
        return None
    if n > lim.s8_seen:
        return Problem(f"{shown}, more than the {lim.s7} of the s7 manual; s8 code is known to use {lim.s8_seen},"
                       " whether s8 accepts more is not known", False)
    return None


def task_name_problem(name: str, major: int | None) -> Problem | None:
    """Why a task name makes taskCreate stop with runtime error 29 (5.10): its characters (any
    version), its length (certain up to s7)."""
    if not name:
        return Problem("it is empty", True)
    bad = next((c for c in name if not (c.isascii() and (c.isalnum() or c == "_"))), None)
    if bad is not None:
        return Problem(f"the character {bad!r} is not allowed", True)
    p = over("task_name", len(name), major, f"{len(name)} characters")
    return p
