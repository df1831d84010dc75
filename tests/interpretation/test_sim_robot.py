"""Chapter 9 with an arm model (`val3check sim --robot`): herej, here, jointToPoint,
pointToJoint, config(joint), isInRange, the checks movej does before motion (which stays R002),
the application's length unit, the choice of the model (name, URDF, arm.cfx of a controller
tree) and the report."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import pytest

from val3check.cli import main
from val3check.simulation.scenario import ScenarioError
from val3check.robot import load_robot

from .simsupport import build, code_pos, codes, errors, gv, out, run_folder, sim

ROOT = Path(__file__).resolve().parents[2]
TX2_60 = load_robot("tx2-60")
GLOBALS = ["joint jHome", "joint jA", "joint jRes", "joint jHere", "point pHere", "point pA", "point pFar",
           "config cA", "bool bOk", "bool bIn", "bool bOut", "tool tTool", "frame fFrame", "trsf trA", "mdesc mD",
           "num nX"]


def rsim(tmp_path, code, *, globals_=GLOBALS, robot=TX2_60, **kw):
    return sim(tmp_path, code, globals_=globals_, robot=robot, **kw)


def t6(result, name):
    v = result.globals[name].data[0]
    return v.trsf.as_tuple() if hasattr(v, "trsf") else v.as_tuple()


def jv(result, name):
    return tuple(gv(result, name).values())


def test_joint_to_point_at_zero_example(tmp_path):
    # robots/README.md: with all joints at zero, here(flange, world) = {0, 20, 670, 0, 0, 0} on a TX2-60
    r = rsim(tmp_path, """begin
  jHome = {0, 0, 0, 0, 0, 0}
  pHere = jointToPoint(flange, world, jHome)
  pA = here(flange, world)
  jHere = herej()
  cA = config(jHome)
end
""")
    assert codes(r) == []
    assert t6(r, "pHere") == (0, 20, 670, 0, 0, 0)
    assert t6(r, "pA") == (0, 20, 670, 0, 0, 0)
    assert jv(r, "jHere") == (0, 0, 0, 0, 0, 0)
    # 9.7.4: d1 sin(j2) + d2 sin(j2 + j3) + delta = 0 >= 0: lefty; j3 >= 0: epositive; j5 >= 0: wpositive
    assert gv(r, "cA") == {"shoulder": "lefty", "elbow": "epositive", "wrist": "wpositive"}
    p = r.globals["pHere"].data[0]
    assert p.ref.is_root and p.ref.name == "world"
    assert p.config == {"shoulder": "lefty", "elbow": "epositive", "wrist": "wpositive"}
    assert r.robot == {"name": "TX2-60", "initial_joints": [0.0] * 6}


def test_point_to_joint_round_trip_with_tool_and_frame(tmp_path):
    r = rsim(tmp_path, """begin
  tTool.trsf = {0, 0, 120, 0, 30, 0}
  fFrame.trsf = {200, -100, 50, 0, 0, 45}
  jA = {10, -20, 95, 30, 40, -50}
  pA = jointToPoint(tTool, fFrame, jA)
  jHome = {0, 0, 0, 0, 0, 0}
  bOk = pointToJoint(tTool, jHome, pA, jRes)
  bIn = jRes == jA
  cA = config(jRes)
end
""")
    assert codes(r) == []
    assert gv(r, "bOk") is True and gv(r, "bIn") is True
    assert jv(r, "jRes") == pytest.approx((10, -20, 95, 30, 40, -50), abs=1e-9)
    assert gv(r, "cA") == dict(zip(("shoulder", "elbow", "wrist"), TX2_60.config_of([10, -20, 95, 30, 40, -50])))
    p = r.globals["pA"].data[0]
    assert p.ref is r.globals["fFrame"].data[0]
    # the same pose computed by the model: fk composed with the tool, expressed in the frame
    from val3check.geometry.trsf import Trsf, close

    flange = Trsf(*TX2_60.fk([10, -20, 95, 30, 40, -50]))
    expected = Trsf(200, -100, 50, 0, 0, 45).inverse() * flange * Trsf(0, 0, 120, 0, 30, 0)
    assert close(Trsf(*t6(r, "pA")), expected, 1e-9, 1e-9)


def test_point_to_joint_free_same_and_nearest_turn(tmp_path):
    # same: jInitial's configuration; free: any (the nearest); j4/j6 (+-270): the turn nearest jInitial
    r = rsim(tmp_path, """begin
  jA = {10, -20, 95, 30, 40, -50}
  pA = jointToPoint(flange, world, jA)
  // same: the configuration of jInitial (here that of jA: the solution is jA)
  pA.config = {ssame, esame, wsame}
  jHome = {10, -20, 95, 30, 40, -40}
  bOk = pointToJoint(flange, jHome, pA, jRes)
  // the point's own configuration, jInitial's axis 4 near -200: axis 4 (+-270) takes the turn -260
  jA.j4 = 100
  pA = jointToPoint(flange, world, jA)
  jHome = {10, -20, 95, -200, 40, -50}
  bIn = pointToJoint(flange, jHome, pA, jHere)
  jA.j4 = 30
  pA = jointToPoint(flange, world, jA)
  // free: the solution nearest jInitial, here the flipped wrist
  pA.config = {sfree, efree, wfree}
  jHome = {10, -20, 95, -150, -40, 130}
  bOut = pointToJoint(flange, jHome, pA, jA)
end
""")
    assert codes(r) == []
    assert gv(r, "bOk") is True and jv(r, "jRes") == pytest.approx((10, -20, 95, 30, 40, -50), abs=1e-9)
    assert gv(r, "bIn") is True and jv(r, "jHere") == pytest.approx((10, -20, 95, -260, 40, -50), abs=1e-9)
    assert gv(r, "bOut") is True and jv(r, "jA") == pytest.approx((10, -20, 95, -150, -40, 130), abs=1e-9)


def test_unreachable_point_to_joint_returns_false(tmp_path):
    r = rsim(tmp_path, """begin
  jRes = {1, 2, 3, 4, 5, 6}
  pFar.trsf = {2000, 0, 0, 0, 0, 0}
  bOk = pointToJoint(flange, jHome, pFar, jRes)
  // reachable (lefty epositive, righty enegative), but not lefty enegative within the limits
  pA = jointToPoint(flange, world, {0, 100, 30, 0, 30, 0})
  pA.config = {lefty, enegative, wfree}
  bOut = pointToJoint(flange, jHome, pA, jA)
end
""")
    assert codes(r) == []
    assert gv(r, "bOk") is False and jv(r, "jRes") == (1, 2, 3, 4, 5, 6)  # jResult unchanged
    assert gv(r, "bOut") is False


def test_is_in_range_uses_the_model_limits(tmp_path):
    lo, hi = TX2_60.joint_limits[4]
    r = rsim(tmp_path, f"""begin
  bIn = isInRange({{0, 0, 0, 0, {hi}, 0}})
  bOut = isInRange({{0, 0, 0, 0, {hi + 0.001}, 0}})
  bOk = isInRange(herej())
end
""")
    assert (gv(r, "bIn"), gv(r, "bOut"), gv(r, "bOk")) == (True, False, True)


def test_scenario_sets_the_initial_joint_position(tmp_path):
    r = rsim(tmp_path, """begin
  jHere = herej()
  pHere = here(flange, world)
  pA = jointToPoint(flange, world, {10, -20, 95, 30, 40, -50})
  bOk = pHere == pA
  // 9.2.3 herej example: wait until the arm is near the reference, timeout 60 s
  jHome = {10, -20, 95, 30, 40, -48}
  jA = {5, 5, 5, 5, 5, 5}
  bIn = watch(abs(herej() - jHome) < jA, 60)
end
""", scenario="[robot]\njoints = [10, -20, 95, 30, 40, -50]\n")
    assert codes(r) == []
    assert jv(r, "jHere") == (10, -20, 95, 30, 40, -50)
    assert gv(r, "bOk") is True and gv(r, "bIn") is True
    assert r.robot["initial_joints"] == [10, -20, 95, 30, 40, -50]


def test_scenario_joints_are_checked(tmp_path):
    with pytest.raises(ScenarioError, match="6-axis"):
        rsim(tmp_path, "begin\nend\n", scenario="[robot]\njoints = [1, 2, 3]\n")
    with pytest.raises(ScenarioError, match="joints"):
        rsim(tmp_path / "b", "begin\nend\n", scenario="[robot]\njoints = \"home\"\n")
    with pytest.raises(ScenarioError, match="unknown key"):
        rsim(tmp_path / "c", "begin\nend\n", scenario="[robot]\nspeed = 3\n")


# ---- movej: what the arm cannot execute ------------------------------------------------------------


def test_movej_to_an_unreachable_point_stops_the_instruction(tmp_path):
    """10.6 movej: "une erreur d'exécution est générée ... si pPosition ne peut pas être atteinte":
    the task stops at the movej with 12.1's 154, reported with its cause (R010)."""
    r = rsim(tmp_path, """begin
  pFar.trsf = {2000, 0, 0, 0, 0, 0}
  pFar.config = {sfree, efree, wfree}
  movej(pFar, flange, mD)
  putln("not reached")
  waitEndMove()
end
""")
    assert out(r) == []
    (far,) = r.diagnostics
    assert far.code == "R010" and far.error == 154 and "reach" in far.message and "pFar" in far.message
    assert far.line == code_pos(r, 4, 3)[0]


def test_movej_outside_the_joint_limits_is_reported(tmp_path):
    r = rsim(tmp_path, "begin\n  movej({0, 0, 0, 0, 0, 300}, flange, mD)\n  waitEndMove()\nend\n")
    assert codes(r) == ["R011"] and r.diagnostics[0].error == 154
    assert "j6" in r.diagnostics[0].message and "limit" in r.diagnostics[0].message


def test_movej_reachable_moves(tmp_path):
    r = rsim(tmp_path, """begin
  pA = jointToPoint(flange, world, {10, -20, 95, 30, 40, -50})
  movej(pA, flange, mD)
  waitEndMove()
  jA = herej()
end
""")
    assert codes(r) == []
    assert jv(r, "jA") == pytest.approx((10, -20, 95, 30, 40, -50), abs=1e-6)


def test_movej_checks_the_point_reference_first(tmp_path):
    r = rsim(tmp_path, "begin\n  movej(l_p, flange, mD)\nend\n", locals_=["point l_p"])
    assert errors(r) == [162]


# ---- length unit (2.1.4.1) -----------------------------------------------------------------------------


def test_inch_application(tmp_path):
    folder = build(tmp_path, """begin
  pHere = here(flange, world)
  pA = jointToPoint(flange, world, {10, -20, 95, 30, 40, -50})
  bOk = pointToJoint(flange, jHome, pA, jRes)
  pFar.trsf = {30, 0, 0, 0, 0, 0}
  bOut = pointToJoint(flange, jHome, pFar, jA)
end
""", globals_=GLOBALS)
    pjx = folder / "Example.pjx"
    text = pjx.read_text(encoding="utf-8")
    assert 'millimeterUnit="true"' in text
    pjx.write_text(text.replace('millimeterUnit="true"', 'millimeterUnit="false"'), encoding="utf-8")
    r = run_folder(folder, robot=TX2_60)
    assert codes(r) == []
    assert t6(r, "pHere") == pytest.approx((0, 20 / 25.4, 670 / 25.4, 0, 0, 0), abs=1e-12)
    mm = TX2_60.fk([10, -20, 95, 30, 40, -50])
    assert t6(r, "pA") == pytest.approx((mm[0] / 25.4, mm[1] / 25.4, mm[2] / 25.4, *mm[3:]), abs=1e-9)
    assert gv(r, "bOk") is True and jv(r, "jRes") == pytest.approx((10, -20, 95, 30, 40, -50), abs=1e-9)
    # 30 inches = 762 mm: beyond the 670 mm of reach (it would be reachable as 30 mm)
    assert gv(r, "bOut") is False


# ---- choosing the model, the report -------------------------------------------------------------------


def _controller_copy(tmp_path: Path) -> Path:
    dst = tmp_path / "controller"
    shutil.copytree(ROOT / "fixtures" / "valid" / "controller", dst)
    return dst / "usr" / "usrapp" / "Welder"


def _json(args, capsys):
    code = main(args)
    captured = capsys.readouterr()
    return code, captured.out, captured.err


def test_arm_cfx_of_the_controller_tree_chooses_the_robot(tmp_path, capsys):
    welder = _controller_copy(tmp_path)
    code, text, err = _json(["sim", str(welder), "--report", "json"], capsys)
    data = json.loads(text)
    assert data["robot"]["name"] == "TX2-60" and data["robot"]["initial_joints"] == [0, 0, 0, 0, 0, 0]  # tx2-60-S1
    # pStart (fatherId fJig, 620 mm in front of the arm, tool 310 mm long) is out of reach: R010,
    # error 154 at the movej (10.6, 12.1)
    assert [d["code"] for d in data["diagnostics"]][:1] == ["R010"]
    assert data["diagnostics"][0]["error"] == 154
    assert _json(["sim", str(welder), "--report", "json"], capsys)[1] == text  # byte-identical
    # --robot none: no model, movej stops with R002
    code, text, err = _json(["sim", str(welder), "--report", "json", "--robot", "none"], capsys)
    data = json.loads(text)
    assert data["robot"] is None
    assert [d["code"] for d in data["diagnostics"]][:1] == ["R002"]


@pytest.mark.parametrize("spec", ["TX2_60", "tx2-60", "robots/tx2-60.urdf"])
def test_robot_option_by_name_or_urdf(tmp_path, capsys, spec):
    folder = build(tmp_path, """begin
  pHere = here(flange, world)
  putln(toString("", pHere.trsf.z))
end
""", globals_=["point pHere"])
    if spec.endswith(".urdf"):
        spec = str(ROOT / spec)
    code, text, err = _json(["sim", str(folder), "--robot", spec], capsys)
    assert code == 0, (text, err)
    assert "arm model: TX2-60" in text and "670" in text


def test_unknown_robot_is_a_usage_error(tmp_path, capsys):
    folder = build(tmp_path, "begin\nend\n")
    code, text, err = _json(["sim", str(folder), "--robot", "nosuch"], capsys)
    assert code == 2 and "TX2-60" in err  # the message lists the known arms


def test_no_robot_outside_a_controller_tree(tmp_path, capsys):
    folder = build(tmp_path, "begin\n  jA = herej()\nend\n", globals_=["joint jA"])
    code, text, err = _json(["sim", str(folder), "--report", "json"], capsys)
    data = json.loads(text)
    assert data["robot"] is None
    d = data["diagnostics"][0]
    assert d["code"] == "R002" and "--robot" in d["message"]


# ---- without an arm model (issue 11 item 14) ---------------------------------------------------------


def test_idle_arm_instructions_need_no_model(tmp_path):
    """resetMotion(), isEmpty(), autoConnectMove() at the top of start() act on an idle arm."""
    r = sim(tmp_path, """begin
  if isEmpty() == false
    resetMotion()
  endIf
  resetMotion()
  autoConnectMove(true)
  bAuto = autoConnectMove()
  bSettled = isSettled()
  waitEndMove()
  nId = getMoveId()
  putln("ready")
end
""", globals_=["bool bAuto", "bool bSettled", "num nId"])
    assert codes(r) == [] and out(r) == ["ready"] and r.end_reason == "ended"
    assert gv(r, "bAuto") is True and gv(r, "bSettled") is True and gv(r, "nId") == 0


@pytest.mark.parametrize("line", ["movej(jA, flange, mD)", "movel(pA, flange, mD)", "movec(pA, pA, flange, mD)"])
def test_motion_without_a_model_says_how_to_name_the_arm(tmp_path, line):
    r = sim(tmp_path, f"begin\n  putln(\"before\")\n  {line}\n  putln(\"after\")\nend\n",
            globals_=["joint jA", "point pA", "mdesc mD"])
    assert out(r) == ["before"] and codes(r) == ["R002"]
    msg = r.diagnostics[0].message
    assert line.split("(")[0] in msg and "--robot" in msg and "arm.cfx" in msg
