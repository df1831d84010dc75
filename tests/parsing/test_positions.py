"""Every node carries FILE positions, mapped through the program's SourceMap."""

from __future__ import annotations

from val3check.parsing import ast as A
from val3check.parsing.parser import parse_code
from val3check.positions import Position, SourceMap

from .shapes import parse


CODE = "begin\n  nX = 1\n  if a\n    b = c + d\n  endIf\nend"


def test_identity_map_with_offset():
    body = parse(CODE, first_line=7, first_col=20)
    # code line 1 starts at file column 20 ...
    assert (body.line, body.col) == (7, 20)
    assert (body.end_line, body.end_col) == (12, 4)
    assign, st = body.statements
    # ... the other lines at column 1
    assert (assign.line, assign.col) == (8, 3)
    assert (assign.target.line, assign.target.col, assign.target.end_col) == (8, 3, 5)
    assert (assign.op_line, assign.op_col) == (8, 6)
    assert (assign.value.line, assign.value.col) == (8, 8)
    inner = st.branches[0].body[0]
    assert (inner.line, inner.col) == (10, 5)
    assert (inner.value.line, inner.value.col, inner.value.op_col) == (10, 9, 11)
    assert (st.end_line, st.end_col) == (11, 8)


def test_code_on_the_first_line():
    body = parse("begin\nend", first_line=3, first_col=11)
    assert (body.line, body.col, body.end_line, body.end_col) == (3, 11, 4, 4)
    # a statement of code line 1 is not possible, but an error there is positioned too
    _, diags = parse_code("begin x = 1\nend", SourceMap.identity("begin x = 1\nend", 3, 11), "f.pgx")
    assert [(d.line, d.col) for d in diags] == [(3, 17)]


def test_col_maps_of_escaped_text():
    # XML text `    <Code>  if a &gt; b` became `  if a > b`: the file columns of each character
    code = "begin\n  if a > b\n    x = 1\n  endIf\nend"
    line2 = [5, 6, 7, 8, 9, 10, 11, 12, 16, 17]  # `>` is the 4 characters `&gt;` at 12..15
    sm = SourceMap(
        line_starts=[Position(10, 1), Position(11, 5), Position(12, 1), Position(13, 1), Position(14, 1)],
        col_maps={1: line2},
    )
    body, diags = parse_code(code, sm, "f.pgx")
    assert not diags
    (st,) = body.statements
    cond = st.branches[0].cond
    assert (st.line, st.col) == (11, 7)
    assert (cond.line, cond.col) == (11, 10)
    assert (cond.op_line, cond.op_col) == (11, 12)  # the `&` of `&gt;`
    assert (cond.right.line, cond.right.col, cond.right.end_col) == (11, 17, 18)
    assert (st.branches[0].body[0].line, st.branches[0].body[0].col) == (12, 5)
    # and errors on such a line
    bad = "begin\n  if a > #\n  endIf\nend"
    _, diags = parse_code(bad, sm, "f.pgx")
    assert [(d.code, d.line, d.col, d.end_col) for d in diags] == [("F102", 11, 17, 18)]


def test_empty_source_map_is_identity():
    body, diags = parse_code("begin\n x = 1\nend", SourceMap(), "f.pgx")
    assert not diags and (body.statements[0].line, body.statements[0].col) == (2, 2)


def test_every_node_has_a_file_position():
    code = ("begin\n  x = {a[1].b, -c, !d, lib:e, $f(), \"s\", true, 1.5, g = h, i + j}\n"
            "  call p(x)\n  switch x\n  case 1\n  break\n  default\n  endSwitch\n"
            "  do\n  until x\n  for i = 1 to 2\n  endFor\n  while x\n    return\n  endWhile\nend")
    body = parse(code, first_line=100, first_col=30)
    for node in A.walk(body):
        assert node.line >= 100 and node.col >= 1, node
        if node is not body:
            assert node.line > 100, node
