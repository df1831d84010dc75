"""The recursive-descent fast path (parsing/descent.py) gives exactly what the LALR engine gives:
the same trees with the same positions, the same diagnostics (it falls back on the engine for
code with errors), on every fixture, the generated benchmark application, hand-written corner
cases and mutated programs; and it does parse every valid program itself."""

from __future__ import annotations

import os
import sys
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from val3check.loading import load
from val3check.parsing import ast as A
from val3check.parsing.descent import MAX_NESTING
from val3check.parsing.parser import get_engine, parse_code
from val3check.positions import Position, SourceMap

ROOT = Path(__file__).resolve().parents[2]


def _programs(folder: Path) -> list:
    ws, _ = load([str(folder)])
    return [p for app in ws.apps.values() for p in app.programs.values() if p.code is not None]


def _both(code: str, sm: SourceMap | None = None, path: str = "t.pgx"):
    """(fast path result, engine-only result, whether the fast path parsed it itself)."""
    sm = sm if sm is not None else SourceMap.identity(code)
    engine = get_engine()
    fast = parse_code(code, sm, path)
    descent = engine.descent
    try:
        engine.descent = None
        lalr = parse_code(code, sm, path)
    finally:
        engine.descent = descent
    engine.builder.setup(code, sm)
    took = descent.parse(code) is not None
    return fast, lalr, took


def _same(code: str, sm: SourceMap | None = None, path: str = "t.pgx") -> bool:
    fast, lalr, took = _both(code, sm, path)
    assert fast == lalr
    if lalr[0] is not None:
        assert took, "a valid program left to the engine"
    else:
        assert not took, "the fast path accepted a program with errors"
    return took


def test_every_fixture_program():
    programs = _programs(ROOT / "fixtures")
    assert len(programs) > 80
    taken = sum(_same(p.code, p.code_map, p.origin.path) for p in programs)
    assert taken > 60  # most fixtures are valid
    # escaped XML text (column maps) goes through the fast path too
    assert any(p.code_map.col_maps for p in programs if p.code_map is not None)


def test_the_generated_benchmark_application(tmp_path):
    sys.path.insert(0, str(ROOT / "bench"))
    try:
        from bench_parse import make_program
        from generate import generate
    finally:
        sys.path.remove(str(ROOT / "bench"))
    generate(tmp_path / "BigApp", min_lines=4000)
    programs = _programs(tmp_path)
    assert len(programs) > 20
    for p in programs:
        assert _same(p.code, p.code_map, p.origin.path)
    code = make_program(600)
    assert _same(code, SourceMap.identity(code, first_line=10, first_col=20))


CORNERS = [
    # contextual keywords: `to` and `step` are names outside a `for` header
    "begin\n  for to = to to step step step\n  endFor\n  x = to + step\nend",
    "begin\n  for i = 0 TO 10 Step -1\n    a[i] = i\n  endFor\n  for lib:c.x[1] = a = 1 to (b)\n  endFor\nend",
    # calls, library names, system names, fields and indices
    "begin\n  movej(j, flange, mNomSpeed)\n  lib:p(1)\n  lib:$sys()\n  $x()\n  call p()\n  call l:p(1, 2)\nend",
    "begin\n  lib:x[2].y = lib:f(1)[0].z\n  a.b.c[1, 2].d = -a[1].b\nend",
    # structures, unary folding, assignment expressions, operators and their case
    "begin\n  x = {}\n  x = {,}\n  x = {1,,2,}\n  x = {{1, 2}, {}}\n  y = - -3\n  y = -(3)\n  y = !-a\nend",
    "begin\n  x = y = 3\n  b = a or b AND c Xor d == e != f < g >= h + i - j * k / l % m\n  ? \"a\", 1\nend",
    "begin\n  b = (a + b) * -c\n  n = 1.e5 + .5 + 1e+3 + 10\nend",
    # tasks, blocks, switch, do
    "begin\n  taskCreate \"t\", 10, p(1)\n  taskCreateSync \"s\", 0.1, b, lib:q()\n  taskCreate \"u\", 1, r()\nend",
    "begin\n  if a\n  elseIf b\n    return\n  elseIf c\n  else\n    break\n  endIf\n  while x\n  endWhile\nend",
    "begin\n  switch x\n    case 1, 2\n      y = 1\n    break\n    default\n  endSwitch\n  switch y\n  endSwitch\n"
    "  do\n  until true\n  DO\n    x = 1\n  UNTIL FALSE\nend",
    # blank lines, comments, tabs, CR LF, code before and after
    "\n// head\n\nbegin // c\n\t// only a comment\n\n  x = 1 // after\r\n\r\n  y = 2\nend // tail",
    "begin\nend\n\n// last\n   ",
    "  begin\n  end",
    # errors: each falls back on the engine
    "begin\n  x = 1 +\nend", "begin\n  x = 'a'\nend", "begin\n  x = 0x1F\nend", "begin\n  s = \"open\nend",
    "begin\n  if a\nend", "begin\n  x = a to b\nend", "begin\n  for i = 0 step 1\n  endFor\nend",
    "begin\n  f(x)(y)\nend", "begin\n  f(x) = 1\nend", "begin\n  x = lib:$s\nend", "begin\n  $s = 1\nend",
    "begin\n  x = é\nend", "begin\nend\nx", "", "begin", "begin\n  call lib:$p()\nend",
    "begin\n  x = {1 2}\nend", "begin\n  whlie x\n  endWhile\nend", "begin\n  taskCreate(\"t\", 1, p())\nend",
]


@pytest.mark.parametrize("code", CORNERS)
def test_corner_cases(code):
    _same(code)
    _same(code, SourceMap.identity(code, first_line=7, first_col=12))


def test_column_maps():
    """Lines with a column map (escaped XML text) map each position through it."""
    code = "begin\n  if a &lt; b and c\n    x = f(a, 1) + 2\n  endIf\nend"
    code = code.replace("&lt;", "<")
    lines = code.split("\n")
    cols = {1: [1, 2, 3, 4, 5, 6, 10, 11, 12, 13, 14, 15, 16, 17, 18, 19, 20],
            2: [c * 2 for c in range(1, len(lines[2]) + 1)]}
    sm = SourceMap([Position(3 + k, 5) for k in range(len(lines))], cols)
    assert _same(code, sm)


def test_deep_nesting_is_left_to_the_engine():
    """Expressions nested past MAX_NESTING and blocks past MAX_BLOCK_DEPTH: the engine parses them
    (without recursion) and reports what it reports."""
    deep = "begin\n  x = " + "(" * (MAX_NESTING + 5) + "1" + ")" * (MAX_NESTING + 5) + "\nend"
    fast, lalr, took = _both(deep)
    assert fast == lalr and fast[0] is not None and not took
    very = "begin\n  x = " + "-" * 150 + "1\nend"
    fast, lalr, took = _both(very)
    assert fast == lalr and fast[0] is None and fast[1][0].code == "F104" and not took
    blocks = "begin\n" + "if a\n" * 65 + "endIf\n" * 65 + "end"
    fast, lalr, took = _both(blocks)
    assert fast == lalr and fast[0] is None and fast[1][0].code == "F104" and not took
    ok = "begin\n" + "if a\n" * 64 + "endIf\n" * 64 + "end"
    assert _same(ok)


def test_the_fast_path_makes_the_same_nodes():
    """The nodes the fast path makes itself (names, numbers, binary operations) are the classes
    and values of the builder's."""
    body, _ = parse_code("begin\n  x = a AND 1.5\nend", SourceMap.identity("x"), "t.pgx")
    value = body.statements[0].value
    assert type(value) is A.Binary and value.op == "and"
    assert (type(value.left), type(value.right), value.right.value) == (A.Name, A.Number, 1.5)


# ---------------------------------------------------------------- mutated programs

_SEEDS = [
    "begin\n  for l_i = 0 to 9 step 2\n    nGrid[l_i, 1] = nGrid[l_i, 1] + x_nIn * 2 - (l_i % 3)\n  endFor\n"
    "  if nCount > 10 and bReady == true\n    nCount = 0\n  elseIf !bReady\n    call lib:p(1, \"s\")\n"
    "  else\n    movej(appro(p, {0, 0, -50, 0, 0, 0}), tool, mDesc)\n  endIf\n  switch n\n    case 1, 2\n"
    "    break\n    default\n  endSwitch\n  do\n    x = -.5e-1\n  until x >= 3 xor b\n  ? x\nend\n",
    "begin\n  taskCreate \"t\", 10, p()\n  while !isSettled() // c\n    delay(0.05)\n  endWhile\n  $s()\nend",
]
_PIECES = ["to", "step", "To", "STEP", "if", "endIf", "for", "endFor", "switch", "case", "default", "do",
           "until", "while", "begin", "end", "call", "taskCreate", "and", "x", "lib:", "$", "1", "1.", ".5",
           "1e", "0x1", '"', '"s"', "(", ")", "[", "]", "{", "}", ",", ".", ":", "=", "==", "!", "!=", "<", "-",
           "+", "?", "//", "\n", "\r", "\t", " ", "é", "'", ";"]


@st.composite
def _mutants(draw) -> str:
    code = draw(st.sampled_from(_SEEDS))
    for _ in range(draw(st.integers(1, 3))):
        pos = draw(st.integers(0, len(code)))
        op = draw(st.integers(0, 2))
        if op == 0:
            code = code[:pos] + draw(st.sampled_from(_PIECES)) + code[pos:]
        elif op == 1:
            code = code[:pos] + code[pos + draw(st.integers(1, 6)):]
        else:
            code = code[:pos] + " " + draw(st.sampled_from(_PIECES)) + " " + code[pos:]
    return code


@settings(max_examples=int(os.environ.get("VAL3CHECK_FUZZ_EXAMPLES", "25")) * 8, deadline=None, database=None,
          derandomize=os.environ.get("VAL3CHECK_FUZZ_LONG") != "1", suppress_health_check=list(HealthCheck))
@given(_mutants())
def test_mutated_programs(code):
    _same(code)


_LINE = st.lists(st.sampled_from(_PIECES[:-6] + ["a", "b", "f(", "l:g(", "n[", "1, 2", "= 1"]), max_size=12).map(" ".join)


@settings(max_examples=int(os.environ.get("VAL3CHECK_FUZZ_EXAMPLES", "25")) * 8, deadline=None, database=None,
          derandomize=os.environ.get("VAL3CHECK_FUZZ_LONG") != "1", suppress_health_check=list(HealthCheck))
@given(st.lists(_LINE, max_size=8))
def test_programs_of_random_lines(lines):
    _same("begin\n" + "\n".join(lines) + "\nend\n")


# ---------------------------------------------------------------- the tokenizer's order of terminals

def _regexes():
    from val3check.parsing.fast_lexer import FIRST, pair_regex

    master = get_engine().lexer
    return pair_regex(master, (), possessive=False), pair_regex(master, FIRST)


def test_terminals_tried_first_are_the_grammars_terminals():
    from val3check.parsing.fast_lexer import FIRST

    grammar_order, ours = _regexes()
    assert grammar_order.pattern != ours.pattern
    master = get_engine().lexer
    for name in FIRST:
        assert f"(?P<{name}>" in master  # a renamed terminal would silently keep the grammar's order


def test_the_line_end_is_the_grammars_with_possessive_repeats():
    from val3check.parsing.fast_lexer import NL_GRAMMAR, NL_POSSESSIVE

    grammar_order, ours = _regexes()
    assert f"(?P<_NL>{NL_GRAMMAR})" in get_engine().lexer  # else it stays as written
    assert NL_POSSESSIVE in ours.pattern and NL_POSSESSIVE not in grammar_order.pattern
    assert NL_POSSESSIVE.replace("*+", "*") == NL_GRAMMAR


def test_terminals_tried_first_find_the_same_tokens_on_every_fixture():
    grammar_order, ours = _regexes()
    programs = _programs(ROOT / "fixtures")
    for p in programs:
        assert ours.findall(p.code) == grammar_order.findall(p.code)


_CHARS = st.sampled_from(_PIECES + list("0123456789eE+-_$aZ/*%<>=!.;\"\n \t\f\r\\@#é") + ["//x\n", "1e+5", "1.5e-3x"])


@settings(max_examples=int(os.environ.get("VAL3CHECK_FUZZ_EXAMPLES", "25")) * 20, deadline=None, database=None,
          derandomize=os.environ.get("VAL3CHECK_FUZZ_LONG") != "1", suppress_health_check=list(HealthCheck))
@given(st.lists(_CHARS, max_size=40).map("".join))
def test_terminals_tried_first_find_the_same_tokens_on_any_text(text):
    grammar_order, ours = _regexes()
    assert ours.findall(text) == grammar_order.findall(text)


@settings(max_examples=int(os.environ.get("VAL3CHECK_FUZZ_EXAMPLES", "25")) * 20, deadline=None, database=None,
          derandomize=os.environ.get("VAL3CHECK_FUZZ_LONG") != "1", suppress_health_check=list(HealthCheck))
@given(st.sampled_from(list("0123456789.")).flatmap(
    lambda first: st.text(alphabet="0123456789eE+-._aZx", max_size=8).map(lambda rest: first + rest)))
def test_numbers_are_told_from_bad_numbers_as_the_master_regex_does(text):
    # the tokenizer asks NUMBER alone (number_regex) what the engine asks its whole master regex
    import re

    from val3check.parsing.fast_lexer import number_regex

    lexer = get_engine().lexer
    m = re.compile(lexer).match(text)
    n = number_regex(lexer).match(text)
    whole = m is not None and m.lastgroup == "NUMBER" and m.end() == len(text)
    assert whole == (n is not None and n.end() == len(text))


def test_the_master_regex_is_compiled_only_for_the_engine():
    from val3check.parsing.engine import Engine

    engine = Engine()
    engine.builder.setup("begin\nend\n", SourceMap.identity("begin\nend\n"))
    assert engine.descent.parse("begin\nend\n") is not None
    assert "regex" not in engine.__dict__
    assert engine.regex.pattern == engine.lexer
