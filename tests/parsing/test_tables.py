"""The shipped LALR tables match the grammar; the parser builds lazily and cheaply."""

from __future__ import annotations

import subprocess
import sys

from val3check.parsing import _tables, build_parser
from val3check.parsing.parser import build_from_grammar, grammar_hash, grammar_text


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
    engine = P._Engine()  # built from grammars/val3.lark
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
