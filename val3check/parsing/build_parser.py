"""Regenerate `_tables.py`, the pre-built LALR tables of `grammars/val3.lark`.

    python -m val3check.parsing.build_parser [--check | --print]

Building the tables from the grammar takes longer than the start-up budget of the tool, so
they are shipped. `--check` exits 1 when the shipped tables do not match the grammar (the
test suite checks the same); `--print` writes the file's content to standard output. The output
is stable (the build runs with PYTHONHASHSEED=0) for a given Lark version.

The tables are plain Python data (`compile_tables`): Lark computes them here, and the parser
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


def compile_tables(parser) -> dict:
    """The parse tables of a Lark LALR parser as plain data:

    LEXER     one regex: every terminal as a named group, in Lark's order of precedence (priority,
              then longest possible match, then longest pattern); leading blanks skipped; `EOF` at
              the end. `TO`/`STEP` are left out: the lexer makes them from names (contextual).
    STATES    per state, {symbol: action}: an action >= 0 shifts to (or goes to) that state, -1-k
              reduces by RULES[k].
    RULES     per rule: (origin, number of symbols, plan); plan None: a `?rule` passing its one
              child through (only the state changes); else (callback, expand1, include, nones):
              `callback` the builder method (None: an inlined `__x` repetition, whose value is the
              list of its kept children), `expand1` a `?rule` alternative that returns a lone kept
              child, `include` the kept children as (index, inline its list, Nones before it),
              `nones` the Nones after them (absent `[x]` at the end); include None: all children
              kept as they are.
    START/END the start state and the state that accepts.
    """
    from lark.parse_tree_builder import maybe_create_child_filter
    from lark.parsers.lalr_analysis import Shift

    from .parser import _Builder

    table = parser.parser.parser._parse_table
    lexer_conf = parser.parser.lexer_conf
    terms = [t for t in lexer_conf.terminals if t.name not in ("WS", "TO", "STEP")]
    terms.sort(key=lambda t: (-t.priority, -t.pattern.max_width, -len(t.pattern.value), t.name))
    alts = "|".join(f"(?P<{t.name}>{t.pattern.to_regexp()})" for t in terms)
    lexer = r"[ \t\f\r]*(?:" + alts + r"|(?P<EOF>\Z))"

    rules: list = []
    index: dict = {}
    states: list[dict] = [dict() for _ in range(len(table.states))]
    for state, row in sorted(table.states.items()):
        for sym, (action, arg) in sorted(row.items()):
            if action is Shift:
                states[state][sym] = arg
                continue
            if arg not in index:
                index[arg] = len(rules)
                rules.append(_rule_plan(arg, maybe_create_child_filter))
            states[state][sym] = -1 - index[arg]
    missing = {r[2][0] for r in rules if r[2] is not None and r[2][0] is not None and not r[2][1]}
    missing -= set(dir(_Builder))
    if missing:
        raise SystemExit(f"no builder method for {sorted(missing)}: add them to parser._Builder")
    return {"LEXER": lexer, "STATES": states, "RULES": rules,
            "START": table.start_states["start"], "END": table.end_states["start"]}


def _rule_plan(rule, maybe_create_child_filter) -> tuple:
    origin = str(rule.origin.name)
    size = len(rule.expansion)
    opts = rule.options
    if (size == 1 and opts.expand1 and not rule.alias and not rule.expansion[0].is_term
            and not rule.expansion[0].name.startswith("_")):
        return (origin, size, None)  # `?rule: other_rule`
    from .parser import _Builder

    name = str(rule.alias or opts.template_source or origin)
    callback = None if name.startswith("_") or not hasattr(_Builder, name) else name
    filt = maybe_create_child_filter(rule.expansion, opts.keep_all_tokens, False, opts.empty_indices)
    if filt is None:
        include, nones = None, 0
    else:
        args = filt.args
        if len(args) == 2:  # ChildFilterLALR(to_include, nones_to_add)
            include, nones = tuple((i, bool(x), n) for i, x, n in args[0]), args[1]
        else:  # ChildFilterLALR_NoPlaceholders(to_include)
            include, nones = tuple((i, bool(x), 0) for i, x in args[0]), 0
    return (origin, size, (callback, bool(opts.expand1 and not rule.alias), include, nones))


def render() -> str:
    import lark
    from lark import Lark

    from .parser import LARK_OPTIONS, grammar_hash, grammar_text

    text = grammar_text()
    if text is None:
        raise SystemExit("grammars/val3.lark not found")
    parser = Lark(text, **LARK_OPTIONS)
    _canonical_numbering(parser.parser.parser._parse_table)
    tables = compile_tables(parser)
    out = [
        '"""Pre-built LALR tables of grammars/val3.lark. GENERATED: do not edit; run\n'
        '`python -m val3check.parsing.build_parser` after changing the grammar (format: build_parser.compile_tables)."""\n',
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
    from .parser import grammar_hash, grammar_text

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
