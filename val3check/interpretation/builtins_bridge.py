"""The pure built-in instructions (math, strings, bit fields) of `builtins/`, looked up by name.

`builtins/` is written separately (see its module docstring for the calling convention); this
module only finds an entry, so that the compiler and the runtime do not depend on its layout.
"""

from __future__ import annotations

from typing import Any


def builtin(name: str) -> Any | None:
    """The `Builtin` entry for a lower-case instruction name, or None."""
    try:
        from .builtins import lookup
    except ImportError:  # pragma: no cover - the package is being written
        return None
    return lookup(name)


def operator(op: str, t: str):
    try:
        from .builtins import OPERATORS
    except ImportError:  # pragma: no cover
        return None
    return OPERATORS.get((op, t))


def format_num(value: float) -> str:
    """How put/putln show a num (4.3)."""
    try:
        from .builtins import format_num_default
    except ImportError:  # pragma: no cover
        return f"{value:.3f}".rstrip("0").rstrip(".") if value == value else str(value)
    return format_num_default(value)
