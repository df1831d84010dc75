"""The runtime errors of the instructions of 10.6 (docs/motion.md, "Runtime errors of 10.6"), one
test per row of the table: what is known when the command is recorded stops the task at the
instruction with the code of 12.1; what is only found while the path is interpolated is error
150 at the next motion instruction. Also the manual's examples of isEmpty and stopMove."""

from __future__ import annotations

import numpy as np
import pytest

from interpretation.simsupport import code_pos, codes, gv, out, sim
from val3check.robot import load_robot

TX = load_robot("TX2-60")
TS = load_robot("TS2-60")
HOME = "{0, 20, 100, 0, 60, 0}"  # tool pointing down in front of the arm
J1_MAX = TX.joint_limits[0][1]


def run(tmp_path, code, globals_=(), robot=TX, **kw):
    return sim(tmp_path, code, globals_=globals_, robot=robot, **kw)


def motions(r):
    return [m for m in r.motion.motions if m.id is not None]


def the_error(r):
    """The one diagnostic of the run: the error that stopped the task."""
    (d,) = r.diagnostics
    return d


# ---- at the instruction ----------------------------------------------------------------------------------


def test_movej_beyond_j1s_limit_stops_at_the_movej_and_taskstatus_reads_154(tmp_path):
    """The issue's case: a movej 20 degrees beyond j1's limit. 10.6: "une erreur d'exécution est
    générée ... si jPosition se situe en dehors des butées logicielles": the task stops at the
    movej (not at the next motion instruction, not with 150), taskStatus reads 154."""
    r = run(tmp_path, """begin
  taskCreate "robot", 10, moves()
  wait(taskStatus("robot") != 1)
  nStatus = taskStatus("robot")
end
""", ["num nStatus", "mdesc mD"], programs={"moves": {"code": f"""begin
  mD.blend = off
  movej({HOME}, flange, mD)
  movej({{{J1_MAX + 20:g}, 20, 100, 0, 60, 0}}, flange, mD)
  putln("not reached")
  movej({HOME}, flange, mD)
end
"""}})
    assert gv(r, "nStatus") == 154 and out(r) == []
    d = the_error(r)
    assert (d.code, d.error, d.task) == ("R011", 154, "robot")
    assert (d.line, d.col) == code_pos(r, 4, 3, "moves")
    assert "j1" in d.message and "20.000" in d.message and "error 154" in d.message
    # the move before it was recorded and executed; nothing of the failing one was recorded
    (home,) = motions(r)
    assert home.state == "done" and home.id == 0
    assert list(r.motion.trajectory.position(r.motion.end_s)) == pytest.approx([0, 20, 100, 0, 60, 0], abs=1e-9)


def test_movej_to_a_point_out_of_reach_is_154_at_the_movej(tmp_path):
    r = run(tmp_path, """begin
  pFar.trsf = {2000, 0, 300, 0, 180, 0}
  pFar.config = {sfree, efree, wfree}
  movej(pFar, flange, mD)
  putln("not reached")
end
""", ["point pFar", "mdesc mD"])
    d = the_error(r)
    assert (d.code, d.error) == ("R010", 154) and d.line == code_pos(r, 4, 3)[0] and out(r) == []
    assert r.motion is None or motions(r) == []


@pytest.mark.parametrize("instruction", ["movel(pA, flange, mD)", "movec(pA, pA, flange, mD)"])
def test_an_invalid_mdesc_is_its_error_at_every_motion_instruction(tmp_path, instruction):
    r = run(tmp_path, f"""begin
  movej({HOME}, flange, mOk)
  waitEndMove()
  pA = here(flange, world)
  mD.tvel = 0
  {instruction}
end
""", ["point pA", "mdesc mD", "mdesc mOk"])
    d = the_error(r)
    assert (d.code, d.error) == ("R017", 103) and d.line == code_pos(r, 6, 3)[0]


def test_movel_to_a_point_out_of_reach_is_154_at_the_movel(tmp_path):
    r = run(tmp_path, f"""begin
  movej({HOME}, flange, mD)
  waitEndMove()
  pFar = compose(here(flange, world), world, {{1500, 0, 0, 0, 0, 0}})
  nId = movel(pFar, flange, mD)
  putln("not reached")
end
""", ["point pFar", "mdesc mD", "num nId"])
    d = the_error(r)
    assert (d.code, d.error) == ("R010", 154) and d.line == code_pos(r, 5, 3)[0] and "pFar" in d.message
    assert gv(r, "nId") == 0 and len(motions(r)) == 1  # no identifier returned, nothing recorded


def test_movel_imposing_another_configuration_is_154_at_the_movel(tmp_path):
    """10.6 movel: "si un mouvement en ligne droite vers pPosition n'est pas possible" (10.1.4.2:
    "on ne peut pas imposer un changement de configuration dans un mouvement en ligne droite")."""
    r = run(tmp_path, f"""begin
  movej({HOME}, flange, mD)
  waitEndMove()
  pA = compose(here(flange, world), world, {{0, 50, 0, 0, 0, 0}})
  pA.config = {{righty, esame, wsame}}
  movel(pA, flange, mD)
  putln("not reached")
end
""", ["point pA", "mdesc mD"])
    d = the_error(r)
    assert (d.code, d.error) == ("R012", 154) and d.line == code_pos(r, 6, 3)[0] and "righty" in d.message


def test_movel_to_a_target_only_reachable_in_another_configuration_is_154(tmp_path):
    """Started wrist-negative, the target's wrist-negative solution has j5 = -125, below j5's
    limit (-121): only the wrist-positive one is in range, and a line cannot change the wrist."""
    r = run(tmp_path, """begin
  movej({0, 20, 100, 180, -60, 180}, flange, mD)
  waitEndMove()
  pA = jointToPoint(flange, world, {0, 20, 100, 0, 125, 0})
  pA.config = {sfree, efree, wfree}
  movel(pA, flange, mD)
end
""", ["point pA", "mdesc mD"])
    d = the_error(r)
    assert d.error == 154 and d.code in ("R011", "R012") and d.line == code_pos(r, 6, 3)[0]


def _circle_code(via: str, target: str) -> str:
    return f"""begin
  movej({HOME}, flange, mD)
  waitEndMove()
  pA = here(flange, world)
  pVia = compose(pA, world, {{{via}}})
  pB = compose(pA, world, {{{target}}})
  movec(pVia, pB, flange, mD)
  waitEndMove()
end
"""


@pytest.mark.parametrize("via,target,rule,what", [
    ("1500, 60, 0, 0, 0, 0", "0, 120, 0, 0, 0, 0", "R010", "intermediate point pVia"),  # via out of reach
    ("60, 60, 0, 0, 0, 0", "0, 1500, 0, 0, 0, 0", "R010", "target pB"),  # target out of reach
    ("0, 60, 0, 0, 0, 0", "0, 120, 0, 0, 0, 0", "R015", "align"),  # three aligned positions: no circle
])
def test_movec_that_cannot_pass_or_end_is_154_at_the_movec(tmp_path, via, target, rule, what):
    """10.6 movec: "si point pIntermédiaire (ou point pCible) ne peut pas être atteint, si le
    mouvement circulaire n'est pas possible"."""
    r = run(tmp_path, _circle_code(via, target), ["point pA", "point pVia", "point pB", "mdesc mD"])
    d = the_error(r)
    assert (d.code, d.error) == (rule, 154) and d.line == code_pos(r, 7, 3)[0] and what in d.message
    assert len(motions(r)) == 1


def test_the_same_circle_through_points_in_reach_runs(tmp_path):
    r = run(tmp_path, _circle_code("60, 60, 0, 0, 0, 0", "0, 120, 0, 0, 0, 0"),
            ["point pA", "point pVia", "point pB", "mdesc mD"])
    assert codes(r) == [] and [m.kind for m in motions(r)] == ["movej", "movec"]


def test_a_joint_of_the_other_arm_family_is_81_at_the_instruction(tmp_path):
    r = run(tmp_path, "begin\n  movej({0, 0, 0, 0, 0, 0}, flange, mD)\nend\n", ["mdesc mD"], robot=TS)
    d = the_error(r)
    assert (d.code, d.error) == ("R001", 81) and d.line == code_pos(r, 2, 3)[0]


@pytest.mark.parametrize("start,code", [("{0, 0, 0, 0, 0, 0}", 81), ("{0, 0, 500, 0}", 70)])
def test_resetmotion_with_a_start_the_arm_cannot_take(tmp_path, start, code):
    r = run(tmp_path, f"begin\n  resetMotion({start})\n  putln(\"no\")\nend\n", robot=TS)
    d = the_error(r)
    assert (d.code, d.error) == ("R001", code) and d.line == code_pos(r, 2, 3)[0] and out(r) == []


def test_getjointforce_into_a_too_small_array_is_70_whatever_the_model_knows(tmp_path):
    """10.6: "une erreur d'exécution est générée si le paramètre n'est pas un tableau de valeurs
    numériques d'une taille suffisante": 70 before the model's missing masses (R002)."""
    r = run(tmp_path, "begin\n  getJointForce(nF)\nend\n", ["num nF[3]"])
    d = the_error(r)
    assert (d.code, d.error) == ("R001", 70) and "3 values for 6 axes" in d.message
    r = run(tmp_path / "six", "begin\n  getJointForce(nF)\nend\n", ["num nF[6]"])
    assert codes(r) == ["R002"]


# ---- later: a path the arm cannot follow, 150 at the next motion instruction ------------------------------

J1_LINE = """begin
  mD.blend = off
  movej({170, 20, 100, 0, 60, 0}, flange, mD)
  waitEndMove()
  pB = jointToPoint(flange, world, {-170, 20, 100, 0, 60, 0})
  nId = movel(pB, flange, mD)
  putln("recorded")
  NEXT
  putln("not reached")
end
"""
J1_GLOBALS = ["point pB", "mdesc mD", "num nId", "tool tGrip"]


@pytest.mark.parametrize("following", ["waitEndMove()", f"movej({HOME}, flange, mD)", "movel(pB, flange, mD)",
                                       "movec(pB, pB, flange, mD)", "open(tGrip)", "close(tGrip)"])
def test_a_path_through_a_joint_limit_is_recorded_and_150_stops_the_next_motion_instruction(tmp_path, following):
    """A line behind the arm from j1 = 170 to j1 = -170 (both ends in range): j1 would have to pass
    180 on the way. Found while the path is interpolated: the movel returns its identifier, and
    the next motion instruction, waitEndMove, open or close stops with 150 (10.6: "si une commande
    de mouvement précédemment enregistrée ne peut pas être exécutée")."""
    r = run(tmp_path, J1_LINE.replace("NEXT", following), J1_GLOBALS)
    assert out(r) == ["recorded"] and gv(r, "nId") == 1
    limit, stop = r.diagnostics
    assert (limit.code, limit.error, limit.line) == ("R011", 150, code_pos(r, 6, 3)[0]) and "j1" in limit.message
    assert (stop.code, stop.error, stop.line) == ("R001", 150, code_pos(r, 8, 3)[0])
    assert motions(r)[1].state == "failed" and motions(r)[1].start is None


def test_the_other_instructions_of_10_6_raise_no_150_and_resetmotion_clears_it(tmp_path):
    """stopMove, restartMove, isEmpty, isSettled, autoConnectMove, getSpeed, getPositionErr,
    getMoveId, setMoveId: 10.6 names no error; a pending 150 does not stop them. resetMotion()
    clears it: the next movej records (identifier 0, 10.6 resetMotion) and runs."""
    r = run(tmp_path, J1_LINE.replace("NEXT", """delay(0.1)
  bEmpty = isEmpty()
  bSettled = isSettled()
  nMove = getMoveId()
  stopMove()
  restartMove()
  nSpeed = getSpeed(flange)
  jErr = getPositionErr()
  autoConnectMove(true)
  bAuto = autoConnectMove()
  setMoveId(5)
  resetMotion()
  nId = movej({170, 20, 90, 0, 60, 0}, flange, mD)
  waitEndMove()
  putln("done")""").replace('  putln("not reached")\n', ""),
        J1_GLOBALS + ["bool bEmpty", "bool bSettled", "num nMove", "num nSpeed", "joint jErr", "bool bAuto"])
    assert out(r) == ["recorded", "done"] and codes(r) == ["R011"]
    assert gv(r, "bEmpty") is True and gv(r, "bSettled") is True and gv(r, "nMove") == 1
    assert gv(r, "nSpeed") == 0 and gv(r, "bAuto") is True and gv(r, "nId") == 0
    assert list(r.motion.trajectory.position(r.motion.end_s)) == pytest.approx([170, 20, 90, 0, 60, 0], abs=1e-9)


# ---- the manual's examples --------------------------------------------------------------------------------


def test_isempty_example_of_10_6_cancels_the_recorded_motions(tmp_path):
    """10.6 isEmpty: "Ce programme annule les mouvements enregistrés, s'il y en a"."""
    r = run(tmp_path, f"""begin
  movej({HOME}, flange, mD)
  movej({{90, 20, 100, 0, 60, 0}}, flange, mD)
  delay(0.2)
  // S'il y a des commandes en cours
  if isEmpty() == false
    // arrêter le robot et annuler les commandes
    resetMotion()
    putln("Mouvements annulés")
  endif
  nId = getMoveId()
  waitEndMove()
  jAt = herej()
end
""", ["mdesc mD", "num nId", "joint jAt"])
    assert out(r) == ["Mouvements annulés"] and codes(r) == []
    first, second = motions(r)
    assert first.state == "cancelled" and second.state == "cancelled" and second.start is None
    assert gv(r, "nId") == 0
    # the arm stopped on its path (before HOME, with j1 still 0) and stays there
    j = list(gv(r, "jAt").values())
    assert j[0] == pytest.approx(0.0, abs=1e-9) and 0.0 < j[2] < 100.0


def test_stopmove_example_of_10_6_holds_the_arm_while_the_signal_is_on(tmp_path):
    """10.6 stopMove: "arrêt des mouvements sur la trajectoire" while diSignal is true, "reprise des
    mouvements sur la trajectoire" when it falls: the same path, later by the hold."""
    code = """begin
  mD.blend = off
  movej({90, 0, 0, 0, 0, 0}, flange, mD)
  // attente d'un signal
  wait(diSignal==true)
  // arrêt des mouvements sur la trajectoire
  stopMove()
  wait(diSignal==false)
  // reprise des mouvements sur la trajectoire
  restartMove()
  waitEndMove()
end
"""
    scenario = "[inputs]\ndiSignal = false\n[[events]]\nat = 0.2\nset = { diSignal = true }\n" \
               "[[events]]\nat = 1.0\nset = { diSignal = false }\n"
    r = run(tmp_path, code, ["mdesc mD", "dio diSignal"], scenario=scenario, links={"diSignal": "BasicIO-1\\%I0"})
    assert codes(r) == []
    (m,) = motions(r)
    v, a = TX.nominal_speeds[0], TX.accelerations[0]
    alone = 90 / v + v / a if 90 >= v * v / a else 2 * (90 / a) ** 0.5
    assert m.state == "done" and m.duration > alone + 0.5  # held from about 0.2 s to 1.0 s
    traj = r.motion.trajectory
    # stopped on the path (j2..j6 never move) and at rest while the signal is on
    assert np.allclose(traj.velocity(0.9), 0.0) and 0.0 < traj.position(0.9)[0] < 90.0
    assert np.allclose(traj.position(0.9)[1:], 0.0) and traj.position(r.motion.end_s)[0] == pytest.approx(90.0)
