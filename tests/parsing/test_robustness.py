"""The parser never raises: garbage, huge input and deep nesting become diagnostics."""

from __future__ import annotations

import random
import sys

import pytest

from val3check.parsing import ast as A
from val3check.parsing.parser import MAX_BLOCK_DEPTH, parse_code
from val3check.positions import SourceMap


def run(code: str):
    body, diags = parse_code(code, SourceMap.identity(code), "t.pgx")
    for d in diags:
        assert d.code.startswith("F10") and d.line >= 1 and d.col >= 1 and d.message.isprintable(), d
    return body, diags


@pytest.mark.parametrize("seed", range(8))
def test_random_bytes(seed):
    rnd = random.Random(seed)
    data = bytes(rnd.getrandbits(8) for _ in range(5000)).decode("latin-1")
    for code in (data, "begin\n" + data + "\nend"):
        body, diags = run(code)
        assert body is None and 1 <= len(diags) <= 10


@pytest.mark.parametrize("seed", range(20))
def test_random_token_soup(seed):
    rnd = random.Random(seed)
    words = ["begin", "end", "if", "endIf", "else", "elseIf", "while", "endWhile", "do", "until", "for",
             "to", "step", "endFor", "switch", "case", "default", "break", "endSwitch", "call", "return",
             "x", "lib:y", "$z", "1", "2.5e3", '"s"', '"', "(", ")", "[", "]", "{", "}", ",", ".", ":", "=",
             "==", "!=", "<", ">=", "+", "-", "*", "/", "%", "!", "and", "or", "xor", "true", "\n", "\n",
             "// c\n", "#", "0x1", ";"]
    code = " ".join(rnd.choice(words) for _ in range(400))
    run(code)
    run("begin\n" + code + "\nend")


def test_deep_parentheses_are_fine():
    n = 10_000
    body, diags = run("begin\n  x = " + "(" * n + "1" + ")" * n + "\nend")
    assert not diags and isinstance(body.statements[0].value, A.Number)
    body, diags = run("begin\n  x = " + "(" * n + "1\nend")
    assert [d.code for d in diags] == ["F101"] and "missing ')'" in diags[0].message


@pytest.mark.parametrize("make", [
    lambda n: "-" * n + "a",
    lambda n: "!" * n + "a",
    lambda n: "f(" * n + "1" + ")" * n,
    lambda n: "{" * n + "1" + "}" * n,
    lambda n: "a[" * n + "1" + "]" * n,
    lambda n: "1" + "+1" * n,
    lambda n: "a = " * n + "1",
])
def test_deep_expressions_are_reported(make):
    body, diags = run("begin\n  x = " + make(10_000) + "\nend")
    assert body is None and [(d.code, d.line, d.col) for d in diags] == [("F104", 2, 3)]


def test_deep_blocks_are_reported():
    n = 10_000
    body, diags = run("begin\n" + "if a\n" * n + "endIf\n" * n + "end")
    assert body is None and [(d.code, d.line, d.col) for d in diags] == [("F104", MAX_BLOCK_DEPTH + 2, 1)]
    body, diags = run("begin\n" + "do\n" * n + "until a\n" * n + "end")
    assert [d.code for d in diags] == ["F104"]


def test_limits_accept_reasonable_code():
    body, diags = run("begin\n" + "while a\n" * MAX_BLOCK_DEPTH + "endWhile\n" * MAX_BLOCK_DEPTH + "end")
    assert not diags
    body, diags = run("begin\n  x = " + "-" * 90 + "a\nend")
    assert not diags


def test_deep_code_does_not_need_a_big_recursion_limit():
    old = sys.getrecursionlimit()
    sys.setrecursionlimit(200)
    try:
        body, diags = run("begin\n" + "if a\n" * 50 + "x = " + "(" * 5000 + "1" + ")" * 5000 + "\n" + "endIf\n" * 50 + "end")
    finally:
        sys.setrecursionlimit(old)
    assert not diags


def test_huge_input():
    body, diags = run("begin\n  x = " + "a" * 5_000_000 + "\nend")
    assert not diags and len(body.statements[0].value.name) == 5_000_000
    body, diags = run("begin\n  x = \"" + "#" * 5_000_000 + "\nend")
    assert [d.code for d in diags] == ["F101"]
    body, diags = run("begin\n" + "  x = 1 +\n" * 200_000 + "end")
    assert len(diags) == 10
    body, diags = run("begin\n" + "  x = 1 + 2\n" * 200_000 + "end")
    assert not diags and len(body.statements) == 200_000


def test_odd_characters():
    for code in ("begin\n\x00\nend", "\ufeffbegin\nend", "begin\n  x = \u2028\nend", "begin\r\nend\r\n", "begin\rend"):
        run(code)
    assert not run("begin\r\n  x = 1\r\n  // c\r\nend\r\n")[1]
    assert not run("begin\n\tx\t=\t1\f\nend")[1]


def test_broken_source_map_does_not_raise():
    from val3check.positions import Position

    sm = SourceMap([Position(1, 1)], {5: []})
    body, diags = parse_code("begin\n  x = 1\n\n\n\n  y = 2 +\nend", sm, "t.pgx")
    assert [d.code for d in diags] == ["F101"]
