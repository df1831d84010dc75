"""`//` comments are kept with file positions, whether they start their line or follow code."""

from __future__ import annotations

from val3check.parsing.parser import parse_code, scan_comments
from val3check.positions import SourceMap

from .shapes import parse


def test_comments_everywhere():
    code = ('// before begin\nbegin // after begin\n  // own line\n  x = "a // b" // after code\n'
            '\t//tab\nend // after end\n// last')
    body = parse(code, first_line=5, first_col=10)
    got = [(c.text, c.line, c.col, c.starts_line) for c in body.comments]
    assert got == [
        ("// before begin", 5, 10, True),
        ("// after begin", 6, 7, False),
        ("// own line", 7, 3, True),
        ("// after code", 8, 16, False),
        ("//tab", 9, 2, True),
        ("// after end", 10, 5, False),
        ("// last", 11, 1, True),
    ]


def test_comment_lines_inside_blocks_and_switch():
    body = parse("begin\n  switch x\n  // before case\n  case 1 // one\n  // in case\n  break\n  endSwitch\nend")
    assert [c.text for c in body.comments] == ["// before case", "// one", "// in case"]


def test_crlf_is_not_part_of_the_comment():
    body = parse("begin\r\n  // c\r\nend\r\n")
    assert [c.text for c in body.comments] == ["// c"]


def test_suppression_comment_on_a_line_with_a_syntax_error():
    code = "begin\n  x = 1 + // val3check: ignore[F101]\nend"
    body, diags = parse_code(code, SourceMap.identity(code, 3, 1), "t.pgx")
    assert body is None and [(d.code, d.line) for d in diags] == [("F101", 4)]
    comments = scan_comments(code, SourceMap.identity(code, 3, 1))
    assert [(c.text, c.line, c.col, c.starts_line) for c in comments] == [
        ("// val3check: ignore[F101]", 4, 11, False)]


def test_unterminated_string_swallows_slashes():
    assert scan_comments('x = "abc // not a comment\n// yes') [0].text == "// yes"
