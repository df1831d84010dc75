"""parse_program fills Program.body and reports in the program's file."""

from __future__ import annotations

from val3check.loading.model import Origin, Program
from val3check.parsing import ast as A
from val3check.parsing.parser import parse_program
from val3check.positions import SourceMap


def make(code):
    return Program("start", "public", [], [], code, SourceMap.identity(code or "", 12, 20),
                   Origin("App/start.pgx", 3, 3))


def test_valid_program():
    p = make("begin\n  x = 1\nend")
    assert parse_program(p) == []
    assert isinstance(p.body, A.ProgramBody) and p.body.statements[0].line == 13


def test_program_with_errors():
    p = make("begin\n  x = 1 +\nend")
    diags = parse_program(p)
    assert p.body is None
    assert [(d.code, d.path, d.line, d.col) for d in diags] == [("F101", "App/start.pgx", 13, 10)]


def test_missing_code_is_the_loaders_business():
    p = make(None)
    assert parse_program(p) == [] and p.body is None
