"""Chapter 9 geometry through `val3check sim`, without an arm model: trsf operators and
instructions, the frame and tool trees, points (compose, appro, position, distance, link,
setFrame), joint operators, the errors 160-165, and R002 for what needs the arm."""

from __future__ import annotations

import math

import pytest

from val3check.geometry import Frame, Point, Tool, Trsf
from val3check.geometry.trsf import close

from .simsupport import build, codes, errors, gv, make_library, out, run_folder, sim


def obj(result, name: str, index: int = 0):
    """The run-time value (geometry object, dict...) of a global at the end of the run."""
    return result.globals[name].data[index]


def tr(result, name: str) -> tuple:
    v = obj(result, name)
    return (v if type(v) is Trsf else v.trsf).as_tuple()


def approx(values, abs_=1e-9):
    return pytest.approx(values, abs=abs_)


# ---- trsf (9.3) ---------------------------------------------------------------------------------


def test_trsf_operators_9_3_3(tmp_path):
    r = sim(tmp_path, """begin
  trA = {10, 20, 30, 0, 0, 90}
  trB = {1, 2, 3, 0, 0, 0}
  trC = trA * trB
  trD = trB * trA
  trI = !trA
  trE = trA * !trA
  bEq = trC == trD
  bNe = trC != trD
  trF = trA
  bSame = trF == trA
  trF.x = trF.x + 1e-9
  bAfter = trF == trA
end
""", globals_=["trsf trA", "trsf trB", "trsf trC", "trsf trD", "trsf trI", "trsf trE", "trsf trF", "bool bEq",
               "bool bNe", "bool bSame", "bool bAfter"])
    assert codes(r) == []
    # trC = trA * trB: trB expressed in trA's frame (Rz(90) turns (1, 2, 3) into (-2, 1, 3))
    assert tr(r, "trC") == (8, 21, 33, 0, 0, 90)
    assert tr(r, "trD") == (11, 22, 33, 0, 0, 90)  # trPosition1 * trPosition2 != trPosition2 * trPosition1
    assert tr(r, "trI") == (-20, 10, -30, 0, 0, -90)
    assert tr(r, "trE") == (0, 0, 0, 0, 0, 0)
    assert (gv(r, "bEq"), gv(r, "bNe"), gv(r, "bSame"), gv(r, "bAfter")) == (False, True, True, False)


def test_trsf_orientation_example_9_3_2(tmp_path):
    # R2 in R1: {250, 350, 450, 20, 10, 30}: rx about x, then ry about y', then rz about z''
    r = sim(tmp_path, """begin
  trR2 = {250, 350, 450, 20, 10, 30}
  trX = trR2 * {1, 0, 0, 0, 0, 0}
  trBack = !trR2 * trR2
end
""", globals_=["trsf trR2", "trsf trX", "trsf trBack"])
    a, b, c = (math.radians(v) for v in (20, 10, 30))
    # first column of Rx(20) Ry(10) Rz(30)
    col = (math.cos(b) * math.cos(c), math.cos(a) * math.sin(c) + math.sin(a) * math.sin(b) * math.cos(c),
           math.sin(a) * math.sin(c) - math.cos(a) * math.sin(b) * math.cos(c))
    x = tr(r, "trX")
    assert x[:3] == approx((250 + col[0], 350 + col[1], 450 + col[2]), 1e-12)
    assert x[3:] == approx((20, 10, 30), 1e-12)
    assert close(obj(r, "trBack"), Trsf())


def test_distance_interpolate_align_9_3_4(tmp_path):
    r = sim(tmp_path, """begin
  trA = {0, 0, 0, 0, 0, 0}
  trB = {30, 40, 0, 0, 0, 90}
  nD = distance(trA, trB)
  trL = interpolateL(trA, trB, 0.5)
  trL0 = interpolateL(trA, trB, 0)
  trL1 = interpolateL(trA, trB, 1)
  trC = interpolateC({100, 0, 0, 0, 0, 0}, {0, 100, 0, 0, 0, 0}, {-100, 0, 0, 0, 0, 0}, 0.5)
  trAl = align({1, 2, 3, 10, 5, 0}, {0, 0, 0, 0, 0, 0})
  // distance between two tools (9.3.4 example)
  nTools = distance(position(tTool1, flange), position(tTool2, flange))
end
""", globals_=["trsf trA", "trsf trB", "num nD", "trsf trL", "trsf trL0", "trsf trL1", "trsf trC", "trsf trAl",
               "num nTools", "tool tTool1", "tool tTool2"])
    assert codes(r) == []
    assert gv(r, "nD") == 50
    assert tr(r, "trL") == approx((15, 20, 0, 0, 0, 45))
    assert tr(r, "trL0") == (0, 0, 0, 0, 0, 0) and tr(r, "trL1") == (30, 40, 0, 0, 0, 90)
    assert tr(r, "trC")[:3] == approx((0, 100, 0))
    al = obj(r, "trAl")
    assert (al.x, al.y, al.z) == (1, 2, 3)
    assert (al.rx, al.ry) == (0, 0)  # Z turned (by the smallest rotation) onto the reference's Z
    assert gv(r, "nTools") == 0


def test_interpolate_out_of_range_is_error_70(tmp_path):
    r = sim(tmp_path, """begin
  trA = interpolateL(trA, {10, 0, 0, 0, 0, 0}, 2)
end
""", globals_=["trsf trA"])
    assert errors(r) == [70]
    r = sim(tmp_path / "c", """begin
  trA = interpolateC({0, 0, 0, 0, 0, 0}, {1, 0, 0, 0, 0, 0}, {2, 0, 0, 0, 0, 0}, 0.5)
end
""", globals_=["trsf trA"])
    assert errors(r) == [70]  # aligned positions define no arc


# ---- frames (9.4) ---------------------------------------------------------------------------------


def _with_values(folder, values: dict[str, str], name: str = "Example"):
    """Give globals of a `build` application their <Value .../> elements."""
    dtx = folder / f"{name}.dtx"
    text = dtx.read_text(encoding="utf-8")
    for var, xml in values.items():
        head = f'<Data name="{var}" '
        i = text.index(head)
        j = text.index("/>", i)
        text = text[:j] + ">" + xml + "</Data>" + text[j + 2:]
    dtx.write_text(text, encoding="utf-8")


def test_frame_tree_from_the_data_file(tmp_path):
    # fPallet in world, fPlace in fPallet, pPick in fPlace (fatherId): re-teaching fPallet moves
    # every point linked below it (9.4.2)
    folder = build(tmp_path, """begin
  trW = position(pPick, world)
  trF = position(fPlace, world)
  trInPallet = position(pPick, fPallet)
  fPallet.trsf.x = fPallet.trsf.x + 100
  trW2 = position(pPick, world)
  bLinked = pPick.trsf.x == 5
end
""", globals_=["frame fPallet", "frame fPlace", "point pPick", "trsf trW", "trsf trF", "trsf trInPallet",
               "trsf trW2", "bool bLinked"])
    _with_values(folder, {
        "fPallet": '<Value key="0" x="400" y="-200" z="10" rz="90" fatherId="world[0]" />',
        "fPlace": '<Value key="0" x="50" y="0" z="0" fatherId="fPallet[0]" />',
        "pPick": '<Value key="0" x="5" y="0" z="20" rx="180" fatherId="fPlace[0]" />',
    })
    r = run_folder(folder)
    assert codes(r) == []
    # fPallet turned 90 about z: fPlace's x goes along world y
    assert tr(r, "trF") == approx((400, -150, 10, 0, 0, 90))
    assert tr(r, "trW") == approx((400, -145, 30, 180, 0, -90))
    assert tr(r, "trInPallet") == approx((55, 0, 20, 180, 0, 0))
    assert tr(r, "trW2") == approx((500, -145, 30, 180, 0, -90))
    assert gv(r, "bLinked") is True
    p, f = obj(r, "pPick"), obj(r, "fPlace")
    assert type(p) is Point and p.ref is f and f.ref is obj(r, "fPallet")
    assert obj(r, "fPallet").ref is r.globals["fPallet"].data[0].ref  # world, shared


def test_frame_assignment_keeps_the_node_link_and_equality(tmp_path):
    r = sim(tmp_path, """begin
  fA.trsf = {100, 0, 0, 0, 0, 0}
  link(pA, fA)
  link(fC, fA)
  trBefore = position(pA, world)
  fB.trsf = {0, 50, 0, 0, 0, 0}
  // 9.4.3: fA takes fB's position and reference; what is linked to fA follows
  fA = fB
  trAfter = position(pA, world)
  trC = position(fC, world)
  bEq = fA == fB
  fB.trsf.z = 1
  bNe = fA != fB
  link(fB, fA)
  bOther = fA == fB
  trFB = position(fB, fA)
end
""", globals_=["frame fA", "frame fB", "frame fC", "point pA", "trsf trBefore", "trsf trAfter", "trsf trC",
               "bool bEq", "bool bNe", "bool bOther", "trsf trFB"])
    assert codes(r) == []
    assert tr(r, "trBefore") == (100, 0, 0, 0, 0, 0)
    assert tr(r, "trAfter") == (0, 50, 0, 0, 0, 0)
    assert tr(r, "trC") == (0, 50, 0, 0, 0, 0)
    assert (gv(r, "bEq"), gv(r, "bNe"), gv(r, "bOther")) == (True, True, False)
    assert tr(r, "trFB") == (0, 50, 1, 0, 0, 0)  # link keeps fB's position in its new reference


def test_set_frame_return_codes_9_4_4(tmp_path):
    r = sim(tmp_path, """begin
  pO.trsf = {100, 100, 0, 0, 0, 0}
  pX.trsf = {200, 100, 0, 0, 0, 0}
  pY.trsf = {150, 300, 0, 0, 0, 0}
  pNear.trsf = {100, 100, 0, 0, 0, 0}
  pOnX.trsf = {300, 100, 0, 0, 0, 0}
  nOk = setFrame(pO, pX, pY, fResult)
  trOk = position(fResult, world)
  nTooClose = setFrame(pO, pNear, pY, fOther)
  nOnAxis = setFrame(pO, pX, pOnX, fOther)
  trOther = position(fOther, world)
  // a point expressed in the new frame
  link(pIn, fResult)
  pIn.trsf = {0, 10, 0, 0, 0, 0}
  trIn = position(pIn, world)
end
""", globals_=["point pO", "point pX", "point pY", "point pNear", "point pOnX", "point pIn", "frame fResult",
               "frame fOther", "num nOk", "num nTooClose", "num nOnAxis", "trsf trOk", "trsf trOther", "trsf trIn"])
    assert codes(r) == []
    assert (gv(r, "nOk"), gv(r, "nTooClose"), gv(r, "nOnAxis")) == (0, 1, 2)
    assert tr(r, "trOk") == approx((100, 100, 0, 0, 0, 0))
    assert tr(r, "trOther") == (0, 0, 0, 0, 0, 0)  # unchanged by the failed calls
    assert tr(r, "trIn") == approx((100, 110, 0, 0, 0, 0))


def test_set_frame_point_without_reference_is_162(tmp_path):
    r = sim(tmp_path, """begin
  nRes = setFrame(l_p, pX, pY, fResult)
end
""", globals_=["point pX", "point pY", "frame fResult", "num nRes"], locals_=["point l_p"])
    assert errors(r) == [162]


# ---- tools (9.5) ----------------------------------------------------------------------------------


def test_tool_tree_gripper_and_times(tmp_path):
    folder = build(tmp_path, """begin
  trT = position(tTorch, flange)
  trTip = position(tTip, flange)
  trTipInTorch = position(tTip, tTorch)
  nOtime = tTorch.otime
  nCtime = tTorch.ctime
  open(tTorch)
  nOpened = clock()
  close(tTorch)
  nClosed = clock()
  bSame = tTip.gripper == doValve
end
""", globals_=["tool tTorch", "tool tTip", "dio doValve", "trsf trT", "trsf trTip", "trsf trTipInTorch",
               "num nOtime", "num nCtime", "num nOpened", "num nClosed", "bool bSame"],
                   links={"doValve": "ValveIO\\valve2"})
    _with_values(folder, {
        "tTorch": '<Value key="0" z="310" ry="22" fatherId="flange[0]" ioLink="ValveIO\\valve2" otime="0.5" '
                  'ctime="0.25" />',
        "tTip": '<Value key="0" z="10" fatherId="tTorch[0]" ioLink="ValveIO\\valve2" />',
    })
    r = run_folder(folder)
    assert codes(r) == []
    assert tr(r, "trT") == (0, 0, 310, 0, 22, 0)
    s, c = math.sin(math.radians(22)), math.cos(math.radians(22))
    assert tr(r, "trTip") == approx((10 * s, 0, 310 + 10 * c, 0, 22, 0))
    assert tr(r, "trTipInTorch") == approx((0, 0, 10, 0, 0, 0), 1e-12)
    assert (gv(r, "nOtime"), gv(r, "nCtime")) == (0.5, 0.25)
    # open: the gripper output goes true, then otime; close: false, then ctime (9.5.4)
    assert [(round(at / 1e6, 3), v) for at, kind, link, v, src in r.io_log if link == "ValveIO\\valve2"] == \
        [(0.0, True), (0.5, False)]
    assert gv(r, "nOpened") == pytest.approx(0.5, abs=0.005)
    assert gv(r, "nClosed") == pytest.approx(0.75, abs=0.005)
    assert type(obj(r, "tTorch")) is Tool


def test_tool_default_gripper_is_valve1_and_unlinked_output_is_123(tmp_path):
    r = sim(tmp_path, """begin
  open(tDefault)
  putln("opened")
  dioLink(tNoOutput.gripper, doUnlinked)
  open(tNoOutput)
  putln("not reached")
end
""", globals_=["tool tDefault", "tool tNoOutput", "dio doUnlinked"])
    # 9.5.1: the default output is valve1; a tool whose dio is not linked: error 123 (3.5.2, 9.5.4)
    assert obj(r, "tDefault").gripper.link == "valve1"
    assert out(r) == ["opened"]
    assert errors(r) == [123]


# ---- points (9.6) ---------------------------------------------------------------------------------


def test_compose_and_appro_examples_9_6_3(tmp_path):
    # the compose example of 9.6.3 (orientation without position, then position without
    # orientation) and the appro example (100 mm above the point)
    folder = build(tmp_path, """begin
  pResultat = compose(pPosition, fReference, trTransformation)
  trTurned = pResultat.trsf
  pResultat.trsf.x = pPosition.trsf.x
  pResultat.trsf.y = pPosition.trsf.y
  pResultat.trsf.z = pPosition.trsf.z
  trOriented = pResultat.trsf
  trTransformation.rx = trTransformation.ry = trTransformation.rz = 0
  pResultat = compose(pResultat, fReference, trTransformation)
  trMoved = pResultat.trsf
  // approche : 100 mm au-dessus du point (axe z de l'outil, qui pointe vers le bas)
  pAppro = appro(pDestination, {0, 0, -100, 0, 0, 0})
  trAppro = pAppro.trsf
  bSameRef = pAppro == appro(pDestination, {0, 0, -100, 0, 0, 0})
end
""", globals_=["point pResultat", "point pPosition", "point pDestination", "point pAppro", "frame fReference",
               "trsf trTransformation", "trsf trTurned", "trsf trOriented", "trsf trMoved", "trsf trAppro",
               "bool bSameRef"])
    _with_values(folder, {
        "fReference": '<Value key="0" x="500" y="-200" z="100" rz="30" fatherId="world[0]" />',
        "pPosition": '<Value key="0" x="400" y="100" z="300" rx="180" shoulder="lefty" elbow="epositive" '
                     'wrist="wpositive" fatherId="world[0]" />',
        "trTransformation": '<Value key="0" x="10" y="20" z="30" rz="45" />',
        "pDestination": '<Value key="0" x="300" y="50" z="20" rx="180" fatherId="fReference[0]" />',
    })
    r = run_folder(folder)
    assert codes(r) == []
    turned, oriented, moved = obj(r, "trTurned"), obj(r, "trOriented"), obj(r, "trMoved")
    assert (turned.x, turned.y) != approx((400, 100))  # "modifie aussi ses coordonnées cartésiennes"
    assert (oriented.x, oriented.y, oriented.z) == (400, 100, 300)
    assert close(Trsf(0, 0, 0, oriented.rx, oriented.ry, oriented.rz), Trsf(0, 0, 0, 0, 0, 45) * Trsf(0, 0, 0, 180))
    # then a pure translation, expressed in fReference's axes (turned 30 about z): orientation kept
    d = Trsf(0, 0, 0, 0, 0, 30) * Trsf(10, 20, 30)
    assert moved.as_tuple() == approx((400 + d.x, 100 + d.y, 300 + d.z, oriented.rx, oriented.ry, oriented.rz))
    assert (moved.rx, moved.ry, moved.rz) == (oriented.rx, oriented.ry, oriented.rz)
    p = obj(r, "pResultat")
    assert p.ref is r.globals["pPosition"].data[0].ref and p.config["shoulder"] == "lefty"
    # appro: 100 mm back along the point's own z axis, which points down: 100 mm higher
    assert tr(r, "trAppro") == (300, 50, 120, 180, 0, 0)
    assert obj(r, "pAppro").ref is obj(r, "fReference") and gv(r, "bSameRef") is True


def test_position_and_distance_example_9_6_3(tmp_path):
    folder = build(tmp_path, """begin
  nD = distance(pPoint1, pPoint2)
  nW = distance(position(pPoint1, world), position(pPoint2, world))
  nLocal = distance(pPoint1.trsf, pPoint2.trsf)
end
""", globals_=["point pPoint1", "point pPoint2", "frame fOne", "frame fTwo", "num nD", "num nW", "num nLocal"])
    _with_values(folder, {
        "fOne": '<Value key="0" x="100" rz="90" fatherId="world[0]" />',
        "fTwo": '<Value key="0" y="300" z="-20" rx="30" ry="20" rz="10" fatherId="fOne[0]" />',
        "pPoint1": '<Value key="0" x="10" y="20" z="30" rx="180" fatherId="fOne[0]" />',
        "pPoint2": '<Value key="0" x="-5" y="7" z="2" ry="90" fatherId="fTwo[0]" />',
    })
    r = run_folder(folder)
    assert codes(r) == []
    assert gv(r, "nD") == pytest.approx(gv(r, "nW"), abs=1e-9)
    assert gv(r, "nD") != pytest.approx(gv(r, "nLocal"))


def test_point_assignment_copies_reference_and_config(tmp_path):
    r = sim(tmp_path, """begin
  fA.trsf = {10, 0, 0, 0, 0, 0}
  link(pA, fA)
  pA.config = {righty, enegative, wfree}
  pB = pA
  pA.config.shoulder = lefty
  pA.trsf.y = 5
  bEq = pB == pA
  pB.trsf.y = 5
  bEq2 = pB == pA
  trB = position(pB, world)
  // 2.4.2: a {...} literal writes the fields; the point keeps its reference frame
  pB = {{1, 2, 3, 0, 0, 0}, {sfree, efree, wfree}}
  trLit = position(pB, world)
end
""", globals_=["frame fA", "point pA", "point pB", "bool bEq", "bool bEq2", "trsf trB", "trsf trLit"])
    assert codes(r) == []
    pa, pb = obj(r, "pA"), obj(r, "pB")
    assert pb.ref is obj(r, "fA")
    assert pa.config["shoulder"] == "lefty" and pb.config == {"shoulder": "sfree", "elbow": "efree", "wrist": "wfree"}
    assert (gv(r, "bEq"), gv(r, "bEq2")) == (False, True)
    assert tr(r, "trB") == (10, 5, 0, 0, 0, 0)
    assert tr(r, "trLit") == (11, 2, 3, 0, 0, 0)


def test_parameters_by_value_and_by_reference(tmp_path):
    r = sim(tmp_path, """begin
  fA.trsf = {100, 0, 0, 0, 0, 0}
  call moveByValue(fA)
  nAfterValue = fA.trsf.x
  call moveByRef(fA)
  nAfterRef = fA.trsf.x
  call linkLocal(fA)
end
""", globals_=["frame fA", "num nAfterValue", "num nAfterRef", "num nInCopy"], programs={
        "moveByValue": {"params": ["frame x_f"], "code": "begin\n  x_f.trsf.x = 1\n  nInCopy = position(x_f, world).x\nend\n"},
        "moveByRef": {"params": ["frame& x_f"], "code": "begin\n  x_f.trsf.x = 2\nend\n"},
        # a by-value parameter is a local of the callee: a global linked to it is error 165
        "linkLocal": {"params": ["frame x_f"], "code": "begin\n  link(fA, x_f)\nend\n"},
    })
    assert (gv(r, "nAfterValue"), gv(r, "nInCopy"), gv(r, "nAfterRef")) == (100, 1, 2)
    assert errors(r) == [165]


# ---- joint (9.2) ----------------------------------------------------------------------------------


def test_joint_operators_9_2_2(tmp_path):
    r = sim(tmp_path, """begin
  jA = {10, 20, 30, 40, 50, 60}
  jB = {5, 25, 30, 40, 50, 60}
  jSum = jA + jB
  jDiff = jA - jB
  bGt = jA > jB
  bLt = jA < jB
  bNotLt = !(jA < jB)
  bEq = jA == {10, 20, 30, 40, 50, 60.0000000001}
  bNe = jA != jB
  jAll = {1, 1, 1, 1, 1, 1}
  bAllGt = jA > jAll
  // 9.2.3 abs: every axis closer than 5 degrees to the reference
  jReference = {90, 45, 45, 0, 30, 0}
  jEcartMax = {5, 5, 5, 5, 5, 5}
  jNear = {92, 44, 47, -1, 33, 4}
  bClose = abs(jNear - jReference) < jEcartMax
  jFar = {92, 44, 47, -1, 36, 4}
  bFar = abs(jFar - jReference) < jEcartMax
end
""", globals_=["joint jA", "joint jB", "joint jSum", "joint jDiff", "bool bGt", "bool bLt", "bool bNotLt",
               "bool bEq", "bool bNe", "joint jAll", "bool bAllGt", "joint jReference", "joint jEcartMax",
               "joint jNear", "bool bClose", "joint jFar", "bool bFar"])
    assert codes(r) == []
    assert list(gv(r, "jSum").values()) == [15, 45, 60, 80, 100, 120]
    assert list(gv(r, "jDiff").values()) == [5, -5, 0, 0, 0, 0]
    # "jPosition1 > jPosition2 n'est pas l'équivalent de !(jPosition1 < jPosition2)"
    assert (gv(r, "bGt"), gv(r, "bLt"), gv(r, "bNotLt")) == (False, False, True)
    assert (gv(r, "bEq"), gv(r, "bNe"), gv(r, "bAllGt")) == (True, True, True)
    assert (gv(r, "bClose"), gv(r, "bFar")) == (True, False)


# ---- errors 160-165 (12.1) ------------------------------------------------------------------------


@pytest.mark.parametrize("code, body, expected", [
    ("local point without reference frame", "nX = distance(l_p, pA)", 162),
    ("local frame without reference frame", "nX = position(l_f, world).x", 163),
    ("local tool without reference tool", "nX = position(l_t, flange).x", 164),
    ("world modified", "world.trsf.x = 1\n  nX = position(fA, world).x", 161),
    ("flange modified", "flange.trsf.z = 1\n  nX = position(tA, flange).x", 160),
    ("world linked", "link(world, fA)\n  nX = distance(pA, pA)", 161),
    ("global linked to a local", "l_f = world\n  link(fA, l_f)", 165),
    ("global assigned a local reference", "l_f = world\n  link(l_p, l_f)\n  pA = l_p", 165),
    ("appro without reference", "pA = appro(l_p, {0, 0, 10, 0, 0, 0})", 162),
    ("compose in an undefined frame", "pA = compose(pA, l_f, {0, 0, 10, 0, 0, 0})", 163),
    ("loop of references", "link(fA, fB)\n  link(fB, fA)\n  nX = position(fA, world).x", 163),
])
def test_errors_160_to_165(tmp_path, code, body, expected):
    r = sim(tmp_path, f"begin\n  {body}\n  putln(\"after\")\nend\n",
            globals_=["point pA", "frame fA", "frame fB", "tool tA", "num nX"],
            locals_=["point l_p", "frame l_f", "tool l_t"])
    assert errors(r) == [expected], code
    assert out(r) == []


def test_local_frame_usable_after_assignment(tmp_path):
    r = sim(tmp_path, """begin
  l_f = fA
  l_f.trsf.x = l_f.trsf.x + 5
  link(l_p, l_f)
  nX = position(l_p, world).x
  // a local may be linked to a global
  link(l_t, flange)
  nT = position(l_t, flange).z
end
""", globals_=["frame fA", "num nX", "num nT"], locals_=["frame l_f", "point l_p", "tool l_t"])
    assert codes(r) == [] and gv(r, "nX") == 5 and gv(r, "nT") == 0


def test_user_type_frames_have_no_reference(tmp_path):
    # 9.4.1: "les repères dans les variables de type d'utilisateur n'ont pas de repère de
    # référence": a frame field must be set (=, link) before it is used (163)
    make_library(tmp_path, "Station", globals_=["frame fBase", "point pPick"])
    folder = build(tmp_path, """begin
  sStation.fBase.trsf = {10, 0, 0, 0, 0, 0}
  link(sStation.fBase, world)
  link(sStation.pPick, sStation.fBase)
  nX = position(sStation.pPick, world).x
  nY = position(sOther.fBase, world).x
end
""", globals_=["Station sStation", "Station sOther", "num nX", "num nY"])
    pjx = folder / "Example.pjx"
    pjx.write_text(pjx.read_text(encoding="utf-8").replace(
        "<Libraries />", '<Libraries />\n  <Types>\n    <Type name="Station" path="Disk://Station" />\n  </Types>'),
        encoding="utf-8")
    r = run_folder(folder)
    assert gv(r, "nX") == 10
    assert errors(r) == [163]


# ---- what needs the arm model -----------------------------------------------------------------------


@pytest.mark.parametrize("line, name", [
    ("pA = here(flange, world)", "here"),
    ("jA = herej()", "herej"),
    ("pA = jointToPoint(flange, world, jA)", "jointToPoint"),
    ("bOk = pointToJoint(flange, jA, pA, jA)", "pointToJoint"),
    ("cA = config(jA)", "config"),
    ("bOk = isInRange(jA)", "isInRange"),
])
def test_arm_instructions_without_robot_stop_with_r002(tmp_path, line, name):
    r = sim(tmp_path, f"begin\n  putln(\"before\")\n  {line}\n  putln(\"after\")\nend\n",
            globals_=["point pA", "joint jA", "bool bOk", "config cA"])
    assert out(r) == ["before"]
    assert codes(r) == ["R002"]
    msg = r.diagnostics[0].message
    assert name in msg and "--robot" in msg and "arm.cfx" in msg and "urdf" in msg.lower()
    assert r.robot is None


def test_geometry_errors_come_before_r002(tmp_path):
    # a tool without reference is error 164 whether there is an arm model or not
    r = sim(tmp_path, "begin\n  pA = here(l_t, world)\nend\n", globals_=["point pA"], locals_=["tool l_t"])
    assert errors(r) == [164]


def test_motion_without_robot_stays_r002(tmp_path):
    r = sim(tmp_path, "begin\n  movej(pA, flange, mD)\nend\n", globals_=["point pA", "mdesc mD"])
    assert codes(r) == ["R002"]
    assert "movej" in r.diagnostics[0].message and "--robot" in r.diagnostics[0].message


def test_values_are_geometry_objects(tmp_path):
    r = sim(tmp_path, "begin\nend\n", globals_=["trsf trA", "frame fA", "tool tA", "point pA", "joint jA",
                                                "config cA"])
    assert type(obj(r, "trA")) is Trsf and type(obj(r, "fA")) is Frame and type(obj(r, "tA")) is Tool
    assert type(obj(r, "pA")) is Point and obj(r, "pA").config == {"shoulder": "ssame", "elbow": "esame",
                                                                    "wrist": "wsame"}
    assert gv(r, "jA") == {f"j{i}": 0 for i in range(1, 7)}
    w = obj(r, "fA").ref
    assert w.is_root and w.name == "world" and obj(r, "pA").ref is w and obj(r, "tA").ref.name == "flange"


def test_library_snapshot_keeps_links_among_its_globals():
    # libSave/libLoad copies (values.copy_globals): a point linked to a frame of the same
    # library follows the copy of that frame, not the original
    from val3check.geometry import new_world
    from val3check.interpretation.values import Arr, copy_globals

    world = new_world()
    f = Frame(Trsf(100, 0, 0), world, name="fBase")
    p = Point(Trsf(1, 2, 3), (), f, name="pPick")
    p.config = {"shoulder": "sfree", "elbow": "efree", "wrist": "wfree"}
    copied = copy_globals({"fBase": Arr("frame", [f]), "pPick": Arr("point", [p])})
    f2, p2 = copied["fBase"].data[0], copied["pPick"].data[0]
    assert f2 is not f and p2 is not p
    assert p2.ref is f2 and f2.ref is world  # inside the copy: relinked; outside (world): shared
    assert p2.config == p.config and p2.config is not p.config


def test_scenario_joints_without_a_robot_have_no_effect(tmp_path):
    r = sim(tmp_path, "begin\n  putln(\"ok\")\nend\n", scenario="[robot]\njoints = [0, 0, 0, 0, 0, 0]\n")
    assert out(r) == ["ok"] and r.robot is None


def test_world_and_flange_pass_by_reference(tmp_path):
    """world and flange are variables of the controller (9.4.1, 9.5.1): passed by reference
    (2.6.2), the callee reads and writes the roots themselves (was R004 "unknown variable")."""
    r = sim(tmp_path, "begin\n  call useTool(flange)\n  call useFrame(world)\n  nO = flange.otime\n"
                      "  call replace(flange)\n  nC = flange.ctime\nend\n",
            globals_=["num nZ", "num nX", "num nO", "num nC", "tool tOther"],
            programs={"useTool": {"params": ["tool& x_tTool"], "code": "begin\n  nZ = x_tTool.trsf.z\n"
                                                                       "  x_tTool.otime = 0.5\nend\n"},
                      "useFrame": {"params": ["frame& x_fRef"], "code": "begin\n  nX = x_fRef.trsf.x\nend\n"},
                      "replace": {"params": ["tool& x_tTool"], "code": "begin\n  tOther.ctime = 0.25\n"
                                                                       "  x_tTool = tOther\nend\n"}})
    assert not r.diagnostics, r.diagnostics
    assert (gv(r, "nZ"), gv(r, "nX"), gv(r, "nO"), gv(r, "nC")) == (0.0, 0.0, 0.5, 0.25)


def test_flange_written_through_a_reference_fails_the_next_computation(tmp_path):
    # 9.5.1: once flange's coordinates are changed, the next computation through it is error 160
    r = sim(tmp_path, "begin\n  call shift(flange)\n  trA = position(tGrip, flange)\nend\n",
            globals_=["tool tGrip", "trsf trA"],
            programs={"shift": {"params": ["tool& x_tTool"], "code": "begin\n  x_tTool.trsf.z = 10\nend\n"}})
    assert errors(r) == [160]
