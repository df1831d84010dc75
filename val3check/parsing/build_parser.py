"""Regenerate `_tables.py`, the pre-built LALR tables of `grammars/val3.lark`.

    python -m val3check.parsing.build_parser [--check]

Building the tables from the grammar takes longer than the start-up budget of the tool, so
they are shipped. `--check` exits 1 when the shipped tables do not match the grammar (the
test suite checks the same).
"""

from __future__ import annotations

import pprint
import sys
from pathlib import Path

OUT = Path(__file__).resolve().parent / "_tables.py"


def render() -> str:
    import lark
    from lark import Lark
    from lark.grammar import Rule
    from lark.lexer import TerminalDef

    from .parser import LARK_OPTIONS, grammar_hash, grammar_text

    text = grammar_text()
    if text is None:
        raise SystemExit("grammars/val3.lark not found")
    parser = Lark(text, **LARK_OPTIONS)
    data, memo = parser.memo_serialize([TerminalDef, Rule])
    return (
        '"""Pre-built LALR tables of grammars/val3.lark. GENERATED: do not edit; run\n'
        '`python -m val3check.parsing.build_parser` after changing the grammar."""\n'
        "# fmt: off\n"
        f"GRAMMAR_SHA256 = {grammar_hash(text)!r}\n"
        f"LARK_VERSION = {lark.__version__!r}\n"
        f"DATA = {pprint.pformat(data, width=120, compact=True)}\n"
        f"MEMO = {pprint.pformat(memo, width=120, compact=True)}\n"
    )


def is_current() -> bool:
    from .parser import grammar_hash, grammar_text

    text = grammar_text()
    try:
        from . import _tables
    except ImportError:
        return False
    return text is not None and _tables.GRAMMAR_SHA256 == grammar_hash(text)


def main(argv: list[str] | None = None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    if "--check" in argv:
        ok = is_current()
        print("up to date" if ok else "out of date: run python -m val3check.parsing.build_parser")
        return 0 if ok else 1
    OUT.write_text(render(), encoding="utf-8")
    print(f"wrote {OUT}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
