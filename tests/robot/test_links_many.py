"""The links' poses at many joint positions at once (robot/links.py `poses_many`, issue 29): the
same values as one position at a time, whatever the positions around it, for a six-axis arm and
a SCARA (a prismatic axis); `links` computes only what those links need, with the same values."""

from __future__ import annotations

import numpy as np
import pytest

from val3check.robot import load_robot
from val3check.robot.links import arm_links


@pytest.mark.parametrize("name", ["TX2-60", "TS2-60"])
def test_many_positions_give_each_position_s_poses(name):
    model = load_robot(name)
    links = arm_links(model)
    rng = np.random.default_rng(7)
    lo, hi = np.array(model.joint_limits, dtype=float).T
    Q = rng.uniform(lo, hi, (300, len(lo)))
    many = links.poses_many(Q)
    assert set(many) == set(links.links)
    for i in (0, 1, 150, 299):
        one = links.poses(Q[i])
        alone = links.poses_many(Q[i:i + 1])
        for link in links.links:
            assert np.allclose(many[link][i], one[link], atol=1e-9)  # the one-position forward kinematics
            assert np.array_equal(many[link][i], alone[link][0])  # the same bits in any batch
    flange = links.poses_many(Q, [model.flange_frame])
    assert model.flange_frame in flange and len(flange) < len(many)
    assert all(np.array_equal(flange[k], many[k]) for k in flange)


def test_a_prismatic_axis_slides_along_its_axis():
    model = load_robot("TS2-60")
    links = arm_links(model)
    k = [i for i, p in enumerate(links.prismatic) if p]
    assert k  # the SCARA's axis 3
    Q = np.zeros((2, len(model.joint_names)))
    Q[1, k[0]] = 25.0
    P = links.poses_many(Q)[model.flange_frame]
    assert np.linalg.norm(P[1][:3, 3] - P[0][:3, 3]) == pytest.approx(25.0, abs=1e-9)
