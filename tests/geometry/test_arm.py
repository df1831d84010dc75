"""Instructions that need the arm model (here, jointToPoint, pointToJoint, config), against a
fake kinematics; and the table of `instructions`."""

from __future__ import annotations

import pytest

from val3check.geometry import arm, points
from val3check.geometry import by_val3_name as I
from val3check.geometry.arm import Kinematics
from val3check.geometry.frames import Frame, Tool, new_flange, new_world
from val3check.geometry.points import Point
from val3check.geometry.trsf import Trsf
from val3check.language.runtime_errors import Val3RuntimeError

from .helpers import FakeArm, trsf_close


@pytest.fixture
def cell():
    return FakeArm(), new_world(), new_flange()


def test_fake_arm_has_the_protocol():
    assert isinstance(FakeArm(), Kinematics)


def test_joint_to_point_flange_in_world(cell):
    kin, world, flange = cell
    j = (400, 100, 300, 180, 0, 45)
    p = arm.joint_to_point(kin, flange, world, j)
    assert p.trsf == Trsf(400, 100, 300, 180, 0, 45)
    assert p.ref is world and p.config == ("lefty", "epositive", "wpositive")


def test_joint_to_point_with_tool_and_frame(cell):
    kin, world, flange = cell
    tool = Tool(Trsf(0, 0, 100), flange)
    f = Frame(Trsf(0, 0, 50), world)
    p = arm.joint_to_point(kin, tool, f, (400, 100, 300, 180, 0, 45))
    # the tool points down: its centre is 100 below the flange
    assert trsf_close(p.trsf, Trsf(400, 100, 150, 180, 0, 45))
    assert p.ref is f


def test_here_and_distance_example(cell):
    # 9.6.3: wait(distance(here(tTool, world), pTarget) < 10)
    kin, world, flange = cell
    tTool = Tool(Trsf(0, 0, 100), flange)
    pTarget = Point(Trsf(400, 100, 200, 180, 0, 0), ("sfree", "efree", "wfree"), world)
    current = (400, 100, 305, 180, 0, 0)
    h = arm.here(kin, current, tTool, world)
    assert points.distance(h, pTarget) == pytest.approx(5)
    assert points.distance(h, pTarget) < 10
    assert h == arm.joint_to_point(kin, tTool, world, current)


def test_config_of_joint(cell):
    kin, _, _ = cell
    assert arm.config_of(kin, (-1, 0, -1, 0, 120, 0)) == ("righty", "enegative", "wnegative")
    assert I.config(kin, (1, 0, 1, 0, 0, 0)) == ("lefty", "epositive", "wpositive")


def test_point_to_joint_round_trip(cell):
    kin, world, flange = cell
    tool = Tool(Trsf(0, 0, 100), flange)
    j0 = (400, 100, 300, 170, 5, 45)
    p = arm.joint_to_point(kin, tool, world, j0)
    ok, j = arm.point_to_joint(kin, tool, (0, 0, 0, 0, 0, 0), p)
    assert ok
    assert j == pytest.approx(j0)
    # the model received the flange pose and the config with "same" resolved
    pose, cfg, near = kin.calls[-1]
    assert pose == pytest.approx(j0)
    assert cfg == ("lefty", "epositive", "wpositive")


def test_point_to_joint_config_same_and_free(cell):
    kin, world, flange = cell
    target = Trsf(100, 100, 100, 20, 30, 40)
    # the twin triple (-160, 150, -140) is the same flange pose with the other wrist
    p = Point(target, ("sfree", "efree", "wnegative"), world)
    ok, j = arm.point_to_joint(kin, flange, (0, 0, 0, 0, 0, 0), p)
    assert ok and j[3:] == pytest.approx((-160, 150, -140))
    p.config = ("sfree", "efree", "wfree")
    ok, j = arm.point_to_joint(kin, flange, (0, 0, 0, 0, 0, 0), p)
    assert ok and j[3:] == pytest.approx((20, 30, 40))  # the nearest to jInitial
    # wsame: the wrist of jInitial (wnegative here)
    p.config = ("ssame", "esame", "wsame")
    ok, j = arm.point_to_joint(kin, flange, (100, 100, 100, 0, 170, 0), p)
    assert ok and kin.config_of(j)[2] == "wnegative"
    assert kin.calls[-1][1] == ("lefty", "epositive", "wnegative")


def test_point_to_joint_nearest_turn(cell):
    kin, world, flange = cell
    p = Point(Trsf(0, 0, 0, 0, 0, 10), ("sfree", "efree", "wpositive"), world)
    ok, j = arm.point_to_joint(kin, flange, (0, 0, 0, 0, 0, 350), p)
    assert ok and j[5] == pytest.approx(370)


def test_point_to_joint_no_solution(cell):
    kin, world, flange = cell
    far = Point(Trsf(5000, 0, 0), ("sfree", "efree", "wfree"), world)  # out of the software limits
    assert arm.point_to_joint(kin, flange, (0,) * 6, far) == (False, None)
    righty = Point(Trsf(10, 0, 0), ("righty", "efree", "wfree"), world)  # j1 >= 0 is lefty
    assert arm.point_to_joint(kin, flange, (0,) * 6, righty) == (False, None)


def test_point_to_joint_without_reference_is_162(cell):
    kin, _, flange = cell
    with pytest.raises(Val3RuntimeError) as e:
        arm.point_to_joint(kin, flange, (0,) * 6, Point(local=True))
    assert e.value.code == 162


def test_modified_flange_in_here_is_160(cell):
    kin, world, flange = cell
    flange.trsf.z = 1
    with pytest.raises(Val3RuntimeError) as e:
        arm.here(kin, (0,) * 6, flange, world)
    assert e.value.code == 160


def test_instruction_table_dispatch(cell):
    kin, world, flange = cell
    f = Frame(Trsf(10, 0, 0), world)
    p = Point(Trsf(1, 0, 0), ("sfree", "efree", "wfree"), f)
    t = Tool(Trsf(0, 0, 5), flange)
    assert I.position(p, world) == Trsf(11, 0, 0)
    assert I.position(f, world) == Trsf(10, 0, 0)
    assert I.position(t, flange) == Trsf(0, 0, 5)
    assert I.distance(p, Point(Trsf(), ref=world)) == 11
    assert I.distance(Trsf(), Trsf(3, 4, 0)) == 5
    assert I.equal(Trsf(1), Trsf(1)) and I.equal((1.0, 2.0), (1.0, 2.0 + 1e-9))
    assert I.equal(("lefty",), ("lefty",)) and not I.equal(("lefty",), ("righty",))
    q = Point(local=True)
    I.assign(q, p)
    I.link(q, world)
    assert I.position(q, world) == Trsf(1, 0, 0)
    assert I.trsf_inv(I.trsf_mul(Trsf(1), Trsf(2))) == Trsf(-3)
    assert I.interpolateL(Trsf(), Trsf(2), 0.5) == Trsf(1)
    assert I.abs_joint((-1, 2)) == (1, 2)
