"""SCARA arms (RS/TS, manual 9.7.5): closed-form kinematics, both elbow branches, configurations."""

from __future__ import annotations

import math
import random

import pytest

from val3check.robot import Config, RobotError, Unreachable, load_robot
from val3check.robot.scara import classify

from .robothelp import SCARAS, close_pose, joint_dist, random_joints


@pytest.mark.parametrize("name", SCARAS)
def test_round_trip_on_random_joints_both_branches(name):
    robot = load_robot(name)
    rng = random.Random(f"scara {name}")
    seen = set()
    for _ in range(400):
        q = random_joints(robot, rng)
        T = robot.fk_matrix(q)
        sols = robot.ik(T, near=q)
        assert joint_dist(sols[0], q) < 1e-6  # the original comes back first (the nearest)
        for s in sols:
            assert robot.in_limits(s)
            assert close_pose(robot.fk_matrix(s), T)
        # the mirrored elbow: j2 -> -j2 on the same flange pose (righty <-> lefty), when in the limits
        other = [s for s in sols if robot.config_of(s) != robot.config_of(q)]
        if other:
            o = other[0]
            assert o[1] == pytest.approx(-q[1], abs=1e-6) and o[2] == pytest.approx(q[2], abs=1e-9)
            seen.add(robot.config_of(o)[0])
        assert joint_dist(robot.ik(robot.fk(q), near=q)[0], q) < 1e-6  # the trsf form too
    assert seen == {"righty", "lefty"}  # both branches were exercised


@pytest.mark.parametrize("name", SCARAS)
def test_both_branches_without_near(name):
    robot = load_robot(name)
    q = [20, 60, 50, 30]
    T = robot.fk_matrix(q)
    sols = robot.ik(T)
    assert sorted(robot.config_of(s)[0] for s in sols) == ["lefty", "righty"]
    righty = robot.ik(T, config=("righty",))
    lefty = robot.ik(T, config="lefty")
    assert len(righty) == len(lefty) == 1
    assert joint_dist(righty[0], q) < 1e-9
    assert lefty[0][1] == pytest.approx(-60)
    for s in sols:
        assert close_pose(robot.fk_matrix(s), T)


# ---- 9.7.5: righty when sin(j2) > 0, lefty when sin(j2) <= 0 -------------------------------------

CASES_975 = [
    (0, "lefty"), (1e-9, "righty"), (-1e-9, "lefty"), (45, "righty"), (90, "righty"), (141.5, "righty"),
    (179.999, "righty"), (180, "lefty"), (-180, "lefty"), (-0.5, "lefty"), (-141.5, "lefty"),
    (270, "lefty"), (-270, "righty"), (360, "lefty"), (-359, "righty"),
]


@pytest.mark.parametrize("j2,expected", CASES_975)
def test_configuration_classification_9_7_5(j2, expected):
    assert classify(j2) == expected
    robot = load_robot("TS2-60")
    assert robot.config_of([33, j2, 120, -250]) == (expected,)  # j1, j3, j4 play no part
    assert robot.config_of([-170, j2, 0, 499]) == (expected,)


def test_righty_puts_the_elbow_on_the_right_of_the_target_seen_from_above():
    """The picture of 9.7.5: seen from above, from axis 1 towards the flange, the elbow (axis 2) is
    on the right for righty (sin(j2) > 0) and on the left for lefty."""
    robot = load_robot("TS60")
    sc = robot.scara
    rng = random.Random(975)
    for _ in range(200):
        q = random_joints(robot, rng, margin=1)
        if abs(math.sin(math.radians(q[1]))) < 1e-3:
            continue
        t1 = math.radians(q[0])
        elbow = (sc.l1 * math.cos(t1), sc.l1 * math.sin(t1))
        T = robot.fk_matrix(q)
        wrist = (T[0][3], T[1][3])
        cross = wrist[0] * elbow[1] - wrist[1] * elbow[0]  # < 0: elbow to the right of the base->wrist line
        assert robot.config_of(q) == (("righty",) if cross < 0 else ("lefty",))


def test_same_and_free_shoulder():
    robot = load_robot("TS2-80")
    q0 = [10, -40, 20, 0]  # lefty
    target = robot.fk_matrix([50, 70, 80, 90])  # reached righty from [50, 70]; lefty too
    got = robot.point_to_joint(target, ("ssame",), initial=q0)
    assert robot.config_of(got) == ("lefty",) and close_pose(robot.fk_matrix(got), target)
    got = robot.point_to_joint(target, ("sfree",), initial=q0)
    assert close_pose(robot.fk_matrix(got), target)
    # three fields as the interpreter builds them: elbow and wrist same/free are not constraints
    assert robot.point_to_joint(target, ("ssame", "esame", "wsame"), initial=q0) == robot.point_to_joint(target, ("ssame",), initial=q0)
    assert Config.parse(("righty", "efree", "wfree"), scara=True) == Config("righty")


def test_elbow_or_wrist_values_on_a_scara_are_refused():
    robot = load_robot("TS2-60")
    T = robot.fk_matrix([0, 45, 10, 0])
    with pytest.raises(RobotError, match="no elbow or wrist configuration.*9.7.2"):
        robot.ik(T, config=("righty", "epositive", "wfree"))
    with pytest.raises(RobotError, match="one field"):
        robot.ik(T, config=("righty", "efree"))


def test_six_axis_configs_keep_three_fields():
    robot = load_robot("TX2-60")
    assert len(robot.config_of([0, 10, 20, 0, 30, 0])) == 3
    assert robot.config_fields == ("shoulder", "elbow", "wrist")
    assert load_robot("TS40").config_fields == ("shoulder",)


# ---- axis 4 turns: the nearest turn (9.6.3) within ±500° ----------------------------------------------


def test_j4_takes_the_turn_nearest_the_initial_position():
    robot = load_robot("TS2-60")
    q = [10, 50, 100, 20]
    T = robot.fk_matrix(q)
    assert robot.point_to_joint(T, ("ssame",), initial=[10, 50, 100, 390])[3] == pytest.approx(380)
    assert robot.point_to_joint(T, ("ssame",), initial=[10, 50, 100, -300])[3] == pytest.approx(-340)
    assert robot.ik(T, config="righty")[0][3] == pytest.approx(20)  # without near: the turn nearest 0
    turns = sorted(round(s[3], 6) for s in robot.ik(T, config="righty", all_turns=True))
    assert turns == [-340, 20, 380]


# ---- the prismatic axis 3: a length, in the application's unit ------------------------------------------


def test_axis_3_is_a_length():
    robot = load_robot("TS2-60")
    assert robot.joint_kinds == ("revolute", "revolute", "prismatic", "revolute")
    assert robot.joint_units == ("deg", "deg", "mm", "deg")
    a, b = robot.fk([10, 20, 0, 30]), robot.fk([10, 20, 150, 30])
    assert b[2] - a[2] == pytest.approx(150, abs=1e-12)  # j3 > 0 raises the flange (S1)
    assert a[:2] == pytest.approx(b[:2]) and a[3:] == pytest.approx(b[3:])
    assert robot.joint_limits[2] == (-0.1, 200.1)
    # mm/s, mm/s² (assumed: the SCARA rule at its reference reach, 2000 mm/s in 0.040 s)
    assert robot.nominal_speeds[2] == 2000 and robot.accelerations[2] == pytest.approx(2000 / 0.040, abs=0.05)


def test_flange_turns_about_the_vertical_only():
    robot = load_robot("TS2-60")
    for q in ([0, 0, 0, 0], [30, 45, 100, 10], [-120, -100, 50, 400]):
        x, y, z, rx, ry, rz = robot.fk(q)
        assert abs(rx) == 180 and ry == pytest.approx(0, abs=1e-9)
        # rz = j4 - j1 - j2 (axis 4 about the flange's own Z, pointing down: the stated assumption)
        assert math.remainder(rz - (q[3] - q[0] - q[1]), 360) == pytest.approx(0, abs=1e-9)


# ---- what a SCARA cannot reach --------------------------------------------------------------------------


def test_tilted_target_is_out_of_reach():
    robot = load_robot("TS2-60")
    with pytest.raises(Unreachable) as err:
        robot.solve((400, 100, 50, 180, 5, 0), None, initial=[0, 0, 0, 0])
    assert err.value.reason == "reach" and "vertical" in str(err.value)
    # a rounding-level tilt is not a tilt
    assert robot.ik((400, 100, 50, 180, 1e-9, 0))


def test_out_of_reach_and_out_of_stroke():
    robot = load_robot("TS2-60")  # links 380 + 240: reaches 140 < r < 620
    for far in ((700, 0, 50, 180, 0, 0), (100, 0, 50, 180, 0, 0)):
        with pytest.raises(Unreachable) as err:
            robot.solve(far, None, initial=[0, 0, 0, 0])
        assert err.value.reason == "reach"
    with pytest.raises(Unreachable) as err:  # in reach, but 250 mm above the flange's lowest: beyond the stroke
        robot.solve((400, 100, 250, 180, 0, 0), None, initial=[0, 0, 0, 0])
    assert err.value.reason == "limits"
    with pytest.raises(Unreachable) as err:  # |j2| > 141.5 needed: inside the limits of neither branch
        robot.solve(robot.fk_matrix([0, 150, 50, 0]), None, initial=[0, 0, 0, 0])
    assert err.value.reason == "limits"


def test_stretched_arm_is_singular_and_gives_one_solution():
    robot = load_robot("TS2-100")
    q = [25, 0, 80, 10]
    assert "elbow" in robot.singularities(q)
    assert robot.singularities([25, 30, 80, 10]) == ()
    sols = robot.ik(robot.fk_matrix(q))
    assert len(sols) == 1 and joint_dist(sols[0], q) < 1e-6 and robot.config_of(sols[0]) == ("lefty",)


def test_six_axis_singularities():
    robot = load_robot("TX2-60")
    assert "wrist" in robot.singularities([10, 20, 30, 40, 0, 50])
    assert "elbow" in robot.singularities([10, 20, 0, 40, 30, 50])
    assert robot.singularities([10, 20, 30, 40, 30, 50]) == ()
    rx = load_robot("RX160")  # b = 0: the wrist centre can sit on axis 1
    j3 = math.degrees(math.asin(-rx.opw.a1 / rx.opw.c3))
    assert "shoulder" in rx.singularities([25, 0, j3, 30, 45, 60])


def test_a_tool_on_a_scara():
    robot = load_robot("TS2-60")
    tool = (0, 0, 60, 0, 0, 0)  # 60 mm along the flange's Z: below the flange
    q = [15, 70, 100, -30]
    pose = robot.fk(q, tool)
    assert pose[2] == pytest.approx(robot.fk(q)[2] - 60)
    assert joint_dist(robot.point_to_joint(pose, ("ssame",), initial=q, tool=tool), q) < 1e-6


def test_scara_through_the_geometry_protocol():
    """val3check.geometry's pointToJoint/jointToPoint (the interpreter's path) work on a SCARA,
    with a one-field config."""
    from val3check.geometry import arm as GA
    from val3check.geometry.frames import new_flange, new_world

    robot = load_robot("TS60")
    world, flange = new_world(), new_flange()
    q = (30.0, 80.0, 120.0, 45.0)
    p = GA.joint_to_point(robot, flange, world, q)
    assert p.config == ("righty",)
    found, j = GA.point_to_joint(robot, flange, (0.0, 10.0, 0.0, 0.0), p)
    assert found and joint_dist(j, q) < 1e-6
    p.config = ("lefty",)
    found, j = GA.point_to_joint(robot, flange, (0.0, 10.0, 0.0, 0.0), p)
    assert found and j[1] == pytest.approx(-80) and robot.config_of(j) == ("lefty",)


# ---- a SCARA of the user's own (another maker's conventions) ----------------------------------------

USER_SCARA = """<?xml version="1.0"?>
<robot name="other_scara">
  <val3check arm="Other SCARA" world_frame="base" flange_frame="tool0"/>
  <link name="base_link"/><link name="base"/><link name="l1"/><link name="l2"/><link name="l3"/><link name="l4"/>
  <link name="tool0"/>
  <joint name="to_base" type="fixed"><origin xyz="0 0 0.1" rpy="0 0 0"/><parent link="base_link"/><child link="base"/></joint>
  <joint name="j1" type="revolute"><origin xyz="0 0 0.4" rpy="0 0 0"/><parent link="base_link"/><child link="l1"/>
    <axis xyz="0 0 1"/><limit lower="-2.5" upper="2.5" velocity="6" effort="0"/></joint>
  <joint name="j2" type="revolute"><origin xyz="0.3 0.1 0" rpy="0 0 0"/><parent link="l1"/><child link="l2"/>
    <axis xyz="0 0 1"/><limit lower="-2.6" upper="2.6" velocity="6" effort="0"/></joint>
  <joint name="j3" type="prismatic"><origin xyz="0.25 0 -0.05" rpy="0 0 0"/><parent link="l2"/><child link="l3"/>
    <axis xyz="0 0 -1"/><limit lower="0" upper="0.15" velocity="1.1" effort="0"/></joint>
  <joint name="j4" type="revolute"><origin xyz="0 0 0" rpy="0 0 0"/><parent link="l3"/><child link="l4"/>
    <axis xyz="0 0 1"/><limit lower="-6.28" upper="6.28" velocity="20" effort="0"/></joint>
  <joint name="flange" type="fixed"><origin xyz="0.02 0 0" rpy="3.141592653589793 0 0.5"/><parent link="l4"/><child link="tool0"/></joint>
</robot>
"""


def test_a_users_scara_urdf_gets_the_closed_form(tmp_path):
    p = tmp_path / "other.urdf"
    p.write_text(USER_SCARA, encoding="utf-8")
    robot = load_robot(str(p))
    assert robot.family == "scara" and robot.type_family == "Rs" and robot.scara is not None
    sc = robot.scara
    assert sc.l1 == pytest.approx(math.hypot(300, 100)) and sc.l2 == pytest.approx(250)
    assert sc.signs == (1, 1, -1, 1) and sc.offset == pytest.approx((20, 0))
    assert robot.joint_limits[2] == (0, 150) and robot.nominal_speeds[2] == pytest.approx(1100)
    assert "assumed" in robot.acceleration_note
    rng = random.Random(11)
    for _ in range(300):
        q = random_joints(robot, rng)
        T = robot.fk_matrix(q)
        assert close_pose(T, robot.fk_chain(q))
        sols = robot.ik(T, near=q)
        assert joint_dist(sols[0], q) < 1e-6
        for s in sols:
            assert close_pose(robot.fk_matrix(s), T)
    pytest.importorskip("pinocchio")
    assert close_pose(robot.fk_matrix([0.3, -0.4, 80, 1]), robot.fk_pinocchio([0.3, -0.4, 80, 1]))


def test_a_scara_with_a_tilted_axis_has_no_closed_form(tmp_path):
    p = tmp_path / "tilted.urdf"
    p.write_text(USER_SCARA.replace('<axis xyz="0 0 1"/><limit lower="-2.6"', '<axis xyz="0 0.1 1"/><limit lower="-2.6"'),
                 encoding="utf-8")
    robot = load_robot(str(p))
    assert robot.family == "scara" and robot.scara is None and "axis 2 is not vertical" in robot.opw_reason
    robot.fk([10, 20, 30, 40])  # forward kinematics still works
    from val3check.robot import IKUnsupported

    with pytest.raises(IKUnsupported, match="four axes vertical"):
        robot.ik(robot.fk([10, 20, 30, 40]))


def test_other_joint_layouts_are_refused(tmp_path):
    p = tmp_path / "rrpp.urdf"
    p.write_text(USER_SCARA.replace('<joint name="j4" type="revolute">', '<joint name="j4" type="prismatic">'), encoding="utf-8")
    with pytest.raises(RobotError, match="a SCARA is revolute, revolute, prismatic, revolute"):
        load_robot(str(p))
