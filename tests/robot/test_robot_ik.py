"""Inverse kinematics: round trips, eight branches, 9.7.4 configurations, free/same, turns, bad input."""

from __future__ import annotations

import math
import random

import pytest

from val3check.robot import Config, RobotError, Unreachable, load_robot
from val3check.robot.config import classify
from val3check.robot.ik import opw_ik
from val3check.robot.kinematics import pose_error

from .robothelp import SIX_AXIS, close_pose, joint_dist, random_joints

ALL_CONFIGS = {(s, e, w) for s in ("righty", "lefty") for e in ("epositive", "enegative") for w in ("wpositive", "wnegative")}


@pytest.mark.parametrize("name", SIX_AXIS)
def test_round_trip_on_random_joints(name):
    robot = load_robot(name)
    rng = random.Random(f"rt {name}")
    for _ in range(400):
        q = random_joints(robot, rng)
        T = robot.fk_matrix(q)
        sols = robot.ik(T, near=q)
        assert sols, q
        assert joint_dist(sols[0], q) < 1e-6  # the original comes back, first (it is the nearest)
        for s in sols:
            assert robot.in_limits(s)
            assert close_pose(robot.fk_matrix(s), T)
        # the VAL 3 trsf form of the pose gives the same answer
        assert joint_dist(robot.ik(robot.fk(q), near=q)[0], q) < 1e-6


@pytest.mark.parametrize("name", SIX_AXIS)
def test_all_eight_branches_away_from_singularities(name):
    robot = load_robot(name)
    q = [15, -10, 100, 35, 55, 65]  # wrist centre near enough to axis 1 for the branches behind it
    T = robot.fk_matrix(q)
    raw = opw_ik(robot.opw, T)
    assert len(raw) == 8
    degs = [[math.degrees(a) for a in s] for s in raw]
    for s in degs:
        assert close_pose(robot.fk_matrix(s), T)
    assert {robot.config_of(s) for s in degs} == ALL_CONFIGS
    # every branch inside the limits comes back from ik(), each in its own configuration
    inside = [s for s in degs if robot.in_limits([((a + 180) % 360) - 180 for a in s])]
    sols = robot.ik(T)
    assert len(sols) == len(inside) >= 2
    assert len({robot.config_of(s) for s in sols}) == len(sols)


def test_all_eight_branches_within_the_limits_of_a_tx2_60():
    robot = load_robot("TX2-60")
    T = robot.fk_matrix([20, 30, 60, 40, 50, 60])
    sols = robot.ik(T)
    assert len(sols) == 8 and {robot.config_of(s) for s in sols} == ALL_CONFIGS


# ---- 9.7.4 configurations, cases worked out by hand ------------------------------------------------
# TX2-90: d1 = 425 (arm), d2 = 425 (forearm), δ = 50 (axis 1 to axis 2 along x)
TX2_90_CASES = [
    # j2, j3, j5, d1·sin j2 + d2·sin(j2+j3) + δ, expected
    ((0, 0, 0), 50.0, ("lefty", "epositive", "wpositive")),
    ((-10, 0, 10), 425 * 2 * math.sin(math.radians(-10)) + 50, ("righty", "epositive", "wpositive")),  # -97.6
    ((-3, 0, -10), 425 * 2 * math.sin(math.radians(-3)) + 50, ("lefty", "epositive", "wnegative")),  # +5.5: δ keeps it lefty
    ((-30, 60, 0), 50.0, ("lefty", "epositive", "wpositive")),  # the two sines cancel
    ((10, -120, 20), 425 * math.sin(math.radians(10)) + 425 * math.sin(math.radians(-110)) + 50, ("righty", "enegative", "wpositive")),
    ((60, -1e-9, -1e-9), None, ("lefty", "enegative", "wnegative")),
    ((-60, 90, 45), 425 * math.sin(math.radians(-60)) + 425 * math.sin(math.radians(30)) + 50, ("righty", "epositive", "wpositive")),
]


@pytest.mark.parametrize("joints,value,expected", TX2_90_CASES)
def test_configuration_formulas_tx2_90(joints, value, expected):
    j2, j3, j5 = joints
    robot = load_robot("TX2-90")
    if value is not None:
        assert (value < 0) == (expected[0] == "righty")
    assert robot.config_of([33, j2, j3, -70, j5, 120]) == expected
    assert classify(j2, j3, j5, 425, 425, 50) == expected


def test_configuration_boundaries_tx2_60():
    robot = load_robot("TX2-60")  # δ = 0: straight up is exactly on the boundary: lefty (>= 0)
    assert robot.config_of([0, 0, 0, 0, 0, 0]) == ("lefty", "epositive", "wpositive")
    assert robot.config_of([0, -0.001, 0, 0, 0, 0])[0] == "righty"
    assert robot.config_of([0, 0.001, -0.001, 0, -0.001, 0]) == ("lefty", "enegative", "wnegative")
    # j1, j4, j6 play no part
    assert robot.config_of([170, 40, 30, 260, 10, -260]) == robot.config_of([-170, 40, 30, -260, 10, 260])


def test_shoulder_branch_is_the_sign_of_the_formula():
    """The two shoulder branches of the closed form are exactly righty and lefty of 9.7.4."""
    robot = load_robot("RX160")  # δ = 150
    rng = random.Random(160)
    for _ in range(300):
        q = random_joints(robot, rng)
        for s in robot.ik(robot.fk_matrix(q)):
            o = robot.opw
            u = o.c2 * math.sin(math.radians(s[1])) + o.c3 * math.sin(math.radians(s[1] + s[2])) + o.a1
            assert robot.config_of(s)[0] == ("righty" if u < 0 else "lefty")


# ---- requested configurations: values, free, same ---------------------------------------------------


def test_config_filter_values_and_free():
    robot = load_robot("TX2-60")
    T = robot.fk_matrix([20, 30, 60, 40, 50, 60])
    assert len(robot.ik(T, config=None)) == 8
    assert len(robot.ik(T, config=("sfree", "efree", "wfree"))) == 8
    righty = robot.ik(T, config=("righty", "efree", "wfree"))
    assert len(righty) == 4 and all(robot.config_of(s)[0] == "righty" for s in righty)
    one = robot.ik(T, config=Config("lefty", "enegative", "wpositive"))
    assert len(one) == 1 and robot.config_of(one[0]) == ("lefty", "enegative", "wpositive")
    assert robot.ik(T, config="righty epositive wfree") == robot.ik(T, config=("righty", "epositive", "free"))


def test_same_keeps_the_configuration_of_the_initial_position():
    robot = load_robot("TX2-90")
    rng = random.Random(90)
    for _ in range(100):
        q0 = random_joints(robot, rng, margin=5)
        q1 = random_joints(robot, rng, margin=5)
        T = robot.fk_matrix(q1)
        got = robot.point_to_joint(T, ("ssame", "esame", "wsame"), initial=q0)
        if got is None:  # the target is not reachable in q0's configuration within the limits
            assert all(robot.config_of(s) != robot.config_of(q0) for s in robot.ik(T))
            continue
        assert robot.config_of(got) == robot.config_of(q0)
        assert close_pose(robot.fk_matrix(got), T)
        # only the shoulder kept: the elbow and wrist may change
        got = robot.point_to_joint(T, ("ssame", "efree", "wfree"), initial=q0)
        assert got is not None and robot.config_of(got)[0] == robot.config_of(q0)[0]


def test_same_from_differs_from_near():
    robot = load_robot("TX2-60")
    T = robot.fk_matrix([20, 30, 60, 40, 50, 60])
    ref = [0, -30, -60, 0, -50, 0]  # righty, enegative, wnegative
    sols = robot.ik(T, config=("same", "same", "same"), near=[20, 30, 60, 40, 50, 60], same_from=ref)
    assert len(sols) == 1 and robot.config_of(sols[0]) == robot.config_of(ref)


def test_same_without_initial_is_an_error():
    robot = load_robot("TX2-60")
    with pytest.raises(RobotError, match="same"):
        robot.ik(robot.fk([0, 10, 20, 0, 30, 0]), config=("ssame", "efree", "wfree"))


def test_bad_configuration_names():
    with pytest.raises(RobotError, match="shoulder"):
        Config.parse(("epositive", "efree", "wfree"))
    with pytest.raises(RobotError, match="three fields"):
        Config.parse(("righty",))
    assert Config.parse(("RIGHTY", "esame", "wfree")).val3() == ("righty", "esame", "wfree")


# ---- axes that turn more than once (9.6.3) -----------------------------------------------------------


def test_j4_j6_take_the_turn_nearest_the_initial_position():
    robot = load_robot("TX2-60")
    q = [10, 20, 30, 200, 40, -250]
    T = robot.fk_matrix(q)
    assert joint_dist(robot.point_to_joint(T, None, initial=q), q) < 1e-6
    near = robot.point_to_joint(T, None, initial=[10, 20, 30, -170, 40, 100])
    assert near[3] == pytest.approx(-160) and near[5] == pytest.approx(110)
    # without an initial position: the principal values
    principal = robot.ik(T, config=robot.config_of(q))
    assert principal[0][3] == pytest.approx(-160) and principal[0][5] == pytest.approx(110)
    # every turn on request: 2 values of j4 x 2 of j6 in the same branch
    every = robot.ik(T, config=robot.config_of(q), all_turns=True)
    assert sorted((round(s[3], 6), round(s[5], 6)) for s in every) == [(-160, -250), (-160, 110), (200, -250), (200, 110)]


def test_turns_respect_the_limits():
    robot = load_robot("TX2-60")
    q = [0, 20, 30, 100, 40, -100]
    T = robot.fk_matrix(q)
    # 100 - 360 = -260 and -100 + 360 = 260 are inside ±270; nearest to ±265 wins
    got = robot.point_to_joint(T, robot.config_of(q), initial=[0, 20, 30, -265, 40, 265])
    assert got[3] == pytest.approx(-260) and got[5] == pytest.approx(260)
    got = robot.point_to_joint(T, robot.config_of(q), initial=[0, 20, 30, 265, 40, -265])
    assert got[3] == pytest.approx(100) and got[5] == pytest.approx(-100)


# ---- singular positions --------------------------------------------------------------------------------


def test_wrist_singularity_keeps_j4_of_the_initial_position():
    robot = load_robot("TX2-60")
    q = [10, 20, 30, 40, 0, 50]
    T = robot.fk_matrix(q)
    got = robot.point_to_joint(T, None, initial=q)
    assert joint_dist(got, q) < 1e-9
    got = robot.point_to_joint(T, None, initial=[10, 20, 30, 0, 0, 0])
    assert got[3] == pytest.approx(0) and got[5] == pytest.approx(90)
    assert close_pose(robot.fk_matrix(got), T)
    sols = robot.ik(T, near=q)
    assert len(sols) == len({tuple(round(v, 6) for v in s) for s in sols})  # coinciding branches once


def test_wrist_centre_on_axis_1_keeps_j1_of_the_initial_position():
    robot = load_robot("RX160")  # b = 0: the shoulder singularity exists
    j3 = math.degrees(math.asin(-robot.opw.a1 / robot.opw.c3))  # wrist centre on axis 1 with j2 = 0
    q = [25, 0, j3, 30, 45, 60]
    T = robot.fk_matrix(q)
    got = robot.point_to_joint(T, None, initial=q)
    assert joint_dist(got, q) < 1e-6
    for s in robot.ik(T, near=q):
        assert close_pose(robot.fk_matrix(s), T)


# ---- poses that nothing reaches -------------------------------------------------------------------------


def test_out_of_reach():
    robot = load_robot("TX2-60")
    far = (2000, 0, 300, 0, 90, 0)
    assert robot.ik(far) == []
    assert robot.point_to_joint(far, None, initial=[0] * 6) is None
    with pytest.raises(Unreachable) as err:
        robot.solve(far, None, initial=[0] * 6)
    assert err.value.reason == "reach" and "reach" in str(err.value)


def test_outside_the_joint_limits():
    robot = load_robot("TX2-60")
    T = robot.fk_matrix([0, 0, 170, 0, 0, 0])  # every branch needs |j3| = 170 > 152.5
    assert robot.ik(T) == []
    with pytest.raises(Unreachable) as err:
        robot.solve(T, None, initial=[0] * 6)
    assert err.value.reason == "limits"


def test_not_in_the_requested_configuration():
    robot = load_robot("TX2-60")
    q0 = [0, 30, 60, 0, 125, 0]  # the wrist flip would need j5 = -125 < -121
    T = robot.fk_matrix(q0)
    assert robot.point_to_joint(T, ("ssame", "esame", "wnegative"), initial=q0) is None
    with pytest.raises(Unreachable) as err:
        robot.solve(T, ("ssame", "esame", "wnegative"), initial=q0)
    assert err.value.reason == "config" and "wnegative" in str(err.value)
    assert robot.point_to_joint(T, ("ssame", "esame", "wfree"), initial=q0) is not None


def test_a_tool_moves_the_target():
    robot = load_robot("TX90")
    tool = (0, 50, 150, 0, 30, 0)
    q = [5, 25, 70, -20, 35, 15]
    pose = robot.fk(q, tool)
    got = robot.point_to_joint(pose, None, initial=q, tool=tool)
    assert joint_dist(got, q) < 1e-6
    assert pose_error(robot.fk_matrix(got, tool), robot.fk_matrix(q, tool))[0] < 1e-9
