"""point (9.6): position, distance, compose, appro, link, =, == and the manual's examples."""

from __future__ import annotations

import pytest

from val3check.geometry import frames, points
from val3check.geometry.frames import Frame, new_world
from val3check.geometry.points import Point
from val3check.geometry.trsf import Trsf, distance
from val3check.language.runtime_errors import Val3RuntimeError

from .helpers import canonical_ok, same_rotation, trsf_close

CFG = ("lefty", "epositive", "wpositive")


@pytest.fixture
def world():
    return new_world()


def code(fn, *args):
    with pytest.raises(Val3RuntimeError) as e:
        fn(*args)
    return e.value.code


def test_position_of_a_point(world):
    f = Frame(Trsf(100, 0, 50, 0, 0, 90), world)
    p = Point(Trsf(10, 0, 0, 180, 0, 0), CFG, f)
    w = points.position(p, world)
    assert trsf_close(w, Trsf(100, 10, 50, 180, 0, -90))  # Rz(90) Rx(180) = Rx(180) Rz(-90)
    assert canonical_ok(w.rx, w.ry, w.rz)
    assert trsf_close(points.position(p, f), p.trsf)
    g = Frame(Trsf(0, 0, 50), world)
    assert trsf_close(points.position(p, g), Trsf(100, 10, 0, 180, 0, -90))


def test_position_example_distance_in_world(world):
    # 9.6.3: distance(position(pPoint1, world), position(pPoint2, world)) is distance(pPoint1, pPoint2)
    f1 = Frame(Trsf(100, 0, 0, 0, 0, 90), world)
    f2 = Frame(Trsf(0, 300, -20, 30, 20, 10), f1)
    p1 = Point(Trsf(10, 20, 30, 180, 0, 0), CFG, f1)
    p2 = Point(Trsf(-5, 7, 2, 0, 90, 0), CFG, f2)
    d = points.distance(p1, p2)
    assert d == pytest.approx(distance(points.position(p1, world), points.position(p2, world)))
    assert d != pytest.approx(distance(p1.trsf, p2.trsf))


def test_compose_example_orientation_then_position(world):
    # 9.6.3 example
    fReference = Frame(Trsf(500, -200, 100, 0, 0, 30), world)
    pPosition = Point(Trsf(400, 100, 300, 180, 0, 0), CFG, world)
    trTransformation = Trsf(10, 20, 30, 0, 0, 45)
    # modification of the orientation without modification of the position
    pResultat = points.compose(pPosition, fReference, trTransformation)
    assert not trsf_close(pResultat.trsf, pPosition.trsf)
    assert (pResultat.trsf.x, pResultat.trsf.y) != pytest.approx((400, 100))  # the rotation moved it
    pResultat.trsf.x = pPosition.trsf.x
    pResultat.trsf.y = pPosition.trsf.y
    pResultat.trsf.z = pPosition.trsf.z
    assert same_rotation(pResultat.trsf, Trsf(0, 0, 0, 0, 0, 45) * pPosition.trsf)  # turned 45 about z
    # modification of the position without modification of the orientation
    trTransformation.rx = trTransformation.ry = trTransformation.rz = 0
    before = pResultat.trsf.copy()
    pResultat = points.compose(pResultat, fReference, trTransformation)
    assert (pResultat.trsf.rx, pResultat.trsf.ry, pResultat.trsf.rz) == (before.rx, before.ry, before.rz)
    # the translation is expressed in the axes of fReference (rotated 30 degrees about z)
    moved = Trsf(0, 0, 0, 0, 0, 30) * Trsf(10, 20, 30)
    assert (pResultat.trsf.x - before.x, pResultat.trsf.y - before.y, pResultat.trsf.z - before.z) == \
        pytest.approx((moved.x, moved.y, moved.z))
    assert pResultat.ref is world and pResultat.config == CFG


def test_compose_rotation_turns_about_the_reference_origin(world):
    f = Frame(Trsf(100, 0, 0), world)
    p = Point(Trsf(110, 0, 0), CFG, world)
    r = points.compose(p, f, Trsf(0, 0, 0, 0, 0, 90))
    assert trsf_close(r.trsf, Trsf(100, 10, 0, 0, 0, 90))
    # at the origin of the reference: only the orientation changes
    q = Point(Trsf(100, 0, 0), CFG, world)
    r = points.compose(q, f, Trsf(0, 0, 0, 0, 0, 90))
    assert (r.trsf.x, r.trsf.y, r.trsf.z) == pytest.approx((100, 0, 0))


def test_compose_keeps_reference_and_config(world):
    f = Frame(Trsf(1, 2, 3, 10, 20, 30), world)
    g = Frame(Trsf(-4, 5, 6, 0, 0, 90), world)
    p = Point(Trsf(7, 8, 9, 180, 0, 0), ("righty", "enegative", "wfree"), f)
    r = points.compose(p, g, Trsf(1, 0, 0, 0, 0, 10))
    assert r.ref is f and r.config == ("righty", "enegative", "wfree")
    expect = frames.position(g, world) * Trsf(1, 0, 0, 0, 0, 10) * frames.position(g, world).inverse() * \
        points.position(p, world)
    assert trsf_close(points.position(r, world), expect, 1e-9)


def test_appro_example_100mm_above(world):
    # 9.6.3: movej(appro(pDestination, {0,0,-100,0,0,0}), flange, mDesc): 100 mm above the point
    pDestination = Point(Trsf(400, 200, 50, 180, 0, 90), CFG, world)
    a = points.appro(pDestination, Trsf(0, 0, -100, 0, 0, 0))
    assert (a.trsf.x, a.trsf.y, a.trsf.z) == pytest.approx((400, 200, 150))
    assert (a.trsf.rx, a.trsf.ry, a.trsf.rz) == (180, 0, 90)  # orientation kept exactly
    assert a.ref is world and a.config == CFG and a is not pDestination
    # in a frame: the transformation is in the point's own axes
    f = Frame(Trsf(0, 0, 0, 0, 90, 0), world)
    p = Point(Trsf(10, 0, 0), CFG, f)
    a = points.appro(p, Trsf(0, 0, -100))
    assert a.trsf == Trsf(10, 0, -100)
    r = points.appro(p, Trsf(5, 0, 0, 0, 0, 90))
    assert trsf_close(r.trsf, p.trsf * Trsf(5, 0, 0, 0, 0, 90))


def test_point_without_reference_is_162(world):
    p = Point(Trsf(1, 2, 3), CFG, None, local=True)
    q = Point(Trsf(), CFG, world)
    assert code(points.compose, p, world, Trsf()) == 162
    assert code(points.appro, p, Trsf()) == 162
    assert code(points.position, p, world) == 162
    assert code(points.distance, q, p) == 162


def test_link_point(world):
    f = Frame(Trsf(100, 0, 0), world)
    p = Point(Trsf(1, 2, 3), CFG, world)
    points.link(p, f)
    assert p.trsf == Trsf(1, 2, 3) and p.ref is f
    assert points.position(p, world) == Trsf(101, 2, 3)
    p2 = Point(local=True)
    points.link(p2, world)  # initialises a local point
    assert points.position(p2, world) == Trsf()


def test_point_assign_and_equality(world):
    f = Frame(Trsf(100, 0, 0), world)
    p1 = Point(Trsf(1, 2, 3), CFG, f)
    p2 = Point(local=True)
    points.assign(p2, p1)
    assert p2 == p1 and p2.ref is f and p2.config == CFG and p2.trsf is not p1.trsf
    # the configuration is not compared (9.6.2)
    p2.config = ("righty", "enegative", "wnegative")
    assert p2 == p1
    # same world position, other reference frame: not equal
    p3 = Point(Trsf(101, 2, 3), CFG, world)
    assert points.position(p3, world) == points.position(p1, world)
    assert p3 != p1
    p2.trsf.z = 4
    assert p2 != p1


def test_appro_raises_what_world_pose_raises(world):
    """appro checks the point's reference as world_pose does (without computing the pose it does
    not use): the same code and message for no reference, a frame without reference, a loop of
    references and a modified world; an infinite angle raises in the product, as it did."""
    loose = Frame(Trsf(1, 2, 3, 0, 0, 0), None, name="fLoose")
    a = Frame(Trsf(), world, name="fA")
    b = Frame(Trsf(), a, name="fB")
    a.ref = b
    moved = new_world()
    moved.trsf = Trsf(1, 0, 0, 0, 0, 0)
    cases = [Point(Trsf(), CFG, None, name="pNone"), Point(Trsf(), CFG, loose, name="pLoose"),
             Point(Trsf(), CFG, a, name="pLoop"), Point(Trsf(), CFG, moved, name="pMoved")]
    for p in cases:
        with pytest.raises(Val3RuntimeError) as want:
            points.world_pose(p)
        with pytest.raises(Val3RuntimeError) as got:
            points.appro(p, Trsf(0, 0, -100, 0, 0, 0))
        assert (got.value.code, str(got.value)) == (want.value.code, str(want.value))
    assert {code(points.appro, p, Trsf()) for p in cases} == {161, 162, 163}
    with pytest.raises(ValueError):
        points.appro(Point(Trsf(0, 0, 0, float("inf"), 0, 0), CFG, world), Trsf())
    ok = Point(Trsf(400, 200, 50, 0, 180, 0), CFG, Frame(Trsf(10, 0, 0, 0, 0, 30), world))
    assert points.appro(ok, Trsf(0, 0, -100, 0, 0, 0)).trsf == ok.trsf * Trsf(0, 0, -100, 0, 0, 0)
