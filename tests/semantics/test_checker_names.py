"""N codes: names and declarations (manual 2.2.3, 2.2.4, 2.5.1, 2.5.2, 6.3)."""

from __future__ import annotations

from .checkhelp import codes, collect, findings, lint, messages, write_app, write_files


def test_undefined_variable_at_its_position_with_a_suggestion(tmp_path):
    code = "begin\n  nCount = nCont + 1\nend"
    assert findings(tmp_path, code, globals_=["num nCount"]) == [("N001", 2, 12)]
    assert "did you mean nCount?" in messages(tmp_path / "Example")[0]


def test_locals_parameters_globals_and_constants_resolve(tmp_path):
    code = """begin
  nX = 1
  pP.config.shoulder = RIGHTY
  pP.config.elbow = efree
  mD.blend = Cartesian
  mD.blend = joint
  mD.blend = off
  movej(pP, flange, mD)
  link(fF, world)
  bB = true or false
end"""
    assert codes(tmp_path, code, globals_=["num nX", "point pP", "mdesc mD", "frame fF", "bool bB"]) == []


def test_a_local_hides_a_global_of_another_type(tmp_path):
    progs = {"show": {"locals": ["string x_s"], "code": "begin\n  x_s = \"text\"\nend"}}
    folder = write_app(tmp_path, "begin\n  call show()\n  x_s = 3\nend", globals_=["num x_s"], programs=progs)
    assert collect(folder) == []


def test_case_mismatch_is_a_warning_of_its_own_and_not_undefined(tmp_path):
    code = "begin\n  ncount = nCount + 1\n  call Pick()\nend"
    found = findings(tmp_path, code, globals_=["num nCount"], programs={"pick": {}})
    assert found == [("N006", 2, 3), ("N006", 3, 8)]


def test_pgx_only_application_does_not_report_unknown_globals_nor_programs(tmp_path):
    files = {"Loose/start.pgx": """<?xml version="1.0" encoding="utf-8"?>
<Programs xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance" xmlns="http://www.staubli.com/robotics/VAL3/Program/2">
  <Program name="start" access="public">
    <Code><![CDATA[begin
  nGlobal = nOther + 1
  call helper(nGlobal)
  x = lib:nValue
  waitEndMov()
end]]></Code>
  </Program>
</Programs>
"""}
    write_files(tmp_path, files)
    # globals, programs and libraries are unknown; an instruction typo is still certain
    assert [c[0] for c in collect(tmp_path / "Loose")] == ["N003"]


def test_undefined_program_and_program_suggestion(tmp_path):
    code = "begin\n  call pik(1)\n  taskCreate \"t\", 10, pik(1)\nend"
    found = findings(tmp_path, code, programs={"pick": {"params": ["num x_n"]}})
    assert found == [("N002", 2, 8), ("N002", 3, 23)]
    assert "did you mean pick?" in messages(tmp_path / "Example")[0]


def test_unknown_instructions_typo_error_far_name_warning_s8_warning_system_never(tmp_path):
    code = "begin\n  waitEndMov()\n  setGripForce(flange, 2)\n  $anything(1, 2)\n  println(\"x\")\nend"
    assert codes(tmp_path, code) == ["N003", "N004", "N003"]


def test_unknown_instruction_in_s8_is_a_warning_even_when_close(tmp_path):
    assert codes(tmp_path, "begin\n  waitEndMov()\n  setGripForce(1)\nend", version="s8.3") == ["N004", "N004"]


def test_variable_called_like_a_function(tmp_path):
    assert codes(tmp_path, "begin\n  nX = nArr(2)\nend", globals_=["num nX", "num nArr[3]"]) == ["N003"]


def test_undefined_alias_but_io_is_never_reported(tmp_path):
    code = "begin\n  nX = lb:nX\n  bB = io:bIn1\n  call io:init()\nend"
    assert findings(tmp_path, code, globals_=["num nX", "bool bB"]) == [("N005", 2, 8)]


def _app_with_program(tmp_path, params=(), locals_=(), name="helper", version="s7.11", globals_=()):
    progs = {name: {"params": list(params), "locals": list(locals_), "code": "begin\nend"}}
    return write_app(tmp_path, "begin\nend", programs=progs, version=version, globals_=globals_)


def test_duplicate_local_and_parameter(tmp_path):
    folder = _app_with_program(tmp_path, params=["num x_n", "num x_n"], locals_=["num l_i", "num x_n", "num l_i"])
    found = collect(folder, "N007", with_path=True)
    assert len(found) == 3 and {f[1] for f in found} == {"helper.pgx"}


def test_invalid_names_of_globals_locals_parameters_programs(tmp_path):
    folder = _app_with_program(tmp_path, params=["num x_ThisNameIsTooLong"], locals_=["num _l"],
                               name="helperWithALongName", globals_=["num nOk", "num nAVeryLongGlobalName"])
    assert collect(folder, "N008") == []  # no bad character: no error
    starts = collect(folder, "N013", with_path=True)  # `_l`: a warning
    assert sorted(f[1] for f in starts) == ["helperWithALongName.pgx"]
    too_long = collect(folder, "N012", with_path=True)  # length alone: warnings
    assert sorted(f[1] for f in too_long) == ["Example.dtx", "helperWithALongName.pgx", "helperWithALongName.pgx"]


def test_s8_names_are_not_limited_to_15_characters(tmp_path):
    folder = _app_with_program(tmp_path, locals_=["num l_aLongLocalVariable"], version="s8.3")
    assert collect(folder, "N008") == [] and collect(folder, "N012") == []


def test_start_and_stop_without_parameters(tmp_path):
    folder = write_app(tmp_path, "begin\nend", programs={"stop": {"params": ["num x_n"], "code": "begin\nend"}})
    assert [f[:2] for f in collect(folder, "N009", with_path=True)] == [("N009", "stop.pgx")]


def test_undefined_type_but_declared_unresolved_user_type_is_left_to_the_loader(tmp_path):
    folder = write_app(tmp_path, "begin\nend", globals_=["Pose pHome", "num nX"])
    assert [f[0] for f in collect(folder, "N010")] == ["N010"]
    pjx = folder / "Example.pjx"
    text = pjx.read_text().replace("<Libraries />", '<Libraries />\n  <Types>\n    <Type name="Pose" path="Disk://Nowhere/Pose.pjx" />\n  </Types>')
    pjx.write_text(text)
    assert collect(folder, "N010") == []


def test_mixed_arm_families_without_a_known_arm_is_one_warning_on_the_minority(tmp_path):
    folder = write_app(tmp_path, "begin\nend", globals_=["pointRx pA", "jointRx jB", "configRs cC", "pointRs pD"])
    assert collect(folder, "N011") == []
    found = collect(folder, "N016", with_path=True)
    assert len(found) == 1 and found[0][1] == "Example.dtx"
    assert "cC" in messages(folder)[0] and "2 Rs and 2 Rx" in messages(folder)[0]


def _in_controller(tmp_path, arm: str, globals_):
    usrapp = tmp_path / "Controller1" / "usr" / "usrapp"
    folder = write_app(usrapp, "begin\nend", globals_=globals_)
    configs = tmp_path / "Controller1" / "usr" / "configs"
    configs.mkdir(parents=True)
    (configs / "arm.cfx").write_text('<?xml version="1.0" encoding="utf-8"?>\n<Configuration>\n  <Arm>\n'
                                     f'    <String name="arm" value="{arm}" />\n  </Arm>\n</Configuration>\n')
    return folder


def test_with_the_arm_of_the_controller_tree_only_the_other_family_is_reported(tmp_path):
    # a SCARA cell: the Rx declarations are wrong, whichever side has more
    folder = _in_controller(tmp_path, "ts2_60-S1", ["pointRx pA", "jointRx jB", "configRs cC"])
    found = collect(folder, "N0", with_path=True)
    assert [(f[0], f[1]) for f in found] == [("N011", "Example.dtx"), ("N011", "Example.dtx")]
    assert all("ts2_60-S1" in m and "SCARA" in m for m in messages(folder))
    # a six-axis cell: the one Rs declaration is wrong, and one without Rs types is clean
    six = _in_controller(tmp_path / "b", "tx2-60-S1", ["pointRx pA", "pointRs pB"])
    assert [f[0] for f in collect(six, "N0")] == ["N011"] and "pB" in messages(six)[0]
    clean = _in_controller(tmp_path / "c", "tx2-60-S1", ["pointRx pA", "jointRx jB"])
    assert collect(clean, "N0") == []


def test_the_other_family_is_a_warning_that_says_why(tmp_path):
    # issue 25: a user-interface library with SCARA forms in a TX200 cell; the manual (9.7.2)
    # does not say that the controller refuses it
    folder = _in_controller(tmp_path, "tx200-S3", ["jointRs jScara", "jointRx jHome"])
    found = [d for d in lint([folder], cwd=tmp_path).result.diagnostics if d.code == "N011"]
    assert [d.severity.label for d in found] == ["warning"]
    assert "does not say that the controller refuses" in found[0].message and "jScara" in found[0].message


def test_an_arm_of_no_known_family_leaves_the_warning(tmp_path):
    folder = _in_controller(tmp_path, "tp80-S1", ["pointRx pA", "pointRx pC", "pointRs pB"])
    assert [f[0] for f in collect(folder, "N0")] == ["N016"]


def test_program_with_a_syntax_error_is_skipped_but_still_callable(tmp_path):
    progs = {"broken": {"params": ["num x_n"], "code": "begin\n  if true\nend"}}
    folder = write_app(tmp_path, "begin\n  call broken(1)\n  call broken()\nend", programs=progs)
    assert [f[0] for f in collect(folder)] == ["T005"]


def test_unreadable_data_or_program_file_relaxes_undefined_names(tmp_path):
    folder = write_app(tmp_path, "begin\n  nX = nY + 1\n  call helper()\nend", globals_=["num nX"])
    assert [f[0] for f in collect(folder)] == ["N001", "N002"]
    (folder / "Example.dtx").write_text("<Database><Datas>", encoding="utf-8")  # malformed: F004
    assert [f[0] for f in collect(folder)] == ["N002"]
    pjx = folder / "Example.pjx"
    text = pjx.read_text()
    # a missing program file exempts the program it is named after, not every other name
    pjx.write_text(text.replace('<Program file="stop.pgx" />', '<Program file="stop.pgx" />\n    <Program file="gone.pgx" />'))
    assert [f[0] for f in collect(folder)] == ["N002"]
    pjx.write_text(text.replace('<Program file="stop.pgx" />', '<Program file="stop.pgx" />\n    <Program file="Sub/helper.pgx" />'))
    assert collect(folder) == []


def test_missing_program_file_exempts_its_program_called_any_way(tmp_path):
    code = "begin\n  call pick()\n  place(1)\n  call place(2)\n  taskCreate \"t\", 10, pick()\nend"
    folder = write_app(tmp_path, code)
    pjx = folder / "Example.pjx"
    pjx.write_text(pjx.read_text().replace('<Program file="stop.pgx" />', '<Program file="stop.pgx" />\n    <Program file="pick.pgx" />'))
    assert [(f[0], f[1]) for f in collect(folder)] == [("N004", 3), ("N002", 4)]


def test_task_name_length_is_not_held_against_s8(tmp_path):
    code = 'begin\n  taskCreate "socketServerTask", 10, helper()\n  taskCreate "aTaskNameOfTwentyOne1", 10, helper()\nend'
    progs = {"helper": {"code": "begin\nend"}}
    s7 = write_app(tmp_path / "s7", code, programs=progs)
    s8 = write_app(tmp_path / "s8", code, programs=progs, version="s8.3")
    assert [f[0] for f in collect(s7, "T023")] == ["T023", "T023"]
    # s8 code uses 16 characters; beyond, the s8 limit is not known (language/version_facts.py)
    assert len(collect(s8, "T023")) == 1
    assert [m for m in messages(s8) if "aTaskNameOfTwentyOne1" in m and "on an s7 controller" in m]


def test_program_names_may_start_with_an_underscore(tmp_path):
    folder = write_app(tmp_path, "begin\n  call _helper()\nend", programs={"_helper": {"code": "begin\nend"}})
    assert collect(folder, "N008") == []
    bad = write_app(tmp_path / "b", "begin\n  call h()\nend", programs={"h": {"code": "begin\nend", "locals": ["num _l"]}})
    assert [f[0] for f in collect(bad, "N013")] == ["N013"]  # a local should start with a letter (a warning)
