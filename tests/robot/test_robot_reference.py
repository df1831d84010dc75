"""Forward kinematics against a second, independent description of the arms.

The models in robots/ are written from per-joint origins. Some arms are also published as
ortho-parallel-wrist parameters (a1, a2, b, c1..c4, metres; Brandstötter et al. 2014), kept here
as data for the arms where they are published (the TX2 family). The textbook forward formula of
that description, written here without the robot package, must give the same flange position
within 0.01 mm over random joint positions.
"""

from __future__ import annotations

import math
import random

import pytest

from val3check.robot import load_robot

OPW = {
    "TX2-60": (0, 0, 0.02, 0.375, 0.29, 0.31, 0.07),
    "TX2-60L": (0, 0, 0.02, 0.375, 0.4, 0.45, 0.07),
    "TX2-90": (0.05, 0, 0.05, 0.478, 0.425, 0.425, 0.1),
    "TX2-90L": (0.05, 0, 0.05, 0.478, 0.5, 0.55, 0.1),
    "TX2-90XL": (0.05, 0, 0.05, 0.478, 0.65, 0.65, 0.1),
}


def opw_flange_mm(params, joints_deg):
    """Flange position in the VAL 3 world frame (on axis 1 at the height of axis 2), mm."""
    a1, a2, b, c1, c2, c3, c4 = params
    t1, t2, t3, t4, t5, t6 = (math.radians(j) for j in joints_deg)
    psi3 = math.atan2(a2, c3)
    k = math.hypot(a2, c3)
    # wrist centre in the plane of the arm, then turned by axis 1
    cx1 = c2 * math.sin(t2) + k * math.sin(t2 + t3 + psi3) + a1
    cy1 = b
    cz1 = c2 * math.cos(t2) + k * math.cos(t2 + t3 + psi3)
    cx0 = cx1 * math.cos(t1) - cy1 * math.sin(t1)
    cy0 = cx1 * math.sin(t1) + cy1 * math.cos(t1)
    # axis 6 direction: Rz(t1) Ry(t2 + t3) Rz(t4) Ry(t5) applied to z
    s5, c5 = math.sin(t5), math.cos(t5)
    v = (math.cos(t4) * s5, math.sin(t4) * s5, c5)
    s23, c23 = math.sin(t2 + t3), math.cos(t2 + t3)
    v = (c23 * v[0] + s23 * v[2], v[1], -s23 * v[0] + c23 * v[2])
    v = (math.cos(t1) * v[0] - math.sin(t1) * v[1], math.sin(t1) * v[0] + math.cos(t1) * v[1], v[2])
    return tuple(1000.0 * (c + c4 * d) for c, d in zip((cx0, cy0, cz1), v))


@pytest.mark.parametrize("name", sorted(OPW))
def test_flange_position_matches_the_opw_description(name):
    robot = load_robot(name)
    rng = random.Random(name)
    worst = 0.0
    for _ in range(300):
        joints = [rng.uniform(lo, hi) for lo, hi in robot.joint_limits]
        got = robot.fk(joints)[:3]
        want = opw_flange_mm(OPW[name], joints)
        worst = max(worst, max(abs(g - w) for g, w in zip(got, want)))
    assert worst < 0.01, f"{name}: worst flange position difference {worst:.6f} mm"
