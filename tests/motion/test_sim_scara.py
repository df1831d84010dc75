"""SCARA (RS/TS) arms in `val3check sim`: jointRs/pointRs values, joint 3 in the application's
length unit, error 81 for the other arm family, chapter 10 motion with a prismatic axis, and
the controller trees of real cells choosing their arm (issue 13)."""

from __future__ import annotations

import math
import shutil
from pathlib import Path

import numpy as np
import pytest
from interpretation.simsupport import build, code_pos, codes, errors, gv, run_folder, sim

from val3check.cli import main
from val3check.motion.kin import ArmKin
from val3check.robot import load_robot

ROOT = Path(__file__).resolve().parents[2]
CONTROLLERS = ROOT / "tests" / "robot" / "controllers"
TS = load_robot("TS2-60")
KIN = ArmKin(TS)
V = np.array(TS.nominal_speeds)
A = np.array(TS.accelerations)


def bang_bang(d: float, v: float, a: float) -> float:
    d = abs(d)
    return d / v + v / a if d >= v * v / a else 2 * math.sqrt(d / a)


def run(tmp_path, code, globals_=(), **kw):
    return sim(tmp_path, code, globals_=globals_, robot=TS, **kw)


def motions(r):
    return [m for m in r.motion.motions if m.id is not None]


def test_joint_values_have_four_axes_and_the_motion_is_timed_with_joint_3_in_mm(tmp_path):
    r = run(tmp_path, """begin
  jA = herej()
  movej({0, 90, 150, 0}, flange, mFast)
  waitEndMove()
  pA = here(flange, world)
  pB = compose(pA, world, {0, 0, -50, 0, 0, 0})
  mSlow.vel = 20
  mSlow.blend = off
  movel(pB, flange, mSlow)
  waitEndMove()
  jB = herej()
  cB = config(jB)
end
""", ["joint jA", "joint jB", "point pA", "point pB", "config cB", "mdesc mFast", "mdesc mSlow"])
    assert codes(r) == []
    assert gv(r, "jA") == {"j1": 0, "j2": 0, "j3": 0, "j4": 0}  # four fields (jointRs, 9.2.1)
    assert set(gv(r, "cB")) == {"shoulder"}  # configRs: the shoulder only (9.7.2)
    j, line = motions(r)
    # j2 90 degrees and j3 150 mm (mm/s, mm/s² for joint 3): the slowest axis's bang-bang time
    assert j.duration == pytest.approx(max(bang_bang(90, V[1], A[1]), bang_bang(150, V[2], A[2])), rel=1e-9)
    # straight down 50 mm: only joint 3 moves, at 20 % of its speed: its bang-bang (the ramps,
    # 9 ms with the SCARA rule's accelerations, exact since issue 23: not set by the path's grid)
    assert line.duration == pytest.approx(bang_bang(50, 0.2 * V[2], A[2]), rel=1e-6)
    assert gv(r, "jB")["j3"] == pytest.approx(100.0, abs=1e-6) and gv(r, "jB")["j2"] == pytest.approx(90, abs=1e-6)


def test_a_straight_line_turns_the_tool_about_z_only(tmp_path):
    r = run(tmp_path, """begin
  movej({20, 70, 80, 0}, flange, mD)
  waitEndMove()
  pA = here(flange, world)
  pB = compose(pA, world, {-120, 80, 30, 0, 0, 0})
  pB = appro(pB, {0, 0, 0, 0, 0, 90})
  mD.tvel = 300
  movel(pB, flange, mD)
  waitEndMove()
end
""", ["point pA", "point pB", "mdesc mD"])
    assert codes(r) == []
    line = motions(r)[1]
    _, Q, _ = r.motion.sample(line.start, line.end)
    T = KIN.fk(Q)
    assert np.allclose(T[:, 2, 2], -1.0, atol=1e-9)  # the tool stays vertical (Z down)
    pa = np.array([gv(r, "pA")["trsf"][k] for k in "xyz"])
    d = np.array([-120.0, 80.0, 30.0])
    off = (T[:, :3, 3] - pa) - np.outer((T[:, :3, 3] - pa) @ d / (d @ d), d)
    assert np.linalg.norm(off, axis=1).max() < 0.01
    assert line.length_mm == pytest.approx(np.linalg.norm(d), abs=1e-3)


def test_near_the_stretched_arm_a_radial_line_slows_down(tmp_path):
    r = run(tmp_path, f"""begin
  pA = jointToPoint(flange, world, {{0, 60, 50, 0}})
  pA.trsf.x = 450
  pA.trsf.y = 0
  pB = pA
  pB.trsf.x = {TS.reach_mm - 0.1}
  movej(pA, flange, mD)
  mD.tvel = 500
  movel(pB, flange, mD)
  waitEndMove()
end
""", ["point pA", "point pB", "mdesc mD"])
    (d,) = [d for d in r.diagnostics if d.code == "R014"]
    assert "arm stretched" in d.message and "axis 2" in d.message and d.line == code_pos(r, 9, 3)[0]


def test_a_line_cannot_change_the_shoulder(tmp_path):
    r = run(tmp_path, """begin
  movej({0, 60, 50, 0}, flange, mD)
  waitEndMove()
  pA = here(flange, world)
  pA.trsf.y = pA.trsf.y + 50
  pA.config = {lefty}
  movel(pA, flange, mD)
  waitEndMove()
end
""", ["point pA", "mdesc mD"])
    (d,) = r.diagnostics  # 10.6 movel: "si un mouvement en ligne droite vers pPosition n'est pas possible"
    assert d.code == "R012" and d.error == 154 and d.line == code_pos(r, 7, 3)[0] and "lefty" in d.message


def test_blending_on_a_scara_is_never_slower(tmp_path):
    code = """begin
  movej({0, 60, 50, 0}, flange, mD)
  waitEndMove()
  mD.blend = BLEND
  mD.leave = 30
  mD.reach = 80
  movej({40, 60, 100, 30}, flange, mD)
  movej({40, 20, 20, -60}, flange, mD)
  mD.blend = off
  movej({-30, 40, 60, 0}, flange, mD)
  waitEndMove()
end
"""
    t = {}
    for blend in ("off", "joint", "Cartesian"):
        r = run(tmp_path / blend, code.replace("BLEND", blend), ["mdesc mD"])
        m = motions(r)[1:]
        t[blend] = m[-1].end - m[0].start
    assert t["joint"] < t["off"] and t["Cartesian"] <= t["off"] * (1 + 1e-9)


def test_a_point_of_a_six_axis_arm_on_a_scara_is_error_81(tmp_path):
    folder = build(tmp_path, "begin\n  movej(pRx, flange, mD)\nend\n", globals_=["point pRx", "mdesc mD"])
    dtx = folder / "Example.dtx"
    dtx.write_text(dtx.read_text(encoding="utf-8").replace('type="point"', 'type="pointRx"'), encoding="utf-8")
    r = run_folder(folder, robot=TS)
    assert errors(r) == [81] and "RX/TX" in r.diagnostics[0].message
    r = run(tmp_path / "j", "begin\n  movej({0, 0, 0, 0, 0, 0}, flange, mD)\nend\n", ["mdesc mD"])
    assert errors(r) == [81]


def test_joint_3_is_in_inches_in_an_inch_application(tmp_path):
    folder = build(tmp_path, """begin
  movej({0, 90, 5, 0}, flange, mD)
  waitEndMove()
  jA = herej()
  bIn = isInRange({0, 0, 7.8, 0})
  bOut = isInRange({0, 0, 7.9, 0})
end
""", globals_=["joint jA", "mdesc mD", "bool bIn", "bool bOut"])
    pjx = folder / "Example.pjx"
    pjx.write_text(pjx.read_text(encoding="utf-8").replace('millimeterUnit="true"', 'millimeterUnit="false"'),
                   encoding="utf-8")
    r = run_folder(folder, robot=TS)
    assert codes(r) == []
    assert gv(r, "jA")["j3"] == pytest.approx(5.0, abs=1e-9)
    (_,) = motions(r)
    assert r.motion.motions[0].joints_end[2] == pytest.approx(127.0, abs=1e-9)  # 5 inches, in mm for the model
    # stroke 200.1 mm = 7.878 inches
    assert gv(r, "bIn") is True and gv(r, "bOut") is False


@pytest.mark.parametrize("tree,app,arm", [("ts2-60-floor", "Pick", "TS2-60"), ("ts60-wall", "Sort", "TS60"),
                                          ("tx200-floor", "Polish", "TX200")])
def test_controller_trees_choose_their_arm_and_run(tmp_path, capsys, tree, app, arm):
    dst = tmp_path / tree
    shutil.copytree(CONTROLLERS / tree, dst)
    code = main(["sim", str(dst / "usr" / "usrapp" / app)])
    text = capsys.readouterr().out
    assert code == 0, text
    assert f"arm model: {arm}" in text and "the application ended" in text


def test_scara_pick_and_place_is_timed_against_its_joint_limits(tmp_path, capsys):
    """The Pick cell of tests/robot/controllers: every 4 ms sample within the joint speed and
    acceleration limits (joint 3 in mm/s and mm/s²), and the first move (blended into the next
    one) no faster than the bang-bang time of its slowest axis allows."""
    dst = tmp_path / "ts2-60-floor"
    shutil.copytree(CONTROLLERS / "ts2-60-floor", dst)
    from val3check.simulation import choose_sim_robot

    app = dst / "usr" / "usrapp" / "Pick"
    r = run_folder(app, robot=choose_sim_robot(None, str(app / "Pick.pjx"))[0])
    assert r.robot["name"] == "TS2-60" and r.end_reason == "ended" and codes(r) == []
    # the arm leaves {0, 0, 0, 0} at t = 0 and passes jHome's neighbourhood no sooner than the
    # bang-bang time of its slowest axis to the leave point allows
    first = motions(r)[0]
    assert first.start == pytest.approx(0.0, abs=1e-4)
    assert first.duration >= bang_bang(90 - 20 * 90 / math.hypot(90, 150), V[1], A[1])
    _, Q, Qd = r.motion.sample(dt=0.001)
    assert Q.shape[1] == 4 and np.all(np.abs(Qd) <= V * (1 + 1e-9))
    assert np.all(np.abs(np.diff(Qd, axis=0)) / 0.001 <= A * 1.01)
    assert np.all(Q[:, 2] >= -0.1 - 1e-9) and np.all(Q[:, 2] <= 200.1 + 1e-9)
    # two pick-and-place cycles, each with two 0.2 s waits
    assert r.motion.cycles["Pick~"].count == 1
    assert 2 * 0.4 < r.sim_time_us / 1e6 < 10.0


def test_an_unreachable_point_written_for_a_six_axis_arm_says_so(tmp_path):
    """Issue 28 item 13: a `point` of the data file whose configuration imposes an elbow and a wrist,
    out of a SCARA's reach: R010 says the configuration is a six-axis arm's (9.7.2)."""
    app = tmp_path / "PickPlace"
    shutil.copytree(ROOT / "fixtures" / "valid" / "PickPlace", app)
    dtx = app / "PickPlace.dtx"
    text = dtx.read_text(encoding="utf-8").replace('type="pointRx"', 'type="point"').replace(
        'type="jointRx"', 'type="joint"')
    dtx.write_text(text.replace('x="0" y="0" z="0" ry="180" shoulder="lefty"', 'x="2000" y="0" z="0" ry="180" '
                                                                              'shoulder="lefty"'), encoding="utf-8")
    pgx = app / "start.pgx"
    pgx.write_text(pgx.read_text(encoding="utf-8").replace("movej(jHome, tGripper, mFast)",
                                                           "movej(pPick, tGripper, mFast)"), encoding="utf-8")
    r = run_folder(app, robot=TS, duration=2.0)
    (d,) = [d for d in r.diagnostics if d.code == "R010"]
    assert "the point pPick is out of the arm's reach; its data gives it a six-axis arm's configuration " \
           "(elbow epositive, wrist wpositive), not a SCARA's" in d.message
