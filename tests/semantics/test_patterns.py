"""S rules (val3check.semantics.patterns): what they report, and above all what they must not.

The catalogue examples (rules/S0xx.toml) are run by tests/test_rule_examples.py; these tests
add the cases that make the rules quiet on idiomatic code, and robustness on odd trees.
"""

from __future__ import annotations

from pathlib import Path

import pytest
from support import lint

from val3check.testing import write_app, write_files

from val3check.semantics import patterns


@pytest.fixture(autouse=True)
def strict():
    patterns.STRICT = True  # a failing check raises instead of being skipped
    yield
    patterns.STRICT = False


def s_found(folder: Path, code: str | None = None) -> list[tuple[str, str, int, int, str]]:
    """(code, file name, line, col, message) of the S findings of the application in `folder`."""
    run = lint([folder], cwd=folder.parent)
    return [(d.code, Path(d.path).name, d.line, d.col, d.message) for d in run.result.diagnostics
            if d.code.startswith("S") and (code is None or d.code == code)]


def codes(folder: Path) -> list[str]:
    return sorted(f[0] for f in s_found(folder))


def at(folder: Path, file: str, marker: str, nth: int = 0) -> tuple[int, int]:
    """File line and column of the nth occurrence of `marker` in folder/file."""
    text = (folder / file).read_text(encoding="utf-8")
    i = -1
    for _ in range(nth + 1):
        i = text.index(marker, i + 1)
    return text.count("\n", 0, i) + 1, i - (text.rfind("\n", 0, i) + 1) + 1


def app(tmp_path, code, globals_=(), locals_=(), programs=None, name="App"):
    return write_app(tmp_path, code, name, globals_=globals_, locals_=locals_, programs=programs)


# ------------------------------------------------------------------ S001 / S002 unused locals, parameters


def test_unused_local_only_when_never_mentioned(tmp_path):
    f = app(tmp_path, "begin\n  l_nRes = clearBuffer(siCom)\n  L_NCASE = 1\nend",
            globals_=["sio siCom"], locals_=["num l_nRes", "num l_nCase", "num l_nDead"])
    found = s_found(f, "S001")
    assert [x[4] for x in found] == ["local variable 'l_nDead' is declared in start() but never used"]
    assert found[0][2:4] == at(f, "start.pgx", '<Local name="l_nDead"')


def test_unused_parameter_reported_for_private_program(tmp_path):
    f = app(tmp_path, "begin\n  call show(1, 2)\nend",
            programs={"show": {"access": "private", "params": ["num x_nA", "num& x_nB"], "code": "begin\n  put(x_nA)\nend"}})
    found = s_found(f, "S002")
    assert [x[4] for x in found] == ["parameter 'x_nB' of show() is never used"]


def test_unused_parameter_not_reported_for_task_programs(tmp_path):
    f = app(tmp_path, 'begin\n  taskCreate "t", 10, worker(1)\nend',
            programs={"worker": {"access": "private", "params": ["num x_nId"], "code": "begin\n  delay(1)\nend"}})
    assert "S002" not in codes(f)


def test_library_interface_is_not_reported(tmp_path):
    # no start(): a library; its public programs and globals are its interface (6.2)
    files = {
        "Lib/Lib.pjx": _pjx(["show", "helper"], "Lib"),
        "Lib/Lib.dtx": _dtx(['<Data name="nPublic" access="public" xsi:type="array" type="num" size="1" />',
                            '<Data name="nSecret" access="private" xsi:type="array" type="num" size="1" />']),
        "Lib/show.pgx": _pgx("show", "begin\n  putln(\"x\")\nend", params=['<Parameter name="x_nLine" type="num" xsi:type="element" />']),
        "Lib/helper.pgx": _pgx("helper", "begin\nend", access="private"),
    }
    write_files(tmp_path, files)
    found = s_found(tmp_path / "Lib")
    assert sorted((x[0], x[4]) for x in found) == [
        ("S003", "private global variable 'nSecret' is never used by a program of the application"),
        ("S004", "private program helper() is never called (call, taskCreate, taskCreateSync) in the application"),
    ]


def test_application_used_as_a_library_keeps_its_public_globals(tmp_path):
    lib = app(tmp_path, "begin\nend", name="Tools", globals_=["num nShared", "private num nOwn"])
    main = app(tmp_path, "begin\n  putln(toString(\"\", t:nShared))\nend", name="Main")
    pjx = main / "Main.pjx"
    pjx.write_text(pjx.read_text(encoding="utf-8").replace(
        "  <Libraries />", '  <Libraries>\n    <Library alias="t" path="../Tools/Tools.pjx" />\n  </Libraries>'),
        encoding="utf-8")
    run = lint([main, lib], cwd=tmp_path)
    found = sorted((Path(d.path).name, d.message) for d in run.result.diagnostics if d.code == "S003")
    assert found == [("Tools.dtx", "private global variable 'nOwn' is never used by a program of the application")]
    # linted alone, Tools's empty start() says it is a library or type (SRS creates them so):
    # its public global is its interface
    assert [x[4] for x in s_found(lib, "S003")] == ["private global variable 'nOwn' is never used by a program of the application"]
    # an application whose start() does something is not: both are unused
    cell = app(tmp_path / "cell", "begin\n  putln(\"go\")\nend", name="Tools", globals_=["num nShared", "private num nOwn"])
    assert len(s_found(cell, "S003")) == 2


def test_user_type_linted_alone_keeps_its_fields(tmp_path):
    # a type project as SRS saves it: empty start() and stop(), public globals = the fields (7.2)
    part = app(tmp_path, "begin\nend", name="Part", globals_=["num nId", "string sName", "point pGrip", "private num nTmp"])
    assert [x[4] for x in s_found(part, "S003")] == ["private global variable 'nTmp' is never used by a program of the application"]


def test_library_without_any_public_program_or_data_is_left_alone(tmp_path):
    files = {
        "Lib/Lib.pjx": _pjx(["helper"], "Lib"),
        "Lib/Lib.dtx": _dtx(['<Data name="nSecret" xsi:type="array" type="num" size="1" />']),
        "Lib/helper.pgx": _pgx("helper", "begin\nend", access=None),
    }
    write_files(tmp_path, files)
    assert codes(tmp_path / "Lib") == []


# ------------------------------------------------------------------ S003 unused globals


def test_unused_global_exclusions(tmp_path):
    f = app(tmp_path, 'begin\n  nUsed = 1\n  putln("see nNamed")\n  l_nCount = 0\n  l_nCount = l_nCount + 1\nend',
            globals_=["num nUsed", "num nNamed", "dio diSpare", "sio siSpare", "aio aiSpare", "frame fSpare",
                      "tool tSpare", "num nDead", "num l_nCount"],
            locals_=["num l_nCount"])
    found = s_found(f, "S003")
    # l_nCount is hidden by the local of the same name (2.5.2): the global is unused
    assert sorted(x[4].split("'")[1] for x in found) == ["l_nCount", "nDead"]


def test_no_unused_global_when_a_program_did_not_parse(tmp_path):
    f = app(tmp_path, "begin\n  nUsed = 1\nend", globals_=["num nUsed", "num nDead"],
            programs={"broken": {"code": "begin\n  if true\nend"}})
    assert "S003" not in codes(f)


def test_no_unused_global_when_getdata_takes_a_computed_name(tmp_path):
    f = app(tmp_path, 'begin\n  nCount = getData(sName, nCopy)\nend',
            globals_=["num nCount", "string sName", "num nCopy", "num nDead"])
    assert "S003" not in codes(f)


def test_frame_used_as_reference_of_a_point_is_used(tmp_path):
    f = app(tmp_path, "begin\n  movej(pA, flange, mDesc)\nend", globals_=["pointRx pA", "mdesc mDesc", "num nDead"])
    dtx = f / "App.dtx"
    text = dtx.read_text(encoding="utf-8").replace(
        "  </Datas>",
        '    <Data name="pB" access="public" xsi:type="array" type="pointRx" size="1">\n'
        '      <Value key="0" fatherId="pA[0]" />\n    </Data>\n  </Datas>')
    dtx.write_text(text, encoding="utf-8")
    names = sorted(x[4].split("'")[1] for x in s_found(f, "S003"))
    assert names == ["nDead", "pB"]  # pA is pB's reference: used


def test_public_globals_of_a_user_type_are_fields(tmp_path):
    files = {
        "Part/Part.pjx": _pjx([], "Part"),
        "Part/Part.dtx": _dtx(['<Data name="nWeight" access="public" xsi:type="array" type="num" size="1" />']),
    }
    write_files(tmp_path, files)
    assert codes(tmp_path / "Part") == []


# ------------------------------------------------------------------ S004 unused programs


def test_unused_private_programs(tmp_path):
    f = app(tmp_path, "begin\n  call used()\nend",
            programs={"used": {"access": "private", "code": "begin\nend"},
                      "selfish": {"access": "private", "code": "begin\n  call selfish()\nend"},
                      "task": {"access": "private", "code": "begin\nend"},
                      "pub": {"access": "public", "code": "begin\nend"},
                      "stop": {"access": "private", "code": 'begin\n  taskCreateSync "t", 0.1, bOver, task()\nend'}},
            globals_=["bool bOver"])
    assert [x[4] for x in s_found(f, "S004")] == [
        "private program selfish() is never called (call, taskCreate, taskCreateSync) in the application"]


# ------------------------------------------------------------------ S005 read before assignment


def rba(tmp_path, code, locals_, globals_=(), programs=None):
    f = app(tmp_path, code, globals_=globals_, locals_=locals_, programs=programs)
    return [x[4].split("'")[1] for x in s_found(f, "S005")]


def test_read_before_assignment_certain_cases(tmp_path):
    code = """begin
  l_nA = l_nA + 1
  if bFlag
    putln(l_sText)
  endIf
  while bFlag
    put(l_nLate)
  endWhile
  l_nLate = 2
end"""
    assert sorted(rba(tmp_path, code, ["num l_nA", "string l_sText", "num l_nLate"], ["bool bFlag"])) == \
        ["l_nA", "l_nLate", "l_sText"]


def test_read_before_assignment_reported_once_at_first_read(tmp_path):
    code = "begin\n  put(l_nA)\n  put(l_nA)\nend"
    f = app(tmp_path, code, locals_=["num l_nA"])
    found = s_found(f, "S005")
    assert [(x[2], x[3]) for x in found] == [at(f, "start.pgx", "l_nA)")]


def test_writes_by_reference_count(tmp_path):
    code = """begin
  l_sRest = toNum("1", l_nVal, l_bOk)
  get(l_sDay)
  l_nGot = sioGet(siCom, l_nBuf)
  call fill(l_nFilled)
  call lib:unknown(l_nLib)
  if l_bOk and (l_sDay == "x") and (l_nBuf[0] == 1) and (l_nFilled == l_nVal) and (l_nLib == l_nGot)
    putln(l_sRest)
  endIf
end"""
    locals_ = ["string l_sRest", "num l_nVal", "bool l_bOk", "string l_sDay", "num l_nGot", "num l_nBuf[10]",
               "num l_nFilled", "num l_nLib"]
    progs = {"fill": {"params": ["num& x_n"], "code": "begin\n  x_n = 1\nend"}}
    assert rba(tmp_path, code, locals_, ["sio siCom"], progs) == []


def test_by_value_argument_is_a_read(tmp_path):
    progs = {"show": {"params": ["num x_n"], "code": "begin\n  put(x_n)\nend"}}
    assert rba(tmp_path, "begin\n  call show(l_nA)\nend", ["num l_nA"], programs=progs) == ["l_nA"]


def test_loops_carry_writes_to_the_next_turn(tmp_path):
    code = """begin
  for l_i = 0 to 9
    l_nSum = l_nSum + l_i
  endFor
  while l_nK < 10
    l_nK = l_nK + 1
  endWhile
  do
    if l_bSeen
      putln("again")
    endIf
    l_bSeen = true
  until l_nK > 20
  while bRun
    while bWait
      put(l_nInner)
    endWhile
    l_nInner = 1
  endWhile
  put(size(l_nArr))
end"""
    locals_ = ["num l_i", "num l_nSum", "num l_nK", "bool l_bSeen", "num l_nInner", "num l_nArr[4]"]
    assert rba(tmp_path, code, locals_, ["bool bRun", "bool bWait"]) == []


def test_any_earlier_write_is_enough(tmp_path):
    # the write is in the `if` branch, the read in the `else` one: not certain, not reported
    code = "begin\n  if bFlag\n    l_nA = 1\n  else\n    put(l_nA)\n  endIf\nend"
    assert rba(tmp_path, code, ["num l_nA"], ["bool bFlag"]) == []


def test_user_type_and_io_locals_are_not_tracked(tmp_path):
    files = {"Part/Part.pjx": _pjx([], "Part"),
             "Part/Part.dtx": _dtx(['<Data name="nWeight" access="public" xsi:type="array" type="num" size="1" />'])}
    write_files(tmp_path, files)
    f = app(tmp_path, "begin\n  put(l_part.nWeight)\n  put(dioGet(l_di))\nend", locals_=["Part l_part", "dio l_di"])
    pjx = f / "App.pjx"
    pjx.write_text(pjx.read_text(encoding="utf-8").replace(
        "  <Libraries />", '  <Libraries />\n  <Types>\n    <Type name="Part" path="../Part/Part.pjx" />\n  </Types>'),
        encoding="utf-8")
    assert "S005" not in codes(f)


def test_case_of_names(tmp_path):
    # a write spelled differently counts (quieter); a read must be the local's exact spelling
    assert rba(tmp_path, "begin\n  L_NA = 1\n  put(l_nA)\nend", ["num l_nA"]) == []


def test_the_walk_stops_once_every_tracked_local_is_written(tmp_path):
    # a read inside a loop still open when the last local is written: its write is in that loop
    # (not reported); a read at the top before its write: reported; reads after: none certain
    code = """begin
  put(l_nA)
  while bRun
    put(l_nB)
    l_nA = 1
    l_nB = 2
    put(l_nC)
  endWhile
  l_nC = 3
  put(l_nA + l_nB + l_nC)
end"""
    assert rba(tmp_path, code, ["num l_nA", "num l_nB", "num l_nC"], ["bool bRun"]) == ["l_nA", "l_nC"]
    code = "begin\n  while bRun\n    put(l_nB)\n    l_nB = 2\n  endWhile\n  put(l_nB)\nend"
    assert rba(tmp_path, code, ["num l_nB"], ["bool bRun"]) == []


def test_the_walk_reads_nothing_after_the_last_write():
    from val3check.parsing.parser import parse_code
    from val3check.positions import SourceMap
    from val3check.semantics.patterns_usage import _certain_reads

    class NoProgram:  # the call after the last write must not be looked at
        def program_writes(self, target, count):
            raise AssertionError("walked past the last write")

    code = "begin\n  put(l_nA)\n  l_nA = 1\n  call other(l_nA)\nend"
    body, errors = parse_code(code, SourceMap.identity(code), "p.pgx")
    assert errors == []
    assert [name for name, _ in _certain_reads(body.statements, {"l_nA"}, NoProgram())] == ["l_nA"]
    with pytest.raises(AssertionError):  # the same call before the write is walked
        _certain_reads(body.statements, {"l_nA", "l_nB"}, NoProgram())


# ------------------------------------------------------------------ S006 / S009 blocks


def test_unreachable_and_switch(tmp_path):
    code = """begin
  switch nKey
    case 1
      return
    break
    case 2
      if bFlag
        break
      endIf
      nKey = 0
    case 3
      nKey = 1
    break
      nKey = 2
    case 4
      return
    default
      nKey = 5
  endSwitch
  while bFlag
    return
  endWhile
  return
end"""
    f = app(tmp_path, code, globals_=["num nKey", "bool bFlag"])
    found = s_found(f)
    got = sorted((x[0], x[2] - at(f, "start.pgx", "begin")[0] + 1, x[3]) for x in found)
    assert got == [("S006", 14, 7), ("S009", 6, 5), ("S009", 17, 5)]


# ------------------------------------------------------------------ S007 / S008 comparisons


def test_comparisons(tmp_path):
    code = """begin
  bA = getMoveId() >= nId
  bA = getMoveId() - 1 != nId
  bA = nCount == 3
  bA = nCount == 2.0
  bA = nCount == -0.5
  bA = (nCount % 2) == 0
  bA = nCount / 2 == round(nCount / 2)
  bA = nCount == 10 / 2
  bA = sin(nAngle) == sin(nOther)
  bA = sqrt(nCount) * 2 != nOther
  bA = sString == "0.5"
  bA = abs(nAngle) == 0
end"""
    f = app(tmp_path, code, globals_=["bool bA", "num nId", "num nCount", "num nAngle", "num nOther", "string sString"])
    first = at(f, "start.pgx", "begin")[0]
    got = sorted((x[0], x[2] - first + 1) for x in s_found(f))
    assert got == [("S007", 3), ("S008", 6), ("S008", 10), ("S008", 11)]


# ------------------------------------------------------------------ S010 / S011 comments, strings


def test_comments_and_strings(tmp_path):
    code = ("begin\n"
            "  // a comment\n"
            "  nA = 1 // trailing\n"
            "  nA = 2 //val3check: ignore[S015]\n"
            f'  sA = "{"é" * 64}"\n'
            f'  sA = "{"é" * 65}"\n'
            f'  sA = sA + "{"x" * 100}" + "{"y" * 100}"\n'
            f'  sA = "{"x" * 100}" + "{"y" * 20}" + "{"z" * 20}"\n'
            f'  sA = toString("", nA) + "{"x" * 120}" + sA\n'
            "end // done\n")
    f = app(tmp_path, code, globals_=["num nA", "string sA"])
    first = at(f, "start.pgx", "begin")[0]
    got = sorted((x[0], x[2] - first + 1, x[3]) for x in s_found(f))
    # the directive on line 4 suppresses nothing (S021, issue 16)
    assert got == [("S010", 3, 10), ("S010", 10, 5), ("S011", 6, 8), ("S011", 7, 8), ("S011", 8, 8), ("S021", 4, 10)]


# ------------------------------------------------------------------ S012 wait


def test_wait_conditions(tmp_path):
    code = """begin
  wait(l_bDone)
  wait(bGlobal)
  wait(diIn == true)
  wait(false)
  wait(l_nCount > size(nArr))
  wait(taskStatus("t") == -1)
  wait(l_nCount >= 3 and l_part.nWeight > 0)
end"""
    files = {"Part/Part.pjx": _pjx([], "Part"),
             "Part/Part.dtx": _dtx(['<Data name="nWeight" access="public" xsi:type="array" type="num" size="1" />'])}
    write_files(tmp_path, files)
    f = app(tmp_path, code, globals_=["bool bGlobal", "dio diIn", "num nArr[3]"],
            locals_=["bool l_bDone", "num l_nCount", "Part l_part"])
    pjx = f / "App.pjx"
    pjx.write_text(pjx.read_text(encoding="utf-8").replace(
        "  <Libraries />", '  <Libraries />\n  <Types>\n    <Type name="Part" path="../Part/Part.pjx" />\n  </Types>'),
        encoding="utf-8")
    found = s_found(f, "S012")
    assert [x[4] for x in found] == [
        "the condition of wait() only reads 'l_bDone', which no other task can change: the task waits forever (or not at all)"]


def test_wait_on_parameters(tmp_path):
    f = app(tmp_path, "begin\n  call w(bG, bG)\nend", globals_=["bool bG"],
            programs={"w": {"params": ["bool x_bVal", "bool& x_bRef"], "code": "begin\n  wait(x_bRef)\n  wait(x_bVal)\nend"}})
    found = s_found(f, "S012")
    assert len(found) == 1 and "'x_bVal'" in found[0][4] and found[0][1] == "w.pgx"


def test_wait_in_an_application_without_data(tmp_path):
    # no project file: globals are unknown, any name may be one
    write_files(tmp_path, {"Hand/start.pgx": _pgx("start", "begin\n  wait(bSomething)\nend"),
                           "Hand/stop.pgx": _pgx("stop", "begin\nend")})
    assert "S012" not in codes(tmp_path / "Hand")


# ------------------------------------------------------------------ S013 / S014 / S015


def test_nested_for_counters(tmp_path):
    code = """begin
  for nI = 0 to 1
    for nJ = 0 to 1
      for nI = 0 to 1
        put(nI)
      endFor
    endFor
  endFor
  for nI = 0 to 1
    for NI = 0 to 1
      put(NI)
    endFor
  endFor
end"""
    f = app(tmp_path, code, globals_=["num nI", "num nJ", "num NI"])
    first = at(f, "start.pgx", "begin")[0]
    assert [(x[0], x[2] - first + 1, x[3]) for x in s_found(f)] == [("S013", 4, 7)]


def test_busy_loops(tmp_path):
    code = """begin
  while diIn == false
  endWhile
  while true
    nCount = nCount + 1
  endWhile
  do
    put(".")
  until taskStatus("t") == -1
  while bRun
    movej(jA, flange, mDesc)
    movej(jB, flange, mDesc)
  endWhile
  while bRun
    call step()
  endWhile
  while nCount < 10
    nCount = nCount + 1
  endWhile
  while true
    if diIn
      return
    endIf
  endWhile
  while logMsg("x") == false
    delay(0)
  endWhile
  while bRun
    sLine = siCom
  endWhile
  do
    nKey = get()
  until nKey == 270
end"""
    f = app(tmp_path, code, globals_=["dio diIn", "num nCount", "bool bRun", "joint jA", "joint jB", "mdesc mDesc",
                                      "sio siCom", "string sLine", "num nKey"],
            programs={"step": {"code": "begin\nend"}})
    first = at(f, "start.pgx", "begin")[0]
    assert sorted(x[2] - first + 1 for x in s_found(f, "S014")) == [2, 4, 7]


def test_self_assignment(tmp_path):
    code = """begin
  nA = nA
  nArr[nA + 1] = nArr[nA + 1]
  nArr[nA] = nArr[nA + 1]
  siCom = siCom
  nArr[getKey()] = nArr[getKey()]
  NA = nA
end"""
    f = app(tmp_path, code, globals_=["num nA", "num NA", "num nArr[4]", "sio siCom"])
    first = at(f, "start.pgx", "begin")[0]
    assert sorted(x[2] - first + 1 for x in s_found(f, "S015")) == [2, 3]


# ------------------------------------------------------------------ robustness


def test_odd_trees_do_not_raise():
    from val3check.loading.model import Application, Origin, Program, Workspace
    from val3check.parsing import ast as A
    from val3check.positions import SourceMap

    n = A.Name("x", 1, 1, 1, 2)
    weird = [
        A.Assign(A.Number(1, "1", 1, 1, 1, 2), A.Name("x", 1, 1, 1, 2), 1, 1, 1, 3),
        A.Assign(A.CallExpr(A.SystemName("$f", 1, 1, 1, 3), [], 1, 1), n, 1, 1, 1, 3),
        A.For(A.Number(1, "1", 1, 1, 1, 2), n, n, None, [A.Return(1, 1), A.Break(1, 1)], 1, 1, 1, 1),
        A.While(A.Struct([None, n], 1, 1), [], 1, 1, 1, 1),
        A.DoUntil([], A.AssignExpr(n, n, 1, 1, 1, 1), 1, 1, 1, 1),
        A.ExprStatement(A.CallExpr(A.Name("wait", 1, 1, 1, 1), [], 1, 1), 1, 1),
        A.ExprStatement(A.CallExpr(A.LibraryName("l", "wait", 1, 1, 1, 1), [A.Index(n, [], 1, 1)], 1, 1), 1, 1),
        A.Call(A.LibraryName("nolib", "p", 1, 1, 1, 1), [n, A.Field(n, "f", 1, 1, 1, 1)], 1, 1),
        A.TaskCreateSync(n, n, A.Number(1, "1", 1, 1, 1, 2), A.Name("p", 1, 1, 1, 1), [n], 1, 1),
        A.Switch(n, [A.Case([], [], 1, 1)], A.Default([A.Break(1, 1), A.Return(1, 1)], 1, 1), 1, 1, 1, 1),
        A.If([A.Branch(A.Binary("==", A.Number(0.5, "0.5", 1, 1, 1, 1), A.Number(0.1, ".1", 1, 1, 1, 1), 1, 1, 1, 1), [], 1, 1)],
             [], 1, 1, 0, 0, 1, 1),
        A.Assign(A.Binary("/", n, A.Number(0, "0", 1, 1, 1, 1), 1, 1, 1, 1),
                 A.Binary("==", A.Binary("/", A.Number(1, "1", 1, 1, 1, 1), A.Number(0, "0", 1, 1, 1, 1), 1, 1, 1, 1),
                          n, 1, 1, 1, 1), 1, 1, 1, 1),
    ]
    body = A.ProgramBody(weird, [A.Comment("// x", 1, 5, False)], 1, 1, 1, 1)
    prog = Program("start", "private", [], [], "", SourceMap(), Origin("start.pgx", 1, 1), body=body)
    application = Application("A", "/nowhere/A.pjx", "s7", programs={"start": prog})
    patterns.check_application(Workspace(targets=[application.path], apps={application.path: application}), application)


def test_very_deep_tree_is_skipped_not_raised():
    from val3check.loading.model import (
        Application,
        Container,
        Local,
        Origin,
        Program,
        Workspace,
    )
    from val3check.parsing import ast as A
    from val3check.positions import SourceMap

    deep = A.Name("l_n", 1, 1, 1, 4)
    for _ in range(20000):  # far beyond what the parser builds (MAX_EXPR_DEPTH)
        deep = A.Binary("+", deep, A.Number(1, "1", 1, 1, 1, 2), 1, 1, 1, 1)
    body = A.ProgramBody([A.Assign(A.Name("l_n", 1, 1, 1, 4), deep, 1, 1, 1, 1)], [], 1, 1, 1, 1)
    local = Local("l_n", "num", Container.ARRAY, (1,), Origin("start.pgx", 1, 1))
    prog = Program("start", "private", [], [local], "", SourceMap(), Origin("start.pgx", 1, 1), body=body)
    application = Application("A", "/nowhere/A.pjx", "s7", programs={"start": prog})
    patterns.STRICT = False
    patterns.check_application(Workspace(targets=[application.path], apps={application.path: application}), application)


# ------------------------------------------------------------------ helpers: hand-written files


def _pjx(programs: list[str], name: str) -> str:
    entries = "\n".join(f'    <Program file="{p}.pgx" />' for p in programs)
    return ('<?xml version="1.0" encoding="utf-8"?>\n<Project xmlns="http://www.staubli.com/robotics/VAL3/Project/3">\n'
            '  <Parameters version="s7.11" stackSize="5000" millimeterUnit="true" />\n'
            f"  <Programs>\n{entries}\n  </Programs>\n"
            f'  <Database>\n    <Data file="{name}.dtx" />\n  </Database>\n  <Libraries />\n</Project>\n')


def _dtx(datas: list[str]) -> str:
    body = "\n".join("    " + d for d in datas)
    return ('<?xml version="1.0" encoding="utf-8"?>\n<Database xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance" '
            f'xmlns="http://www.staubli.com/robotics/VAL3/Data/2">\n  <Datas>\n{body}\n  </Datas>\n</Database>\n')


def _pgx(name: str, code: str, params=(), access: str | None = "public") -> str:
    acc = f' access="{access}"' if access else ""
    head = ('<?xml version="1.0" encoding="utf-8"?>\n<Programs xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance" '
            f'xmlns="http://www.staubli.com/robotics/VAL3/Program/2">\n  <Program name="{name}"{acc}>\n')
    if params:
        head += ('    <Parameters xmlns="http://www.staubli.com/robotics/VAL3/Param/1">\n'
                 + "\n".join("      " + p for p in params) + "\n    </Parameters>\n")
    return head + f"    <Code><![CDATA[{code}]]></Code>\n  </Program>\n</Programs>\n"


def test_nothing_is_unused_when_a_listed_program_file_is_missing(tmp_path):
    folder = app(tmp_path, "begin\n  putln(\"go\")\nend", globals_=["private num nCount"],
                 programs={"helper": {"code": "begin\nend", "access": "private"}})
    assert sorted(c for c in codes(folder) if c in ("S003", "S004")) == ["S003", "S004"]
    pjx = folder / "App.pjx"
    pjx.write_text(pjx.read_text().replace('<Program file="stop.pgx" />',
                                           '<Program file="stop.pgx" />\n    <Program file="lost.pgx" />'))
    assert [c for c in codes(folder) if c in ("S003", "S004")] == []  # lost.pgx may use both


def test_comment_only_program_is_documentation_not_dead_code(tmp_path):
    progs = {"readme": {"code": "begin\n  // how to use this cell:\n  // call pick() then place()\nend", "access": "private"},
             "empty": {"code": "begin\nend", "access": "private"}}
    folder = app(tmp_path, "begin\n  putln(\"go\")\nend", programs=progs)
    assert [x[4] for x in s_found(folder, "S004")] == [
        "private program empty() is never called (call, taskCreate, taskCreateSync) in the application"]


def test_programs_and_globals_bound_by_a_web_user_page_are_used(tmp_path):
    progs = {"onStart": {"code": "begin\n  putln(\"x\")\nend", "access": "private"},
             "onStop": {"code": "begin\n  putln(\"y\")\nend", "access": "private"}}
    folder = app(tmp_path, "begin\n  putln(\"go\")\nend", programs=progs, globals_=["private num nSpeed", "private num nOld"])
    pages = folder / "interface"  # as a CS9 controller tree holds them (s8.10 cell, psi46/cmsrobot)
    pages.mkdir(parents=True)
    (pages / "main.bindings.json").write_text(
        '{"version": "1.0", "bindings": [{"id": "rng1", "attribute": "value", "data": "nSpeed[0]", "size": 1,'
        ' "direction": "rw", "refresh": 1}], "callbacks": [{"id": "btn1", "event": "click", "data": "onStart",'
        ' "priority": 10}], "events": []}', encoding="utf-8")
    assert [x[4] for x in s_found(folder, "S004")] == [
        "private program onStop() is never called (call, taskCreate, taskCreateSync) in the application"]
    assert [x[4] for x in s_found(folder, "S003")] == [
        "global variable 'nOld' is never used by a program of the application"]
    # a broken bindings file is ignored (the page editor owns it), as is one outside the folder
    (pages / "main.bindings.json").write_text("{not json", encoding="utf-8")
    assert len(s_found(folder, "S004")) == 2
