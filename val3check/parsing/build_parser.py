"""Regenerate `_tables.py`, the pre-built LALR tables of `grammars/val3.lark`.

    python -m val3check.parsing.build_parser [--check | --print]

Building the tables from the grammar takes longer than the start-up budget of the tool, so
they are shipped. `--check` exits 1 when the shipped tables do not match the grammar (the
test suite checks the same); `--print` writes the file's content to standard output. The output
is stable (the build runs with PYTHONHASHSEED=0) for a given Lark version.

The tables are plain Python data (`tables.compile_tables`): Lark computes them here, and the parser
runs them without importing Lark (its import and table loading were a third of the start-up).
What Lark's tree builder does for each rule (drop the `_X` tokens, put None for an absent
`[x]`, inline `__x_star` repetitions, pass a `?rule` child through) is compiled into a plan per
rule that parser.py turns into one small function.
"""

from __future__ import annotations

import os
import pprint
import subprocess
import sys
from pathlib import Path

OUT = Path(__file__).resolve().parent / "_tables.py"


def render() -> str:
    import lark
    from lark import Lark

    from .builder import Builder
    from .grammar import LARK_OPTIONS, grammar_hash, grammar_text
    from .tables import compile_tables

    text = grammar_text()
    if text is None:
        raise SystemExit("grammars/val3.lark not found")
    parser = Lark(text, **LARK_OPTIONS)
    _canonical_numbering(parser.parser.parser._parse_table)
    tables = compile_tables(parser, frozenset(dir(Builder)))
    out = [
        '"""Pre-built LALR tables of grammars/val3.lark. GENERATED: do not edit; run\n'
        '`python -m val3check.parsing.build_parser` after changing the grammar (format: tables.compile_tables)."""\n',
        "# fmt: off\n",
        f"GRAMMAR_SHA256 = {grammar_hash(text)!r}\n",
        f"LARK_VERSION = {lark.__version__!r}\n",
    ]
    for key in ("LEXER", "START", "END", "RULES", "STATES"):
        out.append(f"{key} = {pprint.pformat(tables[key], width=120, compact=True)}\n")
    return "".join(out)


def _canonical_numbering(table) -> None:
    """Renumber the LALR states breadth-first from the start state, symbols in sorted order:
    Lark numbers them in set order, which changes from one run to the next."""
    from lark.parsers.lalr_analysis import Shift

    states = table.states
    (start,) = table.start_states.values()
    number = {start: 0}
    queue = [start]
    for state in queue:
        for _sym, (action, arg) in sorted(states.get(state, {}).items()):
            if action is Shift and arg not in number:
                number[arg] = len(number)
                queue.append(arg)
    for state in sorted(states):  # unreachable states, if any, keep their relative order
        if state not in number:
            number[state] = len(number)
    table.states = {
        number[state]: {sym: ((action, number[arg]) if action is Shift else (action, arg))
                        for sym, (action, arg) in sorted(states[state].items())}
        for state in sorted(states, key=number.__getitem__)
    }
    table.start_states = {k: number[v] for k, v in table.start_states.items()}
    table.end_states = {k: number[v] for k, v in table.end_states.items()}


def is_current() -> bool:
    from .grammar import grammar_hash, grammar_text

    text = grammar_text()
    try:
        from . import _tables
    except ImportError:
        return False
    return text is not None and _tables.GRAMMAR_SHA256 == grammar_hash(text)


def main(argv: list[str] | None = None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    if "--check" not in argv and os.environ.get("PYTHONHASHSEED") != "0":
        # Lark numbers the LALR states in set order: fix the hash seed for a stable output
        env = dict(os.environ, PYTHONHASHSEED="0")
        return subprocess.call([sys.executable, "-m", "val3check.parsing.build_parser", *argv], env=env)
    if "--print" in argv:
        sys.stdout.write(render())
        return 0
    if "--check" in argv:
        ok = is_current()
        print("up to date" if ok else "out of date: run python -m val3check.parsing.build_parser")
        return 0 if ok else 1
    OUT.write_text(render(), encoding="utf-8")
    print(f"wrote {OUT}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
