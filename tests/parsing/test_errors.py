"""Syntax errors: exact positions, readable messages, recovery without cascades."""

from __future__ import annotations

import pytest

from .shapes import errors


@pytest.mark.parametrize("code,expected", [
    ("begin\n  if a\n    x = 1\n  endWhile\nend",
     ("F101", 4, 3, "unexpected 'endWhile': the 'if' opened on line 2 is not closed (expected 'endIf')")),
    ("begin\n  x = 1 +\nend", ("F101", 2, 10, "expected an expression after '+'")),
    ("begin\n  x = a and // why\nend", ("F101", 2, 13, "expected an expression after 'and'")),
    ("begin\n  elseIf x\nend", ("F101", 2, 3, "'elseIf' without 'if'")),
    ("begin\n  else\nend", ("F101", 2, 3, "'else' without 'if'")),
    ("begin\n  endIf\nend", ("F101", 2, 3, "'endIf' without 'if'")),
    ("begin\n  until x\nend", ("F101", 2, 3, "'until' without 'do'")),
    ("begin\n  case 1\nend", ("F101", 2, 3, "'case' without 'switch'")),
    ("begin\n  endFor\nend", ("F101", 2, 3, "'endFor' without 'for'")),
    ("begin\n  if x\n  x = 1\nend",
     ("F101", 4, 1, "unexpected 'end': the 'if' opened on line 2 is not closed (expected 'endIf' before it)")),
    ("begin\n  while x\n  x = 1\n",
     ("F101", 4, 1, "unexpected end of the program: the 'while' opened on line 2 is not closed (expected 'endWhile')")),
    ("begin\n  do\n    x = 1\n  endWhile\nend",
     ("F101", 4, 3, "unexpected 'endWhile': the 'do' opened on line 2 is not closed (expected 'until')")),
    ("begin\n  if a\n  else\n  else\n  endIf\nend",
     ("F101", 4, 3, "unexpected 'else': the 'if' already has an 'else' on line 3")),
    ("begin\n  if a\n  else\n  elseIf b\n  endIf\nend",
     ("F101", 4, 3, "unexpected 'elseIf': the 'if' already has an 'else' on line 3")),
    ("begin\n  switch x\n    case 1\n    default\n    case 2\n  endSwitch\nend",
     ("F101", 5, 5, "unexpected 'case': the 'switch' already has a 'default' on line 4")),
    ("begin\n  switch n\n    x = 1\n  endSwitch\nend",
     ("F101", 3, 5, "unexpected name 'x': the statements of a 'switch' of line 2 go in its 'case' or "
                    "'default' clauses (expected 'case', 'default' or 'endSwitch')")),
    ("begin\n  x = foo(a, b\nend", ("F101", 2, 15, "missing ')': the '(' at line 2, column 10 is not closed")),
    ("begin\n  x = y[1\nend", ("F101", 2, 10, "missing ']': the '[' at line 2, column 8 is not closed")),
    ("begin\n  x = {1, 2\nend", ("F101", 2, 12, "missing '}': the '{' at line 2, column 7 is not closed")),
    ("begin\n  x\nend", ("F101", 2, 4, "incomplete statement: expected '=' (assignment) or '(' (call) after 'x'")),
    ("begin\n  x == 1\nend",
     ("F101", 2, 5, "unexpected '==': a statement cannot be a comparison (to assign a value, write '=')")),
    ("begin\n  if\n  endIf\nend", ("F101", 2, 5, "expected a condition after 'if'")),
    ("begin\n  until\nend", ("F101", 2, 3, "'until' without 'do'")),
    ("begin\n  x = if\nend", ("F101", 2, 7, "unexpected keyword 'if': expected an expression")),
    ("begin\n  return 1\nend", ("F101", 2, 10, "unexpected number '1': expected the end of the line")),
    ("begin\n  movej(j, flange, m) x\nend", ("F101", 2, 23, "unexpected name 'x': expected the end of the line")),
    ("begin\n  x = 1 2\nend",
     ("F101", 2, 9, "unexpected number '2': expected an operator, the end of the line, '.' or '['")),
    ("begin\n  for i = 1 5\n  endFor\nend",
     ("F101", 2, 13, "unexpected number '5': expected an operator, 'to', '.' or '['")),
    ("begin\n  call foo\nend", ("F101", 2, 11, "unexpected end of line: expected '(' or ':'")),
    ("begin\n  whlie x\n    y = 1\n  endWhile\nend",
     ("F101", 2, 9, "unexpected name 'x' after 'whlie': did you mean 'while'?")),
    ("x = 1\nend", ("F101", 1, 1, "unexpected name 'x': a program starts with 'begin'")),
    ("", ("F101", 1, 1, "empty program: expected 'begin'")),
    ("begin\n  x = 1\n", ("F101", 3, 1, "missing 'end' at the end of the program")),
    ("begin\nend\nx = 1", ("F101", 3, 1, "unexpected name 'x' after 'end': the program ends with 'end'")),
    ("begin x = 1\nend", ("F101", 1, 7, "unexpected name 'x' after 'begin': statements start on the next line")),
    # lexical errors
    ("begin\n  x = \"abc\nend", ("F101", 2, 7, "unterminated string: a string ends with '\"' on the same line")),
    ("begin\n  x = 0x1F\nend",
     ("F103", 2, 7, "invalid number '0x1F': hexadecimal and binary constants are not VAL 3 numbers (manual 3.2.1)")),
    ("begin\n  x = 1e\nend", ("F103", 2, 7, "invalid number '1e': the exponent has no digits")),
    ("begin\n  x = 3abc\nend",
     ("F103", 2, 7, "invalid number '3abc': a number cannot be followed by letters, and a name starts with a letter")),
    ("begin\n  x = 1.2.3\nend",
     ("F103", 2, 7, "invalid number '1.2.3': numbers are written <digits>[.<digits>][e[-]<digits>] (manual 3.2.1)")),
    ("begin\n  x = 3 # 4\nend", ("F102", 2, 9, "invalid character '#': comments start with '//'")),
    ("begin\n  x = 'abc'\nend", ("F102", 2, 7, "invalid character ''': strings are written between double quotes")),
    ("begin\n  x = 1;\nend", ("F102", 2, 8, "invalid character ';': VAL 3 has one statement per line and no ';'")),
    ("begin\n  if a && b\n  endIf\nend",
     ("F102", 2, 8, "invalid character '&': the logical operators are 'and', 'or', 'xor' and '!'")),
    ("begin\n  nVal\u00e9 = 1\nend",
     ("F102", 2, 7, "invalid character '\u00e9': names use the letters a-z, A-Z, digits and '_' (manual 2.5.1)")),
    ("begin\n  x = \u00a01\nend", ("F102", 2, 7, "invalid character 'U+00A0'")),
])
def test_message_and_position(code, expected):
    assert errors(code) == [expected]


def test_messages_never_show_internal_names():
    samples = [
        "begin\n  x = (\nend", "begin\n  x = ]\nend", "begin\n  for\nend", "begin\n  for i\nend",
        "begin\n  for i =\nend", "begin\n  for i = 1 to\nend", "begin\n  for i = 1 to 2 step\nend",
        "begin\n  call\nend", "begin\n  call a:\nend", "begin\n  x = a.\nend", "begin\n  x = a:\nend",
        "begin\n  x = $\nend", "begin\n  $x = 1\nend", "begin\n  x = {\nend", "begin\n  x = f(,)\nend",
        "begin\n  switch\nend", "begin\n  case\nend", "begin\n  x = a[]\nend", "begin\n  ) = 1\nend",
        "begin\n  x = 1 to 2\nend", "begin\n  x = !\nend", "begin\n  x = a < < b\nend",
    ]
    for code in samples:
        errs = errors(code)
        assert errs, code
        for _, line, col, msg in errs:
            assert "__" not in msg and "$END" not in msg and "_NL" not in msg and "ANON" not in msg, (code, msg)
            assert "_LPAR" not in msg and "NAME" not in msg and "ERROR" not in msg, (code, msg)
            assert line >= 1 and col >= 1


def test_positions_are_file_positions():
    assert errors("begin\n  x = 1 +\nend", first_line=9, first_col=15) == [
        ("F101", 10, 10, "expected an expression after '+'")]
    assert errors("begin\n  if a\n  endWhile\nend", first_line=9, first_col=15) == [
        ("F101", 11, 3, "unexpected 'endWhile': the 'if' opened on line 10 is not closed (expected 'endIf')")]


def test_recovery_reports_independent_errors():
    code = """begin
  x = 3 # 4
  y = ( 1
  z = 2 2
  if a ==
    w = * 2
  endIf
  for i 1 to 2
    v = 1
  endFor
  ok = 1
end"""
    got = [(c, ln, k) for c, ln, k, _ in errors(code)]
    assert got == [("F102", 2, 9), ("F101", 3, 10), ("F101", 4, 9), ("F101", 5, 10), ("F101", 6, 9), ("F101", 8, 9)]


def test_one_error_per_line():
    assert [e[:3] for e in errors("begin\n  x = 1 2 3 ) ( #\nend")] == [("F101", 2, 9)]
    assert [e[:3] for e in errors("begin\n  x = \"abc) + (\nend")] == [("F101", 2, 7)]
    assert [e[:3] for e in errors("begin\n  x = 0x1F 5\nend")] == [("F103", 2, 7)]


def test_no_cascade_after_a_broken_block_opener():
    # the misspelt `while` is reported; its `endWhile` is then not reported again
    assert [e[:3] for e in errors("begin\n  whlie x\n    y = 1\n  endWhile\nend")] == [("F101", 2, 9)]
    # a broken condition keeps its block open: no error at endIf/endFor
    assert [e[:3] for e in errors("begin\n  if x ==\n    y = 1\n  endIf\nend")] == [("F101", 2, 10)]
    assert [e[:3] for e in errors("begin\n  for i = 1\n    y = 1\n  endFor\nend")] == [("F101", 2, 12)]
    assert [e[:3] for e in errors("begin\n  while (a\n    y = 1\n  endWhile\nend")] == [("F101", 2, 11)]
    assert [e[:3] for e in errors("begin\n  switch\n    case 1\n  endSwitch\nend")] == [("F101", 2, 9)]
    assert [e[:3] for e in errors("begin\n  do\n  until x ==\n  y = 1\nend")] == [("F101", 3, 13)]


def test_structural_error_after_recovery_is_not_reported():
    assert [e[:3] for e in errors("begin\n  x = = 1\n  endIf\nend")] == [("F101", 2, 7)]
    assert [e[:3] for e in errors("begin\n  x = (\n  if a\nend")] == [("F101", 2, 8)]


def test_error_count_is_capped():
    code = "begin\n" + "  x = = 1\n" * 50 + "end"
    assert len(errors(code)) == 10


def test_task_creation_errors():
    assert errors('begin\n  taskCreate("t1", 10, read())\nend') == [
        ("F101", 2, 18, "unexpected ',': 'taskCreate' takes its arguments without parentheses: "
                        "taskCreate \"name\", priority, program(...)")]
    assert [e[:3] for e in errors('begin\n  taskCreate "t1", 10, read\nend')] == [("F101", 2, 28)]


def test_no_cascade_after_an_invalid_character_at_a_block_opener():
    assert [e[:3] for e in errors("begin\n  #if a\n    x = 1\n  endIf\nend")] == [("F102", 2, 3)]
    # a lexical error that needs no resynchronisation does not hide a structural one
    assert [e[:3] for e in errors("begin\n  if a\n    x = 0x1\nend")] == [("F103", 3, 9), ("F101", 4, 1)]
