"""Nothing in the kinematics assumes one geometry: other six-axis arms through the same code path."""

from __future__ import annotations

import math
import random

import pytest

from val3check.robot import IKUnsupported, RobotError, from_urdf, load_robot
from val3check.robot.catalog import example_robot_urdf
from val3check.robot.ik import opw_ik
from val3check.robot.kinematics import pose_error

from .robothelp import close_pose, joint_dist, random_joints

UR5 = example_robot_urdf("ur_description/urdf/ur5_robot.urdf")
needs_erd = pytest.mark.skipif(UR5 is None, reason="example-robot-data is not installed (pip install 'val3check[robots]')")


@needs_erd
def test_ur5_forward_kinematics_with_pinocchio():
    pytest.importorskip("pinocchio")
    ur5 = from_urdf(UR5, world_frame="base_link", flange_frame="tool0")
    assert ur5.joint_names == ("shoulder_pan_joint", "shoulder_lift_joint", "elbow_joint", "wrist_1_joint", "wrist_2_joint", "wrist_3_joint")
    assert ur5.joint_limits[0] == (-360, 360)
    rng = random.Random(5)
    for _ in range(200):
        q = random_joints(ur5, rng)
        dp, da = pose_error(ur5.fk_matrix(q), ur5.fk_pinocchio(q))
        assert dp < 1e-9 and da < 1e-12
    # UR5 zero position (arm stretched out horizontally) from its published lengths: upper arm 425,
    # forearm 392.25, base 89.159, wrist 2 94.65 mm, lateral offsets 135.85 - 119.7 + 93 + 82.3 mm
    x, y, z = (ur5.fk_matrix([0] * 6)[i][3] for i in range(3))
    assert (x, y, z) == pytest.approx((425 + 392.25, 135.85 - 119.7 + 93 + 82.3, 89.159 - 94.65), abs=1e-6)


@needs_erd
def test_ur5_has_no_closed_form_here_and_says_so():
    ur5 = from_urdf(UR5, world_frame="base_link", flange_frame="tool0")
    assert ur5.opw is None and ur5.opw_reason
    with pytest.raises(IKUnsupported) as err:
        ur5.ik(ur5.fk([0, -90, 90, 0, 90, 0]))
    assert "spherical wrist" in str(err.value) and ur5.opw_reason in str(err.value)
    with pytest.raises(IKUnsupported):
        ur5.config_of([0] * 6)


@needs_erd
def test_ur5_without_metadata_needs_the_frames():
    with pytest.raises(RobotError, match="world_frame"):
        load_robot(str(UR5))


# A KUKA-like ortho-parallel arm: forearm offset a2 < 0, axes 1, 4 and 6 turning the other way,
# world frame below axis 2, and a flange frame turned like ROS-Industrial's "flange" (X out).
KUKA_LIKE = """<?xml version="1.0"?>
<robot name="kuka_like">
  <val3check arm="KUKA-like" world_frame="base" flange_frame="flange"/>
  <link name="base_link"/><link name="base"/><link name="l1"/><link name="l2"/><link name="l3"/>
  <link name="l4"/><link name="l5"/><link name="l6"/><link name="flange"/>
  <joint name="base_joint" type="fixed"><origin xyz="0 0 0.2" rpy="0 0 0"/><parent link="base_link"/><child link="base"/></joint>
  <joint name="a1" type="revolute"><origin xyz="0 0 0.2" rpy="0 0 0"/><parent link="base_link"/><child link="l1"/>
    <axis xyz="0 0 -1"/><limit lower="-2.967" upper="2.967" velocity="6" effort="0"/></joint>
  <joint name="a2" type="revolute"><origin xyz="0.025 0 0.2" rpy="0 0 0"/><parent link="l1"/><child link="l2"/>
    <axis xyz="0 1 0"/><limit lower="-3.14" upper="3.14" velocity="6" effort="0"/></joint>
  <joint name="a3" type="revolute"><origin xyz="0 0 0.455" rpy="0 0 0"/><parent link="l2"/><child link="l3"/>
    <axis xyz="0 1 0"/><limit lower="-3.14" upper="3.14" velocity="6" effort="0"/></joint>
  <joint name="a4" type="revolute"><origin xyz="-0.035 0 0.2" rpy="0 0 0"/><parent link="l3"/><child link="l4"/>
    <axis xyz="0 0 -1"/><limit lower="-6.1" upper="6.1" velocity="6" effort="0"/></joint>
  <joint name="a5" type="revolute"><origin xyz="0 0 0.22" rpy="0 0 0"/><parent link="l4"/><child link="l5"/>
    <axis xyz="0 1 0"/><limit lower="-2.09" upper="2.09" velocity="6" effort="0"/></joint>
  <joint name="a6" type="revolute"><origin xyz="0 0 0.08" rpy="0 0 0"/><parent link="l5"/><child link="l6"/>
    <axis xyz="0 0 -1"/><limit lower="-6.1" upper="6.1" velocity="6" effort="0"/></joint>
  <joint name="flange_joint" type="fixed"><origin xyz="0 0 0" rpy="0 -1.5707963267948966 0"/><parent link="l6"/><child link="flange"/></joint>
</robot>
"""


@pytest.fixture
def kuka_like(tmp_path):
    p = tmp_path / "kuka_like.urdf"
    p.write_text(KUKA_LIKE, encoding="utf-8")
    return load_robot(str(p))


def test_other_ortho_parallel_geometry_is_detected(kuka_like):
    o = kuka_like.opw
    assert o is not None
    assert (o.a1, o.a2, o.b, o.c1, o.c2, o.c3) == pytest.approx((25, -35, 0, 200, 455, 420))
    assert o.signs == (-1, 1, 1, -1, 1, -1)
    assert o.G is not None  # the flange frame is turned
    assert "assumed" in kuka_like.acceleration_note


def test_other_ortho_parallel_geometry_round_trip(kuka_like):
    pytest.importorskip("pinocchio")
    rng = random.Random(6)
    for _ in range(300):
        q = random_joints(kuka_like, rng)
        T = kuka_like.fk_matrix(q)
        assert close_pose(T, kuka_like.fk_pinocchio(q))
        sols = kuka_like.ik(T, near=q)
        assert joint_dist(sols[0], q) < 1e-6
        for s in sols:
            assert close_pose(kuka_like.fk_matrix(s), T)


def test_other_ortho_parallel_geometry_eight_branches(kuka_like):
    T = kuka_like.fk_matrix([20, -10, 80, 30, 40, 50])
    raw = opw_ik(kuka_like.opw, T)
    assert len(raw) == 8
    for s in raw:
        assert close_pose(kuka_like.fk_matrix([math.degrees(a) for a in s]), T)
    assert len({kuka_like.config_of([math.degrees(a) for a in s]) for s in raw}) == 8


def test_a_non_spherical_wrist_is_refused(tmp_path):
    text = KUKA_LIKE.replace('<origin xyz="0 0 0.08" rpy="0 0 0"/><parent link="l5"/>', '<origin xyz="0.01 0 0.08" rpy="0 0 0"/><parent link="l5"/>')
    p = tmp_path / "bent.urdf"
    p.write_text(text, encoding="utf-8")
    robot = load_robot(str(p))
    assert robot.opw is None and "spherical wrist" in robot.opw_reason
    with pytest.raises(IKUnsupported, match="spherical wrist"):
        robot.ik((500, 0, 500, 0, 90, 0))
    robot.fk([10, 20, 30, 40, 50, 60])  # forward kinematics still works
