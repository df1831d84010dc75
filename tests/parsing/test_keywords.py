"""Keywords are case-insensitive; names that merely start with a keyword are names."""

from __future__ import annotations

import pytest

from val3check.parsing import ast as A

from .shapes import expr, parse, stmts, sx


def test_keywords_in_any_case():
    body = parse("""Begin
  IF a
  ELSEIF b
  Else
  ENDIF
  if a
  elseif b
  endif
  While c
  ENDWHILE
  DO
  UNTIL d
  For i = 1 TO 2 STEP 1
  EndFor
  SWITCH x
  CASE 1
  BREAK
  DEFAULT
  ENDSWITCH
  CALL p()
  RETURN
END""")
    kinds = [type(s).__name__ for s in body.statements]
    assert kinds == ["If", "If", "While", "DoUntil", "For", "Switch", "Call", "Return"]
    assert sx(body.statements[4].step) == "1"


@pytest.mark.parametrize("name", [
    "endPoint", "ifx", "dox", "forward", "caseA", "tool", "breakOut", "order", "android", "endIfx",
    "beginning", "ending", "untilDone", "whileOk", "switchOn", "defaults", "returned", "caller",
    "trueValue", "falsey", "toto", "stepper", "xorMask", "oreo", "andy", "elseWhere", "To", "step",
])
def test_names_starting_with_keywords(name):
    (st,) = stmts(f"{name} = {name} + 1")
    assert isinstance(st.target, A.Name) and st.target.name == name
    assert sx(st.value) == f"(+ {name} 1)"


def test_to_and_step_are_names_outside_for():
    a, b, f = stmts("to = step\nstep = to * 2\nfor to = step to to step step\nendFor")
    assert sx(a.target) == "to" and sx(a.value) == "step"
    assert sx(b.value) == "(* to 2)"
    assert (sx(f.counter), sx(f.start), sx(f.stop), sx(f.step)) == ("to", "step", "to", "step")


def test_identifier_spelling_is_kept():
    e = expr("nCount + NCOUNT + ncount")
    assert sx(e) == "(+ (+ nCount NCOUNT) ncount)"


def test_keyword_operators_need_separation():
    # `aor` is one name, not `a or`
    assert sx(expr("aor")) == "aor"
    assert sx(expr("a or(b)")) == "(or a b)"
    assert sx(expr("(a)or(b)")) == "(or a b)"
