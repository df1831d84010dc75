"""trsf (manual 9.3): orientation convention and canonical form (9.3.2), operators (9.3.3),
distance, interpolateL, interpolateC (with 10.1.4.1), align (9.3.4)."""

from __future__ import annotations

import math
import random

import pytest

from val3check.geometry import rotation as R
from val3check.geometry.trsf import Trsf, align, close, distance, interpolate_c, interpolate_l
from val3check.language.runtime_errors import Val3RuntimeError

from .helpers import canonical_ok, mat_close, rodrigues, same_rotation, trsf_close

# --- 9.3.1 / 9.3.2 ----------------------------------------------------------------------------


def test_default_is_zero():
    assert Trsf().as_tuple() == (0, 0, 0, 0, 0, 0)


def test_translation_only_example_9_3_2():
    # R2 in R1: x = 250, y = 350, z = 450, rx = ry = rz = 0: a pure translation
    t = Trsf(250, 350, 450, 0, 0, 0)
    assert t.rotation() == R.IDENTITY
    p = t * Trsf(1, 2, 3)
    assert p.as_tuple() == (251, 352, 453, 0, 0, 0)


def test_orientation_example_9_3_2_successive_axes():
    # rx = 20, ry = 10, rz = 30: 20 about x, then 10 about the new y', then 30 about the new z''
    m = Trsf(250, 350, 450, 20, 10, 30).rotation()
    f1 = rodrigues((1, 0, 0), 20)  # x' = x
    assert R.column(f1, 0) == (1.0, 0.0, 0.0)
    y1 = R.column(f1, 1)
    f2 = R.mat_mul(rodrigues(y1, 10), f1)  # y'' = y'
    assert mat_close(R.column(f2, 1), y1)
    z2 = R.column(f2, 2)
    f3 = R.mat_mul(rodrigues(z2, 30), f2)  # z''' = z''
    assert mat_close(R.column(f3, 2), z2)
    assert mat_close(m, f3, 1e-12)


def test_literal_angles_are_kept_as_written():
    t = Trsf(0, 0, 0, 400, -200, 270)
    assert (t.rx, t.ry, t.rz) == (400, -200, 270)


# --- canonical form of 9.3.2 ------------------------------------------------------------------


def _random_rotation(rng):
    # uniform random rotation from a random unit quaternion
    q = [rng.gauss(0, 1) for _ in range(4)]
    n = math.sqrt(sum(v * v for v in q))
    return R.mat_of_quat(tuple(v / n for v in q))


def test_canonical_form_of_random_rotations():
    rng = random.Random(9032)
    for _ in range(5000):
        m = _random_rotation(rng)
        rx, ry, rz = R.angles_of(m)
        assert canonical_ok(rx, ry, rz), (rx, ry, rz)
        assert mat_close(R.matrix(rx, ry, rz), m, 1e-12)
        # idempotent: the canonical triple is kept bit for bit
        assert R.canonical_angles(rx, ry, rz) == (rx, ry, rz)


def test_canonical_form_of_random_angles_and_products():
    rng = random.Random(933)
    for _ in range(3000):
        a = Trsf(*(rng.uniform(-500, 500) for _ in range(3)), *(rng.uniform(-720, 720) for _ in range(3)))
        b = Trsf(*(rng.uniform(-500, 500) for _ in range(3)),
                 *(rng.choice([0, 90, -90, 180, 45]) + rng.choice([0, rng.uniform(-1, 1)]) for _ in range(3)))
        cases = ((a.canonical(), a.rotation()), (a * b, R.mat_mul(a.rotation(), b.rotation())),
                 (a.inverse(), R.transpose(a.rotation())))
        for t, m in cases:
            assert canonical_ok(t.rx, t.ry, t.rz), t
            assert mat_close(t.rotation(), m, 1e-9)


def test_angles_within_plus_minus_180_and_180_positive():
    t = Trsf(0, 0, 0, -180, 0, 0).canonical()
    assert (t.rx, t.ry, t.rz) == (180, 0, 0)
    t = Trsf(0, 0, 0, 0, 0, 270).canonical()
    assert (t.rx, t.ry, t.rz) == (0, 0, -90)
    t = Trsf(0, 0, 0, 0, 0, -180) * Trsf()
    assert (t.rx, t.ry, t.rz) == (0, 0, 180)


@pytest.mark.parametrize("rx,ry,rz", [(30, 90, 40), (30, -90, 40), (-170, 90, 5), (0, 270, 12), (77, -270, -33),
                                      (120, 90.0000000000001, 0)])
def test_ry_90_gives_rx_zero(rx, ry, rz):
    t = Trsf(0, 0, 0, rx, ry, rz).canonical()
    assert t.rx == 0 and abs(t.ry) == 90
    assert same_rotation(t, Trsf(0, 0, 0, rx, ry, rz))


def test_ry_90_from_a_product_gives_rx_zero():
    t = Trsf(0, 0, 0, 25, 0, 0) * Trsf(0, 0, 0, 0, 90, 0) * Trsf(0, 0, 0, 0, 0, 15)
    assert (t.rx, t.ry) == (0, 90)
    assert t.rz == pytest.approx(40)


def test_at_least_two_angles_within_90():
    # (150, 30, 160) has only ry within +-90: the system gives the twin triple
    t = Trsf(0, 0, 0, 150, 30, 160).canonical()
    assert t.as_tuple()[3:] == pytest.approx((-30, 150, -20))
    assert same_rotation(t, Trsf(0, 0, 0, 150, 30, 160))
    # already canonical triples are kept exactly
    for a in [(20, 10, 30), (100, 10, 30), (10, 10, 100), (-30, 150, -20), (0, 0, 0)]:
        assert Trsf(0, 0, 0, *a).canonical().as_tuple()[3:] == a


def test_exception_rx_180_ry_0():
    # a tool pointing down stays {.., 180, 0, rz} whatever rz (the exception of 9.3.2)
    for rz in (180, 135, -100, 90, 0):
        t = Trsf(0, 0, 0, 180, 0, rz).canonical()
        assert t.as_tuple()[3:] == (180, 0, rz if rz != -180 else 180)
    t = Trsf(0, 0, 0, 180, 0, 0) * Trsf(0, 0, 0, 0, 0, 135)
    assert (t.rx, t.ry) == (180, 0) and t.rz == pytest.approx(135)
    # the same rotation written the other way is given back in the exception's form
    t = Trsf(0, 0, 0, 0, 180, -45).canonical()
    assert (t.rx, t.ry) == (180, 0) and t.rz == pytest.approx(135)
    assert same_rotation(t, Trsf(0, 0, 0, 0, 180, -45))


# --- 9.3.3 operators --------------------------------------------------------------------------


def test_equality_is_field_by_field():
    assert Trsf(1, 2, 3, 4, 5, 6) == Trsf(1, 2, 3, 4, 5, 6)
    assert not (Trsf(1, 2, 3, 4, 5, 6) != Trsf(1, 2, 3, 4, 5, 6))
    assert Trsf(1, 2, 3, 4, 5, 6) != Trsf(1, 2, 3, 4, 5, 6.0000001)
    # same rotation, different fields: not equal (== compares the fields, 9.3.3)
    assert Trsf(0, 0, 0, 180, 0, 0) != Trsf(0, 0, 0, -180, 0, 0)
    assert close(Trsf(0, 0, 0, 180, 0, 0), Trsf(0, 0, 0, -180, 0, 0))


def test_composition_is_not_commutative():
    a, b = Trsf(100, 0, 0, 0, 0, 90), Trsf(0, 50, 0, 30, 0, 0)
    assert a * b != b * a
    # a * b: b expressed in a's frame
    ab = a * b
    assert (ab.x, ab.y, ab.z) == pytest.approx((100 - 50, 0, 0))


def test_composition_of_known_values():
    t = Trsf(10, 20, 30, 0, 0, 90) * Trsf(1, 0, 0, 0, 0, 0)
    assert t.as_tuple() == pytest.approx((10, 21, 30, 0, 0, 90))
    # pure translations and rotations about the same axis add exactly
    assert (Trsf(1, 2, 3) * Trsf(4, 5, 6)).as_tuple() == (5, 7, 9, 0, 0, 0)
    assert (Trsf(0, 0, 0, 0, 0, 30) * Trsf(0, 0, 0, 0, 0, 60)).rz == pytest.approx(90)


def test_inverse_times_trsf_is_identity():
    rng = random.Random(7)
    for _ in range(500):
        t = Trsf(*(rng.uniform(-1000, 1000) for _ in range(3)), *(rng.uniform(-180, 180) for _ in range(3)))
        for u in (t.inverse() * t, t * t.inverse(), ~t * t):
            assert trsf_close(u, Trsf(), 1e-9)
            assert canonical_ok(u.rx, u.ry, u.rz)
        assert trsf_close(t.inverse().inverse(), t, 1e-9)


def test_inverse_of_known_values():
    t = Trsf(10, 0, 0, 0, 0, 90).inverse()
    assert t.as_tuple() == pytest.approx((0, 10, 0, 0, 0, -90))
    assert Trsf(1, 2, 3).inverse().as_tuple() == (-1, -2, -3, 0, 0, 0)
    assert Trsf(0, 0, 0, 180, 0, 0).inverse().as_tuple() == (0, 0, 0, 180, 0, 0)


def test_associativity():
    rng = random.Random(11)
    for _ in range(500):
        a, b, c = (Trsf(*(rng.uniform(-500, 500) for _ in range(3)), *(rng.uniform(-180, 180) for _ in range(3)))
                   for _ in range(3))
        assert trsf_close((a * b) * c, a * (b * c), 1e-8)


def test_operations_do_not_alias_arguments():
    a = Trsf(1, 2, 3, 4, 5, 6)
    for r in (a * Trsf(), Trsf() * a, interpolate_l(a, a, 0), interpolate_l(a, a, 1), align(a, a), a.copy()):
        assert r is not a
    r = a * Trsf()
    r.x = 99
    assert a.x == 1


def test_matrix4_round_trip():
    t = Trsf(1, -2, 3, 20, 10, 30)
    m = t.matrix4()
    assert m[3] == (0, 0, 0, 1)
    u = Trsf.from_matrix4(m)
    assert trsf_close(u, t, 1e-12)
    assert u.as_tuple() == pytest.approx(t.as_tuple(), abs=1e-12)


def test_dict_round_trip():
    d = {"x": 1.0, "y": 2.0, "z": 3.0, "rx": 4.0, "ry": 5.0, "rz": 6.0}
    assert Trsf.from_dict(d).to_dict() == d


# --- distance ---------------------------------------------------------------------------------


def test_distance_uses_positions_only():
    assert distance(Trsf(0, 0, 0), Trsf(3, 4, 0, 90, 45, 10)) == 5
    assert distance(Trsf(1, 1, 1, 10, 0, 0), Trsf(1, 1, 1, 0, 80, 0)) == 0


# --- interpolateL -----------------------------------------------------------------------------


def test_interpolate_l_ends_and_middle():
    a, b = Trsf(0.1, 10, -5, 20, 10, 30), Trsf(0.3, 30, 15, 20, 10, 30)
    assert interpolate_l(a, b, 0) == a
    assert interpolate_l(a, b, 1) == b
    m = interpolate_l(a, b, 0.5)
    assert (m.x, m.y, m.z) == pytest.approx((0.2, 20, 5))
    assert same_rotation(m, a)  # constant orientation stays constant
    # x = start.x + (end.x - start.x) * s
    for s in (-0.9, -0.5, 0.25, 0.75, 1.5, 1.99):
        t = interpolate_l(a, b, s)
        assert t.x == pytest.approx(a.x + (b.x - a.x) * s)
        assert t.y == pytest.approx(a.y + (b.y - a.y) * s)
        assert t.z == pytest.approx(a.z + (b.z - a.z) * s)


def test_interpolate_l_orientation_is_the_shortest_rotation():
    a, b = Trsf(0, 0, 0, 0, 0, 170), Trsf(0, 0, 0, 0, 0, -170)
    m = interpolate_l(a, b, 0.5)  # 20 degrees the short way: through 180, not through 0
    assert same_rotation(m, Trsf(0, 0, 0, 0, 0, 180))
    m = interpolate_l(Trsf(), Trsf(0, 0, 0, 0, 0, 90), 0.5)
    assert m.as_tuple() == pytest.approx((0, 0, 0, 0, 0, 45))
    m = interpolate_l(Trsf(), Trsf(0, 0, 0, 0, 0, 90), -0.5)
    assert m.rz == pytest.approx(-45)
    m = interpolate_l(Trsf(), Trsf(0, 0, 0, 0, 0, 90), 1.5)
    assert m.rz == pytest.approx(135)
    m = interpolate_l(Trsf(0, 0, 0, 0, 0, 0), Trsf(0, 0, 0, 90, 0, 0), 0.25)
    assert m.as_tuple()[3:] == pytest.approx((22.5, 0, 0))


@pytest.mark.parametrize("s", [-1, 2, -1.5, 2.0001, 10])
def test_interpolate_l_position_outside_range_is_error_70(s):
    with pytest.raises(Val3RuntimeError) as e:
        interpolate_l(Trsf(), Trsf(1, 0, 0), s)
    assert e.value.code == 70


# --- interpolateC -----------------------------------------------------------------------------


def test_interpolate_c_ends_and_middle_of_the_arc():
    a, m, b = Trsf(100, 0, 0), Trsf(0, 100, 0), Trsf(-100, 0, 0)
    assert interpolate_c(a, m, b, 0) == a
    assert interpolate_c(a, m, b, 1) == b
    mid = interpolate_c(a, m, b, 0.5)
    assert (mid.x, mid.y, mid.z) == pytest.approx((0, 100, 0), abs=1e-9)
    q = interpolate_c(a, m, b, 0.25)
    assert (q.x, q.y) == pytest.approx((100 * math.cos(math.pi / 4), 100 * math.sin(math.pi / 4)))
    # the middle of the ARC, not of the intermediate point: intermediate at 30 degrees of 90
    a, m, b = Trsf(10, 0, 5), Trsf(10 * math.cos(math.radians(30)), 10 * math.sin(math.radians(30)), 5), Trsf(0, 10, 5)
    mid = interpolate_c(a, m, b, 0.5)
    assert (mid.x, mid.y, mid.z) == pytest.approx((10 * math.sqrt(0.5), 10 * math.sqrt(0.5), 5))
    # before the start and after the end, on the same circle
    for s in (-0.3, 1.4):
        t = interpolate_c(a, m, b, s)
        assert math.hypot(t.x, t.y) == pytest.approx(10)
        assert math.degrees(math.atan2(t.y, t.x)) == pytest.approx(90 * s)


def test_interpolate_c_in_3d_plane():
    # circle of radius 50 about (1, 2, 3) in a tilted plane
    c = (1.0, 2.0, 3.0)
    u = R.unit((1.0, 1.0, 0.0))
    v = R.unit(R.cross((0.0, 0.0, 1.0), u))
    v = R.unit(R.add(v, (0.0, 0.0, 0.5)))
    v = R.unit(R.sub(v, R.scale(u, R.dot(v, u))))

    def at(deg):
        t = math.radians(deg)
        p = R.add(c, R.add(R.scale(u, 50 * math.cos(t)), R.scale(v, 50 * math.sin(t))))
        return Trsf(*p)

    a, m, b = at(0), at(100), at(160)
    for s in (0.1, 0.5, 0.9):
        t = interpolate_c(a, m, b, s)
        e = at(160 * s)
        assert (t.x, t.y, t.z) == pytest.approx((e.x, e.y, e.z))


def test_interpolate_c_orientation_constant_and_relative_to_trajectory():
    # constant orientation stays constant
    a, m, b = Trsf(100, 0, 0, 180, 0, 30), Trsf(0, 100, 0, 180, 0, 30), Trsf(-100, 0, 0, 180, 0, 30)
    for s in (0.2, 0.5, 0.7):
        assert same_rotation(interpolate_c(a, m, b, s), a)
    # orientation constant relative to the trajectory: rz follows the tangent
    a, m, b = Trsf(100, 0, 0, 0, 0, 90), Trsf(0, 100, 0, 0, 0, 180), Trsf(-100, 0, 0, 0, 0, -90)
    for s in (0.1, 0.3, 0.5, 0.8, 1.2):
        t = interpolate_c(a, m, b, s)
        tangent = math.degrees(math.atan2(t.y, t.x)) + 90
        assert same_rotation(t, Trsf(0, 0, 0, 0, 0, tangent))


def test_interpolate_c_orientation_reaches_the_intermediate():
    a, m, b = Trsf(100, 0, 0, 0, 0, 0), Trsf(0, 100, 0, 40, 0, 0), Trsf(-100, 0, 0, 40, 30, 0)
    t = interpolate_c(a, m, b, 0.5)
    assert same_rotation(t, m)
    t = interpolate_c(a, m, b, 0.25)
    assert same_rotation(t, Trsf(0, 0, 0, 20, 0, 0))


def test_interpolate_c_full_circle_needs_two_arcs():
    # 10.1.4.1: movec(B, C) then movec(D, A) from A
    A, B, C, D = Trsf(1, 0, 0), Trsf(0, 1, 0), Trsf(-1, 0, 0), Trsf(0, -1, 0)
    assert interpolate_c(A, B, C, 0.5) is not None
    assert interpolate_c(C, D, A, 0.5).as_tuple()[:3] == pytest.approx((0, -1, 0))
    with pytest.raises(Val3RuntimeError) as e:  # one arc back to the start: no arc
        interpolate_c(A, C, A, 0.5)
    assert e.value.code == 70


@pytest.mark.parametrize("mid_deg,end_deg", [(180, 270), (200, 270), (30, 210), (10, 350)])
def test_interpolate_c_180_degree_arc_ambiguity_is_error_70(mid_deg, end_deg):
    # the intermediate point makes 180 degrees or more with the start or the end (10.1.4.1)
    def at(deg):
        return Trsf(100 * math.cos(math.radians(deg)), 100 * math.sin(math.radians(deg)), 0)
    with pytest.raises(Val3RuntimeError) as e:
        interpolate_c(at(0), at(mid_deg), at(end_deg), 0.5)
    assert e.value.code == 70


def test_interpolate_c_180_degree_orientation_ambiguity_is_error_70():
    a, m, b = Trsf(100, 0, 0, 0, 0, 0), Trsf(0, 100, 0, 0, 0, 180), Trsf(-100, 0, 0, 0, 0, 180)
    with pytest.raises(Val3RuntimeError) as e:
        interpolate_c(a, m, b, 0.5)
    assert e.value.code == 70
    with pytest.raises(Val3RuntimeError) as e:
        interpolate_c(a, Trsf(0, 100, 0), Trsf(-100, 0, 0, 180, 0, 0), 0.5)
    assert e.value.code == 70
    # 179 degrees is not ambiguous
    interpolate_c(a, Trsf(0, 100, 0, 0, 0, 179), Trsf(-100, 0, 0, 0, 0, 179), 0.5)


@pytest.mark.parametrize("pts", [
    ((0, 0, 0), (0, 0, 0), (1, 1, 0)),           # start = intermediate
    ((0, 0, 0), (1, 1, 0), (1, 1, 0)),           # intermediate = end
    ((0, 0, 0), (1, 0, 0), (2, 0, 0)),           # aligned
    ((0, 0, 0), (1e-9, 0, 0), (1, 1, 0)),        # too close
])
def test_interpolate_c_undefined_arc_is_error_70(pts):
    a, m, b = (Trsf(*p) for p in pts)
    with pytest.raises(Val3RuntimeError) as e:
        interpolate_c(a, m, b, 0.5)
    assert e.value.code == 70


# --- align ------------------------------------------------------------------------------------


def test_align_to_the_nearest_axis():
    t = align(Trsf(10, 20, 30, 10, 5, 3), Trsf(999, 999, 999, 0, 0, 0))
    assert (t.x, t.y, t.z) == (10, 20, 30)
    assert R.column(t.rotation(), 2) == pytest.approx((0, 0, 1))
    assert (t.rx, t.ry) == (0, 0)  # Z is exactly the reference Z
    # tool roughly pointing down: aligned on -Z of world
    t = align(Trsf(0, 0, 0, 170, 8, 45), Trsf())
    assert R.column(t.rotation(), 2) == pytest.approx((0, 0, -1))
    # nearest is the reference's X axis
    t = align(Trsf(0, 0, 0, 0, 80, 0), Trsf())
    assert R.column(t.rotation(), 2) == pytest.approx((1, 0, 0))
    # nearest is -Y of a rotated reference
    ref = Trsf(0, 0, 0, 0, 0, 30)
    t = align(Trsf(0, 0, 0, 85, 0, 20), ref)
    y_ref = R.column(ref.rotation(), 1)
    assert R.column(t.rotation(), 2) == pytest.approx(R.scale(y_ref, -1))


def test_align_is_the_smallest_turn():
    t0 = Trsf(0, 0, 0, 10, 0, 0)
    t = align(t0, Trsf())
    # turning back about x: the x axis is unchanged
    assert R.column(t.rotation(), 0) == pytest.approx(R.column(t0.rotation(), 0))
    assert t.as_tuple()[3:] == pytest.approx((0, 0, 0), abs=1e-12)
    # already aligned: unchanged
    assert align(Trsf(1, 2, 3, 0, 0, 33), Trsf()).as_tuple() == (1, 2, 3, 0, 0, 33)
