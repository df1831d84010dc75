"""Expressions: operators and their precedence (chapters 3 and 9), literals, calls, misuse of `=`."""

from __future__ import annotations

import pytest

from val3check.parsing import ast as A

from .shapes import expr, stmts, sx


@pytest.mark.parametrize("text,shape", [
    # or < and < xor (3.1.2 lists the bool operators by increasing priority)
    ("a or b and c", "(or a (and b c))"),
    ("a and b or c", "(or (and a b) c)"),
    ("a and b xor c", "(and a (xor b c))"),
    ("a xor b and c", "(and (xor a b) c)"),
    ("a or b xor c", "(or a (xor b c))"),
    # comparisons bind tighter than the logical operators, == and != looser than < > <= >=
    ("a == b and c != d", "(and (== a b) (!= c d))"),
    ("a < b == c > d", "(== (< a b) (> c d))"),
    ("a <= b != c >= d", "(!= (<= a b) (>= c d))"),
    ("!b == c", "(== (! b) c)"),
    ("!(b == c)", "(! (== b c))"),
    ("a + b < c * d", "(< (+ a b) (* c d))"),
    # arithmetic (3.2.2): * / % above + -, all left-associative
    ("a + b * c % d", "(+ a (% (* b c) d))"),
    ("a - b + c", "(+ (- a b) c)"),
    ("a - b - c", "(- (- a b) c)"),
    ("a / b * c", "(* (/ a b) c)"),
    ("a % b / c", "(/ (% a b) c)"),
    ("(a + b) * c", "(* (+ a b) c)"),
    # unary - and ! above everything (3.2.2, 3.1.2, 9.3.3 trsf inverse)
    ("-x*y", "(* (- x) y)"),
    ("-x - -y", "(- (- x) (- y))"),
    ("!a and !b", "(and (! a) (! b))"),
    ("- -x", "(- (- x))"),
    ("!!b", "(! (! b))"),
    ("-f(x)[1].y", "(- (. (idx (call f x) 1) y))"),
    # trsf and joint operators of chapter 9
    ("!trA * trB", "(* (! trA) trB)"),
    ("trA * trB * trC", "(* (* trA trB) trC)"),
    ("jA - jB < jC", "(< (- jA jB) jC)"),
    ("!(abs(j - jReference) < jEcartMax)", "(! (< (call abs (- j jReference)) jEcartMax))"),
    # keyword operators in any case
    ("a OR b AND c", "(or a (and b c))"),
    ("a Xor b", "(xor a b)"),
])
def test_precedence(text, shape):
    assert sx(expr(text)) == shape


def test_binary_positions():
    (st,) = stmts("x = ab + cd * 2")
    e = st.value
    assert (e.line, e.col, e.op_line, e.op_col) == (2, 5, 2, 8)
    assert (e.right.line, e.right.col, e.right.op_col) == (2, 10, 13)


@pytest.mark.parametrize("text,value", [
    ("1", 1.0), ("0.2", 0.2), ("3.141592653", 3.141592653), ("6.02214179e23", 6.02214179e23),
    ("1.054571628e-34", 1.054571628e-34), (".5", 0.5), ("1.", 1.0), ("1e-3", 1e-3), ("1.5E+4", 1.5e4),
    ("2e3", 2000.0), ("007", 7.0),
])
def test_numbers(text, value):
    n = expr(text)
    assert isinstance(n, A.Number) and n.value == value and n.text == text


def test_negative_constant_is_folded():
    n = expr("-3.141592653")
    assert isinstance(n, A.Number) and n.value == -3.141592653 and n.text == "-3.141592653"
    assert (n.col, n.end_col) == (5, 17)
    assert sx(expr("--3")) == "(- -3)"
    assert sx(expr("2 - 3")) == "(- 2 3)"


def test_strings_and_bools():
    assert expr('"ceci est une chaîne"').value == "ceci est une chaîne"
    assert expr('""').value == ""
    s = expr('"a // not a comment"')
    assert s.value == "a // not a comment"
    assert [expr(t).value for t in ("true", "FALSE", "True", "false")] == [True, False, True, False]


def test_names_libraries_system_names():
    assert sx(expr("part:sVersion")) == "part:sVersion"
    e = expr("lib:prog(x) + $movejSyncState()")
    assert sx(e) == "(+ (call lib:prog x) (call $movejSyncState))"
    assert isinstance(e.right.func, A.SystemName)
    assert isinstance(expr("lib:x"), A.LibraryName)


def test_calls_index_fields():
    assert sx(expr("sin(x)")) == "(call sin x)"
    assert sx(expr("size(sColl)")) == "(call size sColl)"
    assert sx(expr("distance(here(tTool,world),pTarget) < 10")) == "(< (call distance (call here tTool world) pTarget) 10)"
    assert sx(expr("a[1, 2, 3].trsf.x")) == "(. (. (idx a 1 2 3) trsf) x)"
    assert sx(expr("here(t, w).trsf.x")) == "(. (. (call here t w) trsf) x)"
    assert sx(expr("n2dArray[5.01, 6.99]")) == "(idx n2dArray 5.01 6.99)"
    f = expr("p.trsf")
    assert (f.line, f.col, f.name_line, f.name_col) == (2, 5, 2, 7)


def test_structs():
    assert sx(expr("{,,,,,}")) == "{, , , , , }"
    assert expr("{,,,,,}").fields == [None] * 6
    assert expr("{}").fields == []
    assert expr("{1}").fields[0].value == 1.0
    assert sx(expr("{l_k * 10.5, 0, 0, 0, 0, 0}")) == "{(* l_k 10.5), 0, 0, 0, 0, 0}"
    assert sx(expr("appro(p, {0, 0, -50, 0, 0, 0})")) == "(call appro p {0, 0, -50, 0, 0, 0})"
    s = expr("{1, 2}")
    assert (s.line, s.col) == (2, 5)


def test_assignment_inside_expressions_is_a_node():
    # 3.1.2 / 3.2.2: `=` is not allowed in instruction parameters and conditions, but it parses
    (st,) = stmts("if(b1=b2)\nendIf")
    cond = st.branches[0].cond
    assert isinstance(cond, A.AssignExpr) and sx(cond) == "(= b1 b2)"
    assert (cond.line, cond.col, cond.op_line, cond.op_col) == (2, 4, 2, 6)
    assert sx(expr("cos(n=30)")) == "(call cos (= n 30))"
    assert sx(expr("y = 0")) == "(= y 0)"
    assert sx(expr("a = b = c")) == "(= a (= b c))"  # right-associative
    assert sx(expr("a = b or c")) == "(= a (or b c))"  # lowest precedence
    assert sx(expr("len(sChaine=\"hello wild world\")")) == '(call len (= sChaine "hello wild world"))'
    (w,) = stmts("while(a = b == c)\nendWhile")
    assert sx(w.cond) == "(= a (== b c))"
