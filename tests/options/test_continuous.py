"""11.5 resetTurn and the continuous axis: the manual's example (a cycle from 0° to 720° on
axis 6, the next one starts again at 0° without turning back), the range the option gives."""

from __future__ import annotations

import pytest
from interpretation.simsupport import codes, errors, gv, sim

from val3check.robot import load_robot

TX = load_robot("TX2-60")
CYCLE = """begin
  mD.blend = off
  movej({0, 0, 90, 0, 45, 0}, flange, mD)
  waitEndMove()
  movej({0, 0, 90, 0, 45, 360}, flange, mD)
  movej({0, 0, 90, 0, 45, 720}, flange, mD)
  waitEndMove()
  nBefore = clock()
  jR = resetTurn(jRef)
  nAfter = clock()
  jH = herej()
  pH = here(flange, world)
  movej({0, 0, 90, 0, 45, 90}, flange, mD)
  waitEndMove()
  jEnd = herej()
end
"""
GLOBALS = ["mdesc mD", "joint jR", "joint jH", "joint jEnd", "joint jRef", "num nBefore", "num nAfter", "point pH"]


@pytest.mark.parametrize("ref,expected", [(0, 0), (350, 360), (-200, -360), (720, 720)])
def test_reset_turn_brings_the_continuous_axis_nearest_the_reference(tmp_path, ref, expected):
    r = sim(tmp_path, CYCLE.replace("jRef", f"{{0, 0, 90, 0, 45, {ref}}}"), globals_=GLOBALS, robot=TX,
            scenario="version = 1\n[options]\ncontinuousAxis = true\n")
    assert codes(r) == ["R052"]  # the calibration data are not written
    assert gv(r, "jR")["j6"] == pytest.approx(expected, abs=1e-9)
    assert gv(r, "jH") == gv(r, "jR")
    assert [gv(r, "jH")[k] for k in ("j1", "j2", "j3", "j4", "j5")] == pytest.approx([0, 0, 90, 0, 45], abs=1e-9)
    # the arm did not move: the same flange position as at 720°
    assert gv(r, "pH")["trsf"]["rz"] == pytest.approx(0.0, abs=1e-9)
    # about 50 ms for the adjustment (clock(): seconds, on the 4 ms cycle)
    assert 0.050 <= gv(r, "nAfter") - gv(r, "nBefore") <= 0.058
    # the next cycle turns from there: to 90°, not back through 720°
    last = [m for m in r.motion.motions if m.id is not None][-1]
    assert gv(r, "jEnd")["j6"] == pytest.approx(90, abs=1e-9)
    assert list(last.joints_start)[5] == pytest.approx(expected)
    moved = abs(90 - expected)
    assert last.duration == pytest.approx(
        max(_t(moved, TX.nominal_speeds[5], TX.accelerations[5]), 0.0), rel=1e-6)
    # the record: axis 6 at its turned value after the reset
    t = last.start
    assert r.motion.trajectory.position(t)[5] == pytest.approx(expected, abs=1e-6)


def _t(d: float, v: float, a: float) -> float:
    """A rest-to-rest joint move of d degrees at speed v, acceleration and deceleration a."""
    if d >= v * v / a:
        return d / v + v / a
    return 2 * (d / a) ** 0.5


def test_the_option_is_in_use_when_the_application_calls_reset_turn(tmp_path):
    """Without a scenario: resetTurn in the program gives axis 6 the continuous range (720° is
    reached, not an error), the option licensed and said once (R050)."""
    r = sim(tmp_path, CYCLE.replace("jRef", "{0, 0, 90, 0, 45, 0}"), globals_=GLOBALS, robot=TX)
    assert sorted(codes(r)) == ["R050", "R052"]
    assert gv(r, "jR")["j6"] == 0


def test_without_the_option_the_axis_keeps_its_range_and_reset_turn_is_250(tmp_path):
    r = sim(tmp_path, """begin
  movej({0, 0, 90, 0, 45, 260}, flange, mD)
  waitEndMove()
  jR = resetTurn({0, 0, 90, 0, 45, 0})
end
""", globals_=["mdesc mD", "joint jR"], robot=TX, scenario="version = 1\n[options]\ncontinuousAxis = false\n")
    assert errors(r) == [250]
    r = sim(tmp_path / "b", """begin
  movej({0, 0, 90, 0, 45, 360}, flange, mD)
  waitEndMove()
end
""", globals_=["mdesc mD"], robot=TX, scenario="version = 1\n[options]\ncontinuousAxis = false\n")
    # 10.6: a joint target outside the software limits stops movej with 154 (R011)
    assert [(d.code, d.error) for d in r.diagnostics] == [("R011", 154)]


def test_reset_turn_cancels_the_motion_like_reset_motion(tmp_path):
    r = sim(tmp_path, """begin
  mD.blend = off
  movej({0, 0, 90, 0, 45, 700}, flange, mD)
  delay(0.2)
  jR = resetTurn({0, 0, 90, 0, 45, 0})
  nId = getMoveId()
  bEmpty = isEmpty()
end
""", globals_=["mdesc mD", "joint jR", "num nId", "bool bEmpty"], robot=TX,
            scenario="version = 1\n[options]\ncontinuousAxis = true\n")
    (m,) = r.motion.motions
    assert m.state == "cancelled"
    assert gv(r, "bEmpty") is True and gv(r, "nId") == 0
    assert -180 <= gv(r, "jR")["j6"] <= 180
