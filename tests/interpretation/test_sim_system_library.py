"""Instructions of s8 and of the system library met in real code: the file instructions run on a
virtual disk the scenario fills (never the user's disk), user-interface and export calls are
recorded events, and what nothing can simulate goes on with an info (R041), never a stop."""

from __future__ import annotations

import os

from val3check.language import s8
from val3check.simulation.run import build_registry

from .simsupport import gv, out, sim

FILES = '[[files]]\npath = "Disk://input_day1.txt"\ntext = "199\\n200\\r\\n208\\n"\n'

# The way public code reads a file line by line (written after the helpers of a public VAL 3
# repository that read puzzle inputs: open, $fileGet one line at a time until 0, close).
READ = {"readFile": {"params": ["string x_sFile", "string& x_sLine[]"],
                     "locals": ["num l_nHandle", "num l_nRead", "string l_sLine", "num l_n"],
                     "code": """begin
  l_nHandle = $fileOpen(x_sFile, "r")
  l_n = 0
  do
    l_nRead = $fileGet(l_nHandle, l_sLine, 1)
    if l_nRead > 0
      x_sLine[l_n] = l_sLine
      l_n = l_n + 1
    endIf
  until l_nRead == 0
  $fileClose(l_nHandle)
end
"""}}


def test_a_file_the_scenario_gives_is_read_line_by_line(tmp_path):
    r = sim(tmp_path, 'begin\n  call readFile("Disk://input_day1.txt", sLines)\n  putln(sLines[0] + sLines[1] + sLines[2])\nend',
            globals_=["string sLines[3]"], programs=READ, scenario=FILES, check_lint=False)
    assert r.end_reason == "ended" and out(r) == ["199200208"]
    assert not [d for d in r.diagnostics if d.code in ("R001", "R004", "R041")]
    said = [e.text for e in r.transcript if e.kind == "file"]
    assert said == ["$fileOpen Disk://input_day1.txt r -> 0", "$fileClose 0 -> true"]


def test_files_written_by_the_program_stay_on_the_virtual_disk(tmp_path):
    before = set(os.listdir(tmp_path))
    r = sim(tmp_path, """begin
  nW = $fileOpen("Disk://logs/run.txt", "w")
  sOut[0] = "a"
  sOut[1] = "b"
  nSet = $fileSet(nW, sOut, 2)
  bClosed = $fileClose(nW)
  bThere = $fileExists("Disk://logs/run.txt")
  nR = $fileOpen("Disk://logs/run.txt", "r")
  nGot = $fileGet(nR, sIn, 5)
  $fileClose(nR)
  bMoved = $rename("Disk://logs/run.txt", "Disk://logs/old.txt")
  bGone = $fileExists("Disk://logs/run.txt")
  nMissing = $fileOpen("Disk://none.txt", "r")
  bDeleted = $delete("Disk://logs")
end""", globals_=["num nW", "num nSet", "bool bClosed", "bool bThere", "num nR", "num nGot", "bool bMoved",
                  "bool bGone", "num nMissing", "bool bDeleted", "string sOut[2]", "string sIn[5]"], check_lint=False)
    assert r.end_reason == "ended", r.diagnostics
    assert (gv(r, "nSet"), gv(r, "bClosed"), gv(r, "bThere"), gv(r, "nGot")) == (2, True, True, 2)
    assert gv(r, "sIn")[:2] == ["a", "b"]
    assert (gv(r, "bMoved"), gv(r, "bGone"), gv(r, "nMissing"), gv(r, "bDeleted")) == (True, False, -1, True)
    assert set(os.listdir(tmp_path)) - before == {"Example"}  # nothing written beside the application
    assert not any("logs" in f for _d, _s, files in os.walk(tmp_path) for f in files + _s)


def test_byte_files_and_the_ten_open_files(tmp_path):
    r = sim(tmp_path, """begin
  nH = $fileOpen("Disk://raw.bin", "r")
  nGot = $fileGet(nH, nBytes, 10)
  for i = 0 to 9
    nOpen[i] = $fileOpen("Disk://raw.bin", "r")
  endFor
end""", globals_=["num nH", "num nGot", "num nBytes[4]", "num i", "num nOpen[10]"],
            scenario='[[files]]\npath = "Disk://raw.bin"\nbytes = [1, 2, 255]\n', check_lint=False)
    assert gv(r, "nGot") == 3 and gv(r, "nBytes")[:3] == [1, 2, 255]
    assert gv(r, "nOpen")[-1] == -1  # at most 10 files open at once (1 + 9 more)


def test_user_interface_and_export_calls_are_recorded_and_the_run_goes_on(tmp_path):
    r = sim(tmp_path, """begin
  nRet = userPage("main")
  userPageAlert("part missing")
  bOk = userPageConfirm("go on?")
  bIn = userPagePrompt("name", sName)
  userPageSet("menu", 1)
  opcuaExport(nRet)
  $recStart("c", 10, 100)
  $jogPage()
  logMsg("started", 2)
  putln("done")
end""", globals_=["num nRet", "bool bOk", "bool bIn", "string sName"], check_lint=False)
    assert r.end_reason == "ended" and out(r) == ["done"]
    kinds = [e.kind for e in r.transcript]
    for kind in ("userPage", "userPageAlert", "userPageConfirm", "userPagePrompt", "userPageSet", "opcuaExport",
                 "recorder", "system", "logMsg"):
        assert kind in kinds, kind
    assert (gv(r, "nRet"), gv(r, "bOk"), gv(r, "bIn")) == (0, True, True)
    r020 = [d for d in r.diagnostics if d.code == "R041"]
    assert len(r020) == len({d.line for d in r020}) == 7  # one per line; none for the alert, shown as is
    assert not [d for d in r.diagnostics if d.code in ("R001", "R004")]


def test_an_unknown_system_call_goes_on_with_an_info_once_per_line(tmp_path):
    r = sim(tmp_path, """begin
  for i = 1 to 3
    nDelay = $getBoxcarDelay()
    sText = $whatever(1, "a")
    $movejSyncState()
  endFor
end""", globals_=["num i", "num nDelay", "string sText"], check_lint=False)
    assert r.end_reason == "ended"
    assert [d.code for d in r.diagnostics] == ["R041", "R041", "R041"]
    assert gv(r, "nDelay") == 0 and gv(r, "sText") == ""


def test_every_s8_instruction_of_the_catalogue_has_a_behaviour():
    registry = build_registry()
    missing = [name for name in s8.load_s8().instructions if registry.handler(name) is None]
    assert missing == []


def test_s8_sioset_with_a_count_sends_that_many_values(tmp_path):
    r = sim(tmp_path, "begin\n  nBuf[0] = 65\n  nBuf[1] = 66\n  nBuf[2] = 67\n  nSent = sioSet(siOut, nBuf, 2)\nend",
            globals_=["sio siOut", "num nBuf[3]", "num nSent"], links={"siOut": "Socket\\Out"}, check_lint=False)
    assert gv(r, "nSent") == 2 and [e.value for e in r.io_log if e.source != "scenario"] == ["AB"]


def test_a_file_the_disk_does_not_hold_names_the_scenario_entry_and_reads_nothing(tmp_path):
    r = sim(tmp_path, 'begin\n  call readFile("Disk://input_day1.txt", sLines)\n  putln("read")\nend',
            globals_=["string sLines[3]"], programs=READ, check_lint=False)
    assert out(r) == ["read"]  # $fileGet on a handle not open reads nothing (0): the loop ends
    (d,) = [d for d in r.diagnostics if d.code == "R041"]
    assert "[[files]]" in d.message and 'path = "Disk://input_day1.txt"' in d.message
