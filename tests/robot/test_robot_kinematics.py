"""Forward kinematics: the VAL 3 pose convention, three engines that agree, and public descriptions."""

from __future__ import annotations

import math
import random

import pytest

from val3check.robot import load_robot
from val3check.robot.kinematics import matrix_trsf, pose_error, trsf_matrix

from .robothelp import ARMS, random_joints


def _rx(a):
    c, s = math.cos(math.radians(a)), math.sin(math.radians(a))
    return [[1, 0, 0], [0, c, -s], [0, s, c]]


def _ry(a):
    c, s = math.cos(math.radians(a)), math.sin(math.radians(a))
    return [[c, 0, s], [0, 1, 0], [-s, 0, c]]


def _rz(a):
    c, s = math.cos(math.radians(a)), math.sin(math.radians(a))
    return [[c, -s, 0], [s, c, 0], [0, 0, 1]]


def _mm(A, B):
    return [[sum(A[i][k] * B[k][j] for k in range(3)) for j in range(3)] for i in range(3)]


def test_trsf_is_rx_then_ry_prime_then_rz_second():
    # 9.3.2: turn rx about x, then ry about the new y', then rz about the new z'' (intrinsic x-y'-z'')
    T = trsf_matrix((250, 350, 450, 20, 10, 30))
    R = _mm(_mm(_rx(20), _ry(10)), _rz(30))
    assert max(abs(T[i][j] - R[i][j]) for i in range(3) for j in range(3)) < 1e-15
    assert (T[0][3], T[1][3], T[2][3]) == (250, 350, 450)
    assert matrix_trsf(T) == pytest.approx((250, 350, 450, 20, 10, 30), abs=1e-12)


def test_trsf_round_trip_and_ranges():
    rng = random.Random(7)
    for _ in range(3000):
        t = (rng.uniform(-1e3, 1e3), rng.uniform(-1e3, 1e3), rng.uniform(-1e3, 1e3),
             rng.uniform(-180, 180), rng.uniform(-180, 180), rng.uniform(-180, 180))
        back = matrix_trsf(trsf_matrix(t))
        dp, da = pose_error(trsf_matrix(back), trsf_matrix(t))
        assert dp < 1e-9 and da < 1e-12
        rx, ry, rz = back[3:]
        assert all(-180 < a <= 180 for a in (rx, ry, rz))
        assert sum(-90 <= a <= 90 for a in (rx, ry, rz)) >= 2  # 9.3.2


@pytest.mark.parametrize("ry", [90 - 1e-7, 90 - 1e-10, -90 + 1e-9, 89.99])
def test_trsf_near_gimbal_lock_stays_exact(ry):
    # The conversion is geometry's (val3check/geometry/rotation.py): within GIMBAL_EPS of the
    # gimbal lock (|cos ry| < 1e-10) the canonical form writes ry = ±90 exactly and rx = 0, which
    # moves the rotation by less than 1e-10 rad; farther away the round trip is exact.
    from val3check.geometry.rotation import GIMBAL_EPS

    snapped = abs(math.cos(math.radians(ry))) < GIMBAL_EPS
    for rx, rz in ((35, 20), (-170, 160), (120, -45)):
        T = trsf_matrix((1, 2, 3, rx, ry, rz))
        t = matrix_trsf(T)
        dp, da = pose_error(trsf_matrix(t), T)
        if snapped:
            assert t[3] == 0 and abs(t[4]) == 90 and da < GIMBAL_EPS
        else:
            assert da < 1e-13


def test_trsf_conversion_is_the_geometry_convention():
    # one convention: fk() and here()/compose()/position() write the same triple, including the
    # manual's exception (rx = 180, ry = 0 is kept rather than turned into {0, 180, rz -+ 180})
    from val3check.geometry import rotation as R

    assert matrix_trsf(trsf_matrix((0, 0, 0, 180, 0, 150))) == (0, 0, 0, 180, 0, 150)
    rng = random.Random(3)
    for _ in range(500):
        t = (1, 2, 3, rng.uniform(-180, 180), rng.uniform(-180, 180), rng.uniform(-180, 180))
        assert matrix_trsf(trsf_matrix(t))[3:] == R.angles_of(R.matrix(*t[3:]))


@pytest.mark.parametrize("ry", [90, -90])
def test_trsf_gimbal_lock_sets_rx_null(ry):
    t = matrix_trsf(trsf_matrix((0, 0, 0, 35, ry, 20)))
    assert t[3] == 0 and t[4] == pytest.approx(ry)
    dp, da = pose_error(trsf_matrix(t), trsf_matrix((0, 0, 0, 35, ry, 20)))
    assert da < 1e-12


@pytest.mark.parametrize("name", ARMS)
def test_closed_form_chain_and_pinocchio_agree(name):
    pytest.importorskip("pinocchio")
    robot = load_robot(name)
    rng = random.Random(name)
    for _ in range(300):
        q = random_joints(robot, rng)
        A, B, C = robot.fk_matrix(q), robot.fk_chain(q), robot.fk_pinocchio(q)
        for other in (B, C):
            dp, da = pose_error(A, other)
            assert dp < 1e-9 and da < 1e-12


def test_fk_with_a_tool():
    robot = load_robot("TX2-60")
    q = [10, -20, 95, 30, 40, -50]
    tool = (0, 0, 120, 0, 0, 0)
    F, T = robot.fk_matrix(q), robot.fk_matrix(q, tool)
    assert [T[i][3] for i in range(3)] == pytest.approx([F[i][3] + 120 * F[i][2] for i in range(3)], abs=1e-9)


# ---- independent public descriptions ---------------------------------------------------------------
# Brandstötter et al.'s ortho-parallel parameters (metres) as published with the ROS-Industrial
# Stäubli descriptions (opw_parameters_*.yaml; for the arms without such a file, the same numbers
# read from their public URDF/xacro: joint 2 offset a1, lateral offset b, arm c2, forearm c3,
# flange c4, base c1 = height of axis 2 above the mounting plane).
PUBLIC_OPW = {
    "TX60": (0.0, 0.0, 0.020, 0.375, 0.290, 0.310, 0.070),
    "TX60L": (0.0, 0.0, 0.020, 0.375, 0.400, 0.450, 0.070),
    "TX90": (0.050, 0.0, 0.050, 0.478, 0.425, 0.425, 0.100),
    "TX90L": (0.050, 0.0, 0.050, 0.478, 0.500, 0.550, 0.100),
    "TX90XL": (0.050, 0.0, 0.050, 0.478, 0.650, 0.650, 0.100),
    "TX2-60": (0.0, 0.0, 0.020, 0.375, 0.290, 0.310, 0.070),
    "TX2-60L": (0.0, 0.0, 0.020, 0.375, 0.400, 0.450, 0.070),
    "TX2-90": (0.050, 0.0, 0.050, 0.478, 0.425, 0.425, 0.100),
    "TX2-90L": (0.050, 0.0, 0.050, 0.478, 0.500, 0.550, 0.100),
    "TX2-90XL": (0.050, 0.0, 0.050, 0.478, 0.650, 0.650, 0.100),
    "RX160": (0.150, 0.0, 0.0, 0.550, 0.825, 0.625, 0.110),
    "RX160L": (0.150, 0.0, 0.0, 0.550, 0.825, 0.925, 0.110),
}


def _opw_reference(params, q_deg):
    """Flange position (mm) above the mounting plane from the OPW parameters, by rotation matrices."""
    a1, a2, b, c1, c2, c3, c4 = (v * 1000 for v in params)
    j1, j2, j3, j4, j5, j6 = q_deg
    R1 = _rz(j1)
    R2 = _mm(R1, _ry(j2))
    R3 = _mm(R2, _ry(j3))
    R6 = _mm(_mm(_mm(R3, _rz(j4)), _ry(j5)), _rz(j6))

    def act(R, v):
        return [sum(R[i][k] * v[k] for k in range(3)) for i in range(3)]

    p = [0.0, 0.0, c1]
    for R, v in ((R1, [a1, b, 0.0]), (R2, [0.0, 0.0, c2]), (R3, [a2, 0.0, c3]), (R6, [0.0, 0.0, c4])):
        p = [x + y for x, y in zip(p, act(R, v))]
    return p, R6


@pytest.mark.parametrize("name", sorted(PUBLIC_OPW))
def test_fk_matches_the_public_description(name):
    robot = load_robot(name)
    c1 = PUBLIC_OPW[name][3] * 1000
    rng = random.Random(f"public {name}")
    for _ in range(500):
        q = random_joints(robot, rng)
        p, R = _opw_reference(PUBLIC_OPW[name], q)
        T = robot.fk_matrix(q)
        # the VAL 3 world frame is c1 above the mounting plane (on axis 1 at the height of axis 2)
        assert math.dist([T[0][3], T[1][3], T[2][3] + c1], p) < 0.01
        assert max(abs(T[i][j] - R[i][j]) for i in range(3) for j in range(3)) < 1e-9


TX60_ROS_INDUSTRIAL = """<?xml version="1.0"?>
<robot name="staubli_tx60">
  <val3check arm="TX60 (ROS-Industrial layout)" world_frame="base" flange_frame="{flange}"/>
  <link name="base_link"/><link name="link_1"/><link name="link_2"/><link name="link_3"/>
  <link name="link_4"/><link name="link_5"/><link name="link_6"/>
  <link name="base"/><link name="flange"/><link name="tool0"/>
  <joint name="joint_1" type="revolute"><origin xyz="0 0 0.375" rpy="0 0 0"/><parent link="base_link"/><child link="link_1"/>
    <axis xyz="0 0 1"/><limit lower="-3.141592653589793" upper="3.141592653589793" effort="126" velocity="7.592182246175334"/></joint>
  <joint name="joint_2" type="revolute"><origin xyz="0 0.2175 0" rpy="0 0 0"/><parent link="link_1"/><child link="link_2"/>
    <axis xyz="0 1 0"/><limit lower="-2.2252947962927703" upper="2.2252947962927703" effort="71" velocity="7.155849933176751"/></joint>
  <joint name="joint_3" type="revolute"><origin xyz="0 0 0.290" rpy="0 0 0"/><parent link="link_2"/><child link="link_3"/>
    <axis xyz="0 1 0"/><limit lower="-2.4870941840919194" upper="2.4870941840919194" effort="38" velocity="9.42477796076938"/></joint>
  <joint name="joint_4" type="revolute"><origin xyz="0 -0.1975 0" rpy="0 0 0"/><parent link="link_3"/><child link="link_4"/>
    <axis xyz="0 0 1"/><limit lower="-4.71238898038469" upper="4.71238898038469" effort="7" velocity="17.366329719804337"/></joint>
  <joint name="joint_5" type="revolute"><origin xyz="0 0 0.310" rpy="0 0 0"/><parent link="link_4"/><child link="link_5"/>
    <axis xyz="0 1 0"/><limit lower="-2.1380283336930777" upper="2.3125612588924866" effort="8" velocity="18.587756305847964"/></joint>
  <joint name="joint_6" type="revolute"><origin xyz="0 0 0.07" rpy="0 0 0"/><parent link="link_5"/><child link="link_6"/>
    <axis xyz="0 0 1"/><limit lower="-4.71238898038469" upper="4.71238898038469" effort="2" velocity="25.219958655107842"/></joint>
  <joint name="base_link-base" type="fixed"><origin xyz="0 0 0.375" rpy="0 0 0"/><parent link="base_link"/><child link="base"/></joint>
  <joint name="joint_6-flange" type="fixed"><origin xyz="0 0 0" rpy="0 -1.5707963267948966 0"/><parent link="link_6"/><child link="flange"/></joint>
  <joint name="flange-tool0" type="fixed"><origin xyz="0 0 0" rpy="0 1.5707963267948966 0"/><parent link="flange"/><child link="tool0"/></joint>
</robot>
"""


def test_ros_industrial_layout_of_the_tx60_gives_the_same_arm(tmp_path):
    """The public ROS-Industrial TX60 description splits the 20 mm lateral offset differently
    (+217.5 mm at axis 2, -197.5 mm at axis 4) and names the frames base/tool0."""
    p = tmp_path / "tx60.urdf"
    p.write_text(TX60_ROS_INDUSTRIAL.format(flange="tool0"), encoding="utf-8")
    theirs, ours = load_robot(str(p)), load_robot("TX60")
    assert theirs.opw is not None and theirs.opw.G is None
    rng = random.Random(60)
    for _ in range(300):
        q = random_joints(ours, rng)
        dp, da = pose_error(theirs.fk_matrix(q), ours.fk_matrix(q))
        assert dp < 1e-9 and da < 1e-12
        sols = theirs.ik(ours.fk(q), near=q)
        assert max(abs(a - b) for a, b in zip(sols[0], q)) < 1e-6
