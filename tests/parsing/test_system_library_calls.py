"""`alias:$name(...)`: an undocumented system instruction reached through a library identifier,
as Stäubli's own sample applications write it (`lib:$libOpen()`)."""

from __future__ import annotations

from val3check.parsing import ast as A
from val3check.parsing.parser import parse_code
from val3check.positions import SourceMap


def test_library_system_call_as_statement_and_in_an_expression():
    code = "begin\n  lib:$libOpen()\n  n = lib:$count(1, 2)\nend"
    body, diags = parse_code(code, SourceMap.identity(code), "x.pgx")
    assert diags == []
    call = body.statements[0].call
    assert isinstance(call.func, A.LibraryName) and (call.func.alias, call.func.name) == ("lib", "$libOpen")
    value = body.statements[1].value
    assert value.func.name == "$count" and len(value.args) == 2
