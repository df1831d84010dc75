"""The arm as collision bodies: link poses, the allowed-collision matrix, the motion bound."""

from __future__ import annotations

import math
import random

import numpy as np
import pytest

from val3check.collision import ArmModel, arm_model  # noqa: E402
from val3check.collision.acm import acm_inputs, compute_acm, read_acm  # noqa: E402
from val3check.collision.bodies import make_bodies  # noqa: E402
from val3check.robot import from_urdf, load_robot  # noqa: E402
from val3check.robot.catalog import example_robot_urdf  # noqa: E402
from val3check.robot.links import arm_links  # noqa: E402

from .helpers import ARM, ROBOT


@pytest.mark.parametrize("name", ["TX2-60", "TX90XL", "RX160L"])
def test_link_poses_agree_with_the_kinematics(name):
    robot = load_robot(name)
    links = arm_links(robot)
    rng = random.Random(3)
    Q = [[rng.uniform(lo, hi) for lo, hi in robot.joint_limits] for _ in range(50)]
    many = links.poses_many(np.array(Q))
    for i, q in enumerate(Q):
        P = links.poses(q)
        assert np.allclose(P[robot.flange_frame][:3], np.array(robot.fk_matrix(q)), atol=1e-9)
        assert all(np.allclose(P[k], many[k][i], atol=1e-9) for k in P)
    assert np.allclose(links.poses([0] * 6)["world"], np.eye(4))  # the VAL 3 world frame is the reference


def test_reach_bound_holds_in_every_configuration():
    links = ARM.links
    rng = random.Random(5)
    for _ in range(300):
        q = [rng.uniform(lo, hi) for lo, hi in ROBOT.joint_limits]
        P = links.poses(q)
        for link in ("link_3", "link_5", "flange"):
            for j, r in links.reach_from_joint(link).items():
                child = [e for e in links.edges.values() if e.index == j][0].child
                axis_p, axis_d = P[child][:3, 3], P[child][:3, :3] @ links.edges[child].axis
                o = P[link][:3, 3] - axis_p
                assert np.linalg.norm(o - (o @ axis_d) * axis_d) <= r + 1e-6


def test_the_catalogue_matrix_of_the_tx2_60():
    acm = ARM.acm
    assert acm.source == "stored" and acm.trials == 10_000 and acm.seed == 0  # robots/generate.py
    checked = sorted((a, b) for a in ARM.bodies for b in ARM.bodies if a < b and not acm.allowed(a, b))
    # what remains to check: the forearm, wrist and flange against the base, shoulder and upper arm
    assert checked == [("base_link", "link_4"), ("base_link", "link_5"), ("base_link", "link_6"),
                       ("link_1", "link_4"), ("link_1", "link_5"), ("link_1", "link_6"),
                       ("link_2", "link_5"), ("link_2", "link_6")]
    assert acm.disabled[("base_link", "link_1")] == "adjacent"
    assert acm.disabled[("base_link", "link_2")] == "user"  # robots/generate.py: beside the base column
    assert acm.disabled[("link_4", "link_6")] == "user"
    assert acm.disabled[("link_2", "link_4")] == "default"  # in contact at the zero position
    assert acm.disabled[("link_1", "link_3")] == "never"


def test_the_matrix_is_deterministic_and_follows_moveit_rules():
    links = ARM.links
    a = compute_acm(links, ARM.bodies, ROBOT.joint_limits, trials=2000, seed=4)
    b = compute_acm(links, ARM.bodies, ROBOT.joint_limits, trials=2000, seed=4)
    assert a == b
    # adjacent pairs are exactly the links one joint apart
    adjacent = {p for p, why in a.disabled.items() if why == "adjacent"}
    assert adjacent == {("base_link", "link_1"), ("link_1", "link_2"), ("link_2", "link_3"), ("link_3", "link_4"),
                        ("link_4", "link_5"), ("link_5", "link_6")}
    # a pair found "never" in collision is indeed never in collision on other random positions
    never = [p for p, why in a.disabled.items() if why == "never"]
    rng = random.Random(99)
    import fcl

    for _ in range(500):
        q = [rng.uniform(lo, hi) for lo, hi in ROBOT.joint_limits]
        P = links.poses(q)
        for x, y in never:
            for bx in ARM.bodies[x]:
                bx.place(P[x])
                for by in ARM.bodies[y]:
                    by.place(P[y])
                    assert not fcl.collide(bx.obj, by.obj, fcl.CollisionRequest(), fcl.CollisionResult())


def _without_stored_matrix(text: str) -> str:
    """A catalogue URDF's text without the matrix robots/generate.py stored in it."""
    import re

    return re.sub(r"    <!-- allowed-collision matrix.*?(?=  </val3check>)", "", text, count=1, flags=re.S)


def test_a_urdf_may_carry_its_whole_matrix(tmp_path):
    text = _without_stored_matrix(open(ROBOT.source).read()).replace(
        "  </val3check>", '    <acm trials="5" seed="1"/>\n'
        '    <disable_collisions link1="link_1" link2="base_link" reason="Adjacent"/>\n  </val3check>')
    path = tmp_path / "arm.urdf"
    path.write_text(text)
    declared, head = read_acm(str(path))
    assert head == (5, 1, None) and declared[("base_link", "link_1")] == "adjacent"
    model = ArmModel(from_urdf(path))
    assert model.acm.source == "urdf" and model.acm.trials == 5
    assert not model.acm.allowed("link_2", "link_3")  # only what the URDF says


def test_an_arm_with_mesh_solids():
    urdf = example_robot_urdf("ur_description/urdf/ur5_robot.urdf")
    if urdf is None:
        pytest.skip("example-robot-data is not installed")
    ur5 = from_urdf(urdf, world_frame="base_link", flange_frame="tool0")
    model = arm_model(ur5)
    assert len(model.bodies) == 8 and sum(len(b) for b in model.bodies.values()) > 8  # pieces of meshes
    assert model.acm.disabled[("base_link", "shoulder_link")] == "adjacent"
    assert model.touch_links[0] == "wrist_3_link"


@pytest.mark.parametrize("seed", range(2))
def test_the_motion_bound_is_never_exceeded(seed):
    """Along a straight joint-space segment from q0 to q1, the distance from any fixed point to the
    bodies of a link (or of a tool on the flange) changes by at most Σ|Δq_j|·w_j times the fraction
    of the segment travelled: the bound the checker's advancement relies on."""
    import fcl

    rng = random.Random(seed)
    tool = make_bodies("tool", "t", "t", "t", "box", (60.0, 30.0, 150.0), np.array(
        [[1, 0, 0, 20.0], [0, 1, 0, 0], [0, 0, 1, 90.0], [0, 0, 0, 1]]))
    groups = [(link, bodies) for link, bodies in ARM.bodies.items()] + [(ARM.flange_link, tool)]
    probe = fcl.CollisionObject(fcl.Sphere(1e-3), fcl.Transform())
    for _ in range(15):
        q0 = np.array([rng.uniform(lo, hi) for lo, hi in ROBOT.joint_limits])
        q1 = q0 + np.array([rng.uniform(-10.0, 10.0) for _ in range(6)])
        for link, bodies in groups:
            bound = float(np.abs(np.radians(q1 - q0)) @ ARM.weights(link, bodies))
            P0 = ARM.links.poses(q0)[link]
            centre = P0[:3, 3] + P0[:3, :3] @ bodies[0].local[:3, 3]
            points = [centre + rng.uniform(60.0, 300.0) * _unit(rng) for _ in range(6)]

            def dist(q, x):
                P = ARM.links.poses(q)[link]
                probe.setTranslation(x)
                best = math.inf
                for b in bodies:
                    b.place(P)
                    best = min(best, fcl.distance(b.obj, probe, fcl.DistanceRequest(), fcl.DistanceResult()))
                return best

            start = [dist(q0, x) for x in points]
            for s in np.linspace(0.0, 1.0, 21)[1:]:
                q = q0 + s * (q1 - q0)
                for x, d0 in zip(points, start):
                    assert abs(dist(q, x) - d0) <= s * bound + 1e-6, (link, s, bound)


def _unit(rng) -> np.ndarray:
    v = np.array([rng.gauss(0, 1) for _ in range(3)])
    return v / np.linalg.norm(v)


def test_a_solid_of_revolution_does_not_move_when_its_own_joint_turns():
    w = ARM.weights("link_4", ARM.bodies["link_4"])  # the forearm tube, on axis 4
    assert w[3] == 0.0 and w[2] > 0.0
    assert ARM.weights("link_1", ARM.bodies["link_1"])[0] == 0.0  # the shoulder drum on axis 1
    assert math.isclose(ARM.weights("link_5", ARM.bodies["link_5"])[4],
                        max(b.from_line(np.zeros(3), np.array([0.0, 1.0, 0.0])) for b in ARM.bodies["link_5"]))


@pytest.mark.parametrize("name", ["TX2-60", "RX160L", "TS2-60", "TP80"])
def test_the_stored_matrix_of_a_catalogue_arm_is_the_one_computed(name):
    robot = load_robot(name)
    stored = ArmModel(robot).acm
    assert stored.source == "stored"
    user = {p: why for p, why in stored.disabled.items() if why == "user"}
    arm = ArmModel(robot, acm=stored)
    fresh = compute_acm(arm.links, arm.bodies, robot.joint_limits, user=user)
    assert fresh.disabled == stored.disabled and (fresh.trials, fresh.seed) == (stored.trials, stored.seed)


# each input of the stored matrix changed in the URDF's text: (old, new)
CHANGES = {
    "a solid": ('<cylinder radius="0.11" length="0.265"/>', '<cylinder radius="0.12" length="0.265"/>'),
    "a joint limit": (None, None),  # joint_2's upper limit, below
    "a joint origin": (None, None),
    "a user pair": ('<disable_collisions link1="link_4" link2="link_6" reason="user"/>', ""),
    "trials": ('<acm trials="10000"', '<acm trials="9000"'),
    "seed": ('seed="0" inputs', 'seed="1" inputs'),
}


@pytest.mark.parametrize("what", sorted(CHANGES))
def test_a_stored_matrix_is_used_only_for_the_inputs_it_was_computed_for(tmp_path, what):
    import re

    text = open(ROBOT.source).read()
    old, new = CHANGES[what]
    if what == "a joint limit":
        old = re.search(r'<joint name="joint_2" type="revolute">.*?<limit lower="[^"]*" upper="[^"]*"', text, re.S).group(0)
        new = re.sub(r'upper="[^"]*"$', 'upper="1.5"', old)
    elif what == "a joint origin":
        old = re.search(r'<joint name="joint_3" type="revolute">.*?<origin xyz="[^"]*"', text, re.S).group(0)
        new = re.sub(r'xyz="([^ ]*) ([^ ]*) ([^"]*)"$', r'xyz="\1 \2 0.31"', old)
    assert old in text and old != new
    path = tmp_path / "arm.urdf"
    path.write_text(text.replace(old, new, 1))
    robot = from_urdf(path)
    acm = ArmModel(robot).acm
    assert acm.source == "computed", what
    declared, (trials, seed, inputs) = read_acm(str(path))
    user = {p: why for p, why in declared.items() if why == "user"}
    arm = ArmModel(robot, acm=acm)
    assert inputs != acm_inputs(arm.links, arm.bodies, robot.joint_limits, user, trials, seed)
    assert acm == compute_acm(arm.links, arm.bodies, robot.joint_limits, trials, seed, user=user)
    # the same text unchanged: the stored matrix; without it: computed, the same
    path.write_text(text)
    assert ArmModel(from_urdf(path)).acm.source == "stored"
    path.write_text(_without_stored_matrix(text))
    again = ArmModel(from_urdf(path)).acm
    assert again.source == "computed" and again.disabled == ARM.acm.disabled


def test_the_digest_of_the_inputs_ignores_the_last_bit_and_sees_a_real_change():
    from val3check.collision.acm import _bits

    x = np.array([290.0, 0.1 + 0.2, -1e-12, 375.00000000000006, 3.141592653589793])
    assert _bits(x) == _bits(np.nextafter(x, np.inf)) == _bits(np.nextafter(x, -np.inf))  # sin, cos, inv of another libm
    assert _bits(x) != _bits(x + np.array([0.0, 0.0, 0.0, 0.0, 1e-6]))
    assert _bits([-0.0]) == _bits([0.0])


def test_one_urdf_with_other_limits_is_another_model():
    # the ACM samples the joint limits: a robot file overriding them must not share the model
    import dataclasses

    robot = load_robot("tx2-60")
    narrow = dataclasses.replace(robot, joint_limits=tuple((lo / 2, hi / 2) for lo, hi in robot.joint_limits))
    assert arm_model(robot) is arm_model(dataclasses.replace(robot))
    other = arm_model(narrow)
    assert other is not arm_model(robot)
    assert arm_model(robot).acm.source == "stored" and other.acm.source == "computed"  # the digest saw the limits
