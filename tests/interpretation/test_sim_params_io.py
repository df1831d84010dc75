"""Parameters (manual 2.6), I/O with a scenario, libraries, determinism and the CLI."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

from val3check.cli import main

from .simsupport import build, errors, out, sim

ROOT = Path(__file__).resolve().parents[2]


def test_parameters_by_value_and_reference(tmp_path):
    # 2.6.1 by value: the caller's variable is unchanged; 2.6.2 by reference: it is changed
    r = sim(tmp_path, """begin
  sMessage = "a"
  sArr[23] = "b"
  s2d[1, 2] = "c"
  sColl["k"] = "d"
  call byValue(sMessage)
  call byValue(sArr[23])
  call byValue(s2d[1, 2])
  call byValue(sColl["k"])
  putln(sMessage + sArr[23] + s2d[1,2] + sColl["k"])
  call byRef(sMessage)
  call byRef(sArr[23])
  call byRef(s2d[1, 2])
  call byRef(sColl["k"])
  putln(sMessage + sArr[23] + s2d[1,2] + sColl["k"])
end
""", globals_=["string sMessage", "string sArr[30]", "string s2d[3,4]", 'string sColl[""]'],
        programs={"byValue": {"params": ["string x_s"], "code": "begin\n  x_s = \"X\"\nend\n"},
                  "byRef": {"params": ["string& x_s"], "code": "begin\n  x_s = x_s + \"!\"\nend\n"}},
        check_lint=False)
    assert out(r)[0] == "abcd"
    assert out(r)[1] == "a!b!c!d!"


def test_part_of_1d_array_by_reference(tmp_path):
    # 2.6.3: call send1dMessage(sMessageArray[23]) passes the values from index 23 on
    r = sim(tmp_path, """begin
  call fill(nArr[23])
  putln(nArr[22])
  putln(nArr[23])
  putln(nArr[29])
  call fill(nArr)
  putln(nArr[0])
end
""", globals_=["num nArr[30]"], programs={"fill": {"params": ["num& x_a[]"], "locals": ["num l_i"], "code": """begin
  putln(size(x_a))
  for l_i = 0 to size(x_a) - 1
    x_a[l_i] = l_i + 1
  endFor
end
"""}})
    assert out(r) == ["7", "0", "1", "7", "30", "1"]


def test_collection_and_2d_by_reference(tmp_path):
    r = sim(tmp_path, """begin
  insert(nColl["a"])
  call touch(nColl, n2d)
  putln(nColl["a"])
  putln(n2d[1, 1])
end
""", globals_=['num nColl[""]', "num n2d[2,2]"], programs={"touch": {
        "params": ['num& x_c[""]', "num& x_m[,]"], "code": "begin\n  x_c[\"a\"] = 5\n  x_m[1, 1] = 6\nend\n"}})
    assert out(r) == ["5", "6"]


def test_user_type_copy_is_deep(tmp_path):
    folder = build(tmp_path, "begin\nend\n")
    # a user type from the fixtures: Sorter uses Part
    r = subprocess.run([sys.executable, "-m", "val3check", "sim", str(ROOT / "fixtures/valid/Sorter"), "--report", "json",
                        "--duration", "1"], capture_output=True, text=True, cwd=ROOT)
    assert r.returncode in (0, 1), r.stderr
    data = json.loads(r.stdout)
    assert data["end"]["reason"] == "deadlock"
    assert folder.exists()


def test_io_scenario_reaction_and_log(tmp_path):
    scenario = """
[inputs]
diClosed = false

[[reactions]]
when = "doValve"
becomes = true
after = 0.3
set = { diClosed = true }
"""
    r = sim(tmp_path, """begin
  doValve = true
  nT = clock()
  wait(diClosed == true)
  putln(toString(".1", clock() - nT))
  doValve = false
end
""", globals_=["dio doValve", "dio diClosed", "num nT"], scenario=scenario,
        links={"doValve": "BasicIO-1\\%Q0", "diClosed": "BasicIO-1\\%I0"})
    assert out(r) == ["0.3"]
    log = [(round(t / 1e6, 3), link, v, src) for t, kind, link, v, src in r.io_log]
    assert log == [(0.0, "BasicIO-1\\%I0", False, "scenario"), (0.0, "BasicIO-1\\%Q0", True, "Example~"),
                   (0.3, "BasicIO-1\\%I0", True, "scenario"), (0.304, "BasicIO-1\\%Q0", False, "Example~")]


def test_write_to_input_and_unlinked(tmp_path):
    r = sim(tmp_path, "begin\n  diIn = true\nend\n", globals_=["dio diIn"], scenario="[inputs]\ndiIn = false\n",
            links={"diIn": "BasicIO-1\\%I0"})
    assert errors(r) == [122]
    r = sim(tmp_path / "u", "begin\n  doOut = true\nend\n", globals_=["dio doOut"])
    assert errors(r) == [123]


def test_dioget_dioset_examples(tmp_path):
    # 3.5.3: dioGet of false,true,false,true is 10; dioSet(4 bits, 26) returns 10
    links = {"diA": [f"IO\\%Q{i}" for i in range(4)]}
    r = sim(tmp_path, """begin
  diA[0] = false
  diA[1] = true
  diA[2] = false
  diA[3] = true
  putln(dioGet(diA))
  putln(dioSet(diA, 26))
end
""", globals_=["dio diA[4]"], links=links)
    assert out(r) == ["10", "10"]


def test_scenario_errors_name_the_line(tmp_path):
    import pytest

    from val3check.simulation.scenario import ScenarioError

    with pytest.raises(ScenarioError) as exc:
        sim(tmp_path, "begin\nend\n", globals_=["dio diIn"], links={"diIn": "IO\\%I0"},
            scenario="[inputs]\ndiIn = false\n\n[[events]]\nat = 1\nset = { diNope = true }\n")
    assert exc.value.line == 6 and "diNope" in exc.value.message
    with pytest.raises(ScenarioError) as exc:
        sim(tmp_path / "b", "begin\nend\n", globals_=["dio diIn"], links={"diIn": "IO\\%I0"},
            scenario="[inputs]\ndiIn = 3\n")
    assert exc.value.line == 2


def test_sio_peer_and_reply(tmp_path):
    scenario = """
[[serial]]
sio = "siPort"
when_sent = "PING"
after = 0.2
send = "PONG"
"""
    r = sim(tmp_path, """begin
  siPort = "PING"
  sLine = siPort
  putln(sLine)
end
""", globals_=["sio siPort", "string sLine"], scenario=scenario, links={"siPort": "Serial0"})
    assert out(r) == ["PONG"]
    assert r.sim_time_us >= 200_000


def test_controller_state(tmp_path):
    r = sim(tmp_path, """begin
  enablePower()
  if watch(isPowered(), 5) == false
    putln("no power")
  endIf
  putln(workingMode(nState))
  putln(getMonitorSpeed())
end
""", globals_=["num nState"], scenario="[controller]\nworking_mode = 2\nmonitor_speed = 10\npowered = false\n")
    assert out(r) == ["no power", "2", "10"]


def test_libraries_load_save_on_simulated_disk(tmp_path):
    lib = tmp_path / "Lib"
    build(tmp_path, "begin\nend\n", name="Lib", globals_=["num nX"])
    (lib / "start.pgx").unlink()
    (lib / "stop.pgx").unlink()
    pjx = lib / "Lib.pjx"
    pjx.write_text(pjx.read_text().replace('    <Program file="start.pgx" />\n    <Program file="stop.pgx" />\n', ""))
    folder = build(tmp_path, """begin
  putln(lib:libLoad("Lib"))
  lib:nX = 4
  putln(lib:libSave("Disk://Copy"))
  putln(lib:libSave("Disk://Copy"))
  putln(other:libLoad("Disk://Copy"))
  putln(other:nX)
  putln(other:libLoad("Nowhere"))
end
""", globals_=[])
    text = (folder / "Example.pjx").read_text().replace("<Libraries />", '<Libraries><Library alias="lib" path="Disk://Lib" /><Library alias="other" path="Disk://Lib" /></Libraries>')
    (folder / "Example.pjx").write_text(text)
    from val3check.config import Settings
    from val3check.simulation import SimOptions, simulate
    from val3check.lint import run

    lr = run([str(folder)], Settings())
    app = lr.workspace.apps[lr.workspace.targets[0]]
    res = simulate(lr.workspace, app, SimOptions(duration=5))
    assert out(res) == ["0", "0", "31", "0", "4", "39"]
    assert not (tmp_path / "Copy").exists()  # never written to the user's files


def _run_cli(args, capsys):
    code = main(args)
    captured = capsys.readouterr()
    return code, captured.out, captured.err


def test_cli_json_is_deterministic(tmp_path, capsys):
    folder = build(tmp_path, """begin
  taskCreate "t1", 10, worker()
  nX = 1 / nZero
end
""", globals_=["num nX", "num nZero"], programs={"worker": {"code": "begin\n  putln(\"w\")\n  delay(0.5)\nend\n"}})
    a = _run_cli(["sim", str(folder), "--report", "json", "--duration", "3"], capsys)
    b = _run_cli(["sim", str(folder), "--report", "json", "--duration", "3"], capsys)
    assert a == b
    assert a[0] == 1
    data = json.loads(a[1])
    assert data["version"] == 2
    assert data["end"]["reason"] == "stalled"
    d = data["diagnostics"][0]
    assert (d["code"], d["error"], d["task"], d["program"]) == ("R001", 10, "Example~", "start")
    assert [t["name"] for t in data["tasks"]] == ["Example~", "t1", "~Example"]


def test_cli_refuses_an_application_with_lint_errors_and_prints_only_them(tmp_path, capsys):
    # a local never used (S001, a warning) and a syntax error in another program
    folder = build(tmp_path, "begin\nend\n", locals_=["num l_nUnused"],
                   programs={"other": {"code": "begin\n  if true\nend\n"}})
    code, stdout, stderr = _run_cli(["lint", str(folder)], capsys)
    assert "S001" in stdout and "F101" in stdout
    code, stdout, stderr = _run_cli(["sim", str(folder)], capsys)
    assert code == 2 and "F101" in stderr and "S001" not in stderr
    assert code == 2
    assert "not run" in stderr and "F101" in stderr


def test_cli_text_and_bad_scenario(tmp_path, capsys):
    folder = build(tmp_path, "begin\n  putln(\"hi\")\nend\n")
    code, stdout, stderr = _run_cli(["sim", str(folder)], capsys)
    assert code == 0 and "putln 'hi'" in stdout
    sc = tmp_path / "s.toml"
    sc.write_text("[inputs]\nnothing = true\n")
    code, stdout, stderr = _run_cli(["sim", str(folder), "--scenario", str(sc)], capsys)
    assert code == 2 and "s.toml:2" in stderr


def test_lint_does_not_import_the_interpreter():
    code = ("import sys\nfrom val3check.cli import main\ntry:\n    main(['lint', 'fixtures/valid/Cell'])\n"
            "except SystemExit:\n    pass\nprint(sorted(m for m in sys.modules if 'interpretation' in m))\n")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT)
    assert r.stdout.strip().endswith("[]"), r.stdout


def test_controller_io_library(tmp_path):
    # `io:` is the controller's own I/O library (lint's L003): its symbols are inputs/outputs
    # linked to "io:NAME", of the kind their uses give (dioLink -> dio, "= text" -> sio)
    from .simsupport import add_libraries, gv, run_folder

    folder = build(tmp_path, """begin
  dioLink(diSensor, io:bIn0)
  dioLink(doMotor, io:bOut0)
  wait(diSensor == true)
  doMotor = true
  io:tcp_server = "hello"
  sReply = io:tcp_server
  nStatus = ioStatus(io:bIn0)
  bExist = io:libExist("bIn0")
end
""", globals_=["dio diSensor", "dio doMotor", "string sReply", "num nStatus", "bool bExist"])
    add_libraries(folder, {"io": "Disk://io"})
    r = run_folder(folder, scenario="""[[events]]
at = 0.5
set = { "io:bIn0" = true }
[[serial]]
sio = "io:tcp_server"
when_sent = "hello"
after = 0.1
send = "world"
""")
    assert r.end_reason == "ended", r.diagnostics
    assert gv(r, "sReply") == "world" and gv(r, "nStatus") == 0 and gv(r, "bExist") is True
    assert [(e[2], e[3], e[4]) for e in r.io_log if e[1] == "dio"] == [("io:bIn0", True, "scenario"),
                                                                      ("io:bOut0", True, "Example~")]


def test_exported_controller_io_library(tmp_path):
    """A controller export holds usr/usrapp/io/io.pjx, the controller's io library: its dio,
    aio and sio are the controller's inputs/outputs (linked to "io:NAME", driven by the
    scenario), not unlinked variables of a plain library (was error 123)."""
    from .simsupport import add_libraries, gv, make_library, run_folder

    make_library(tmp_path, "io", globals_=["dio bOut7", "dio bIn0", "aio aSpeed", "sio tcpLine"])
    folder = build(tmp_path, "begin\n  io:bOut7 = true\n  wait(io:bIn0)\n  nSpeed = aioGet(io:aSpeed)\n"
                             "  sioLink(siLine, io:tcpLine)\n  siLine = \"hello\"\nend\n",
                   globals_=["sio siLine", "num nSpeed"])
    add_libraries(folder, {"io": "Disk://io"}, autoload="true")
    r = run_folder(folder, tmp_path=tmp_path, scenario='[inputs]\n"io:aSpeed" = 12.5\n'
                                                      '[[events]]\nat = 1\nset = { "io:bIn0" = true }\n')
    assert r.end_reason == "ended" and not r.diagnostics, r.diagnostics
    assert gv(r, "nSpeed") == 12.5
    assert [(round(e.time_us / 1e6, 3), e.link, e.value, e.source) for e in r.io_log if e.kind != "aio"] == [
        (0.0, "io:bOut7", True, "Example~"), (1.0, "io:bIn0", True, "scenario"),
        (1.0, "io:tcpLine", "hello\r", "Example~")]


def test_a_library_named_io_with_programs_is_a_plain_library(tmp_path):
    from .simsupport import add_libraries, gv, make_library, run_folder

    make_library(tmp_path, "io", globals_=["num nValue"], programs={"init": {"code": "begin\n  nValue = 3\nend\n"}})
    folder = build(tmp_path, "begin\n  call io:init()\n  nGot = io:nValue\nend\n", globals_=["num nGot"])
    add_libraries(folder, {"io": "Disk://io"}, autoload="true")
    r = run_folder(folder, tmp_path=tmp_path)
    assert not r.diagnostics and gv(r, "nGot") == 3.0


def test_controller_io_passed_to_a_sio_parameter_is_a_sio(tmp_path):
    """io:NAME given to a program's sio parameter is a serial line or socket, as the parameter
    says (was typed as a dio by its name: error 70 at sioLink)."""
    from .simsupport import add_libraries, run_folder

    folder = build(tmp_path, "begin\n  call openLine(io:tcp_server)\n  taskCreate \"t2\", 10, talk(io:com1)\nend\n",
                   globals_=["sio siLine", "sio siCom"],
                   programs={"openLine": {"params": ["sio x_siLine"],
                                          "code": "begin\n  sioLink(siLine, x_siLine)\n  siLine = \"hi\"\nend\n"},
                             "talk": {"params": ["sio& x_siCom"],
                                      "code": "begin\n  sioLink(siCom, x_siCom)\n  siCom = 7\nend\n"}})
    add_libraries(folder, {"io": "Disk://io"})
    r = run_folder(folder, tmp_path=tmp_path)
    assert not r.diagnostics, r.diagnostics
    assert [(e.kind, e.link, e.value) for e in r.io_log] == [("sio", "io:tcp_server", "hi\r"), ("sio", "io:com1", "\x07")]


def test_an_aio_where_a_num_is_needed_is_read(tmp_path):
    """3.6.2: lint accepts an aio where a num is needed (its value, as aioGet reads it): a for
    bound or step, an operand, an index, put(), a switch (was error 61 or R004; found by
    bench/fuzz.py)."""
    from .simsupport import gv, run_folder

    folder = build(tmp_path, "begin\n  for nI = 0 to aiX step aiX\n    nCount = nCount + 1\n  endFor\n"
                             "  nSum = aiX + 1\n  nNeg = -aiX\n  nItem = nA[aiX]\n  put(aiX)\n"
                             "  switch aiX\n    case 2\n      bTwo = true\n    break\n  endSwitch\nend\n",
                   globals_=["aio aiX", "num nI", "num nCount", "num nSum", "num nNeg", "num nItem", "num nA[3]",
                             "bool bTwo"], links={"aiX": "Cell\\analog0"})
    r = run_folder(folder, tmp_path=tmp_path, scenario='[inputs]\naiX = 2\n')
    assert not r.diagnostics, r.diagnostics
    assert (gv(r, "nCount"), gv(r, "nSum"), gv(r, "nNeg"), gv(r, "nItem"), gv(r, "bTwo")) == (2.0, 3.0, -2.0, 0.0, True)
    assert out(r) == ["2"]
