"""Parts grasped and left in the cell, surfaces touched on purpose, solids inside closed meshes."""

from __future__ import annotations

import numpy as np
import pytest

from val3check.collision import Cell, Obstacle, Part, Shape, ToolSolid  # noqa: E402
from val3check.collision.cell import MeshData  # noqa: E402
from val3check.collision.cellfile import trsf_matrix  # noqa: E402

from .helpers import TOOL, MotionSpan, checker, line_motion

TABLE_TOP = -100.0
BRICK = 40.0  # a cube carried with its centre 20 mm below the TCP: its bottom is 40 mm below the TCP


def _cell(margin: float = 5.0, tool_jaws: bool = True) -> Cell:
    c = Cell(path="test", margin_mm=margin)
    c.obstacles.append(Obstacle("table", Shape("box", (600.0, 800.0, 40.0)), "world",
                                trsf_matrix((450.0, 0.0, TABLE_TOP - 20.0, 0, 0, 0))))
    c.obstacles.append(Obstacle("post", Shape("cylinder", (25.0, 300.0)), "world",
                                trsf_matrix((350.0, 250.0, TABLE_TOP + 150.0, 0, 0, 0))))
    if tool_jaws:  # two jaws beside the brick, touching it
        for side in (-1, 1):
            c.tools.append(ToolSolid(f"jaw {side}", "tTool", Shape("box", (10.0, 30.0, 30.0)),
                                     trsf_matrix((side * 25.0, 0.0, 15.0, 0, 0, 0))))
    c.parts.append(Part("brick", "tTool", "close", Shape("box", (BRICK, BRICK, BRICK)), trsf_matrix((0, 0, 20, 0, 0, 0))))
    return c


def _at(x, y, z):
    return (x, y, z)


def test_pick_carry_place_is_clean_and_the_touches_at_both_ends_are_no_near_miss():
    chk = checker(_cell())
    t = 0.0
    pick = (350.0, -150.0, TABLE_TOP + BRICK)  # the brick lies on the table
    place = (450.0, 100.0, TABLE_TOP + BRICK)
    reports = []

    def move(a, b, v=200.0):
        nonlocal t
        times, q = line_motion(a, b, v, t0=t)
        reports.append(chk.check_motion(MotionSpan(len(reports), label=f"{a}->{b}"), times, q))
        t = float(times[-1])

    above = (pick[0], pick[1], pick[2] + 100.0)
    move(above, pick)
    assert chk.gripper("tTool", "close", t) == []
    assert "brick" in chk.carried
    move(pick, above)  # lifted off the table it lay on
    move(above, (place[0], place[1], place[2] + 100.0), 400.0)
    move((place[0], place[1], place[2] + 100.0), place)  # set down on the table
    assert chk.gripper("tTool", "open", t) == []
    assert not chk.carried
    move(place, (place[0], place[1], place[2] + 100.0))  # the jaws leave the brick they let go
    for r in reports:
        assert r.first_contact is None and r.starts_in_collision is None, r.motion.label
        assert not r.too_close, (r.motion.label, r.min_clearance)
    # the brick left on the table is an obstacle now: the next pass through it is a contact
    times, q = line_motion((place[0] - 150.0, place[1], place[2] + 20.0), (place[0] + 50.0, place[1], place[2] + 20.0),
                           200.0, t0=t)
    rep = chk.check_motion(MotionSpan(9), times, q)
    assert rep.first_contact is not None and "part 'brick'" in (rep.first_contact.body_a, rep.first_contact.body_b)


def test_setting_a_part_down_into_the_table_is_a_contact():
    chk = checker(_cell())
    pick = (350.0, -150.0, TABLE_TOP + BRICK)
    times, q = line_motion((pick[0], pick[1], pick[2] + 100.0), pick, 200.0)
    chk.check_motion(MotionSpan(1), times, q)
    chk.gripper("tTool", "close", float(times[-1]))
    times, q = line_motion(pick, (pick[0], pick[1], pick[2] + 100.0), 200.0, t0=float(times[-1]))
    chk.check_motion(MotionSpan(2), times, q)
    low = (400.0, 0.0, TABLE_TOP + BRICK - 2.0)  # 2 mm too low
    times, q = line_motion((low[0], low[1], low[2] + 100.0), low, 200.0, t0=float(times[-1]))
    rep = chk.check_motion(MotionSpan(3), times, q)
    c = rep.first_contact
    assert c is not None and {c.body_a, c.body_b} == {"part 'brick'", "obstacle 'table'"}


def test_a_part_taken_again_where_it_was_left_leaves_the_cell():
    chk = checker(_cell())
    spot = (400.0, 0.0, TABLE_TOP + BRICK)
    up = (spot[0], spot[1], spot[2] + 100.0)
    times, q = line_motion(up, spot, 200.0)
    chk.check_motion(MotionSpan(1), times, q)
    chk.gripper("tTool", "close", float(times[-1]))
    chk.gripper("tTool", "open", float(times[-1]) + 0.1)
    assert len(chk.world.dropped) == 1
    chk.gripper("tTool", "close", float(times[-1]) + 0.2)  # the same brick, taken again
    assert chk.world.dropped == [] and "brick" in chk.carried
    times, q = line_motion(spot, up, 200.0, t0=float(times[-1]) + 0.3)
    rep = chk.check_motion(MotionSpan(2), times, q)
    assert rep.first_contact is None and rep.starts_in_collision is None


def test_a_tool_solid_inside_a_closed_mesh_is_a_collision():
    pytest.importorskip("trimesh")
    import trimesh

    ico = trimesh.creation.icosphere(subdivisions=2, radius=80.0)
    mesh = MeshData("dome.stl", np.asarray(ico.vertices), np.asarray(ico.faces), solid=True)
    c = Cell(path="test")
    c.obstacles.append(Obstacle("dome", Shape("mesh", (), mesh), "world", trsf_matrix((350.0, -200.0, 100.0, 0, 0, 0))))
    c.tools.append(ToolSolid("tip", "tTool", Shape("sphere", (10.0,)), np.eye(4)))
    times, q = line_motion((350.0, -200.0, 100.0), (350.0, -180.0, 100.0), 100.0)  # the tip in the dome's middle
    rep = checker(c).check_motion(MotionSpan(1), times, q)
    s = rep.starts_in_collision
    assert s is not None and s.kind == "inside" and s.body_b == "obstacle 'dome'"
    # the penetration depth: the tip must move its radius past the nearest face (docs/cell.md)
    inradius = float(np.abs((ico.face_normals * ico.triangles_center).sum(axis=1)).min())
    assert s.depth_mm == pytest.approx(inradius + 10.0, abs=1e-6)
    # an open surface holds nothing inside
    open_mesh = MeshData("dome.stl", np.asarray(ico.vertices), np.asarray(ico.faces), solid=False)
    c.obstacles[0] = Obstacle("dome", Shape("mesh", (), open_mesh), "world", trsf_matrix((350.0, -200.0, 100.0, 0, 0, 0)))
    assert checker(c).check_motion(MotionSpan(1), times, q).starts_in_collision is None


def test_a_non_convex_mesh_is_measured_exactly():
    pytest.importorskip("trimesh")
    import trimesh

    # a ring (non-convex): the tip passes through its hole, 20 mm from the inner wall at the closest
    ring = trimesh.creation.annulus(r_min=60.0, r_max=120.0, height=40.0, sections=64)
    mesh = MeshData("ring.stl", np.asarray(ring.vertices), np.asarray(ring.faces), solid=True)
    c = Cell(path="test")
    c.obstacles.append(Obstacle("ring", Shape("mesh", (), mesh), "world",
                                trsf_matrix((380.0, 0.0, 60.0, 0, 0, 0))))
    c.tools.append(ToolSolid("tip", "tTool", Shape("sphere", (10.0,)), np.eye(4)))
    times, q = line_motion((380.0, 0.0, 200.0), (380.0, 0.0, 0.0), 200.0)
    # the tool's flange and wrist follow the tip down the axis: leave them out of this check
    chk = checker(c)
    rep = chk.check_motion(MotionSpan(1), times, q)
    m = rep.min_clearance
    ring_clear = [x for x in (m,) if "ring" in x.body_b]
    assert rep.first_contact is not None or (ring_clear and m.mm <= 60.0 - 10.0 + 0.5)
    # the tip alone down the hole's axis: 60 - 10 = 50 mm from the inner wall (polygon: a little less)
    tip_only = Cell(path="test", obstacles=c.obstacles, tools=c.tools)
    a = checker(tip_only)
    times2, q2 = line_motion((380.0, 0.0, 200.0), (380.0, 0.0, 100.0), 200.0)
    r2 = a.check_motion(MotionSpan(2), times2, q2)
    assert r2.first_contact is None
    assert r2.min_clearance.mm == pytest.approx(60.0 * np.cos(np.pi / 64) - 10.0, abs=0.5) or r2.min_clearance.mm > 0


def test_tool_pose_from_the_program():
    c = Cell(path="test")
    c.obstacles.append(Obstacle("ball", Shape("sphere", (20.0,)), "world", trsf_matrix((395.0, 30.0, 100.0, 0, 0, 0))))
    c.tools.append(ToolSolid("tip", "tTool", Shape("sphere", (10.0,)), np.eye(4)))
    times, q = line_motion((350.0, -200.0, 100.0), (350.0, 200.0, 100.0), 250.0)
    # the tool variable's value decides where its solids are: here 15 mm closer to the ball
    longer = (15.0, 0.0, TOOL[2], 0.0, 0.0, 0.0)
    rep = checker(c, tools={"tTool": longer}).check_motion(MotionSpan(1), times, q)
    assert rep.min_clearance.mm == pytest.approx(15.0 - 15.0, abs=0.5)
    missing = checker(c, tools={})
    rep = missing.check_motion(MotionSpan(1), times, q)
    assert rep.min_clearance is None or "tTool" not in rep.min_clearance.body_a
    assert any("tTool" in p.message for p in missing.problems)


def test_touching_at_a_grasp_is_allowed_only_until_the_bodies_are_apart():
    chk = checker(_cell())
    pick = (350.0, -150.0, TABLE_TOP + BRICK - 1.0)  # the brick taken 1 mm into the table (a teaching error)
    times, q = line_motion((pick[0], pick[1], pick[2] + 100.0), pick, 200.0)
    assert chk.check_motion(MotionSpan(1), times, q).first_contact is None  # the jaws stay above the table
    chk.gripper("tTool", "close", float(times[-1]))
    up = (pick[0], pick[1], pick[2] + 60.0)
    t1, q1 = line_motion(pick, up, 200.0, t0=float(times[-1]))
    t2, q2 = line_motion(up, (pick[0], pick[1], pick[2] - 1.0), 200.0, t0=float(t1[-1]))
    # one motion: up and back down 2 mm deeper: lifting off is allowed, coming back is not
    T = np.concatenate([t1, t2[1:]])
    Q = np.concatenate([q1, q2[1:]])
    rep = chk.check_motion(MotionSpan(2), T, Q)
    assert rep.starts_in_collision is None
    c = rep.first_contact
    assert c is not None and c.time > t1[-1] and "part 'brick'" in (c.body_a, c.body_b)


def test_jaws_overlapping_a_part_they_let_go_may_leave_it():
    c = _cell()
    c.tools[:] = [ToolSolid(f"jaw {side}", "tTool", Shape("box", (12.0, 30.0, 30.0)),  # 1 mm into the brick
                            trsf_matrix((side * 25.0, 0.0, 15.0, 0, 0, 0))) for side in (-1, 1)]
    chk = checker(c)
    spot = (400.0, 0.0, TABLE_TOP + BRICK + 5.0)
    up = (spot[0], spot[1], spot[2] + 100.0)
    times, q = line_motion(up, spot, 200.0)
    chk.check_motion(MotionSpan(1), times, q)
    chk.gripper("tTool", "close", float(times[-1]))
    chk.gripper("tTool", "open", float(times[-1]) + 0.1)  # left 5 mm above the table: a drop, not a crash
    times, q = line_motion(spot, up, 200.0, t0=float(times[-1]) + 0.2)
    rep = chk.check_motion(MotionSpan(2), times, q)
    assert rep.starts_in_collision is None and rep.first_contact is None


def test_a_solid_inside_a_non_convex_closed_mesh_is_found():
    pytest.importorskip("trimesh")
    import trimesh

    # a thick ring (non-convex, cut into pieces): the tip starts inside its material, far from the
    # pieces' boxes
    ring = trimesh.creation.annulus(r_min=60.0, r_max=220.0, height=120.0, sections=512)
    assert not ring.is_convex and ring.is_watertight
    mesh = MeshData("ring.stl", np.asarray(ring.vertices), np.asarray(ring.faces), solid=True)
    c = Cell(path="test")
    c.obstacles.append(Obstacle("ring", Shape("mesh", (), mesh), "world", trsf_matrix((350.0 + 140.0, -200.0, 100.0, 0, 0, 0))))
    c.tools.append(ToolSolid("tip", "tTool", Shape("sphere", (10.0,)), np.eye(4)))
    times, q = line_motion((350.0, -200.0, 100.0), (350.0, -190.0, 100.0), 50.0)
    chk = checker(c)
    rep = chk.check_motion(MotionSpan(1), times, q)
    s = rep.starts_in_collision
    assert s is not None and s.kind == "inside" and s.body_b == "obstacle 'ring'"
    # the penetration depth: the tip's centre is 60 mm from the top and bottom faces (70 from the
    # sides): it must move 60 + 10 to get out
    assert s.depth_mm == pytest.approx(70.0, abs=1e-6)
    # a part left there is reported too
    c.parts.append(Part("pin", "tTool", "close", Shape("sphere", (5.0,)), np.eye(4)))
    chk = checker(c)
    chk.check_motion(MotionSpan(1), times, q)
    chk.gripper("tTool", "close", float(times[-1]))
    drops = chk.gripper("tTool", "open", float(times[-1]) + 0.1)
    assert drops and drops[0].obstacle == "obstacle 'ring'"


def test_part_let_go_while_the_arm_moves_is_no_near_miss_as_the_tool_leaves_it():
    # open() after resetMotion() (stop()) may release a part while the arm still decelerates: the
    # tool and the part move apart during the next motion without being a near miss, and a contact
    # with the part once apart is still reported
    from val3check.collision import Cell, Part, Shape, ToolSolid
    from val3check.collision.cellfile import trsf_matrix

    from .helpers import DT, MotionSpan, checker, line_motion

    cell = Cell(path="test", margin_mm=10.0)
    cell.tools.append(ToolSolid("tip", "tTool", Shape("sphere", (10.0,)), np.eye(4)))
    cell.parts.append(Part("cube", "tTool", "close", Shape("box", (40.0, 40.0, 40.0)), trsf_matrix((0, 0, 30, 0, 0, 0))))
    chk = checker(cell)
    t, Q = line_motion((400.0, 0.0, 100.0), (400.0, 0.0, 160.0), 100.0)
    chk.gripper("tTool", "close", 0.0, joints=Q[0])
    # released 20 mm up the line (the part is left there, touching the tip), the arm goes on up
    k = int(round(0.2 / DT))
    chk.gripper("tTool", "open", float(t[k]), joints=Q[k])
    rep = chk.check_motion(MotionSpan(1), t[k + 1:], Q[k + 1:])
    assert rep.first_contact is None and not rep.too_close
    # and back down into the cube: a contact
    t2, Q2 = line_motion((400.0, 0.0, 160.0), (400.0, 0.0, 100.0), 100.0, t0=float(t[-1]))
    rep = chk.check_motion(MotionSpan(2), t2, Q2)
    assert rep.first_contact is not None and "part 'cube'" in (rep.first_contact.body_a, rep.first_contact.body_b)
