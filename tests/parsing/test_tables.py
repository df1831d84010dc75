"""The shipped LALR tables match the grammar; the parser builds lazily and cheaply."""

from __future__ import annotations

import subprocess
import sys

from val3check.parsing import _tables, build_parser
from val3check.parsing.engine import Engine
from val3check.parsing.grammar import build_from_grammar, grammar_hash, grammar_text


def test_shipped_tables_match_the_grammar():
    text = grammar_text()
    assert text is not None
    assert _tables.GRAMMAR_SHA256 == grammar_hash(text), (
        "val3check/parsing/_tables.py is out of date: run python -m val3check.parsing.build_parser")
    assert build_parser.is_current()


def test_rendered_tables_equal_the_shipped_file():
    import lark
    import pytest
    from pathlib import Path

    if lark.__version__ != _tables.LARK_VERSION:
        pytest.skip(f"tables made with Lark {_tables.LARK_VERSION}, Lark {lark.__version__} installed")
    out = subprocess.run([sys.executable, "-m", "val3check.parsing.build_parser", "--print"],
                         capture_output=True, text=True, check=True)
    assert out.stdout == Path(_tables.__file__).read_text(encoding="utf-8")


def test_grammar_builds_without_conflicts():
    lk = build_from_grammar(grammar_text())
    assert lk.parser.parser._parse_table.states


def test_import_does_not_build_the_parser():
    code = "import val3check.parsing.parser as p; assert p._engine is None; print('ok')"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "ok"


def test_build_parser_check_command():
    out = subprocess.run([sys.executable, "-m", "val3check.parsing.build_parser", "--check"],
                         capture_output=True, text=True)
    assert out.returncode == 0, out.stdout + out.stderr


def test_engine_falls_back_on_the_grammar(monkeypatch):
    from val3check.parsing import parser as P
    from val3check.positions import SourceMap

    monkeypatch.setattr(_tables, "GRAMMAR_SHA256", "stale")
    engine = Engine()  # built from grammars/val3.lark
    code = "begin\n  if a or b\n    x = {1,,2}\n  endIf\n  y = 1 +\nend"
    monkeypatch.setattr(P, "_engine", engine)
    body, diags = P.parse_code(code, SourceMap.identity(code), "t.pgx")
    assert [(d.code, d.line, d.col) for d in diags] == [("F101", 5, 10)]
    monkeypatch.undo()
    body2, diags2 = P.parse_code(code, SourceMap.identity(code), "t.pgx")
    assert diags == diags2
    good = "begin\n  if a or b\n    x = {1,,2}\n  endIf\nend"
    monkeypatch.setattr(P, "_engine", engine)
    assert P.parse_code(good, SourceMap.identity(good), "t.pgx") [0] is not None


def _lark_callback_engine():
    """The engine as it was driven before the tables were compiled: Lark's own tree-building
    callbacks (child filters, placeholders, inlined repetitions) around the same builder."""

    engine = Engine()
    lk = build_from_grammar(grammar_text(), engine.builder)
    lalr = lk.parser.parser
    table, callbacks = lalr._parse_table, lalr.parser.callbacks
    actions = [dict() for _ in range(len(table.states))]
    for state, row in table.states.items():
        for sym, (_kind, arg) in row.items():
            if type(arg) is int:
                actions[state][sym] = arg
            elif (len(arg.expansion) == 1 and arg.options.expand1 and not arg.alias
                  and not arg.expansion[0].is_term and not arg.expansion[0].name.startswith("_")):
                actions[state][sym] = (1, arg.origin.name, None)
            else:
                actions[state][sym] = (len(arg.expansion), arg.origin.name, callbacks[arg])
    engine.actions = actions
    engine.start_state = table.start_states["start"]
    engine.end_state = table.end_states["start"]
    engine.unit_memo = {}
    engine.descent = None  # the tables alone (the fast path is compared in test_descent.py)
    engine.expected = [frozenset(k for k in acts if k.isupper()) for acts in actions]
    return engine


def test_compiled_rule_plans_build_what_lark_builds(monkeypatch, tmp_path):
    from pathlib import Path

    from val3check.loading import load
    from val3check.parsing import parser as P

    root = Path(__file__).resolve().parents[2]
    ws, _ = load([str(root / "fixtures")])
    programs = [p for app in ws.apps.values() for p in app.programs.values() if p.code]
    codes = [p.code for p in programs] + [
        "begin\n  call f()\n  call f(1, 2)\n  x = {1,,2,}\n  x = {}\n  y = (a + b) * -c\n  ? x\n"
        "  taskCreate \"t\", 1, g()\n  if a\n  elseIf b\n  else\n  endIf\n  for i = 0 to 3 step 2\n  endFor\n"
        "  switch x\n    case 1, 2\n    break\n    default\n  endSwitch\n  do\n  until true\nend",
        "begin\n  if true\nend", "begin\n  x = 1 +\n  y = )\nend",
    ]
    from val3check.positions import SourceMap

    new = [P.parse_code(c, SourceMap.identity(c), "t.pgx") for c in codes]
    monkeypatch.setattr(P, "_engine", _lark_callback_engine())
    old = [P.parse_code(c, SourceMap.identity(c), "t.pgx") for c in codes]
    assert len(codes) > 40
    assert new == old


def test_the_automaton_is_made_on_first_use_only(monkeypatch):
    """Code without errors takes the fast path: the engine's tables of actions are made only
    when a program has syntax errors (4 ms of lint's start-up otherwise)."""
    from val3check.parsing import parser as P
    from val3check.positions import SourceMap

    engine = Engine()
    monkeypatch.setattr(P, "_engine", engine)
    good, bad = "begin\n  x = f(1, 2)\nend", "begin\n  x = 1 +\nend"
    assert P.parse_code(good, SourceMap.identity(good), "t.pgx")[0] is not None
    assert "actions" not in vars(engine)
    body, diags = P.parse_code(bad, SourceMap.identity(bad), "t.pgx")
    assert body is None and diags and "actions" in vars(engine) and "expected" in vars(engine)
    fresh = Engine()
    assert fresh.expected == engine.expected and len(fresh.actions) == len(engine.actions)
