"""T codes about calls: instructions, programs, tasks (manual 2.2.5, 2.6, 5.10, 6.7)."""

from __future__ import annotations

from .checkhelp import codes, collect, findings, messages, write_app, write_files

G = ["num nX", "string sA", "bool bA", "joint jA", "point pA", "tool tA", "mdesc mA", "frame fA", "num nArr[4]",
     "sio siA", "dio diA", "dio doArr[3]", "trsf trA"]


def test_idiomatic_instruction_calls(tmp_path):
    code = """begin
  movej(jA, tA, mA)
  nX = movej(pA, flange, mA)
  movel(appro(pA, trA), tA, mA)
  waitEndMove()
  nX = get()
  nX = get(nX)
  get(sA)
  sA = toNum(sA, nX, bA)
  if watch(diA == true, 2) == false
    popUpMsg("x")
  endIf
  wait(diA)
  logMsg("x")
  nX = sioGet(siA, nArr)
  nX = sioGet(siA, nArr[2])
  nX = dioGet(doArr)
  nX = dioSet(doArr, 3)
  sioCtrl(siA, "timeout", 2)
  sioCtrl(siA, "endOfString", "x")
  link(pA, fA)
  userPage()
  put(nX)
  put(sA)
  nX = abs(nX) + abs(jA).j1
  pA = here(tA, world)
  $anything(sA, 1)
  nX = sel(bA, 1, 2)
  delay(0)
  setMutex(bA)
end"""
    assert codes(tmp_path, code, globals_=G) == []


def test_argument_counts(tmp_path):
    code = "begin\n  movej(jA, tA)\n  nX = sin()\n  putln(\"a\", \"b\", \"c\")\nend"
    assert findings(tmp_path, code, globals_=G) == [("T005", 2, 3), ("T005", 3, 8), ("T005", 4, 3)]
    assert "movej(joint jPosition, tool tOutil, mdesc mDesc)" in messages(tmp_path / "Example")[0]


def test_argument_types_at_the_argument(tmp_path):
    code = "begin\n  delay(\"1\")\n  movel(jA, tA, mA)\n  put(bA)\n  sioCtrl(siA, \"port\", pA)\nend"
    assert findings(tmp_path, code, globals_=G) == [("T006", 2, 9), ("T006", 3, 9), ("T006", 4, 7), ("T006", 5, 24)]


def test_reference_parameters_of_instructions(tmp_path):
    code = "begin\n  get(5)\n  sA = toNum(sA, 3, bA)\n  link(here(tA, world), fA)\n  setMutex(true)\nend"
    assert findings(tmp_path, code, globals_=G) == [("T007", 2, 7), ("T007", 3, 18), ("T007", 4, 8), ("T007", 5, 12)]


def test_void_instruction_in_an_expression(tmp_path):
    assert findings(tmp_path, "begin\n  nX = delay(1)\nend", globals_=G) == [("T019", 2, 8)]


def test_programs_and_instructions_misused(tmp_path):
    progs = {"pick": {"params": ["num x_n"]}}
    code = "begin\n  call movej(jA, tA, mA)\n  pick(1)\n  nX = pick\n  nX = clock\n  nX = libLoad(\"x\")\nend"
    assert findings(tmp_path, code, globals_=G, programs=progs) == [
        ("T018", 2, 8), ("T018", 3, 3), ("T018", 4, 8), ("T018", 5, 8), ("T018", 6, 8)]


def test_program_arguments(tmp_path):
    progs = {"p": {"params": ["num x_v", "num& x_r", "point x_p", "num& x_a[]", 'string& x_c[""]']}}
    ok = "begin\n  call p(nX + 1, nX, pA, nArr, sColl)\n  call p(1, nArr[2], {{1,2,3,4,5,6},{righty}}, nArr[1], sColl)\nend"
    assert codes(tmp_path, ok, globals_=G + ['string sColl[""]'], programs=progs) == []
    bad = "begin\n  call p(sA, nX, pA, nArr, sColl)\n  call p(1, bA, pA, nArr, sColl)\n  call p(1, nX, jA, nArr, sColl)\n  call p(1, nX, pA, nArr)\nend"
    assert codes(tmp_path / "b", bad, globals_=G + ['string sColl[""]'], programs=progs) == ["T006", "T006", "T006", "T005"]


def test_task_creation(tmp_path):
    progs = {"worker": {"params": ["num x_n", "num& x_r"]}, "sync": {}}
    ok = """begin
  taskCreate "worker", 10, worker(1, nX)
  taskCreate sA, nX + 1, worker(nX, nArr[1])
  taskCreateSync "sync", 0.004, bA, sync()
end"""
    assert codes(tmp_path, ok, globals_=G, programs=progs) == []
    bad = """begin
  taskCreate 3, 10, worker(1, nX)
  taskCreate "w", "10", worker(1, nX)
  taskCreate "w", 10, worker(1, 2)
  taskCreate "w", 10, worker(1)
  taskCreate "w", 10, movej(jA, tA, mA)
  taskCreateSync "s", 1, nX, sync()
  taskCreateSync "s", 1, true, sync()
end"""
    assert findings(tmp_path / "b", bad, globals_=G, programs=progs) == [
        ("T006", 2, 14), ("T006", 3, 19), ("T007", 4, 33), ("T005", 5, 23), ("T018", 6, 23), ("T006", 7, 26),
        ("T007", 8, 26)]


def test_local_by_reference_to_a_task(tmp_path):
    progs = {"worker": {"params": ["num& x_r"]}, "sync": {},
             "launch": {"params": ["num& x_p"], "locals": ["num l_n", "bool l_b"],
                        "code": "begin\n  taskCreate \"a\", 1, worker(l_n)\n  taskCreate \"b\", 1, worker(x_p)\n"
                                "  taskCreate \"c\", 1, worker(nX)\n  taskCreateSync \"d\", 1, l_b, sync()\nend"}}
    folder = write_app(tmp_path, "begin\n  call launch(nX)\nend", globals_=G, programs=progs)
    assert [f[0] for f in collect(folder)] == ["T022", "T022"]


def test_is_defined_and_lib_exist_probe_an_interface(tmp_path):
    files = {
        "App/App.pjx": """<?xml version="1.0" encoding="utf-8"?>
<Project xmlns="http://www.staubli.com/robotics/VAL3/Project/3">
  <Parameters version="s7.11" stackSize="5000" millimeterUnit="true" />
  <Programs><Program file="start.pgx" /></Programs>
  <Database><Data file="App.dtx" /></Database>
  <Libraries><Library alias="part" path="./Lib/Lib.pjx" /></Libraries>
</Project>
""",
        "App/App.dtx": """<?xml version="1.0" encoding="utf-8"?>
<Database xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance" xmlns="http://www.staubli.com/robotics/VAL3/Data/2">
  <Datas><Data name="nLoadCode" access="public" xsi:type="array" type="num" size="1" /></Datas>
</Database>
""",
        "App/start.pgx": """<?xml version="1.0" encoding="utf-8"?>
<Programs xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance" xmlns="http://www.staubli.com/robotics/VAL3/Program/2">
  <Program name="start" access="public">
    <Code><![CDATA[begin
  nLoadCode = part:libLoad("Disk://x")
  if isDefined(part:sVersion) == false
    nLoadCode = 1
  endIf
  if part:libExist("init()")
    nLoadCode = part:nCode
  endIf
  nLoadCode = part:libSave()
end]]></Code>
  </Program>
</Programs>
""",
        "App/Lib/Lib.pjx": """<?xml version="1.0" encoding="utf-8"?>
<Project xmlns="http://www.staubli.com/robotics/VAL3/Project/3">
  <Parameters version="s7.11" stackSize="5000" millimeterUnit="true" />
  <Programs />
  <Database><Data file="Lib.dtx" /></Database>
</Project>
""",
        "App/Lib/Lib.dtx": """<?xml version="1.0" encoding="utf-8"?>
<Database xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance" xmlns="http://www.staubli.com/robotics/VAL3/Data/2">
  <Datas><Data name="nCode" access="public" xsi:type="array" type="num" size="1" /></Datas>
</Database>
""",
    }
    write_files(tmp_path, files)
    assert collect(tmp_path / "App") == []


def test_s6_containers_are_not_known(tmp_path):
    # s6 files write arrays without size and array parameters without container
    files = {
        "Old/Old.pjx": """<?xml version="1.0" encoding="utf-8"?>
<project xmlns="ProjectNameSpace">
  <parameters version="s6.8" stackSize="5000" millimeterUnit="true" />
  <programSection><program file="start.pgx" /><program file="stop.pgx" /><program file="sum.pgx" /></programSection>
  <dataSection><data file="Old.dtx" /></dataSection>
</project>
""",
        "Old/Old.dtx": """<?xml version="1.0" encoding="utf-8"?>
<dataList xmlns="DataNameSpace">
  <numSection>
    <num name="nVals" public="false"><valueNum index="0" value="1" /><valueNum index="1" value="2" /></num>
    <num name="nTotal" public="false"><valueNum index="0" value="0" /></num>
  </numSection>
</dataList>
""",
        "Old/start.pgx": """<?xml version="1.0" encoding="utf-8"?>
<programList xmlns="ProgramNameSpace">
  <program name="start" public="false"><paramSection /><localSection />
    <source><code>begin
  call sum(nVals, nTotal)
  nTotal = nVals[1, 0] + size(nVals[1])
  append(nVals)
end</code></source></program>
</programList>
""",
        "Old/stop.pgx": """<?xml version="1.0" encoding="utf-8"?>
<programList xmlns="ProgramNameSpace">
  <program name="stop" public="false"><paramSection /><localSection /><source><code>begin
end</code></source></program>
</programList>
""",
        "Old/sum.pgx": """<?xml version="1.0" encoding="utf-8"?>
<programList xmlns="ProgramNameSpace">
  <program name="sum" public="false">
    <paramSection><param name="x_nVals" type="num" dimensions="1" byVal="false" /><param name="x_nTotal" type="num" byVal="false" /></paramSection>
    <localSection><local name="l_i" type="num" size="1" /></localSection>
    <source><code>begin
  for l_i = 0 to size(x_nVals) - 1
    x_nTotal = x_nTotal + x_nVals[l_i]
  endFor
end</code></source></program>
</programList>
""",
    }
    write_files(tmp_path, files)
    assert collect(tmp_path / "Old") == []
