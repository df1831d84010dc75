"""Helpers for the parser tests: parse snippets, show trees as compact S-expressions."""

from __future__ import annotations

from val3check.parsing import ast as A
from val3check.parsing.parser import parse_code
from val3check.positions import SourceMap


def parse(code: str, first_line: int = 1, first_col: int = 1) -> A.ProgramBody:
    """Parse `code`, which must be valid."""
    body, diags = parse_code(code, SourceMap.identity(code, first_line, first_col), "t.pgx")
    assert not diags, [(d.code, d.line, d.col, d.message) for d in diags]
    assert body is not None
    return body


def stmts(lines: str) -> list:
    """Parse statements wrapped in begin/end."""
    return parse("begin\n" + lines.strip("\n") + "\nend\n").statements


def expr(text: str):
    """The value of `x = <text>`."""
    (st,) = stmts(f"x = {text}")
    assert isinstance(st, A.Assign)
    return st.value


def errors(code: str, first_line: int = 1, first_col: int = 1) -> list[tuple[str, int, int, str]]:
    body, diags = parse_code(code, SourceMap.identity(code, first_line, first_col), "t.pgx")
    assert body is None if diags else body is not None
    return [(d.code, d.line, d.col, d.message) for d in diags]


def sx(node) -> str:
    """A compact S-expression of an expression tree: `(+ a (* b c))`."""
    if node is None:
        return "_"
    t = type(node)
    if t is A.Number:
        return node.text
    if t is A.String:
        return f'"{node.value}"'
    if t is A.Bool:
        return "true" if node.value else "false"
    if t is A.Name:
        return node.name
    if t is A.LibraryName:
        return f"{node.alias}:{node.name}"
    if t is A.SystemName:
        return node.name
    if t is A.Index:
        return f"(idx {sx(node.base)} {' '.join(sx(i) for i in node.indices)})"
    if t is A.Field:
        return f"(. {sx(node.base)} {node.name})"
    if t is A.CallExpr:
        return f"(call {sx(node.func)}{''.join(' ' + sx(a) for a in node.args)})"
    if t is A.Unary:
        return f"({node.op} {sx(node.operand)})"
    if t is A.Binary:
        return f"({node.op} {sx(node.left)} {sx(node.right)})"
    if t is A.Struct:
        return "{" + ", ".join(sx(f) if f is not None else "" for f in node.fields) + "}"
    if t is A.AssignExpr:
        return f"(= {sx(node.target)} {sx(node.value)})"
    raise AssertionError(f"not an expression: {node!r}")
