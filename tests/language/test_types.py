"""Built-in types, arm-family names, constants and operators."""

from __future__ import annotations

from val3check.language.types import (
    data_type_names,
    find_operator,
    load_aliases,
    load_constants,
    load_families,
    load_operators,
    load_removed_operators,
    load_types,
    operators_of,
    resolve_type,
)


def _fields(name: str) -> list[tuple[str, str]]:
    return [(f.name, f.type) for f in load_types()[name].fields]


def test_simple_and_structured_types():
    types = load_types()
    assert {n for n, t in types.items() if t.kind == "simple"} == {"bool", "num", "string", "dio", "aio", "sio", "screen"}
    assert {n for n, t in types.items() if t.kind == "structured"} == {
        "trsf", "frame", "tool", "point", "joint", "config", "mdesc"
    }
    assert data_type_names() == {n for n, t in types.items() if t.kind in ("simple", "structured")}
    for t in types.values():
        assert t.section, t.name
        for f in t.fields:
            assert f.type in types, (t.name, f)


def test_fields_in_literal_order():
    assert _fields("trsf") == [(n, "num") for n in ("x", "y", "z", "rx", "ry", "rz")]
    assert _fields("frame") == [("trsf", "trsf")]
    assert _fields("tool") == [("trsf", "trsf"), ("gripper", "dio"), ("otime", "num"), ("ctime", "num")]
    assert _fields("point") == [("trsf", "trsf"), ("config", "config")]
    assert _fields("joint") == [(f"j{i}", "num") for i in range(1, 7)]
    assert _fields("config") == [("shoulder", "shoulder"), ("elbow", "elbow"), ("wrist", "wrist")]
    assert [n for n, _ in _fields("mdesc")] == ["accel", "vel", "decel", "tvel", "rvel", "blend", "leave", "reach"]
    assert load_types()["mdesc"].default == "{100,100,100,9999,9999,joint,50,50}"
    assert load_types()["mdesc"].field("tmax").name == "tvel"  # .dtx spelling


def test_reference_frames_and_tools():
    types = load_types()
    assert types["point"].reference == types["frame"].reference == "frame"
    assert types["tool"].reference == "tool"


def test_arm_family_aliases():
    assert set(load_aliases()) == {"jointRx", "jointRs", "pointRx", "pointRs", "configRx", "configRs"}
    assert resolve_type("pointRx") == ("point", "Rx")
    assert resolve_type("configrs") == ("config", "Rs")
    assert resolve_type("num") == ("num", None)
    assert resolve_type("widget") is None
    families = load_families()
    assert families["Rs"].joint_fields == ("j1", "j2", "j3", "j4")
    assert families["Rs"].config_fields == ("shoulder",)
    assert families["Rx"].config_fields == ("shoulder", "elbow", "wrist")


def test_constants():
    constants = load_constants()
    expected = {
        "true": "bool", "false": "bool", "world": "frame", "flange": "tool",
        "righty": "shoulder", "lefty": "shoulder", "ssame": "shoulder", "sfree": "shoulder",
        "epositive": "elbow", "enegative": "elbow", "esame": "elbow", "efree": "elbow",
        "wpositive": "wrist", "wnegative": "wrist", "wsame": "wrist", "wfree": "wrist",
        "off": "blend", "joint": "blend", "Cartesian": "blend",
    }
    assert {n: c.type for n, c in constants.items()} == expected
    types = load_types()
    for enum in ("shoulder", "elbow", "wrist", "blend"):
        assert set(types[enum].values) == {n for n, t in expected.items() if t == enum}


def test_operator_table():
    assert all(o.section for o in load_operators())
    assert find_operator("+", "string", "string").result == "string"
    assert find_operator("*", "trsf", "trsf").result == "trsf"
    assert find_operator("!", "trsf").result == "trsf"
    assert find_operator("!", "bool").result == "bool"
    assert find_operator("neg", "num").result == "num"
    assert find_operator("%", "num", "num").result == "num"
    assert find_operator("<", "joint", "joint").result == "bool"
    assert find_operator(">", "joint", "joint").result == "bool"
    assert find_operator("+", "jointRx", "jointRx").result == "joint"
    assert find_operator("<=", "joint", "joint") is None
    assert find_operator("==", "dio", "bool").result == "bool"
    assert find_operator("=", "dio", "bool").result == "bool"
    assert find_operator("=", "num", "sio").result == "num"
    assert find_operator("and", "bool", "bool").result == "bool"
    assert find_operator("and", "num", "num") is None


def test_point_has_no_arithmetic_and_aio_no_operator():
    assert {o.op for o in operators_of("point")} == {"=", "==", "!="}
    assert {o.op for o in operators_of("frame")} == {"=", "==", "!="}
    assert {o.op for o in operators_of("mdesc")} == {"=", "==", "!="}
    assert find_operator("+", "point", "point") is None
    assert operators_of("aio") == () and operators_of("screen") == ()


def test_dio_to_dio_assignment_was_removed_in_s7():
    assert find_operator("=", "dio", "dio") is None
    (removed,) = load_removed_operators()
    assert (removed.op, removed.operands, removed.section, removed.since) == ("=", ("dio", "dio"), "3.5.2", "s7")
