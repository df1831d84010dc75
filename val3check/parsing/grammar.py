"""The grammar file and its LALR tables: the shipped ones, or built by Lark while it is edited."""

from __future__ import annotations


from .builder import Builder

TYPE_CHECKING = False  # not typing's: importing typing costs 3 ms at lint's start-up
if TYPE_CHECKING:
    from typing import Any

# Lark options; build_parser.py uses the same ones.
LARK_OPTIONS: dict[str, Any] = dict(parser="lalr", lexer="contextual", maybe_placeholders=True)


def grammar_text() -> str | None:
    """The grammar file's text (line ends normalised), or None when it cannot be read."""
    import os

    from ..resources import resource_path

    try:
        with open(os.path.join(resource_path("grammars"), "val3.lark"), encoding="utf-8") as f:
            return f.read().replace("\r\n", "\n")
    except OSError:
        return None


def grammar_hash(text: str) -> str:
    from ..resources import sha256_hex

    return sha256_hex(text.encode("utf-8"))


def build_from_grammar(text: str, transformer: Any = None):
    """A Lark parser built from the grammar text (slow: ~70 ms)."""
    from lark import Lark

    return Lark(text, **LARK_OPTIONS, transformer=transformer)


def load_tables() -> dict:
    """The parse tables (tables.compile_tables): the shipped ones when they match the
    grammar file, else computed from the grammar file itself with Lark (while editing it)."""
    text = grammar_text()
    try:
        from . import _tables

        if text is None or _tables.GRAMMAR_SHA256 == grammar_hash(text):
            return {k: getattr(_tables, k) for k in ("LEXER", "STATES", "RULES", "START", "END")}
    except Exception:  # missing or incompatible tables: fall back on the grammar
        if text is None:
            raise
    from .tables import compile_tables

    return compile_tables(build_from_grammar(text), frozenset(dir(Builder)))  # type: ignore[arg-type]

