"""joint (9.2): operators of 9.2.2, abs and isInRange of 9.2.3, with the manual's examples."""

from __future__ import annotations

import pytest

from val3check.geometry import jointops as J
from val3check.language.runtime_errors import Val3RuntimeError


def test_abs_example_9_2_3():
    # if(! (abs(j - jReference) < jEcartMax)) popUpMsg("Rapprochez vous des marques")
    jReference = (90, 45, 45, 0, 30, 0)
    jEcartMax = (5, 5, 5, 5, 5, 5)

    def must_warn(j):
        return not J.lt(J.abs_(J.sub(j, jReference)), jEcartMax)

    assert not must_warn((92, 41, 49, -4.9, 30, 1))
    assert must_warn((92, 41, 49, -5, 30, 1))  # 5 degrees is not "less than 5"
    assert must_warn((80, 45, 45, 0, 30, 0))


def test_herej_watch_example():
    # bDebut = watch(abs(herej() - jReference) < jEcartMax, 60)
    jReference = (90, 45, 45, 0, 30, 0)
    current = [91.0, 44.0, 45.5, 0.0, 30.0, -2.0]
    j = J.herej(current)
    assert j == (91, 44, 45.5, 0, 30, -2) and j is not current
    assert J.lt(J.abs_(J.sub(j, jReference)), (5,) * 6)


def test_greater_is_not_not_less():
    a, b = (1, 5, 3), (2, 2, 2)
    assert not J.gt(a, b) and not J.lt(a, b)  # so a > b is not !(a < b)
    assert J.gt((3, 3, 3), b) and J.lt(b, (3, 3, 3))
    assert not J.gt((2, 3, 3), b)  # strictly


def test_plus_minus_field_by_field():
    assert J.add((1, 2, 3, 4, 5, 6), (10, 20, 30, 40, 50, 60)) == (11, 22, 33, 44, 55, 66)
    assert J.sub((1, 2, 3, 4), (1, 1, 1, 1)) == (0, 1, 2, 3)


def test_abs():
    assert J.abs_((-1, 2, -0.0, -360, 5, -6)) == (1, 2, 0, 360, 5, 6)


def test_equality_within_the_robot_precision():
    a = (10, 20, 30, 40, 50, 60)
    assert J.eq(a, (10, 20, 30, 40, 50, 60 + 1e-9))
    assert not J.ne(a, (10, 20, 30, 40, 50, 60 + 1e-9))
    assert J.ne(a, (10, 20, 30, 40, 50, 60.01))
    assert not J.eq(a, (10, 20, 30, 40, 50, 60.01))


def test_different_axis_counts_is_81():
    with pytest.raises(Val3RuntimeError) as e:
        J.add((1, 2, 3, 4), (1, 2, 3, 4, 5, 6))
    assert e.value.code == 81


def test_is_in_range():
    limits = [(-180, 180), (-127.5, 127.5), (-152.5, 152.5), (-270, 270), (-121, 132.5), (-270, 270)]
    assert J.is_in_range((0, 0, 0, 0, 0, 0), limits)
    assert J.is_in_range((180, -127.5, 152.5, 270, -121, 270), limits)  # bounds included
    assert not J.is_in_range((0, 0, 0, 0, 133, 0), limits)
    assert not J.is_in_range((-180.001, 0, 0, 0, 0, 0), limits)


def test_dict_round_trip():
    d = {"j1": 1.0, "j2": 2.0, "j3": 3.0, "j4": 4.0}
    assert J.from_dict(d) == (1, 2, 3, 4)
    assert J.to_dict(J.from_dict(d)) == d
