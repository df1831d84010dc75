"""9.2.3 setLatch/getLatch: the scenario's rising edge captures the arm's position at that
instant, between the 4 ms setpoints; checked against a hand-computed bang-bang joint line."""

from __future__ import annotations

import math

import pytest
from interpretation.simsupport import codes, gv, sim

from val3check.robot import load_robot

TX = load_robot("TX2-60")
V1 = TX.nominal_speeds[0]
A1 = TX.accelerations[0]
PROGRAM = """begin
  mD.vel = 50
  mD.blend = off
  setLatch(diLatch)
  delay(0)
  jB = herej()
  jB.j1 = 90
  movej(jB, flange, mD)
  bLatch = watch(getLatch(jL) == true, 5)
  waitEndMove()
  bAgain = getLatch(jAgain)
end
"""
GLOBALS = ["dio diLatch", "joint jB", "joint jL", "joint jAgain", "mdesc mD", "bool bLatch", "bool bAgain"]


def scenario(at: float) -> str:
    return f"""version = 1
[robot]
joints = [0, 20, 100, 0, 60, 0]
[[events]]
at = {at}
set = {{ diLatch = true }}
"""


def j1_at(t: float, v: float, a: float) -> float:
    """The hand computation: joint 1 of a 90° trapezoid (speed v, acceleration = deceleration a)
    started at 0 s, at t seconds after its start."""
    t_acc = v / a
    d_acc = v * v / (2 * a)
    cruise = (90 - 2 * d_acc) / v
    if t <= t_acc:
        return a * t * t / 2
    if t <= t_acc + cruise:
        return d_acc + v * (t - t_acc)
    td = t - t_acc - cruise
    return d_acc + v * cruise + v * td - a * td * td / 2


@pytest.mark.parametrize("edge", [0.0713, 0.3371, 0.4602])  # acceleration, cruise, deceleration
def test_the_latch_captures_the_position_at_the_edge_between_4_ms_setpoints(tmp_path, edge):
    r = sim(tmp_path, PROGRAM, globals_=GLOBALS, links={"diLatch": "fIn0"}, scenario=scenario(edge), robot=TX)
    assert codes(r) == []
    (m,) = [m for m in r.motion.motions if m.id is not None]
    v = V1 * 0.5  # mD.vel = 50; accel, decel 100 % (10.5.1); no blend: a stop at the target
    a = A1
    assert 90 > v * v / a  # a trapezoid (cruise phase), not a triangle
    t0 = m.start
    tick = 0.004
    k0 = math.floor(edge / tick + 1e-9)
    q0 = j1_at(k0 * tick - t0, v, a)
    q1 = j1_at((k0 + 1) * tick - t0, v, a)
    expected = q0 + (edge - k0 * tick) / tick * (q1 - q0)
    assert gv(r, "bLatch") is True and gv(r, "bAgain") is True
    jl = gv(r, "jL")
    assert jl["j1"] == pytest.approx(expected, abs=1e-9)
    assert [jl[k] for k in ("j2", "j3", "j4", "j5", "j6")] == pytest.approx([20, 100, 0, 60, 0], abs=1e-9)
    assert gv(r, "jAgain") == jl  # the same capture until setLatch arms a new one


def test_without_an_edge_get_latch_is_false_and_leaves_the_joint(tmp_path):
    r = sim(tmp_path, """begin
  jL = {1, 2, 3, 4, 5, 6}
  bNever = getLatch(jL)
  setLatch(diLatch)
  bWait = getLatch(jL)
end
""", globals_=["dio diLatch", "joint jL", "bool bNever", "bool bWait"], links={"diLatch": "fIn1"}, robot=TX)
    assert codes(r) == []
    assert gv(r, "bNever") is False and gv(r, "bWait") is False
    assert list(gv(r, "jL").values()) == [1, 2, 3, 4, 5, 6]


def test_an_edge_before_set_latch_does_not_capture_and_set_latch_rearms(tmp_path):
    r = sim(tmp_path, """begin
  delay(0.5)
  setLatch(diLatch)
  bFirst = watch(getLatch(jL) == true, 1)
  setLatch(diLatch)
  bSecond = getLatch(jL)
end
""", globals_=["dio diLatch", "joint jL", "bool bFirst", "bool bSecond"], links={"diLatch": "fIn0"}, robot=TX,
            scenario="""version = 1
[[events]]
at = 0.1
set = { diLatch = true }
[[events]]
at = 0.8
set = { diLatch = false }
[[events]]
at = 0.9
set = { diLatch = true }
""")
    assert codes(r) == []
    # the edge at 0.1 s came before setLatch; the one at 0.9 s is captured; a new setLatch
    # forgets it
    assert gv(r, "bFirst") is True and gv(r, "bSecond") is False


def test_an_input_that_is_not_a_fast_input_warns_once_and_still_captures(tmp_path):
    r = sim(tmp_path, """begin
  setLatch(diLatch)
  setLatch(diLatch)
  bOk = watch(getLatch(jL) == true, 1)
end
""", globals_=["dio diLatch", "joint jL", "bool bOk"], links={"diLatch": "BasicIO-1\\%I0"}, robot=TX,
            scenario="version = 1\n[[events]]\nat = 0.2\nset = { diLatch = true }\n")
    assert codes(r) == ["R051"]
    assert gv(r, "bOk") is True


def test_without_an_arm_model_the_latch_stops_with_r002(tmp_path):
    r = sim(tmp_path, "begin\n  setLatch(diLatch)\nend\n", globals_=["dio diLatch"], links={"diLatch": "fIn0"})
    assert codes(r) == ["R002"]
