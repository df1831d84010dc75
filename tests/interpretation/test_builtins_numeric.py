"""num instructions (manual 3.2.3) and the num operators that fail (3.2.2)."""

from __future__ import annotations

import math

import pytest

from val3check.interpretation.builtins import numeric as n
from val3check.language.runtime_errors import Val3RuntimeError


def error_code(func, *args) -> int:
    with pytest.raises(Val3RuntimeError) as info:
        func(*args)
    return info.value.code


# --- every stated result of 3.2.3 --------------------------------------------------------------


@pytest.mark.parametrize(
    ("func", "args", "expected"),
    [
        (n.sin, (30,), 0.5),  # 3.2.3 sin(30) renvoie 0.5
        (n.asin, (0.5,), 30.0),  # 3.2.3 asin(0.5) renvoie 30
        (n.cos, (60,), 0.5),  # 3.2.3 cos(60) renvoie 0.5
        (n.acos, (0.5,), 60.0),  # 3.2.3 acos(0.5) renvoie 60
        (n.tan, (45,), 1.0),  # 3.2.3 tan(45) renvoie 1.0
        (n.atan, (1,), 45.0),  # 3.2.3 atan(1) renvoie 45
        (n.abs_, (3.1415,), 3.1415),  # 3.2.3 abs(3.1415) renvoie 3.1415
        (n.abs_, (-3.1415,), 3.1415),  # 3.2.3 abs(-3.1415) renvoie 3.1415
        (n.sqrt, (9,), 3.0),  # 3.2.3 sqrt(9) renvoie 3
        (n.power, (5, 7), 78125.0),  # 3.2.3 power(5, 7): 5 to the power 7
        (n.log, (1000,), 3.0),  # 3.2.3 log(1000) renvoie 3
        (n.round_up, (7.8,), 8.0),  # 3.2.3
        (n.round_up, (-7.8,), -7.0),
        (n.round_down, (7.8,), 7.0),
        (n.round_down, (-7.8,), -8.0),
        (n.round_, (7.8,), 8.0),
        (n.round_, (-7.8,), -8.0),
        (n.round_, (0.5,), 1.0),
        (n.round_, (-0.5,), 0.0),
        (n.min_, (-1, 10), -1.0),
        (n.max_, (-1, 10), 10.0),
        (n.limit, (30, -90, 90), 30.0),
        (n.limit, (100, -90, 90), 90.0),
        (n.limit, (-100, -90, 90), -90.0),
        (n.sel, (True, -90, 90), -90.0),
        (n.sel, (False, -90, 90), 90.0),
    ],
)
def test_stated_results_exact(func, args, expected):
    result = func(*args)
    assert result == expected
    assert isinstance(result, float)


def test_exp_and_ln_stated_results_to_14_digits():
    # 3.2.3: exp(1) renvoie 2.718281828459 ; ln(2.718281828) renvoie 0.99999999983113
    assert n.exp(1) == pytest.approx(2.718281828459, rel=1e-13)
    assert n.ln(2.718281828) == pytest.approx(0.99999999983113, rel=1e-13)


def test_power_and_exp_ln_agree_with_imprecision():
    # 3.2.3: power(5,7) and exp(7*ln(5)) compute the same "with numeric imprecision"
    assert n.exp(7 * n.ln(5)) == pytest.approx(n.power(5, 7), rel=1e-13)


def test_cos_zero_is_exact_at_90():
    # 3.2.1 advises abs(cos(nAngle)) < 1e-10 rather than cos(nAngle) == 0; both hold here
    assert n.cos(90) == 0.0
    assert abs(n.cos(90)) < 1e-10


# --- trigonometry in degrees ---------------------------------------------------------------


@pytest.mark.parametrize(
    "angle",
    [
        -725.5,
        -400,
        -190,
        -180,
        -135,
        -90,
        -45,
        -30,
        0,
        1e-9,
        17.3,
        30,
        45,
        60,
        90,
        120,
        135,
        150,
        180,
        210,
        270,
        300,
        359.9,
        360,
        720,
        1e6 + 0.25,
    ],
)
def test_trig_matches_radians(angle):
    assert n.sin(angle) == pytest.approx(math.sin(math.radians(angle)), abs=1e-12)
    assert n.cos(angle) == pytest.approx(math.cos(math.radians(angle)), abs=1e-12)


def test_exact_angles():
    assert n.sin(150) == 0.5 and n.sin(-30) == -0.5 and n.sin(390) == 0.5
    assert n.cos(120) == -0.5 and n.cos(-60) == 0.5 and n.cos(180) == -1.0
    assert n.sin(180) == 0.0 and n.sin(360) == 0.0
    assert n.tan(-45) == -1.0 and n.tan(135) == -1.0 and n.tan(225) == 1.0 and n.tan(0) == 0.0
    assert n.tan(60) == math.sqrt(3.0)


def test_tan_at_90_is_large_not_an_error():
    assert abs(n.tan(90)) > 1e15
    assert abs(n.tan(-90)) > 1e15


def test_inverse_round_trips_on_exact_angles():
    for angle in (-90, -60, -45, -30, 0, 30, 45, 60, 90):
        assert n.asin(n.sin(angle)) == angle
        if abs(angle) != 90:
            assert n.atan(n.tan(angle)) == angle
    for angle in (0, 30, 45, 60, 90, 120, 135, 150, 180):
        assert n.acos(n.cos(angle)) == angle


def test_inverse_ranges():
    assert n.asin(1) == 90.0 and n.asin(-1) == -90.0
    assert n.acos(1) == 0.0 and n.acos(-1) == 180.0
    assert n.atan(1e300) == pytest.approx(90.0) and n.atan(-1e300) == pytest.approx(-90.0)
    assert n.asin(0.3) == pytest.approx(math.degrees(math.asin(0.3)))


@pytest.mark.parametrize("func", [n.asin, n.acos])
@pytest.mark.parametrize("value", [1.0000001, -1.0000001, 2, -50])
def test_asin_acos_outside_unit_interval_is_error_11(func, value):
    # 3.2.3: "Une erreur d'exécution est générée si nValeur est supérieur à 1 ou inférieur à -1"
    assert error_code(func, value) == 11


# --- errors --------------------------------------------------------------------------------


def test_sqrt_of_negative_is_error_11():
    assert error_code(n.sqrt, -1) == 11  # 3.2.3, 12.1
    assert n.sqrt(0) == 0.0


@pytest.mark.parametrize("value", [0, -1, -1e-300])
def test_ln_log_of_non_positive_is_error_11(value):
    assert error_code(n.ln, value) == 11  # 12.1: "par exemple ln(-1)"
    assert error_code(n.log, value) == 11


def test_exp_too_large_is_error_11():
    assert error_code(n.exp, 1000) == 11
    assert n.exp(-1000) == 0.0


@pytest.mark.parametrize(("x", "y"), [(0, 2), (-2, 2), (-8, 1 / 3), (10, 400)])
def test_power_errors(x, y):
    # 3.2.3: error if nX is negative or zero, or if the result is too large
    assert error_code(n.power, x, y) == 11


def test_power_values():
    assert n.power(2, 10) == 1024.0
    assert n.power(2, -1) == 0.5
    assert n.power(4, 0.5) == 2.0
    assert n.power(7, 0) == 1.0


@pytest.mark.parametrize("bad", [math.inf, -math.inf, math.nan])
@pytest.mark.parametrize("func", [n.sin, n.cos, n.tan, n.atan, n.abs_, n.sqrt, n.exp, n.round_, n.round_up])
def test_non_finite_input_is_error_11(func, bad):
    assert error_code(func, bad) == 11


# --- rounding ------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("value", "expected"),
    [
        (1.5, 2.0),
        (2.5, 3.0),
        (-1.5, -1.0),
        (-2.5, -2.0),
        (0.49999999999999994, 0.0),
        (-0.49999999999999994, 0.0),
        (4503599627370497.0, 4503599627370497.0),
        (1e300, 1e300),
        (-0.2, 0.0),
    ],
)
def test_round_half_up(value, expected):
    assert n.round_(value) == expected


def test_no_negative_zero():
    for value in (n.round_(-0.2), n.round_up(-0.5), n.round_down(-0.0), n.modulo(-4, 2), n.sin(-360)):
        assert value == 0.0 and math.copysign(1.0, value) == 1.0


def test_limit_with_crossed_bounds_returns_max():
    assert n.limit(0, 10, -10) == -10.0


def test_sel_does_not_care_about_the_unchosen_value_sign():
    assert n.sel(True, 0, -5) == 0.0


# --- operators (3.2.2) ---------------------------------------------------------------------


def test_divide():
    assert n.divide(7, 2) == 3.5
    assert error_code(n.divide, 1, 0) == 10  # 3.2.2, 12.1 code 10
    assert error_code(n.divide, 1e300, 1e-300) == 11


def test_modulo_sign_of_dividend():
    # 3.2.2: "Le signe du reste est le signe de nValeur1"; error if nValeur2 is 0
    assert n.modulo(7, 3) == 1.0
    assert n.modulo(-7, 3) == -1.0
    assert n.modulo(7, -3) == 1.0
    assert n.modulo(7.5, 2) == 1.5
    assert error_code(n.modulo, 5, 0) == 10
