"""Issue 21 O: a scenario's `[robot] joints` must lie within the arm's joint limits: j1 = 400 was
accepted, and with 1e300 numpy overflowed and the first movej was computed with NaN (0 s, exit
0). Each is a scenario error at its line that names the joint and the limit."""

from __future__ import annotations

import pytest
from interpretation.simsupport import sim

from val3check.robot import load_robot
from val3check.simulation.scenario import ScenarioError

TX2_60 = load_robot("tx2-60")
MOVE = "begin\n  movej(jJ, flange, mNomSpeed)\n  waitEndMove()\nend\n"
GLOBALS = ["joint jJ", "mdesc mNomSpeed"]


@pytest.mark.parametrize("joints,message", [
    ("[400, 0, 90, 0, 0, 0]", "joint 1 = 400 is outside the limits of the arm TX2-60: [-180, 180] degrees"),
    ("[1e300, 0, 0, 0, 0, 0]", "joint 1 = 1e+300 is outside the limits of the arm TX2-60: [-180, 180] degrees"),
    ("[0, 0, 0, 0, 133, 0]", "joint 5 = 133 is outside the limits of the arm TX2-60: [-121, 132.5] degrees"),
    ("[0, 0, 0, 0, 0, -9223372036854775808]",
     ("joint 6 = -9223372036854775808 is outside the limits of the arm TX2-60: [-270, 270] degrees")),
])
def test_joints_outside_the_limits_are_refused_at_their_line(tmp_path, joints, message):
    with pytest.raises(ScenarioError) as e:
        sim(tmp_path, MOVE, globals_=GLOBALS, robot=TX2_60, duration=1.0,
            scenario=f"version = 1\n\n[robot]\n# the start\njoints = {joints}\n")
    assert e.value.line == 5 and e.value.message == f"[robot] joints: {message}", e.value


@pytest.mark.parametrize("joints", ["[nan, 0, 0, 0, 0, 0]", "[inf, 0, 0, 0, 0, 0]", "[1e301, 0, 0, 0, 0, 0]"])
def test_non_finite_joints_are_refused(tmp_path, joints):
    with pytest.raises(ScenarioError, match=r"\[robot\] joints = \[finite numbers\]"):
        sim(tmp_path, MOVE, globals_=GLOBALS, robot=TX2_60, scenario=f"[robot]\njoints = {joints}\n")


def test_a_scara_axis_3_is_in_millimetres(tmp_path):
    with pytest.raises(ScenarioError, match=r"joint 3 = 250 is outside the limits of the arm TS2-60: \[-0.1, 200.1\] mm"):
        sim(tmp_path, "begin\nend\n", robot=load_robot("TS2-60"), scenario="[robot]\njoints = [0, 0, 250, 0]\n")


def test_joints_at_the_limits_run(tmp_path):
    r = sim(tmp_path, "begin\nend\n", robot=TX2_60, duration=0.1,
            scenario="[robot]\njoints = [-180, 127.5, -152.5, 270, 132.5, -270]\n")
    assert r.robot["initial_joints"] == [-180, 127.5, -152.5, 270, 132.5, -270]
