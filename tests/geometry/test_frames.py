"""frame (9.4) and tool (9.5) trees: position, link, =, ==, setFrame, errors 160-165."""

from __future__ import annotations

import pytest

from val3check.geometry import frames, points
from val3check.geometry.frames import Frame, Tool, new_flange, new_world
from val3check.geometry.points import Point
from val3check.geometry.trsf import Trsf, distance
from val3check.language.runtime_errors import Val3RuntimeError

from .helpers import trsf_close


def code(fn, *args):
    with pytest.raises(Val3RuntimeError) as e:
        fn(*args)
    return e.value.code


@pytest.fixture
def world():
    return new_world()


@pytest.fixture
def flange():
    return new_flange()


# --- positions in the tree --------------------------------------------------------------------


def test_world_in_world_is_identity(world):
    assert frames.position(world, world) == Trsf()


def test_position_of_frames(world):
    f1 = Frame(Trsf(100, 0, 0, 0, 0, 90), world, name="f1")
    f2 = Frame(Trsf(10, 0, 0, 0, 0, 0), f1, name="f2")
    assert frames.position(f1, world) == Trsf(100, 0, 0, 0, 0, 90)
    p = frames.position(f2, world)
    assert trsf_close(p, Trsf(100, 10, 0, 0, 0, 90))
    assert frames.position(f2, f1) == Trsf(10, 0, 0, 0, 0, 0)
    back = frames.position(world, f2)
    assert trsf_close(back, p.inverse())
    assert trsf_close(frames.position(f1, f2), Trsf(-10, 0, 0))


def test_link_keeps_the_position_in_the_reference(world):
    f1 = Frame(Trsf(100, 0, 0), world, name="f1")
    f2 = Frame(Trsf(0, 50, 0), world, name="f2")
    frames.link(f2, f1)
    assert f2.trsf == Trsf(0, 50, 0)
    assert frames.position(f2, world) == Trsf(100, 50, 0)


def test_reteaching_a_frame_moves_what_is_linked_to_it(world):
    # 9.4.2: re-teach the object's frame and every point linked to it follows
    fObj = Frame(Trsf(100, 0, 0), world, name="fObj")
    p = Point(Trsf(0, 0, 10), ("lefty", "epositive", "wpositive"), fObj)
    fSub = Frame(Trsf(1, 0, 0), fObj)
    assert points.position(p, world) == Trsf(100, 0, 10)
    fObj.trsf = Trsf(0, 200, 0)
    assert points.position(p, world) == Trsf(0, 200, 10)
    assert frames.position(fSub, world) == Trsf(1, 200, 0)
    # "=" into the node has the same effect (the node keeps its identity)
    frames.assign(fObj, Frame(Trsf(5, 5, 5), world))
    assert points.position(p, world) == Trsf(5, 5, 15)


def test_assign_copies_position_and_reference(world):
    f1 = Frame(Trsf(100, 0, 0), world)
    f2 = Frame(Trsf(1, 2, 3), f1)
    f3 = Frame(Trsf(), world)
    frames.assign(f3, f2)
    assert f3.ref is f1 and f3.trsf == Trsf(1, 2, 3) and f3.trsf is not f2.trsf
    assert f3 == f2
    f3.trsf.x = 7
    assert f2.trsf.x == 1 and f3 != f2


def test_frame_equality(world):
    f1 = Frame(Trsf(100, 0, 0), world)
    a = Frame(Trsf(1, 2, 3), f1)
    b = Frame(Trsf(1, 2, 3), f1)
    c = Frame(Trsf(101, 2, 3), world)  # same place in world, other reference
    assert a == b and not (a != b)
    assert a != c
    assert frames.position(a, world) == frames.position(c, world)
    f = Frame(local=True)
    frames.assign(f, world)  # f = world: a copy of world, linked to world
    assert f == world and f.ref is world
    assert frames.position(f, world) == Trsf()


# --- tools ------------------------------------------------------------------------------------


def test_tool_tree_and_distance_example(flange):
    # 9.3.4 example: distance(position(tTool1, flange), position(tTool2, flange))
    t1 = Tool(Trsf(0, 0, 100), flange, name="tTool1")
    t2 = Tool(Trsf(0, 0, 20, 0, 90, 0), t1, name="tTool2")
    assert frames.position(t1, flange) == Trsf(0, 0, 100)
    assert trsf_close(frames.position(t2, flange), Trsf(0, 0, 120, 0, 90, 0))
    assert distance(frames.position(t1, flange), frames.position(t2, flange)) == pytest.approx(20)
    assert trsf_close(frames.position(t1, t2), Trsf(0, 0, 20, 0, 90, 0).inverse())


def test_tool_fields_and_equality(flange):
    valve1, valve2 = object(), object()
    t1 = Tool(Trsf(0, 0, 100), flange, gripper=valve1, otime=0.5, ctime=0.2)
    t2 = Tool(Trsf(0, 0, 100), flange, gripper=valve1, otime=0.5, ctime=0.2)
    assert t1 == t2
    for field, value in (("gripper", valve2), ("otime", 0.6), ("ctime", 0.1), ("trsf", Trsf(0, 0, 101)),
                         ("ref", t2)):
        t3 = Tool(Trsf(0, 0, 100), flange, gripper=valve1, otime=0.5, ctime=0.2)
        setattr(t3, field, value)
        assert t3 != t1, field
    t4 = Tool(local=True)
    frames.assign(t4, t1)
    assert t4 == t1 and (t4.gripper, t4.otime, t4.ctime, t4.ref) == (valve1, 0.5, 0.2, flange)


def test_tool_link(flange):
    t1 = Tool(Trsf(0, 0, 100), flange)
    t2 = Tool(Trsf(0, 0, 10), flange)
    frames.link(t2, t1)
    assert frames.position(t2, flange) == Trsf(0, 0, 110)
    assert t2.trsf == Trsf(0, 0, 10)


def test_frame_and_tool_trees_do_not_mix(world, flange):
    with pytest.raises(TypeError):
        frames.link(Frame(), flange)
    with pytest.raises(TypeError):
        frames.position(Tool(Trsf(), flange), world)


# --- errors 160-165 ---------------------------------------------------------------------------


def test_frame_without_reference_is_163(world):
    f = Frame(local=True)
    assert code(frames.position, f, world) == 163
    assert code(frames.position, world, f) == 163
    child = Frame(Trsf(), f)  # a frame whose reference is undefined
    assert code(frames.position, child, world) == 163
    p = Point(Trsf(), ref=child)
    assert code(points.position, p, world) == 163


def test_frame_loop_is_163(world):
    a, b = Frame(Trsf(), world), Frame(Trsf(), world)
    frames.link(a, b)
    frames.link(b, a)
    assert code(frames.position, a, world) == 163


def test_tool_without_reference_is_164(flange):
    t = Tool(local=True)
    assert code(frames.position, t, flange) == 164
    assert code(frames.position, Tool(Trsf(), t), flange) == 164


def test_point_without_reference_is_162(world):
    p = Point(local=True)
    assert code(points.position, p, world) == 162
    assert code(points.distance, p, Point(ref=world)) == 162


@pytest.mark.parametrize("change", ["field", "link", "assign", "setframe"])
def test_modified_world_is_161(world, change):
    f = Frame(Trsf(1, 0, 0), world)
    other = Frame(Trsf(5, 0, 0), world)
    assert frames.position(f, world) == Trsf(1, 0, 0)
    if change == "field":
        world.trsf.x = 10
    elif change == "link":
        frames.link(world, other)
    elif change == "assign":
        frames.assign(world, other)
    else:
        a, b, c = (Point(Trsf(*v), ref=world) for v in ((1, 1, 0), (2, 1, 0), (1, 2, 0)))
        assert points.set_frame(a, b, c, world) == 0
    assert code(frames.position, f, world) == 161
    assert code(frames.position, world, world) == 161
    assert code(points.position, Point(ref=f), other) == 161


def test_world_assigned_itself_is_not_modified(world):
    frames.assign(world, world)
    g = Frame(local=True)
    frames.assign(g, world)
    frames.assign(world, g)  # world = a copy of world
    assert frames.position(world, world) == Trsf()


@pytest.mark.parametrize("change", ["field", "link", "assign"])
def test_modified_flange_is_160(flange, change):
    t = Tool(Trsf(0, 0, 100), flange)
    other = Tool(Trsf(0, 0, 5), flange)
    if change == "field":
        flange.trsf.rz = 90
    elif change == "link":
        frames.link(flange, other)
    else:
        frames.assign(flange, other)
    assert code(frames.position, t, flange) == 160


def test_global_linked_to_local_is_165(world, flange):
    local_f = Frame(Trsf(), world, local=True)
    global_f = Frame(Trsf(), world)
    assert code(frames.link, global_f, local_f) == 165
    assert code(frames.assign, global_f, Frame(Trsf(), local_f, local=True)) == 165
    global_p = Point(ref=world)
    assert code(points.link, global_p, local_f) == 165
    assert code(points.assign, global_p, Point(ref=local_f, local=True)) == 165
    local_t = Tool(Trsf(), flange, local=True)
    assert code(frames.link, Tool(Trsf(), flange), local_t) == 165
    # local to local, local to global: fine
    frames.link(Frame(local=True), local_f)
    frames.link(local_f, global_f)
    points.link(Point(local=True), local_f)
    assert global_f.ref is world and global_p.ref is world


# --- setFrame ---------------------------------------------------------------------------------


def _pt(ref, x, y, z, cfg=("lefty", "epositive", "wpositive")):
    return Point(Trsf(x, y, z, 180, 0, 45), cfg, ref)


def test_set_frame_builds_the_frame(world):
    f = Frame(Trsf(), world, name="fPallet")
    rc = points.set_frame(_pt(world, 100, 200, 0), _pt(world, 100, 300, 0), _pt(world, 0, 250, 0), f)
    assert rc == 0
    # origin at the first point, X towards the second, Y on the side of the third
    assert trsf_close(frames.position(f, world), Trsf(100, 200, 0, 0, 0, 90))
    assert f.ref is world


def test_set_frame_in_the_frame_reference(world):
    parent = Frame(Trsf(0, 0, 500, 0, 0, 0), world)
    f = Frame(Trsf(), parent)
    base = Frame(Trsf(10, 0, 0), world)
    rc = points.set_frame(_pt(base, 0, 0, 0), _pt(base, 10, 0, 0), _pt(base, 3, 5, 0), f)
    assert rc == 0 and f.ref is parent
    assert trsf_close(f.trsf, Trsf(10, 0, -500))
    # a local frame without reference takes the reference frame of the origin point
    g = Frame(local=True)
    assert points.set_frame(_pt(base, 0, 0, 0), _pt(base, 0, 0, 10), _pt(base, 0, 10, 0), g) == 0
    assert g.ref is base
    assert trsf_close(g.trsf, Trsf(0, 0, 0, 0, -90, 0))


def test_set_frame_return_codes(world):
    f = Frame(Trsf(1, 2, 3), world)
    o = _pt(world, 100, 100, 100)
    assert points.set_frame(o, _pt(world, 100, 100, 100), _pt(world, 0, 0, 0), f) == 1
    assert points.set_frame(o, _pt(world, 200, 100, 100), _pt(world, 300, 100, 100), f) == 2
    assert points.set_frame(o, _pt(world, 200, 100, 100), _pt(world, 150, 100, 100), f) == 2
    assert f.trsf == Trsf(1, 2, 3)  # unchanged on failure


def test_set_frame_point_without_reference_is_162(world):
    f = Frame(Trsf(), world)
    assert code(points.set_frame, _pt(world, 0, 0, 0), _pt(None, 1, 0, 0), _pt(world, 0, 1, 0), f) == 162


def test_kept_gives_the_value_again_only_while_the_chain_is_the_very_same_objects():
    """geometry.frames.kept (issue 29): each input of root_pose changed in turn computes afresh."""
    from val3check.geometry.frames import kept, pose_values

    world = Frame(is_root=True, name="world")
    other_world = Frame(is_root=True, name="world")
    base = Frame(Trsf(100.0, 0.0, 0.0, 0.0, 0.0, 30.0), world)
    f = Frame(Trsf(0.0, 50.0, 0.0, 90.0, 0.0, 0.0), base)
    table: dict = {}
    calls = []

    def compute(node):
        calls.append(node)
        return pose_values(node)

    first = kept(table, f, compute)
    assert kept(table, f, compute) is first and len(calls) == 1
    changes = [lambda: setattr(f.trsf, "x", 1.0), lambda: setattr(f.trsf, "y", 2.0), lambda: setattr(f.trsf, "z", 3.0),
               lambda: setattr(f.trsf, "rx", 4.0), lambda: setattr(f.trsf, "ry", 5.0),
               lambda: setattr(f.trsf, "rz", 6.0), lambda: setattr(f, "trsf", Trsf(7.0)),
               lambda: setattr(base.trsf, "x", 8.0), lambda: setattr(base, "trsf", Trsf(9.0)),
               lambda: setattr(f, "ref", world), lambda: setattr(f, "ref", base),
               lambda: setattr(base, "ref", other_world), lambda: setattr(f.trsf, "x", f.trsf.x + 0.0)]
    for k, change in enumerate(changes):
        n = len(calls)
        change()
        assert kept(table, f, compute) == pose_values(f), k
        assert len(calls) == n + 1, k  # computed afresh (the last: an equal float, another object)
    base.is_root = True  # a root with a reference: 161 each time, nothing kept
    for _ in range(2):
        with pytest.raises(Val3RuntimeError) as e:
            kept(table, f, compute)
        assert e.value.code == 161
