"""How a message quotes a value read from a file: short, on one line, every character visible.

A hostile file may hold megabytes in one value (an arm id, a key, a signal name) or control
characters that would move a terminal's cursor: a message shows at most `LIMIT` characters of it
and says how long it was.

    excerpt("tx2-60-S1")        -> tx2-60-S1
    excerpt("-s1" * 60000)      -> -s1-s1-s1... (180000 characters)
    shown("a\\x00b")            -> 'a\\x00b'        (repr-like: strings quoted, escapes visible)
    shown([1, 2, ...])          -> a bounded repr of the list
"""

from __future__ import annotations

import reprlib

TYPE_CHECKING = False  # not typing's: importing typing costs 3 ms at lint's start-up
if TYPE_CHECKING:
    from typing import Any

LIMIT = 60

_REPR = reprlib.Repr()
_REPR.maxlevel, _REPR.maxlist, _REPR.maxtuple, _REPR.maxdict, _REPR.maxset = 3, 8, 8, 6, 8
_REPR.maxstring, _REPR.maxother, _REPR.maxlong = LIMIT, LIMIT, 40


def _cut(text: str, limit: int) -> tuple[str, str]:
    if len(text) <= limit:
        return text, ""
    return text[:limit], f"... ({len(text)} characters)"


def excerpt(text: str, limit: int = LIMIT) -> str:
    """`text` cut after `limit` characters, control characters and undecodable bytes escaped."""
    head, tail = _cut(str(text), limit)
    return "".join(c if c.isprintable() else repr(c)[1:-1] for c in head) + tail


def shown(value: Any, limit: int = LIMIT) -> str:
    """A value as `repr` writes it (strings quoted, escapes visible), at most about `limit`
    characters long."""
    if isinstance(value, str):
        head, tail = _cut(value, limit)
        return repr(head) + tail
    try:
        text = _REPR.repr(value)
    except (RecursionError, ValueError):  # ValueError: an int beyond the int-to-string limit
        return f"a {type(value).__name__} too long to show"
    return text if len(text) <= 2 * limit else text[:2 * limit] + "..."
