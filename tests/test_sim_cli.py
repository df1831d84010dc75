"""`val3check sim` conventions of issue 16: the application of a folder that holds its
libraries (item 11) and `--init-scenario` (item 13)."""

from __future__ import annotations

import json
import tomllib

from test_cli_conventions import val3check

from val3check.testing import database_xml, write_app

CODE = """begin
  if workingMode() != 4
    putln("not remote")
  endIf
  wait(diStart == true)
  doValve = true
  nX = aiPressure
  call check(diDoor, diArr[1])
  l_n = getKey()
  if isKeyPressed(272)
    putln(getDate("%Y"))
  endIf
  l_s = siScan
  taskCreate "t1", 10, watcher(diArr)
  putln("started")
end
"""
DATAS = [
    ("diStart", "dio", 1, ["BasicIO-1\\%I0"]), ("doValve", "dio", 1, ["BasicIO-1\\%Q0"]),
    ("aiPressure", "aio", 1, ["BasicIO-1\\%IW0"]), ("diDoor", "dio", 1, ["BasicIO-1\\%I1"]),
    ("diArr", "dio", 3, ["BasicIO-1\\%I2", "BasicIO-1\\%I3"]), ("siScan", "sio", 1, ["Socket\\scan"]),
    ("diUnused", "dio", 1, ["BasicIO-1\\%I9"]),
]


def _cell(root):
    folder = write_app(root, CODE, name="Cell", globals_=["num nX"], locals_=["num l_n", "string l_s"], programs={
        "check": {"params": ["dio& x_d", "dio x_e"], "code": "begin\n  wait(x_d == true and x_e == false)\nend\n"},
        "watcher": {"params": ["dio& x_a[]"], "code": "begin\n  x_a[0] = true\nend\n"}})
    rows = ['    <Data name="nX" access="public" xsi:type="array" type="num" size="1" />']
    for name, kind, size, links in DATAS:
        values = "".join(f'<Value key="{i}" link="{link}" />' for i, link in enumerate(links))
        rows.append(f'    <Data name="{name}" access="public" xsi:type="array" type="{kind}" size="{size}">{values}</Data>')
    (folder / "Cell.dtx").write_text(database_xml("\n".join(rows)), encoding="utf-8")
    return folder


def test_init_scenario_lists_what_the_application_reads(tmp_path):
    _cell(tmp_path)
    r = val3check("sim", "Cell", "--init-scenario", "cell.toml", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    text = (tmp_path / "cell.toml").read_text(encoding="utf-8")
    data = tomllib.loads(text)
    assert data["inputs"] == {"diStart": False, "aiPressure": 0, "diDoor": False}  # read, never written
    assert "doValve" not in text and "diUnused" not in text  # an output; a signal nothing reads
    assert '# "diArr[1]" = false' in text and "written by the program too" in text  # watcher() writes diArr
    assert "# diArr[2]: read at start.pgx:15, but linked to no input" in text
    assert "start.pgx:16: getKey()" in text and "# key = 272" in text and "isKeyPressed()" in text
    assert '# sio = "siScan"' in text
    assert data["controller"] == {"working_mode": 4, "working_state": 0, "date": data["controller"]["date"]}
    assert str(data["controller"]["date"]) == "2000-01-01 00:00:00"
    assert val3check("sim", "Cell", "--init-scenario", "cell.toml", cwd=tmp_path).returncode == 2  # never overwritten


def test_the_skeleton_runs_as_no_scenario_and_drives_the_run_once_edited(tmp_path):
    _cell(tmp_path)
    assert val3check("sim", "Cell", "--init-scenario", "cell.toml", cwd=tmp_path).returncode == 0
    plain = json.loads(val3check("sim", "Cell", "--duration", "2", "--report", "json", cwd=tmp_path).stdout)
    r = val3check("sim", "Cell", "--duration", "2", "--report", "json", "--scenario", "cell.toml", cwd=tmp_path)
    with_skeleton = json.loads(r.stdout)
    for key in ("end", "tasks", "diagnostics", "transcript"):
        assert with_skeleton[key] == plain[key], key
    assert plain["end"]["reason"] == "deadlock"  # wait(diStart == true) never passes
    edited = (tmp_path / "cell.toml").read_text().replace("diStart = false", "diStart = true")
    edited = edited.replace("diDoor = false", "diDoor = true")
    # the program reads siScan (it waits for a line): uncomment the serial entry and give it text
    edited = edited.replace('# [[serial]]', '[[serial]]').replace('# sio = "siScan"', 'sio = "siScan"')
    edited = edited.replace("# at = 1.0\n# send = \"\"", "at = 0.5\nsend = \"4711\"")
    (tmp_path / "edited.toml").write_text(edited)
    r = val3check("sim", "Cell", "--duration", "2", "--report", "json", "--scenario", "edited.toml", cwd=tmp_path)
    run = json.loads(r.stdout)
    assert [e["text"] for e in run["transcript"] if e["kind"] == "putln"] == ["started"]


def test_sim_of_a_folder_with_its_libraries_in_sub_folders(tmp_path):
    write_app(tmp_path, 'begin\n  putln("main")\nend\n', name="Cell")
    write_app(tmp_path / "Cell" / "libs", "begin\nend\n", name="Tools")
    r = val3check("sim", "Cell", "--duration", "1", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    assert "holds 2 applications; running Cell/Cell.pjx, the one named after the folder" in r.stderr
    r = val3check("sim", ".", "--duration", "1", cwd=tmp_path)
    assert r.returncode == 2 and "holds 2 applications (Cell/Cell.pjx, Cell/libs/Tools/Tools.pjx)" in r.stderr


def test_init_scenario_suggests_the_version_components_asked_and_the_state_waits(tmp_path):
    """getVersion: the components the code asks for by name, as the run answers them (8.1); a
    wait() on the controller's state: a commented `changes` entry that would end it (R009)."""
    code = ('begin\n  if mid(getVersion("System"), 1, 1) == "8"\n    putln("CS9")\n  endIf\n'
            '  wait(esStatus() < 2)\nend\n')
    write_app(tmp_path, code, name="Ver")
    assert val3check("sim", "Ver", "--init-scenario", "ver.toml", cwd=tmp_path).returncode == 0
    text = (tmp_path / "ver.toml").read_text(encoding="utf-8")
    data = tomllib.loads(text)
    assert data["controller"]["versions"] == {"System": "s7.11"}
    assert "# changes = [ { at = 1.0, es_status = 0 } ]   # start.pgx:" in text


def test_init_scenario_suggests_the_files_the_application_opens(tmp_path):
    write_app(tmp_path, 'begin\n  nH = $fileOpen("Disk://input.txt", "r")\n  $fileClose(nH)\n'
              '  nH = $fileOpen("disk://INPUT.txt", "r")\n  nH = $fileOpen("Disk://out.txt", "w")\nend\n',
              name="Files", globals_=["num nH"])
    assert val3check("sim", "Files", "--init-scenario", "f.toml", cwd=tmp_path).returncode == 0
    text = (tmp_path / "f.toml").read_text(encoding="utf-8")
    # one entry per file read (however spelt), none for a file the program creates
    assert text.count("# [[files]]") == 1 and '# path = "Disk://input.txt"' in text and "out.txt" not in text
    edited = text.replace("# [[files]]", "[[files]]").replace('# path = "Disk', 'path = "Disk').replace(
        '# text = ""', 'text = "1"')
    (tmp_path / "g.toml").write_text(edited, encoding="utf-8")
    r = val3check("sim", "Files", "--scenario", "g.toml", "--report", "json", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    assert not [d for d in json.loads(r.stdout)["diagnostics"] if d["code"] == "R041"]
