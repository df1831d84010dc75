"""s8 forms, instructions and the `? expr` statement against the target (T030, T031, T024)."""

from __future__ import annotations

from .checkhelp import findings, lint, write_app

from val3check.config import Settings
from val3check.language.target import parse_target

S8_CODE = """begin
  userPage("menu")
  nStatus = ioStatus(siSocket)
  logMsg("started", 2)
  userPageSet("menu")
  ? nStatus
end"""
G = ["sio siSocket", "num nStatus"]


def _codes(tmp_path, code, target=None, version="s7.11", globals_=G):
    folder = write_app(tmp_path, code, globals_=globals_, version=version)
    run = lint([folder], Settings(target=parse_target(target) if target else None), cwd=tmp_path)
    return [(d.code, d.severity.label) for d in run.result.diagnostics if d.code[0] in "NTL"]


def test_s8_uses_in_a_project_saved_as_s7_are_warnings(tmp_path):
    # real CS9 code is often saved as s7: never an error, and each use at its line
    found = findings(tmp_path, S8_CODE, globals_=G)
    assert found == [("T030", 2, 3), ("T030", 3, 13), ("T030", 4, 3), ("T030", 5, 3), ("T030", 6, 3)]


def test_s8_uses_in_an_s8_project_are_fine(tmp_path):
    assert findings(tmp_path, S8_CODE, globals_=G, version="s8.13") == []
    # a version as SRS writes it for CS9
    assert findings(tmp_path / "b", S8_CODE, globals_=G, version="s8.20.2Cs9_BS4270") == []


def test_configured_target_accepts_or_refuses_them(tmp_path):
    assert _codes(tmp_path / "a", S8_CODE, "CS9") == []
    assert _codes(tmp_path / "b", S8_CODE, "s8.13") == []
    refused = _codes(tmp_path / "c", S8_CODE, "CS8 s7.11")
    assert refused == [("T031", "error")] * 5
    # the target wins over the project file's version, both ways
    assert [c for c, _ in _codes(tmp_path / "d", S8_CODE, "CS8", version="s8.13")] == ["T031"] * 5


def test_s8_messages_say_why(tmp_path):
    folder = write_app(tmp_path, 'begin\n  userPage("menu")\nend')
    msg = lint([folder], cwd=tmp_path).result.diagnostics[0].message
    assert "num userPage(string sPage)" in msg and "s8 only" in msg and "s7.11 (project file)" in msg
    assert 'target = "CS9"' in msg


def test_unknown_forms_keep_the_s7_findings(tmp_path):
    # s7: a form neither s7 nor known s8 is a sure error; s8: the T024 warning
    code = 'begin\n  popUpMsg("x", 2)\n  userPage(3)\nend'
    assert [f[0] for f in findings(tmp_path, code)] == ["T005", "T006"]
    assert [f[0] for f in findings(tmp_path / "b", code, version="s8.3")] == ["T024", "T024"]


def test_s8_forms_are_typed_like_instructions(tmp_path):
    # the s8 form's parameters and return type are checked once it is chosen
    code = 'begin\n  sX = ioStatus(siSocket)\n  nX = logMsg("a", 1)\nend'
    found = findings(tmp_path, code, globals_=["sio siSocket", "string sX", "num nX"], version="s8.13")
    assert [f[0] for f in found] == ["T003", "T003"]


def test_print_statement_checks_its_expression(tmp_path):
    found = findings(tmp_path, "begin\n  ? nUndefined + 1\nend", version="s8.13")
    assert found == [("N001", 2, 5)]


def test_code_saved_as_s7_that_uses_s8_forms_is_cs9_code(tmp_path):
    # one known s8 form is evidence: other calls matching no s7 signature, and names one slip
    # from an instruction, may be s8 forms val3check does not know: warnings, as in an s8 project
    code = 'begin\n  popUpMsg("x", 2)\n  waitEndMov()\n  userPage("menu")\nend'
    assert [f[0] for f in findings(tmp_path, code)] == ["T024", "N004", "T030"]
    # without that evidence they are sure errors on s7
    plain = 'begin\n  popUpMsg("x", 2)\n  waitEndMov()\nend'
    assert [f[0] for f in findings(tmp_path / "b", plain)] == ["T005", "N003"]
    # and with an s7 target named in the configuration they stay errors
    assert [c for c, _ in _codes(tmp_path / "c", code, "CS8")] == ["T005", "N003", "T031"]


def test_web_user_pages_are_s8_evidence(tmp_path):
    # *.bindings.json files are s8 web user pages: the application is CS9 code
    folder = write_app(tmp_path, 'begin\n  popUpMsg("x", 2)\nend')
    (folder / "main.bindings.json").write_text('{"callbacks": [{"id": "b", "event": "click", "data": "start"}]}')
    run = lint([folder], cwd=tmp_path)
    assert [d.code for d in run.result.diagnostics if d.code[0] == "T"] == ["T024"]


# Issue 25 class 3: what Stäubli's own s8 templates and a CS9 application with OPC UA and a web
# user page call (language/s8.toml, sources there).
TEMPLATE_CODE = """begin
  nRet = userPage("main")
  userPage("main")
  if (userPagePrompt(sPrompt, sInput) == true)
    userPageAlert("done")
  endIf
  bOk = userPageConfirm("Press update")
  bOk = setSafetyRestart() and hasCpuExtPowerSupply()
  while wakeUpRobot() != 0
    delay(1)
  endWhile
  jRef = getJntRef("safeReference1")
  nRet = abs(getSafeRefStatus())
  opcuaExport(nRet, "nRet")
  nRet = sioSet(siSocket, nData, 3)
end"""
TG = ["num nRet", "string sPrompt", "string sInput", "bool bOk", "joint jRef", "sio siSocket", "num nData[8]"]


def test_the_s8_instructions_of_real_code_are_known(tmp_path):
    assert _codes(tmp_path, TEMPLATE_CODE, version="s8.3", globals_=TG) == []


def test_in_a_project_saved_as_s7_they_are_s8_only_warnings(tmp_path):
    found = _codes(tmp_path, TEMPLATE_CODE, globals_=TG)
    assert found and set(found) == {("T030", "warning")}


def test_a_project_saved_for_a_cs9_is_cs9_code(tmp_path):
    # Stäubli's j213_external24V template is saved as "s7.0.1Cs9" and calls userPageAlert
    assert _codes(tmp_path, TEMPLATE_CODE, version="s7.0.1Cs9", globals_=TG) == []


def test_a_call_against_a_signature_read_from_code_is_a_warning(tmp_path):
    code = 'begin\n  userPageAlert(3)\n  nRet = userPageAlert("x")\n  userPagePrompt("x", "literal")\nend'
    assert _codes(tmp_path, code, version="s8.3", globals_=TG) == [("T024", "warning")] * 3
