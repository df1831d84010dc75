"""Bit fields (manual 3.3): bNot, bAnd, bOr, bXor, toBinary, fromBinary."""

from __future__ import annotations

import math
import struct

import pytest

from val3check.interpretation.builtins import bits as b
from val3check.interpretation.builtins import numeric as n
from val3check.language.runtime_errors import Val3RuntimeError


def error_code(func, *args) -> int:
    with pytest.raises(Val3RuntimeError) as info:
        func(*args)
    return info.value.code


# --- 32-bit operations ---------------------------------------------------------------------


def test_basic_operations():
    assert b.b_and(0b1100, 0b1010) == 0b1000
    assert b.b_or(0b1100, 0b1010) == 0b1110
    assert b.b_xor(0b1100, 0b1010) == 0b0110
    assert b.b_not(0) == 4294967295.0
    assert b.b_not(4294967295) == 0.0
    assert b.b_not(1) == 4294967294.0
    assert all(isinstance(v, float) for v in (b.b_and(1, 1), b.b_not(0)))


def test_inputs_are_rounded_to_nearest_integer():
    # 3.3.1: "les instructions ... arrondissent automatiquement une valeur numérique à un nombre
    # entier positif de 32 bits"
    assert b.b_and(5.4, 0xFF) == 5.0
    assert b.b_and(5.5, 0xFF) == 6.0
    assert b.b_or(0.49, 0) == 0.0


def test_negative_and_too_large_inputs_are_clamped():
    # our reading of "rounded to a positive integer in [0, 2^32]": the nearest one
    assert b.b_and(-1, 0xFF) == 0.0
    assert b.b_not(-5) == 4294967295.0
    assert b.b_and(2.0**40, 0xFFFFFFFF) == 4294967295.0
    assert b.b_or(2.0**32, 0) == 4294967295.0


def test_non_finite_input_is_error_11():
    assert error_code(b.b_not, math.nan) == 11
    assert error_code(b.b_and, math.inf, 1) == 11


def test_manual_bit_mask_examples():
    i, j = 3, 6
    # 3.3.3 bOr: two ways of computing the mask of bits i to j give the same result
    field = 0.0
    for k in range(i, j + 1):
        field = b.b_or(field, n.power(2, k))
    assert field == (n.power(2, j - i + 1) - 1) * n.power(2, i) == 0b1111000
    # 3.3.3 bNot: reset bits i to j
    mask = b.b_not((n.power(2, j - i + 1) - 1) * n.power(2, i))
    assert b.b_and(0b11111111, mask) == 0b10000111
    # 3.3.3 bXor: invert bits i to j
    assert b.b_xor(0b10101010, 0b1111000) == 0b11010010
    # 3.3.3 bAnd: test each bit of a field
    shown = "".join("1" if b.b_and(0xA5, n.power(2, k)) == n.power(2, k) else "0" for k in range(31, -1, -1))
    assert shown == "0" * 24 + "10100101"


# --- toBinary ------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("fmt", "value", "expected"),
    [
        ("1", 200, [200]),
        ("-1", -1, [255]),
        ("-1", 127, [127]),
        ("-2l", -2, [0xFE, 0xFF]),
        ("-2b", -2, [0xFF, 0xFE]),
        ("2l", 0x1234, [0x34, 0x12]),
        ("2b", 0x1234, [0x12, 0x34]),
        ("-4l", -1, [255, 255, 255, 255]),
        ("-4b", 0x01020304, [1, 2, 3, 4]),
        ("4l", 0xDEADBEEF, [0xEF, 0xBE, 0xAD, 0xDE]),
        ("4b", 0xDEADBEEF, [0xDE, 0xAD, 0xBE, 0xEF]),
        ("4.0l", 1.0, [0, 0, 0x80, 0x3F]),
        ("4.0b", 1.0, [0x3F, 0x80, 0, 0]),
        ("8.0l", 1.0, [0, 0, 0, 0, 0, 0, 0xF0, 0x3F]),
        ("8.0b", -2.0, [0xC0, 0, 0, 0, 0, 0, 0, 0]),
    ],
)
def test_to_binary_every_format_of_the_table(fmt, value, expected):
    # 3.3.3: the 14 encodings of the table
    count, data = b.to_binary([value], 1, fmt, [0.0] * 8)
    assert count == len(expected)
    assert data[: len(expected)] == expected
    assert data[len(expected) :] == [0.0] * (8 - len(expected))
    assert all(isinstance(x, float) for x in data)


def test_every_table_format_is_supported():
    assert set(b.FORMATS) == {
        "-1",
        "1",
        "-2l",
        "-2b",
        "2l",
        "2b",
        "-4l",
        "-4b",
        "4l",
        "4b",
        "4.0l",
        "4.0b",
        "8.0l",
        "8.0b",
    }


def test_to_binary_manual_example_trsf_48_bytes():
    # 3.3.3: 6 doubles "8.0b" into 48 bytes, then fromBinary(nByteIn, 48, "8.0b", nTrsfIn) == 6
    trsf = [100.5, -20.25, 300.0, 0.1, 179.99, -90.0]
    count, out = b.to_binary(trsf, 6, "8.0b", [0.0] * 48)
    assert count == 48
    assert bytes(int(x) for x in out) == struct.pack(">6d", *trsf)
    decoded, values = b.from_binary(out, 48, "8.0b", [0.0] * 6)
    assert decoded == 6
    assert values == trsf


def test_to_binary_keeps_the_rest_of_the_output_array():
    count, out = b.to_binary([1, 2, 3], 2, "1", [9.0] * 5)
    assert (count, out) == (2.0, [1.0, 2.0, 9.0, 9.0, 9.0])


def test_to_binary_zero_values():
    assert b.to_binary([], 0, "4b", []) == (0.0, [])


def test_to_binary_integer_rounding_and_saturation():
    assert b.to_binary([2.5, 300, -1, 1.4], 4, "1", [0] * 4)[1] == [3.0, 255.0, 0.0, 1.0]
    assert b.to_binary([-200, 200], 2, "-1", [0] * 2)[1] == [0x80, 0x7F]
    assert b.to_binary([70000], 1, "2b", [0] * 2)[1] == [0xFF, 0xFF]


def test_to_binary_single_precision():
    _, out = b.to_binary([0.1], 1, "4.0b", [0] * 4)
    assert bytes(int(x) for x in out) == struct.pack(">f", 0.1)
    _, out = b.to_binary([1e300, -1e300], 2, "4.0b", [0] * 8)
    assert struct.unpack(">2f", bytes(int(x) for x in out)) == (math.inf, -math.inf)


@pytest.mark.parametrize("fmt", ["2.0b", "-4.0l", "1l", "1b", "8l", "8b", "4", "", "4L", "-8.0b", "3b"])
def test_unsupported_format_is_error_70(fmt):
    # 3.3.3: "si le format spécifié n'est pas pris en charge"
    assert error_code(b.to_binary, [1.0], 1, fmt, [0.0] * 8) == 70
    assert error_code(b.from_binary, [1.0] * 8, 8, fmt, [0.0] * 8) == 70


def test_to_binary_size_errors():
    # 3.3.3: nTailleValeur larger than nValeur, or nOctetDonnées too small
    assert error_code(b.to_binary, [1.0, 2.0], 3, "1", [0.0] * 8) == 70
    assert error_code(b.to_binary, [1.0, 2.0], 2, "2b", [0.0] * 3) == 70
    assert error_code(b.to_binary, [1.0], -1, "1", [0.0]) == 70


def test_to_binary_non_finite_value_is_error_11():
    assert error_code(b.to_binary, [math.nan], 1, "8.0b", [0.0] * 8) == 11


# --- fromBinary ----------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("fmt", "data", "expected"),
    [
        ("1", [255], 255.0),
        ("-1", [255], -1.0),
        ("-1", [128], -128.0),
        ("-2l", [0xFE, 0xFF], -2.0),
        ("-2b", [0xFF, 0xFE], -2.0),
        ("2l", [0x34, 0x12], 0x1234),
        ("2b", [0x12, 0x34], 0x1234),
        ("-4l", [255, 255, 255, 255], -1.0),
        ("-4b", [0x80, 0, 0, 0], -2147483648.0),
        ("4l", [0xEF, 0xBE, 0xAD, 0xDE], 0xDEADBEEF),
        ("4b", [0xDE, 0xAD, 0xBE, 0xEF], 0xDEADBEEF),
        ("4.0l", [0, 0, 0x80, 0x3F], 1.0),
        ("4.0b", [0xC0, 0, 0, 0], -2.0),
        ("8.0l", [0, 0, 0, 0, 0, 0, 0xF0, 0x3F], 1.0),
        ("8.0b", [0x40, 0x09, 0x21, 0xFB, 0x54, 0x44, 0x2D, 0x18], math.pi),
    ],
)
def test_from_binary_every_format(fmt, data, expected):
    count, values = b.from_binary([float(x) for x in data], len(data), fmt, [7.0, 7.0])
    assert count == 1.0
    assert values == [expected, 7.0]


@pytest.mark.parametrize("fmt", sorted(b.FORMATS))
def test_round_trip(fmt):
    values = [0.0, 1.0, 100.0] if not fmt.startswith("-") else [-100.0, 0.0, 1.0]
    if "." in fmt:
        values = [-1.5, 0.0, 3.25]
    size, data = b.to_binary(values, 3, fmt, [0.0] * 24)
    count, back = b.from_binary(data, size, fmt, [0.0] * 3)
    assert (count, back) == (3.0, values)


def test_from_binary_corrupt_byte_returns_minus_the_good_count():
    # 3.3.3: bytes outside [0, 255] -> "l'opposé du nombre de valeurs correctement décryptées"
    count, values = b.from_binary([1, 2, 256, 4], 4, "1", [0.0] * 4)
    assert count == -2.0
    assert values == [1.0, 2.0, 0.0, 0.0]
    count, values = b.from_binary([0, 1, -1, 0], 4, "2b", [9.0] * 2)
    assert (count, values) == (-1.0, [1.0, 9.0])


def test_from_binary_invalid_float_encoding():
    # 3.3.3: "codage de la virgule flottante invalide" (NaN, infinities)
    nan = list(struct.pack(">f", math.nan))
    inf = list(struct.pack(">d", math.inf))
    one = list(struct.pack(">f", 1.0))
    assert b.from_binary(one + nan + one, 12, "4.0b", [0.0] * 3) == (-1.0, [1.0, 0.0, 0.0])
    assert b.from_binary(inf, 8, "8.0b", [5.0]) == (0.0, [5.0])


def test_from_binary_fractional_bytes_are_rounded():
    assert b.from_binary([1.4, 254.6], 2, "1", [0.0, 0.0]) == (2.0, [1.0, 255.0])


def test_from_binary_trailing_partial_value_is_ignored():
    assert b.from_binary([0, 1, 0, 2, 0], 5, "2b", [0.0] * 2) == (2.0, [1.0, 2.0])


def test_from_binary_uses_only_the_given_byte_count():
    assert b.from_binary([1, 2, 3, 4], 2, "1", [0.0] * 4) == (2.0, [1.0, 2.0, 0.0, 0.0])


def test_from_binary_size_errors():
    # 3.3.3: nTailleDonnées larger than nOctetDonnées, or nValeur too small
    assert error_code(b.from_binary, [1.0, 2.0], 3, "1", [0.0] * 8) == 70
    assert error_code(b.from_binary, [1.0] * 8, 8, "2b", [0.0] * 3) == 70
    assert error_code(b.from_binary, [1.0], -1, "1", [0.0]) == 70
