"""T codes: operators, conditions, assignments, literals, switch and for (chapters 2.2.5, 2.4.2,
3, 9, 10)."""

from __future__ import annotations

import pytest
from .checkhelp import codes, findings

G = ["num nX", "num nY", "string sA", "string sB", "bool bA", "bool bB", "dio diA", "dio doB", "aio aiA", "sio siA",
     "joint jA", "joint jB", "trsf trA", "trsf trB", "point pA", "point pB", "frame fA", "tool tA", "config cA",
     "mdesc mA", "num nArr[3]"]


@pytest.mark.parametrize("expr", [
    "sA = sA + sB", "bA = jA < jB", "bA = jA > jB", "jA = jA + jB - jA", "trA = trA * !trB", "bA = pA == pB",
    "bA = fA != fA", "bA = tA == tA", "bA = cA == cA", "bA = mA != mA", "nX = -nY % 3 / 2 * 1", "bA = !bB xor bA",
    "bA = diA == bB", "bA = diA == doB", "bA = !diA", "bA = diA and bB", "bA = sA != \"\"", "nX = aiA + 1",
    "bA = pA.config.shoulder == righty", "bA = mA.blend != off",
])
def test_operators_the_manual_defines(tmp_path, expr):
    assert codes(tmp_path, f"begin\n  {expr}\nend", globals_=G) == []


@pytest.mark.parametrize("expr,col", [
    ("sA = sA + nX", 11), ("pA = pA + pB", 11), ("jA = jA * jB", 11), ("bA = bA and nX", 11), ("bA = sA < sB", 11),
    ("bA = jA <= jB", 11), ("trA = -trA", 9), ("bA = !nX", 8), ("bA = sA == nX", 11), ("nX = trA + trB", 12),
])
def test_operators_the_manual_does_not_define(tmp_path, expr, col):
    assert findings(tmp_path, f"begin\n  {expr}\nend", globals_=G) == [("T001", 2, col)]


def test_user_types_have_only_assignment(tmp_path):
    # an unresolved user type is unknown: no error; see test_checker_libraries for resolved ones
    assert codes(tmp_path, "begin\n  bA = uA == uB\nend", globals_=["bool bA", "Part uA", "Part uB"]) == ["N010", "N010"]


def test_conditions(tmp_path):
    code = "begin\n  if nX\n  elseIf sA\n  endIf\n  while diA\n  endWhile\n  do\n  until bA or diA\nend"
    assert findings(tmp_path, code, globals_=G) == [("T002", 2, 6), ("T002", 3, 10)]


def test_assignment_in_a_condition_is_one_finding_at_the_equal_sign(tmp_path):
    code = "begin\n  if nX = 1\n  endIf\n  if(bA=bB)\n  endIf\n  nX = cos(nY=30)\n  nX = len(sA=\"x\")\nend"
    assert findings(tmp_path, code, globals_=G) == [("T004", 2, 9), ("T004", 4, 8), ("T004", 6, 14), ("T004", 7, 14)]


def test_chained_assignment_is_not_reported(tmp_path):
    assert codes(tmp_path, "begin\n  nX = nY = 0\nend", globals_=G) == []


@pytest.mark.parametrize("stmt", [
    "sA = toString(\"\", nX)", "siA = sA", "siA = nX", "sA = siA", "nX = siA", "doB = bA", "doB = (diA == true)",
    "bA = diA", "nX = aiA", "pA = pB", "pA.trsf = trA", "pA.config = cA", "tA.gripper = bA", "mA.vel = 50",
    "jA.j7 = 0", "mA.tvel = 1", "mA.tmax = 1",
])
def test_assignments_that_compile(tmp_path, stmt):
    assert codes(tmp_path, f"begin\n  {stmt}\nend", globals_=G) == []


@pytest.mark.parametrize("stmt,code", [
    ("sA = nX", "T003"), ("nX = sA", "T003"), ("nX = bA", "T003"), ("pA = jA", "T003"), ("trA = pA", "T003"),
    ("bA = nX", "T003"), ("doB = diA", "T016"), ("righty = cA.shoulder", "T013"), ("pA.trsf.q = 1", "T012"),
    ("nX = nY.x", "T012"), ("nX = pA.z", "T012"),
])
def test_assignments_that_do_not(tmp_path, stmt, code):
    assert codes(tmp_path, f"begin\n  {stmt}\nend", globals_=G) == [code]


def test_dio_copy_is_allowed_in_s6(tmp_path):
    assert codes(tmp_path, "begin\n  doB = diA\nend", globals_=G, version="s6.8") == []


def test_an_undefined_name_causes_one_finding_only(tmp_path):
    code = "begin\n  sA = nUnknown + 1\n  bA = nUnknown.x == 3\n  call nowhere(nUnknown[2])\n  movej(nUnknown, flange, mA)\nend"
    assert codes(tmp_path, code, globals_=G) == ["N001", "N001", "N002", "N001", "N001"]


def test_structured_literals(tmp_path):
    ok = """begin
  pA = {{100, -50, 200, 0, 0, 0}, {sfree, efree, wfree}}
  pA.trsf = {100, -50, 200,,}
  trA = {}
  movel(appro(pA, {0, 0, -10, 0, 0, 0}), flange, mA)
  mA = {100, 100, 100, 9999, 9999, joint, 50, 50}
  bA = trA == {0, 0, 0, 0, 0, 0}
end"""
    assert codes(tmp_path, ok, globals_=G) == []
    bad = """begin
  trA = {1, 2, 3, 4, 5, 6, 7}
  nX = {1}
  pA = {{1, 2, 3, 4, 5, 6}, {sfree, efree, wfree}, 1}
  pA = {{1, 2, 3, 4, 5, 6, 7}, {sfree}}
  trA = {1, "2"}
end"""
    assert findings(tmp_path, bad, globals_=G) == [("T017", 2, 9), ("T017", 3, 8), ("T017", 4, 8), ("T017", 5, 9),
                                                   ("T017", 6, 13)]


def test_switch_case_types(tmp_path):
    code = """begin
  switch nX
    case 1, nY
    break
    case "2"
    break
  endSwitch
  switch sA
    case "a", sB
    break
    case 3
    break
  endSwitch
end"""
    assert findings(tmp_path, code, globals_=G) == [("T014", 5, 10), ("T014", 11, 10)]


def test_for_header(tmp_path):
    code = """begin
  for nX = 0 to 3 step 1
  endFor
  for nArr[1] = nY to size(nArr) - 1
  endFor
  for jA.j1 = 0 to 90 step 10
  endFor
  for sA = 0 to 3
  endFor
  for nX = 0 to "3"
  endFor
end"""
    assert findings(tmp_path, code, globals_=G) == [("T015", 8, 7), ("T015", 10, 17)]
