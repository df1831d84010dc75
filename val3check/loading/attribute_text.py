"""Attribute text as values: numbers, booleans, counts, array sizes and fatherIds, each read in linear time."""

from __future__ import annotations

import re

# Unambiguous (`\d+(?:\.\d*)?`, not `\d+\.?\d*`, which can split a run of digits in two in
# n ways and takes quadratic time on "111...1x"): linear on any text.
_NUM = re.compile(r"^\s*[+-]?(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][+-]?\d+)?\s*$")


def parse_num(text: str) -> float | None:
    if _NUM.match(text):
        return float(text)
    return None


_IDENTIFIER = re.compile(r"[A-Za-z_]\w*")


def parse_father(text: str) -> tuple[str, str | None] | None:
    """A fatherId as (name, index): "fPallet[2]" -> ("fPallet", "2"), "world" -> ("world", None),
    " a [ 1 2 ] " -> ("a", "1 2"); None when it is not `name` or `name[index]`. Written without
    a backtracking regular expression: the lazy index pattern with blanks on both sides that it
    replaces took quadratic time on "world[x" followed by thousands of spaces (17 s for 150 KB)."""
    t = text.strip()
    m = _IDENTIFIER.match(t)
    if m is None:
        return None
    rest = t[m.end():].lstrip()
    if not rest:
        return m.group(), None
    if rest[0] != "[" or rest[-1] != "]" or "]" in rest[1:-1]:
        return None
    return m.group(), rest[1:-1].strip()


def parse_bool(text: str) -> bool | None:
    low = text.strip().lower()
    if low == "true":
        return True
    if low == "false":
        return False
    return None


_DIGITS = re.compile(r"[0-9]+")
HUGE = 10**12  # what a longer run of digits counts as: beyond every limit, and no 4,300-digit int()


def parse_uint(text: str) -> int | None:
    """A non-negative integer written in ASCII digits ("²" and other Unicode digits are not),
    None otherwise; more than 12 digits count as HUGE (Python refuses to convert 4,300)."""
    text = text.strip()
    if not _DIGITS.fullmatch(text):
        return None
    digits = text.lstrip("0") or "0"
    return int(digits) if len(digits) <= 12 else HUGE


def parse_sizes(text: str) -> tuple[int, ...] | None:
    """ "3 4" -> (3, 4); None when not 1 to 3 positive integers."""
    parts = text.replace(",", " ").split()
    if not 1 <= len(parts) <= 3:
        return None
    out = []
    for p in parts:
        n = parse_uint(p)
        if n is None or n < 1:
            return None
        out.append(n)
    return tuple(out)
