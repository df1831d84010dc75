"""11.4 the absolute robot: getDefaultDH gives the TX2-60's parameters in the manual's form,
setDH changes the geometry for the rest of the run, and the kinematics follow: forward (here,
jointToPoint) against the product of 11.4.1 computed here by hand, inverse and motion (a movel
stays a straight line of the new geometry), the links of the collision model."""

from __future__ import annotations

import math

import numpy as np
import pytest
from interpretation.simsupport import codes, errors, gv, out, sim

from val3check.robot import load_robot

TX = load_robot("TX2-60")
# TX2-60 in the form of 11.4.1 (classic DH: frame i's x on the common normal of axes i and i+1;
# the arm's lengths: 290 mm arm, 310 mm forearm, 20 mm offset, 70 mm flange)
THETA = [0, -90, 90, 0, 0, 0]
D = [0, 0, 20, 310, 0, 70, 0]
A = [0, 290, 0, 0, 0, 0]
ALPHA = [-90, 0, 90, -90, 90, 0]
BETA = [0, 0, 0, 0, 0, 0]
ARRAYS = ["num nTheta[6]", "num nD[7]", "num nA[6]", "num nB[6]", "num nAlpha[6]", "num nBeta[6]"]


def trsf(x, y, z, rx, ry, rz):
    """9.3.2: translation, then Rx(rx)·Ry(ry)·Rz(rz)."""
    def rot(axis, deg):
        c, s = math.cos(math.radians(deg)), math.sin(math.radians(deg))
        m = np.eye(4)
        i, j = [(1, 2), (2, 0), (0, 1)][axis]
        m[i, i], m[i, j], m[j, i], m[j, j] = c, -s, s, c
        return m
    t = np.eye(4)
    t[:3, 3] = (x, y, z)
    return t @ rot(0, rx) @ rot(1, ry) @ rot(2, rz)


def hand_fk(j, theta, d, a, b, alpha, beta, upto=5):
    """The product of 11.4.1, written from the manual (`upto` < 5: the frame of joint upto + 2)."""
    m = trsf(0, 0, 0, 0, 0, j[0] + theta[0])
    for i in range(5):
        m = m @ trsf(a[i], b[i], d[i], alpha[i], beta[i], j[i + 1] + theta[i + 1])
        if i == upto:
            return m
    m = m @ trsf(a[5], b[5], d[5], alpha[5], beta[5], 0)
    return m @ trsf(0, 0, d[6], 0, 0, 0)


def as_matrix(p):
    return trsf(p["x"], p["y"], p["z"], p["rx"], p["ry"], p["rz"])


def test_get_default_dh_is_the_tx2_60_in_the_manual_form_and_its_product_is_the_arm(tmp_path):
    r = sim(tmp_path, """begin
  getDefaultDH(nTheta, nD, nA, nAlpha, nBeta)
  getDH(nTheta2, nD2, nA2, nAlpha2, nBeta2)
end
""", globals_=ARRAYS + ["num nTheta2[6]", "num nD2[6]", "num nA2[6]", "num nAlpha2[6]", "num nBeta2[6]"], robot=TX)
    assert codes(r) == []
    assert gv(r, "nTheta") == THETA and gv(r, "nD") == D and gv(r, "nA") == A
    assert gv(r, "nAlpha") == ALPHA and gv(r, "nBeta") == BETA
    assert gv(r, "nTheta2") == THETA and gv(r, "nD2") == D[:6]  # d[] of 6: no flange entry
    rng = np.random.default_rng(7)
    for _ in range(20):
        j = rng.uniform(-120, 120, 6)
        model = np.eye(4)
        model[:3, :4] = np.array(TX.fk_matrix(j))
        assert np.abs(hand_fk(j, THETA, D, A, [0] * 6, ALPHA, BETA) - model).max() < 1e-9


SET = """begin
  getDefaultDH(nTheta, nD, nA, nAlpha, nBeta)
  nD[0] = nD[0] + 2.5
  nA[1] = nA[1] + 0.8
  nB[2] = -0.4
  nTheta[1] = nTheta[1] + 0.3
  nAlpha[3] = nAlpha[3] + 0.2
  nBeta[1] = 0.1
  nD[6] = 1.5
  bOk = setDH(nTheta, nD, nA, nB, nAlpha, nBeta)
  getDH(nTheta2, nD2, nA2, nAlpha2, nBeta2)
  pJ = jointToPoint(flange, world, {10, -20, 80, 30, 40, 50})
  movej({10, -20, 80, 30, 40, 50}, flange, mD)
  waitEndMove()
  pHere = here(flange, world)
  bRev = pointToJoint(flange, herej(), pJ, jBack)
  pB = appro(pHere, {0, 150, -60, 0, 0, 0})
  movel(pB, flange, mD)
  waitEndMove()
  pEnd = here(flange, world)
end
"""
SET_GLOBALS = ARRAYS + ["num nTheta2[6]", "num nD2[7]", "num nA2[6]", "num nAlpha2[6]", "num nBeta2[6]", "bool bOk",
                        "point pJ", "point pHere", "point pB", "point pEnd", "joint jBack", "bool bRev", "mdesc mD"]
NEW = {"theta": [0, -89.7, 90, 0, 0, 0], "d": [2.5, 0, 20, 310, 0, 70, 1.5], "a": [0, 290.8, 0, 0, 0, 0],
       "b": [0, 0, -0.4, 0, 0, 0], "alpha": [-90, 0, 90, -89.8, 90, 0], "beta": [0, 0.1, 0, 0, 0, 0]}


def test_after_set_dh_the_kinematics_are_the_new_geometry(tmp_path):
    r = sim(tmp_path, SET, globals_=SET_GLOBALS, robot=TX, collisions=True)
    assert sorted(codes(r)) == ["R050", "R052"]  # the absoluteRobot licence assumed; the file not written
    assert gv(r, "bOk") is True
    assert gv(r, "nTheta2") == pytest.approx(NEW["theta"]) and gv(r, "nD2") == pytest.approx(NEW["d"])
    j = [10, -20, 80, 30, 40, 50]
    expected = hand_fk(j, **NEW)
    nominal = hand_fk(j, THETA, D, A, [0] * 6, ALPHA, BETA)
    assert np.abs(expected[:3, 3] - nominal[:3, 3]).max() > 1.0  # the change is visible
    for name in ("pJ", "pHere"):
        assert np.abs(as_matrix(gv(r, name)["trsf"]) - expected).max() < 1e-9
    # the inverse of the new geometry gives the joints back
    assert gv(r, "bRev") is True
    assert list(gv(r, "jBack").values()) == pytest.approx(j, abs=1e-7)
    # movel: the flange on the straight line of the new geometry, to its target
    end = as_matrix(gv(r, "pEnd")["trsf"])
    target = as_matrix(gv(r, "pB")["trsf"])
    assert np.abs(end - target).max() < 1e-6
    m = next(m for m in r.motion.motions if m.kind == "movel")
    times = np.linspace(m.start, m.end, 60)
    p0, p1 = expected[:3, 3], target[:3, 3]
    u = (p1 - p0) / np.linalg.norm(p1 - p0)
    for q in r.motion.trajectory.positions(times):
        p = hand_fk(q, **NEW)[:3, 3]
        off = (p - p0) - np.dot(p - p0, u) * u
        assert np.linalg.norm(off) < 1e-3
    # the run's arm (the reports, the collision model) is the new geometry
    poses = r.motion.scene.kinematics.link_poses(np.array(j, dtype=float))
    assert np.abs(poses[TX.flange_frame] - expected).max() < 1e-9
    assert r.collision is not None


def test_set_dh_refuses_a_geometry_too_different_or_arrays_that_do_not_fit(tmp_path):
    r = sim(tmp_path, """begin
  getDefaultDH(nTheta, nD, nA, nAlpha, nBeta)
  nA[1] = nA[1] + 100
  bFar = setDH(nTheta, nD, nA, nB, nAlpha, nBeta)
  bShort = setDH(nTheta, nD, nA, nShort, nAlpha, nBeta)
  getDH(nTheta, nD, nA, nAlpha, nBeta)
end
""", globals_=ARRAYS + ["num nShort[5]", "bool bFar", "bool bShort"], robot=TX,
            scenario="version = 1\n[options]\nabsoluteRobot = true\n")
    assert codes(r) == []
    assert gv(r, "bFar") is False and gv(r, "bShort") is False
    assert gv(r, "nA") == A  # unchanged
    logged = [t for _, _, kind, t, _ in r.transcript if kind == "logMsg"]
    assert len(logged) == 2 and "setDH refused" in logged[0] and "b[]" in logged[1]


def test_set_dh_without_its_licence_is_error_250_and_a_scara_has_no_dh_form(tmp_path):
    r = sim(tmp_path, """begin
  getDefaultDH(nTheta, nD, nA, nAlpha, nBeta)
  bOk = setDH(nTheta, nD, nA, nB, nAlpha, nBeta)
end
""", globals_=ARRAYS + ["bool bOk"], robot=TX, scenario="version = 1\n[options]\nabsoluteRobot = false\n")
    assert errors(r) == [250]
    r = sim(tmp_path / "s", "begin\n  getDefaultDH(nTheta, nD, nA, nAlpha, nBeta)\nend\n", globals_=ARRAYS,
            robot=load_robot("TS2-60"))
    assert codes(r) == ["R002"]


def test_set_dh_waits_for_the_motion_to_be_empty(tmp_path):
    r = sim(tmp_path, """begin
  mD.blend = off
  movej({30, 0, 90, 0, 0, 0}, flange, mD)
  getDefaultDH(nTheta, nD, nA, nAlpha, nBeta)
  bOk = setDH(nTheta, nD, nA, nB, nAlpha, nBeta)
  nAt = clock()
end
""", globals_=ARRAYS + ["bool bOk", "num nAt", "mdesc mD"], robot=TX,
            scenario="version = 1\n[options]\nabsoluteRobot = true\n")
    (m,) = r.motion.motions
    assert gv(r, "bOk") is True
    assert m.end - 1e-3 <= gv(r, "nAt") <= m.end + 0.005
    assert out(r) == []


def _cell() -> str:
    """A small sphere 60 mm in front of the flange, on its z axis, at the end of the motion; the
    margin beyond it, so that the clearance is measured exactly wherever it is below (a minimum of
    50 mm is otherwise reported within 5 %: docs/cell.md)."""
    F = np.array(TX.fk_matrix((0, 40, 80, 0, 60, 0)))
    x, y, z = F[:, 3] + 60 * F[:, 2]
    return f"""version = 1
margin_mm = 60
[[obstacle]]
name = "pin"
shape = "sphere"
radius = 10
at = {{ x = {x}, y = {y}, z = {z} }}
"""


DOWN = """begin
  mD.blend = off
  getDefaultDH(nTheta, nD, nA, nAlpha, nBeta)
  nD[3] = nD[3] + nDelta
  bOk = setDH(nTheta, nD, nA, nB, nAlpha, nBeta)
  movej({0, 40, 80, 0, 60, 0}, flange, mD)
  waitEndMove()
end
"""


def test_the_collision_checks_see_the_new_geometry(tmp_path):
    """The forearm 4 mm longer (d[3]): the wrist, nearest a pin in front of the flange, moves by the
    forearm's direction times 4 mm, and its clearance by that displacement along the contact
    normal."""
    reports = []
    for k, delta in enumerate((0.0, 4.0)):
        (tmp_path / str(k)).mkdir()
        cell = tmp_path / str(k) / "cell.toml"
        cell.write_text(_cell(), encoding="utf-8")
        r = sim(tmp_path / str(k), DOWN, globals_=ARRAYS + ["bool bOk", "mdesc mD", "num nDelta"], robot=TX,
                values={"nDelta": str(delta)}, cell=str(cell), collisions=True,
                scenario="version = 1\n[options]\nabsoluteRobot = true\n")
        assert gv(r, "bOk") is True
        (report,) = r.collision.by_motion.values()
        reports.append(report.min_clearance)
    near = reports[0]
    assert near.body_a.startswith("link_5") and reports[1].body_a == near.body_a
    j = [0, 40, 80, 0, 60, 0]
    d4 = list(D)
    d4[3] += 4.0
    shift = hand_fk(j, THETA, d4, A, [0] * 6, ALPHA, BETA, upto=3)[:3, 3] - \
        hand_fk(j, THETA, D, A, [0] * 6, ALPHA, BETA, upto=3)[:3, 3]
    assert np.linalg.norm(shift) == pytest.approx(4.0)
    normal = np.subtract(near.point_a, near.point_b) / near.mm
    assert reports[1].mm - near.mm == pytest.approx(float(np.dot(shift, normal)), abs=0.02)
    assert abs(reports[1].mm - near.mm) > 1.0
