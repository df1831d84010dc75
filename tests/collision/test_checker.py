"""The collision checker against analytic answers (issue 14, "What will be checked")."""

from __future__ import annotations

import math

import numpy as np
import pytest

from val3check.collision import Cell, Obstacle, Part, Shape, ToolSolid  # noqa: E402
from val3check.collision.cellfile import trsf_matrix  # noqa: E402
from val3check.geometry import Trsf  # noqa: E402

from .helpers import DT, ROBOT, TOOL, MotionSpan, checker, joint_motion, line_motion, read_cell, write_cell

TIP = 10.0  # radius of the tool's tip ball, centred on the TCP of tTool


def _cell(*obstacles, margin=0.0, parts=(), tip=True) -> Cell:
    c = Cell(path="test", margin_mm=margin)
    c.obstacles.extend(obstacles)
    if tip:
        c.tools.append(ToolSolid("tip", "tTool", Shape("sphere", (TIP,)), np.eye(4)))
    c.parts.extend(parts)
    return c


def _ball(x, y, z, r, name="ball", frame="world") -> Obstacle:
    return Obstacle(name, Shape("sphere", (r,)), frame, trsf_matrix((x, y, z, 0, 0, 0)))


def _box(size, at, name="box", frame="world") -> Obstacle:
    return Obstacle(name, Shape("box", tuple(size)), frame, trsf_matrix(tuple(at) + (0, 0, 0)[: 6 - len(at)]))


# A straight TCP line at 250 mm/s: y from -200 to 200 at x = 350, z = 100; it passes (350, 30, 100)
# at 230 mm from the start, 0.92 s, exactly on a sample.
A, B, V = (350.0, -200.0, 100.0), (350.0, 200.0, 100.0), 250.0


@pytest.mark.parametrize("gap", [3.0, 15.0, 47.3])
def test_sphere_beside_a_movel_line_clearance(gap):
    times, Q = line_motion(A, B, V)
    r = 20.0
    ball = _ball(350.0 + gap + r + TIP, 30.0, 100.0, r)
    rep = checker(_cell(ball)).check_motion(MotionSpan(1), times, Q)
    assert rep.first_contact is None and rep.starts_in_collision is None
    m = rep.min_clearance
    assert abs(m.mm - gap) <= 0.5
    # where: a measured value, at its time (the line runs at 250 mm/s from y = -200)
    y = -200.0 + V * m.time
    assert m.mm == pytest.approx(math.hypot(gap + r + TIP, y - 30.0) - r - TIP, abs=1e-3)
    assert abs(m.time - 0.92) <= 0.1
    assert {m.body_a, m.body_b} == {"tool tTool 'tip'", "obstacle 'ball'"}
    # the per-sample clearance is a lower bound everywhere, exact at the minimum
    k = int(round(m.time / DT))
    assert rep.exact[k] and rep.clearance[k] == m.mm
    assert rep.clearance.min() >= m.mm - 0.4
    assert (rep.clearance <= _true_clearance(times, Q, ball, r) + 1e-3).all()


def _true_clearance(times, Q, ball, r):
    """Tool ball to obstacle ball, at every sample: centre distance minus both radii."""
    c = ball.pose[:3, 3]
    out = []
    for q in Q:
        tcp = np.array(ROBOT.fk_matrix(q, tool=TOOL))[:, 3]
        out.append(np.linalg.norm(tcp - c) - r - TIP)
    return np.array(out)


def test_sphere_on_the_movel_line_contact_time():
    times, Q = line_motion(A, B, V)
    r, off = 20.0, 20.0  # ball centre 20 mm beside the line: the tip meets it 22.36 mm before the closest point
    rep = checker(_cell(_ball(350.0 + off, 30.0, 100.0, r))).check_motion(MotionSpan(1), times, Q)
    c = rep.first_contact
    assert c is not None and rep.starts_in_collision is None
    expected = (230.0 - math.sqrt((r + TIP) ** 2 - off**2)) / V
    assert abs(c.time - expected) <= DT
    assert {c.body_a, c.body_b} == {"tool tTool 'tip'", "obstacle 'ball'"}
    assert c.depth_mm > 0.0 and c.kind == "contact"
    assert math.dist(c.point, (350.0 + off, 30.0, 100.0)) == pytest.approx(r, abs=1.0)


def test_fast_movej_touching_a_thin_box_only_between_two_samples():
    # the stretched arm turns on axis 1 at 600 deg/s: the tip (770 mm out) moves 32 mm per sample
    q0 = np.array([-30.0, 90.0, 0.0, 0.0, 0.0, 0.0])
    q1 = np.array([30.0, 90.0, 0.0, 0.0, 0.0, 0.0])
    times, Q = joint_motion(q0, q1, 0.1)
    k = 12  # between samples 12 and 13
    mid = 0.5 * (Q[k][0] + Q[k + 1][0])
    tip = np.array(ROBOT.fk_matrix([mid, 90, 0, 0, 0, 0], tool=TOOL))[:, 3]
    # a plate 4 mm thick across the tip's path where the tip is halfway between the two samples,
    # only as high and as deep as the tip ball: nothing else of the arm reaches it
    plate = Obstacle("plate", Shape("box", (60.0, 4.0, 40.0)), "world",
                     trsf_matrix((tip[0], tip[1], tip[2], 0, 0, math.degrees(math.atan2(tip[1], tip[0])))))
    rep = checker(_cell(plate)).check_motion(MotionSpan(1), times, Q)
    # at the two samples around it the tip is clear of the plate ...
    assert rep.clearance[k] > 0.0 and rep.clearance[k + 1] > 0.0
    # ... and still the contact between them is reported, at its time
    c = rep.first_contact
    assert c is not None and {c.body_a, c.body_b} == {"tool tTool 'tip'", "obstacle 'plate'"}
    assert times[k] < c.time < times[k + 1]


def test_tool_hits_a_pallet_placed_in_a_program_computed_frame():
    pallet = _box((200.0, 200.0, 20.0), (0.0, 0.0, 10.0), name="pallet", frame="fPallet[2]")
    base = Trsf(300.0, -150.0, 0.0, 0.0, 0.0, 0.0)

    def frames(name, time):  # as the program computes it: fPallet[1] shifted by one pitch
        assert name == "fPallet[2]"
        return base * Trsf(100.0, 50.0, 0.0, 0.0, 0.0, 0.0)

    times, Q = line_motion((400.0, -100.0, 100.0), (400.0, -100.0, 10.0), 100.0)
    rep = checker(_cell(pallet), frames=frames).check_motion(MotionSpan(1), times, Q)
    c = rep.first_contact
    assert c is not None and {c.body_a, c.body_b} == {"tool tTool 'tip'", "obstacle 'pallet'"}
    assert abs(c.time - (100.0 - 30.0) / 100.0) <= DT  # the tip ball meets the top (z = 20) at TCP z = 30
    # the same motion with the frame computed elsewhere: clean
    rep = checker(_cell(pallet), frames={"fPallet[2]": (300.0, 250.0, 0.0, 0.0, 0.0, 0.0)}).check_motion(
        MotionSpan(1), times, Q)
    assert rep.first_contact is None and rep.min_clearance.mm > 50.0


def test_self_collision_of_a_folded_arm():
    q0 = [-25.0, 13.0, 90.0, 154.0, 73.0, -172.0]
    q1 = [-25.0, 13.0, 150.0, 154.0, 73.0, -172.0]  # the forearm folded onto the shoulder
    times, Q = joint_motion(q0, q1, 0.5)
    rep = checker(_cell(tip=False)).check_motion(MotionSpan(1), times, Q)
    assert rep.starts_in_collision is None
    c = rep.first_contact
    assert c is not None and c.kind == "self"
    assert c.body_a.split()[0] in ("link_1", "link_2", "base_link") and c.body_b.split()[0] in ("link_4", "link_5")
    assert 0.0 < c.time < times[-1]


def test_carried_part_hits_a_wall_after_close():
    wall = _box((20.0, 600.0, 200.0), (440.0, 0.0, -100.0), name="wall")  # x 430..450, top at z = 0
    part = Part("bar", "tTool", "close", Shape("box", (40.0, 40.0, 120.0)), trsf_matrix((0, 0, 60, 0, 0, 0)))
    cell = _cell(wall, parts=[part])
    times, Q = line_motion((300.0, 0.0, 50.0), (520.0, 0.0, 50.0), 200.0)
    chk = checker(cell)
    rep = chk.check_motion(MotionSpan(1), times, Q)
    assert rep.first_contact is None  # nothing carried: the tip passes 40 mm above the wall
    back_t, back_q = line_motion((520.0, 0.0, 50.0), (300.0, 0.0, 50.0), 200.0, t0=float(times[-1]))
    chk.check_motion(MotionSpan(2), back_t, back_q)
    assert chk.gripper("tTool", "close", float(back_t[-1])) == []
    again_t, again_q = line_motion((300.0, 0.0, 50.0), (440.0, 0.0, 50.0), 200.0, t0=float(back_t[-1]) + 0.2)
    rep = chk.check_motion(MotionSpan(3), again_t, again_q)
    c = rep.first_contact
    assert c is not None and {c.body_a, c.body_b} == {"part 'bar'", "obstacle 'wall'"}
    assert abs(c.time - again_t[0] - (430.0 - 20.0 - 300.0) / 200.0) <= DT
    # open leaves it where it is: in the wall
    drops = chk.gripper("tTool", "open", float(again_t[-1]), source="line 12")
    assert drops and drops[0].part == "part 'bar'" and drops[0].obstacle == "obstacle 'wall'"
    assert drops[0].source == "line 12" and drops[0].depth_mm > 1.0
    assert not chk.carried


def test_clean_cell_reported_clean():
    cell = _cell(_box((700.0, 1200.0, 40.0), (600.0, 0.0, -240.0), name="table"),
                 _ball(600.0, 300.0, 300.0, 50.0),
                 _box((20.0, 1500.0, 1500.0), (-600.0, 0.0, 300.0), name="fence"), margin=5.0)
    chk = checker(cell)
    t1, q1 = line_motion((350.0, -200.0, 50.0), (350.0, 200.0, 50.0), 500.0)
    t2, q2 = joint_motion(q1[-1], [60.0, 30.0, 90.0, 0.0, 60.0, 0.0], 0.6, t0=float(t1[-1]))
    for i, (t, q) in enumerate(((t1, q1), (t2, q2))):
        rep = chk.check_motion(MotionSpan(i), t, q)
        assert rep.first_contact is None and rep.starts_in_collision is None and not rep.contacts
        assert not rep.too_close and rep.min_clearance.mm > 5.0
        assert (rep.clearance > 0.0).all()
    assert chk.problems == []


def test_motion_starting_in_collision():
    times, Q = line_motion(A, B, V)
    rep = checker(_cell(_ball(350.0, -200.0, 80.0, 15.0))).check_motion(MotionSpan(1), times, Q)
    s = rep.starts_in_collision
    assert s is not None and s.time == 0.0 and {s.body_a, s.body_b} == {"tool tTool 'tip'", "obstacle 'ball'"}


def test_margin_turns_a_near_miss_into_a_warning():
    times, Q = line_motion(A, B, V)
    near = _ball(350.0 + 4.0 + 20.0 + TIP, 30.0, 100.0, 20.0)
    assert checker(_cell(near, margin=5.0)).check_motion(MotionSpan(1), times, Q).too_close
    assert not checker(_cell(near, margin=3.0)).check_motion(MotionSpan(1), times, Q).too_close
    rep = checker(_cell(near, margin=5.0)).check_motion(MotionSpan(1), times, Q)
    closer = rep.clearance < 5.0
    assert closer.any() and rep.exact[closer].all()  # every sample closer than the margin is measured


def test_obstacle_in_a_frame_the_program_does_not_have_is_left_out_and_said():
    times, Q = line_motion(A, B, V)
    chk = checker(_cell(_ball(350.0, 30.0, 100.0, 20.0, frame="fNone")), frames={})
    rep = chk.check_motion(MotionSpan(1), times, Q)
    assert rep.first_contact is None
    assert len(chk.problems) == 1 and "fNone" in chk.problems[0].message


def test_between_samples_the_given_path_is_followed():
    # q_at: positions between samples from the same IK; the result is that of the samples alone
    times, Q = line_motion(A, B, V)

    def q_at(t):
        s = min(1.0, t * V / 400.0)
        y = -200.0 + 400.0 * s
        return ROBOT.solve((350.0, y, 100.0, 180.0, 0.0, 0.0), None, Q[min(int(t / DT), len(Q) - 1)], tool=TOOL)

    ball = _ball(350.0 + 15.0 + 20.0 + TIP, 30.0, 100.0, 20.0)
    a = checker(_cell(ball)).check_motion(MotionSpan(1), times, Q)
    b = checker(_cell(ball)).check_motion(MotionSpan(1), times, Q, q_at=q_at)
    assert abs(a.min_clearance.mm - b.min_clearance.mm) < 0.05
    # q_at.many: the same positions in one call, the same result
    calls = []

    def many(ts):
        calls.append(len(ts))
        return np.array([q_at(t) for t in ts])

    q_at.many = many
    c = checker(_cell(ball)).check_motion(MotionSpan(1), times, Q, q_at=q_at)
    assert calls == [len(times) - 1]
    assert c.min_clearance == b.min_clearance and np.array_equal(c.clearance, b.clearance)


def test_same_input_same_output():
    times, Q = line_motion(A, B, V)
    ball = _ball(350.0 + 5.0 + 20.0 + TIP, 30.0, 100.0, 20.0)
    r1 = checker(_cell(ball, margin=10.0)).check_motion(MotionSpan(1), times, Q)
    r2 = checker(_cell(ball, margin=10.0)).check_motion(MotionSpan(1), times, Q)
    assert r1.min_clearance == r2.min_clearance and r1.checks == r2.checks
    assert np.array_equal(r1.clearance, r2.clearance) and np.array_equal(r1.exact, r2.exact)


def test_bad_trajectories_are_refused_clearly():
    chk = checker(_cell())
    with pytest.raises(ValueError, match="at least one sample"):
        chk.check_motion(MotionSpan(1), [], np.zeros((0, 6)))
    with pytest.raises(ValueError, match="6 axes"):
        chk.check_motion(MotionSpan(1), [0.0, 0.004], np.zeros((2, 5)))
    with pytest.raises(ValueError, match="finite"):
        chk.check_motion(MotionSpan(1), [0.0, math.nan], np.zeros((2, 6)))


def test_a_single_sample_motion_is_checked():
    rep = checker(_cell(_ball(350.0, -200.0, 80.0, 15.0))).check_motion(
        MotionSpan(1), [0.0], [ROBOT.solve((350.0, -200.0, 100.0, 180.0, 0.0, 0.0), None, None, tool=TOOL)])
    assert rep.starts_in_collision is not None


def test_cell_file_end_to_end(tmp_path):
    path = write_cell(tmp_path, """
margin_mm = 2
[[obstacle]]
name = "ball"
shape = "sphere"
radius = 20
at = { x = 395, y = 30, z = 100 }
[[tool]]
name = "tip"
tool = "tTool"
shape = "sphere"
radius = 10
""")
    times, Q = line_motion(A, B, V)
    rep = checker(read_cell(path)).check_motion(MotionSpan(1), times, Q)
    assert abs(rep.min_clearance.mm - 15.0) <= 0.5 and not rep.too_close


def test_a_scara_quill_coming_down_on_a_box():
    # the prismatic axis 3: every point of the quill and the flange moves by |Δq3| mm
    from val3check.collision import CollisionChecker, arm_model
    from val3check.robot import load_robot

    scara = load_robot("TS2-60")
    q0, q1 = [30.0, 40.0, 150.0, 0.0], [30.0, 40.0, 0.0, 0.0]
    x, y, _ = np.array(scara.fk_matrix(q0))[:, 3]
    box = _box((60.0, 60.0, 40.0), (x, y, 20.0), name="fixture")  # top at z = 40
    cell = Cell(path="test", obstacles=[box], tools=[ToolSolid("tip", "flange", Shape("sphere", (10.0,)), np.eye(4))])
    times, Q = joint_motion(q0, q1, 0.5)  # axis 3 at 300 mm/s
    z0 = np.array(scara.fk_matrix(q0))[2, 3]
    z1 = np.array(scara.fk_matrix(q1))[2, 3]
    rep = CollisionChecker(arm_model(scara), cell).check_motion(MotionSpan(1), times, Q)
    c = rep.first_contact
    assert c is not None and {c.body_a, c.body_b} == {"tool flange 'tip'", "obstacle 'fixture'"}
    expected = 0.5 * (z0 - 50.0) / (z0 - z1)  # the tip's bottom (10 below the flange) reaches z = 40
    assert abs(c.time - expected) <= DT


def test_per_sample_clearance_never_exceeds_the_true_clearance():
    """Against a brute-force oracle: every solid of the arm and the tool measured against every
    obstacle at every sample, the triangles of meshes included."""
    import fcl
    import trimesh

    from val3check.collision import arm_model
    from val3check.collision.bodies import make_bodies
    from val3check.collision.cell import MeshData

    ring = trimesh.creation.annulus(r_min=40.0, r_max=90.0, height=60.0, sections=96)
    cell = _cell(_box((700.0, 1200.0, 40.0), (600.0, 0.0, -240.0), name="table"),
                 _ball(420.0, 150.0, 20.0, 35.0),
                 Obstacle("ring", Shape("mesh", (), MeshData("ring.stl", np.asarray(ring.vertices),
                                                            np.asarray(ring.faces), solid=True)), "world",
                          trsf_matrix((300.0, -250.0, -60.0, 0, 0, 0))), margin=20.0)
    q0 = ROBOT.solve((300.0, -250.0, 120.0, 180.0, 0.0, 0.0), None, None, tool=TOOL)
    q1 = ROBOT.solve((380.0, 150.0, 90.0, 180.0, 0.0, 30.0), None, q0, tool=TOOL)
    times, Q = joint_motion(q0, q1, 0.8)
    chk = checker(cell)
    rep = chk.check_motion(MotionSpan(1), times, Q)
    assert rep.first_contact is None
    arm = arm_model(ROBOT)
    tool = make_bodies("tool", "tTool", "tip", "tip", "sphere", (TIP,), np.array(
        [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, TOOL[2]], [0, 0, 0, 1.0]]))
    obstacles = [b for o in cell.obstacles for b in make_bodies(
        "obstacle", o.name, o.name, o.name, o.shape.kind, o.shape.size, o.pose,
        *((o.shape.mesh.vertices, o.shape.mesh.faces) if o.shape.mesh else (None, None)))]
    for b in obstacles:
        b.place(np.eye(4))
    for k, q in enumerate(Q):
        P = arm.links.poses(q)
        moving = [(b, P[link]) for link, bodies in arm.bodies.items() for b in bodies]
        moving += [(b, P[arm.flange_link]) for b in tool]
        true = math.inf
        for b, frame in moving:
            b.place(frame)
            for o in obstacles:
                d = fcl.distance(b.exact_obj(), o.exact_obj(), fcl.DistanceRequest(), fcl.DistanceResult())
                true = min(true, d)
        assert rep.clearance[k] <= true + 1e-6, (k, rep.clearance[k], true)
        if rep.exact[k]:
            assert rep.clearance[k] == pytest.approx(true, abs=1e-3)
    assert rep.min_clearance.mm == pytest.approx(min(rep.clearance[rep.exact]), abs=1e-9)
