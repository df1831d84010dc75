"""11.1 compliant moves: movejf/movelf follow their path as standard moves when the net force
drives them, hold when it does not, go back to their start (and no further) when it pulls them
back, and stop on a surface of the scenario; isCompliant while they run; the limitations of 11.1.4
with the manual's errors. The manual's isCompliant example, with the press's ejector as a push."""

from __future__ import annotations

import numpy as np
import pytest
from interpretation.simsupport import codes, errors, gv, sim

from val3check.robot import load_robot

TX = load_robot("TX2-60")
LICENCE = "version = 1\n[options]\ncompliance = true\n"
SETUP = """  mD.blend = off
  movej({0, 20, 100, 0, 60, 0}, flange, mD)
  waitEndMove()
  pA = here(flange, world)
  pB = appro(pA, {0, 0, 100, 0, 0, 0})
"""
G = ["mdesc mD", "point pA", "point pB", "point pEnd", "bool bDuring", "bool bAfter", "num nId", "bool bEmpty",
     "joint jEnd", "joint jStart", "dio doEjection", "point pMid"]


def run(tmp_path, body, scenario=LICENCE, **kw):
    return sim(tmp_path, "begin\n" + SETUP + body + "end\n", globals_=G, robot=TX,
               links={"doEjection": "BasicIO-1\\%Q0"}, scenario=scenario, **kw)


def motions(r):
    return [m for m in r.motion.motions if m.id is not None]


@pytest.mark.parametrize("kind", ["movel", "movej"])
def test_a_positive_force_without_the_cell_is_the_standard_move(tmp_path, kind):
    target = "pB" if kind == "movel" else "{30, 0, 90, 10, 40, 20}"
    std = run(tmp_path / "std", f"  {kind}({target}, flange, mD)\n  waitEndMove()\n")
    comp = run(tmp_path / "comp", f"""  nId = {kind}f({target}, flange, mD, 30)
  delay(0.05)
  bDuring = isCompliant()
  waitEndMove()
  bAfter = isCompliant()
  jEnd = herej()
""")
    assert codes(comp) == ["R052"]  # the memory limit of 11.1.4 is not simulated
    a, b = motions(std)[-1], motions(comp)[-1]
    assert b.duration == pytest.approx(a.duration, rel=1e-12)
    assert b.start == pytest.approx(a.start, abs=1e-12)
    assert gv(comp, "bDuring") is True and gv(comp, "bAfter") is False
    assert gv(comp, "nId") == 1


def test_the_manual_example_the_ejector_pushes_the_passive_arm(tmp_path):
    """11.1.5 isCompliant: movelf(..., 0); wait(isCompliant()); diEjection = true; waitForEndMove()
    (the manual's spelling of waitEndMove) with the press's ejector: a push of 40 % towards the
    target 0.1 s after the output is set."""
    body = """  nId = movelf(pB, flange, mD, 0)
  wait(isCompliant())
  doEjection = true
  waitEndMove()
  bAfter = isCompliant()
  pEnd = here(flange, world)
  movej({0, 20, 100, 0, 60, 0}, flange, mD)
  waitEndMove()
"""
    r = run(tmp_path, body, scenario=LICENCE + '[[pushes]]\nwhen = "doEjection"\nafter = 0.1\nforce = 40\n')
    assert codes(r) == ["R052"]
    std = run(tmp_path / "std", "  movel(pB, flange, mD)\n  waitEndMove()\n")
    (eject,) = [e.time_us / 1e6 for e in r.io_log if e.link.endswith("Q0")]
    line = motions(r)[1]
    assert line.start == pytest.approx(eject + 0.1, abs=1e-9)  # passive until the ejector pushes
    assert line.duration == pytest.approx(motions(std)[1].duration, rel=1e-9)
    assert np.allclose(list(gv(r, "pEnd")["trsf"].values()), list(gv(r, "pB")["trsf"].values()), atol=1e-6)
    assert gv(r, "bAfter") is False
    assert motions(r)[2].state == "done"


def test_a_passive_arm_nothing_pushes_is_a_deadlock_that_says_why(tmp_path):
    r = run(tmp_path, "  nId = movelf(pB, flange, mD, 0)\n  waitEndMove()\n", duration=5)
    assert "R003" in codes(r)
    (d,) = [d for d in r.diagnostics if d.code == "R003"]
    assert "compliant move" in d.message and "[[pushes]]" in d.message
    assert motions(r)[1].end is None


SURFACE = LICENCE + """[[surfaces]]
name = "die"
point = [0, 0, {z}]
normal = [0, 0, 1]
"""


def test_the_tool_meets_a_surface_and_presses_on_it_until_reset_motion(tmp_path):
    body = """  nId = movelf(pB, flange, mD, 25)
  delay(1)
  bDuring = isCompliant()
  bEmpty = isEmpty()
  pEnd = here(flange, world)
  resetMotion()
  bAfter = isCompliant()
  movej({0, 20, 100, 0, 60, 0}, flange, mD)
  waitEndMove()
"""
    z_a = _z_home()
    r = run(tmp_path, body, scenario=SURFACE.format(z=z_a - 40.0))
    assert sorted(codes(r)) == ["R052", "R054"]
    (d,) = [d for d in r.diagnostics if d.code == "R054"]
    assert "'die'" in d.message and "25 %" in d.message
    end = gv(r, "pEnd")["trsf"]
    assert end["z"] == pytest.approx(z_a - 40.0, abs=1e-6)  # on the surface, not at the target 100 mm down
    assert end["x"] == pytest.approx(gv(r, "pA")["trsf"]["x"], abs=1e-6)
    assert gv(r, "bDuring") is True and gv(r, "bEmpty") is False and gv(r, "bAfter") is False
    line = motions(r)[1]
    assert line.state == "cancelled"
    assert motions(r)[2].state == "done"
    # the arm stayed on the surface until the reset: the record shows it there
    assert line.start < d.time_us / 1e6 < 1.2
    q = r.motion.trajectory.position(d.time_us / 1e6 + 0.5)
    assert TX.fk(q)[2] == pytest.approx(z_a - 40.0, abs=1e-6)


def _z_home() -> float:
    return TX.fk((0, 20, 100, 0, 60, 0))[2]


def test_pulled_back_the_arm_returns_to_its_start_and_stops_there(tmp_path):
    """nForce -20: a push of 50 % for 0.12 s drives it forward (net +30), then the arm goes back
    along its path (net -20) and stops on its start point (11.1.4)."""
    body = """  jStart = herej()
  nId = movelf(pB, flange, mD, -20)
  delay(2)
  jEnd = herej()
  bDuring = isCompliant()
"""
    r = run(tmp_path, body, scenario=LICENCE + "[[pushes]]\nat = 1.0\nuntil = 1.12\nforce = 50\n")
    assert codes(r) == ["R052"]
    assert list(gv(r, "jEnd").values()) == pytest.approx(list(gv(r, "jStart").values()), abs=1e-9)
    assert gv(r, "bDuring") is True
    traj = r.motion.trajectory
    start = np.array(list(gv(r, "jStart").values()))
    z0 = TX.fk(start)[2]
    std = run(tmp_path / "std", "  movel(pB, flange, mD)\n  waitEndMove()\n")
    m = motions(std)[1]
    # the furthest point: where the standard movel is 0.12 s after its start, reached at 1.12 s
    z_far = TX.fk(std.motion.trajectory.position(m.start + 0.12))[2]
    assert TX.fk(traj.position(1.12))[2] == pytest.approx(z_far, abs=1e-6)
    assert TX.fk(traj.position(1.18))[2] == pytest.approx(TX.fk(std.motion.trajectory.position(m.start + 0.06))[2],
                                                          abs=1e-6)  # going back on the same path
    assert TX.fk(traj.position(1.3))[2] == pytest.approx(z0, abs=1e-9)


def test_stop_move_makes_the_arm_not_compliant_until_restart_move(tmp_path):
    r = run(tmp_path, """  nId = movelf(pB, flange, mD, 30)
  delay(0.02)
  stopMove()
  bDuring = isCompliant()
  restartMove()
  bAfter = isCompliant()
  waitEndMove()
""")
    assert gv(r, "bDuring") is False and gv(r, "bAfter") is True


@pytest.mark.parametrize("body,code", [
    ("  nId = movelf(pB, flange, mD, 1000.5)\n", 70),
    ("  nId = movelf(pB, flange, mD, -2000)\n", 70),
    ("  mD.blend = joint\n  movej({0, 20, 90, 0, 60, 0}, flange, mD)\n  nId = movelf(pB, flange, mD, 10)\n", 154),
])
def test_the_limitations_of_11_1_4_are_the_manuals_errors(tmp_path, body, code):
    r = run(tmp_path, body)
    (d,) = [d for d in r.diagnostics if d.code == "R053"]
    assert d.error == code
    assert [t.error for t in r.tasks if t.error] == [code]


def test_after_wait_end_move_a_blended_move_may_precede_a_compliant_one(tmp_path):
    r = run(tmp_path, "  mD.blend = joint\n  movej({0, 20, 90, 0, 60, 0}, flange, mD)\n  waitEndMove()\n"
                      "  nId = movelf(pB, flange, mD, 10)\n  waitEndMove()\n")
    assert errors(r) == []


def test_without_the_licence_error_250(tmp_path):
    r = run(tmp_path, "  nId = movelf(pB, flange, mD, 10)\n", scenario="version = 1\n[options]\ncompliance = false\n")
    assert errors(r) == [250]


@pytest.mark.parametrize("text,line", [
    ("[[surfaces]]\npoint = [0, 0]\nnormal = [0, 0, 1]\n", 3),
    ("[[surfaces]]\npoint = [0, 0, 0]\nnormal = [0, 0, 0]\n", 4),
    ("[[surfaces]]\nnormal = [0, 0, 1]\n", 2),
    ("[[pushes]]\nforce = \"hard\"\n", 3),
    ("[[pushes]]\nforce = 10\nat = 2\nuntil = 1\n", 5),  # the key at fault
    ("[[pushes]]\nforce = 10\nwhen = \"diNope\"\n", 4),
    ("[[pushes]]\nforce = 10\nwhen = \"doEjection\"\nat = 1\n", 2),
    ("[[pushes]]\nforce = 10\nspeed = 3\n", 4),
])
def test_bad_surfaces_and_pushes_are_scenario_errors_with_their_line(tmp_path, text, line):
    from val3check.simulation.scenario import ScenarioError

    with pytest.raises(ScenarioError) as exc:
        run(tmp_path, "", scenario="version = 1\n" + text)
    assert exc.value.line == line


def test_reset_motion_while_a_compliant_move_holds_mid_path_leaves_the_arm_there(tmp_path):
    """A passive move pushed for 0.1 s stops mid-path (the push ends); resetMotion() cancels it:
    the arm stays where it stopped (no braking along the path: it was at rest), and the next move
    goes from there to its target."""
    r = run(tmp_path, """  nId = movelf(pB, flange, mD, 0)
  delay(1)
  pMid = here(flange, world)
  resetMotion()
  delay(0.5)
  pEnd = here(flange, world)
  movej({0, 20, 100, 0, 60, 0}, flange, mD)
  waitEndMove()
  jEnd = herej()
""", scenario=LICENCE + "[[pushes]]\nat = 0.6\nuntil = 0.7\nforce = 50\n")
    mid = gv(r, "pMid")["trsf"]
    a = gv(r, "pA")["trsf"]
    assert mid["z"] < a["z"] - 1.0  # it moved down part of the way
    assert gv(r, "pEnd")["trsf"] == pytest.approx(mid, abs=1e-9)
    assert list(gv(r, "jEnd").values()) == pytest.approx([0, 20, 100, 0, 60, 0], abs=1e-9)
    # the record: the arm at pMid until the next move starts, then on its way to the target
    nxt = motions(r)[-1]
    z = [TX.fk(r.motion.trajectory.position(t))[2] for t in (1.05, 1.4, nxt.start)]
    assert z == pytest.approx([mid["z"]] * 3, abs=1e-9)
