"""The `github` format: workflow commands and their escaping."""

from __future__ import annotations

from val3check.diagnostics import Severity
from val3check.reporting import render
from val3check.reporting.github import escape_data, escape_property


def test_commands(make_result, d):
    result = make_result(
        [
            d("F001", "cannot read", "b.pgx"),
            d("F101", "unexpected 'endWhile'", "a.pgx", 12, 5, 12, 13),
            d("S301", "unused", "a.pgx", 13, 0),
            d("N201", "bad name", "a.pgx", 14, 2),
            d("F101", "demoted", "a.pgx", 15, 1, severity=Severity.INFO),
        ]
    )
    assert render("github", result).splitlines() == [
        "::error file=a.pgx,line=12,col=5,endLine=12,endColumn=13,title=F101 syntax-error::unexpected 'endWhile'",
        "::warning file=a.pgx,line=13,title=S301 unused-variable::unused",
        "::notice file=a.pgx,line=14,col=2,title=N201 bad-name::bad name",
        "::notice file=a.pgx,line=15,col=1,title=F101 syntax-error::demoted",
        "::error file=b.pgx,title=F001 file-unreadable::cannot read",
    ]


def test_escaping(make_result, d):
    out = render("github", make_result([d("X999", "a <&\">,:% b\r\nc %0A", "dir, x/a:b%.pgx", 1, 1)]))
    assert out == "::warning file=dir%2C x/a%3Ab%25.pgx,line=1,col=1,title=X999::a <&\">,:%25 b%0D%0Ac %250A\n"
    assert escape_data("100%\n") == "100%25%0A"
    assert escape_property("a:b,c%\r") == "a%3Ab%2Cc%25%0D"


def test_no_findings_no_output(make_result):
    assert render("github", make_result([], files=["a"])) == ""
