"""Signatures checked by hand against the body of the manual (not only its table of contents)."""

from __future__ import annotations

from val3check.language import lookup
from val3check.language.instructions import language_facts, load_errata, load_instructions


def _sigs(name: str) -> set[str]:
    instr = lookup(name)
    return {o.signature(instr.name) for o in instr.overloads}


def test_tonum_returns_the_rest_of_the_string():  # 3.4.3
    (o,) = lookup("toNum").overloads
    assert o.returns == "string"
    assert [(p.type, p.ref) for p in o.params] == [("string", False), ("num", True), ("bool", True)]


def test_sioget_and_sioset_take_a_num_array_by_reference():  # 3.7.3
    for name in ("sioGet", "sioSet"):
        (o,) = lookup(name).overloads
        assert o.returns == "num" and o.section == "3.7.3"
        assert (o.params[1].type, o.params[1].container, o.params[1].ref) == ("num", "array", True)
    assert lookup("sioGet").yields


def test_sioctrl_value_is_of_any_listed_type():  # 3.7.3
    (o,) = lookup("sioCtrl").overloads
    value = o.params[2]
    assert value.type == "*" and set(value.accepts) == {"num", "string", "bool"}
    assert o.matches(["sio", "string", "num"]) and o.matches(["sio", "string", "bool"])
    assert not o.matches(["sio", "string", "joint"])


def test_liblist_is_not_called_through_an_identifier():  # 6.7
    instr = lookup("libList")
    assert instr.kind == "function" and instr.library_prefix == "none"
    assert _sigs("libList") == {"bool libList(string sChemin, string& sContenu[])"}


def test_library_instructions():  # 6.7
    assert lookup("libLoad").library_prefix == "required"
    assert [o.max_arity for o in lookup("libLoad").overloads] == [1, 2]
    (save,) = lookup("libSave").overloads
    assert lookup("libSave").library_prefix == "optional"
    assert save.accepts_arity(0) and save.accepts_arity(1) and save.params[0].optional
    assert lookup("libPath").library_prefix == "optional"
    assert lookup("libExist").library_prefix == "required"
    assert lookup("libDelete").library_prefix == "none"


def test_movej_takes_a_joint_or_a_point_and_movel_only_a_point():  # 10.6
    assert _sigs("movej") == {
        "num movej(joint jPosition, tool tOutil, mdesc mDesc)",
        "num movej(point pPosition, tool tOutil, mdesc mDesc)",
    }
    movel = lookup("movel")
    assert movel.overloads_for(["point", "tool", "mdesc"])
    assert not movel.overloads_for(["joint", "tool", "mdesc"])
    assert [p.type for p in lookup("movec").overloads[0].params] == ["point", "point", "tool", "mdesc"]


def test_getkey_with_and_without_screen():  # 4.3
    assert _sigs("getKey") == {"num getKey()", "num getKey(screen scPage)"}
    assert len(lookup("get").overloads) == 6
    assert len(lookup("put").overloads) == 4 and lookup("put").kind == "procedure"


def test_workingmode_with_and_without_state():  # 8.1
    assert _sigs("workingMode") == {"num workingMode()", "num workingMode(num& nEtat)"}


def test_container_instructions():  # 2.5.4 to 2.5.6
    size = lookup("size")
    assert [o.section for o in size.overloads] == ["2.5.4", "2.5.5"]
    assert size.overloads[0].params[0].container == "any"
    assert size.overloads[1].params[0].container == "array"
    (get_data,) = lookup("getData").overloads
    assert [p.type for p in get_data.params] == ["string", "*"] and get_data.returns == "num"
    assert lookup("next").overloads[0].params[0].container == "collection"
    assert lookup("next").overloads[0].params[0].index == "required"
    assert lookup("first").overloads[0].params[0].index == "none"
    assert lookup("append").kind == "procedure"


def test_insert_and_delete_are_also_string_functions():  # 2.5.4 and 3.4.3
    for name, string_params in (("insert", ["string", "string", "num"]), ("delete", ["string", "num", "num"])):
        container, text = lookup(name).overloads
        assert (container.returns, container.section, [p.type for p in container.params]) == ("bool", "2.5.4", ["*"])
        assert (text.returns, text.section, [p.type for p in text.params]) == ("string", "3.4.3", string_params)


def test_task_creation_is_a_special_form():  # 5.10
    create = lookup("taskCreate")
    assert create.kind == "special" and create.special_form == "task"
    assert create.syntax.startswith("taskCreate <string sNom>, <num nPriorité>,")
    assert [p.type for p in create.overloads[0].params] == ["string", "num", "program"]
    sync = lookup("taskCreateSync")
    assert sync.special_form == "sync_task"
    assert [(p.type, p.ref) for p in sync.overloads[0].params] == [
        ("string", False), ("num", False), ("bool", True), ("program", False)
    ]


def test_overloads_across_chapters():  # 3.2.3 / 9.2.3, 9.3.4 / 9.6.3, 9.4.4 / 9.5.4 / 9.6.3
    assert {(o.returns, o.params[0].type, o.section) for o in lookup("abs").overloads} == {
        ("num", "num", "3.2.3"), ("joint", "joint", "9.2.3")
    }
    assert {(o.params[0].type, o.section) for o in lookup("distance").overloads} == {("trsf", "9.3.4"), ("point", "9.6.3")}
    assert {(o.params[0].type, o.params[1].type, o.section, o.returns) for o in lookup("position").overloads} == {
        ("frame", "frame", "9.4.4", "trsf"), ("tool", "tool", "9.5.4", "trsf"), ("point", "frame", "9.6.3", "trsf")
    }
    assert {(o.params[0].type, o.section) for o in lookup("link").overloads} == {
        ("frame", "9.4.4"), ("tool", "9.5.4"), ("point", "9.6.3")
    }
    assert all(o.params[0].needs_variable for o in lookup("link").overloads)
    assert {(o.params[0].type, o.section) for o in lookup("ioStatus").overloads} == {("dio", "3.5.3"), ("aio", "3.6.2")}
    assert len(lookup("ioStatus").overloads) == 4


def test_autoconnectmove_sets_or_reads():  # 10.6
    assert _sigs("autoConnectMove") == {"void autoConnectMove(bool bActif)", "bool autoConnectMove()"}


def test_dh_arrays():  # 11.4.4: get* have no b[], setDH has one
    assert [p.name for p in lookup("getDH").overloads[0].params] == ["theta", "d", "a", "alpha", "beta"]
    assert [p.name for p in lookup("setDH").overloads[0].params] == ["theta", "d", "a", "b", "alpha", "beta"]
    assert all(p.container == "array" and p.ref for p in lookup("setDH").overloads[0].params)
    assert lookup("setDH").option == "absoluteRobot"


def test_getjointforce_takes_an_array():  # 10.6 text, though its signature writes num& nForce
    (o,) = lookup("getJointForce").overloads
    assert o.returns == "void" and o.params[0].container == "array" and o.params[0].ref


def test_wait_and_watch_reevaluate_their_condition():  # 5.10
    assert lookup("wait").overloads[0].params[0].reevaluated
    assert lookup("watch").overloads[0].params[0].reevaluated
    assert lookup("watch").overloads[0].returns == "bool"


def test_instructions_that_yield_to_other_tasks():  # 5.4
    expected = {
        "watch", "delay", "wait", "waitEndMove", "open", "close", "get", "taskResume", "taskKill",
        "disablePower", "libLoad", "libSave", "libDelete", "libList", "setProfile", "sioGet", "sioSet", "setMutex",
    }
    assert {i.name for i in load_instructions().values() if i.yields} == expected


def test_options_of_chapter_11():
    assert {i.name for i in load_instructions().values() if i.option == "alter"} == {
        "alterMovej", "alterMovel", "alterMovec", "alterBegin", "alterEnd", "alter", "alterStopTime"
    }
    assert lookup("movejf").option == lookup("movelf").option == lookup("isCompliant").option == "compliance"
    assert lookup("resetTurn").option == "continuousAxis"
    assert lookup("getLicence").option == "oemLicence"
    assert lookup("setLatch").controllers == ("CS8C",)


def test_lookup_ignores_case_the_way_the_manual_does():
    # the manual writes moveL/movel, alterMoveL/alterMovel, getMoveId/getMoveld
    assert lookup("moveL").name == "movel"
    assert lookup("alterMoveL").name == "alterMovel"
    assert lookup("GETMOVEID").name == "getMoveId"
    assert lookup("println") is None and load_errata()["println"].canonical == "putln"
    assert load_errata()["waitforendmove"].canonical == "waitEndMove"


def test_functions_may_be_called_as_statements():  # get(sDay) in the `if` example of 2.2.5
    facts = language_facts()
    assert facts["function_as_statement"] is True
    assert "2.2.5" in facts["function_as_statement_sections"]
    assert facts["assignment_in_arguments"] is False
