"""string instructions (manual 3.4), getDisplayLen (4.3), `+` (3.4.2), put's num display (4.3)."""

from __future__ import annotations

import math

import pytest

from val3check.interpretation.builtins import format_num_default
from val3check.interpretation.builtins import strings as s
from val3check.language.runtime_errors import Val3RuntimeError

PI = 3.141592654  # 3.4.3: nPi = 3.141592654
CHINESE = "中"  # 3 bytes in UTF-8


def error_code(func, *args) -> int:
    with pytest.raises(Val3RuntimeError) as info:
        func(*args)
    return info.value.code


# --- 128 bytes (3.4.1, 3.4.2) ------------------------------------------------------------------


def test_max_length_ascii_and_chinese():
    # 3.4.1: "La longueur maximale d'une chaîne ASCII est donc de 128 caractères, celle d'une chaîne
    # en chinois de 42 caractères."
    assert s.fit("a" * 200) == "a" * 128
    assert s.fit(CHINESE * 50) == CHINESE * 42
    assert s.utf8_size(CHINESE * 42) == 126


def test_concat_is_limited_to_128_bytes_without_cutting_a_character():
    # 3.4.2: "+" returns the first characters (limited to 128 bytes)
    assert s.concat("ab", "cd") == "abcd"
    assert s.concat("a" * 100, "b" * 100) == "a" * 100 + "b" * 28
    assert s.concat("a" * 127, "é") == "a" * 127  # "é" is 2 bytes: never half a character
    assert s.concat("a" * 126, "é") == "a" * 126 + "é"
    assert s.concat("a" * 125, "😀") == "a" * 125  # 4 bytes
    assert s.concat("", "") == ""


def test_utf8_sizes():
    assert [s.utf8_size(c) for c in ("A", "é", CHINESE, "😀")] == [1, 2, 3, 4]


# --- toString (3.4.3) ---------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("fmt", "value", "expected"),
    [
        (".4", PI, "3.1416"),  # 3.4.3
        ("8", PI, " " * 7 + "3"),  # 3.4.3: "(7 espaces avant le '3')"
        ("8.4", PI, "  3.1416"),  # 3.4.3: "(2 espaces avant le '3')"
        ("8.4", 2.70001, "  2.7   "),  # 3.4.3: "(2 espaces avant le '2', 3 espaces après le '7')"
        ("", PI, "3"),  # 3.4.3
        ("1.2", 1234.1234, "1234.12"),  # 3.4.3: the integer part is never cut
    ],
)
def test_to_string_manual_examples(fmt, value, expected):
    assert s.to_string(fmt, value) == expected


@pytest.mark.parametrize(
    ("fmt", "value", "expected"),
    [
        ("6.2", 3.14159, "  3.14"),
        (".3", 0.1 + 0.2, "0.3  "),
        (".2", 3.0, "3   "),  # all decimals zero: the point is replaced too (our choice)
        ("5.2", 10.0, "10   "),
        (".0", 100.0, "100"),  # zeros of the integer part are kept
        ("", -2.7, "-3"),
        (".2", -0.001, "0   "),  # no "-0"
        ("", -0.4, "0"),
        ("3", -42.0, "-42"),
        (".", 2.5, "2"),  # printf rounding: exact tie to even
        ("", 0.5, "0"),
        (".1", 0.25, "0.2"),
        ("8.", 7.0, "       7"),
        (".3", 1e20, "100000000000000000000    "),
    ],
)
def test_to_string_more(fmt, value, expected):
    assert s.to_string(fmt, value) == expected


@pytest.mark.parametrize("fmt", ["%5.2f", "-3", "a", "1.2.3", " 8", "8 ", "+4", "1e2"])
def test_to_string_invalid_format_is_error_70(fmt):
    assert error_code(s.to_string, fmt, 1.0) == 70


def test_to_string_results_fit_128_bytes():
    assert s.to_string("500", 1.0) == " " * 128
    assert s.to_string("130", 1.0) == " " * 128
    assert s.to_string("128", 1.0) == " " * 127 + "1"
    long = s.to_string(".200", 1 / 3)
    assert len(long) == 128 and long.startswith("0.3333")
    assert s.to_string(".999999999999", 0.1).startswith("0.1000000000000000055511151231257827")


def test_to_string_non_finite_is_error_11():
    assert error_code(s.to_string, "", math.inf) == 11


# --- put / putln of a num (4.3) ---------------------------------------------------------------


def test_num_display_toNum_loop_example():
    # 3.4.3: this program displays successively 90, 0, -7.6, 17.3
    buffer, value, ok = "+90 0.0 -7.6 17.3", 0.0, False
    shown = []
    while True:
        buffer, value, ok = s.to_num(buffer, value, ok)
        shown.append(format_num_default(value))
        if buffer == "" or ok is not True:
            break
    assert shown == ["90", "0", "-7.6", "17.3"]


@pytest.mark.parametrize(
    ("value", "expected"),
    [
        (PI, "3.142"),
        (0.0004, "0"),
        (-0.0004, "0"),
        (2.0004, "2"),
        (2.0006, "2.001"),
        (1234567.891, "1234567.891"),
        (-1e-3, "-0.001"),
        (1e15, "1000000000000000"),
        (12.5, "12.5"),
    ],
)
def test_num_display_three_decimals(value, expected):
    # 4.3: put/putln display the num "à 3 décimales"
    assert format_num_default(value) == expected


# --- toNum (3.4.3) ------------------------------------------------------------------------------


def test_to_num_manual_examples():
    # 3.4.3
    assert s.to_num("10 20 30", 0.0, False) == ("20 30", 10.0, True)
    assert s.to_num("a10 20 30", 5.0, True) == ("a10 20 30", 5.0, False)  # nVal unchanged
    assert s.to_num("10 end", 0.0, False) == ("", 10.0, True)


@pytest.mark.parametrize(
    ("text", "rest", "value"),
    [
        ("-7.6 17.3", "17.3", -7.6),
        ("+90", "", 90.0),
        ("1e3 x", "", 1000.0),
        ("1.5e-2,2", "2", 0.015),
        ("6.02214179e23", "", 6.02214179e23),  # 3.2.1 constants
        ("1.054571628e-34", "", 1.054571628e-34),
        ("-3.141592653", "", -3.141592653),
        (".5 1", "1", 0.5),
        ("5. 1", "1", 5.0),
        ("1E+2", "", 100.0),
        ("  42 7", "7", 42.0),  # leading blanks, as strtod
        ("10e", "", 10.0),  # no digits after 'e': the number is 10
        ("10  -x -5", "-5", 10.0),
        ("1.5.3", ".3", 1.5),
        ("12abc34", "34", 12.0),
        ("-0", "", 0.0),
    ],
)
def test_to_num_more(text, rest, value):
    result = s.to_num(text, 99.0, False)
    assert result == (rest, value, True)
    assert math.copysign(1.0, result[1]) == 1.0 or value != 0


@pytest.mark.parametrize("text", ["", " ", "-", "+", ".", "e5", "abc", "- 5", "inf", "nan", "x10", "1e999"])
def test_to_num_not_a_number(text):
    # 3.4.3: bRapport false, nValeur unchanged, sChaîne returned unchanged
    assert s.to_num(text, 3.0, True) == (text, 3.0, False)


def test_to_num_hex_and_inf_are_not_read_as_such():
    assert s.to_num("0x10", 0.0, False) == ("10", 0.0, True)
    assert s.to_num("inf", 1.0, True) == ("inf", 1.0, False)


# --- chr / asc (3.4.3) --------------------------------------------------------------------------


def test_chr_asc_manual_examples():
    assert s.chr_(65) == "A"  # 3.4.3
    assert s.asc("A", 0) == 65.0  # 3.4.3


def test_chr_unicode_code_points():
    assert s.chr_(0xE9) == "é"
    assert s.chr_(0x4E2D) == CHINESE
    assert s.chr_(0x1F600) == "😀"
    assert s.chr_(0x10FFFF) == "\U0010ffff"
    assert s.chr_(0) == "\x00"
    assert s.chr_(64.6) == "A"  # rounded like an index


@pytest.mark.parametrize("code", [-1, 0xD800, 0xDFFF, 0x110000, 1e12])
def test_chr_invalid_code_point_is_empty(code):
    # 3.4.3: "Dans le cas contraire, il renvoie une chaîne vide."
    assert s.chr_(code) == ""


def test_asc_positions():
    text = "aé中😀"
    assert [s.asc(text, i) for i in range(4)] == [97.0, 0xE9, 0x4E2D, 0x1F600]
    # 3.4.3: -1 if nPosition is negative or beyond the text
    assert s.asc(text, 4) == -1.0
    assert s.asc(text, 100) == -1.0
    assert s.asc(text, -1) == -1.0
    assert s.asc("", 0) == -1.0
    assert s.asc(text, 0.6) == 0xE9  # rounded like an index


def test_chr_asc_round_trip():
    for code in (1, 32, 65, 127, 128, 0x7FF, 0x800, 0xFFFF, 0x10000):
        assert s.asc(s.chr_(code), 0) == code


# --- left, right, mid (3.4.3) ---------------------------------------------------------------------


def test_left_right_manual_examples():
    text = "salut tout le monde"
    assert s.left(text, 5) == "salut"
    assert s.left(text, 20) == text
    assert s.right(text, 5) == "monde"
    assert s.right(text, 20) == text


def test_left_right_edges():
    assert s.left("abc", 0) == "" and s.right("abc", 0) == ""
    assert s.left("", 3) == "" and s.right("", 3) == ""
    assert s.left("é中😀x", 3) == "é中😀"  # characters, not bytes
    assert s.right("é中😀x", 2) == "😀x"
    assert s.left("abc", -0.4) == ""  # rounds to 0
    assert error_code(s.left, "abc", -1) == 70  # 3.4.3: negative nTaille
    assert error_code(s.right, "abc", -1) == 70


def test_mid_manual_examples():
    assert s.mid("salut joli monde", 4, 6) == "joli"  # 3.4.3
    assert s.mid("salut joli monde", 20, 6) == "joli monde"


def test_mid_edges():
    assert s.mid("abc", 2, 3) == ""
    assert s.mid("abc", 2, 10) == ""
    assert s.mid("abc", 0, 1) == ""
    assert s.mid("中文字", 1, 1) == "文"
    assert error_code(s.mid, "abc", -1, 0) == 70  # 3.4.3: nTaille or nPosition negative
    assert error_code(s.mid, "abc", 1, -1) == 70


# --- insert, delete, replace (3.4.3) --------------------------------------------------------------


def test_insert_manual_example():
    # The French 3.4.3 example, insert("salut tout le monde", "joli", 6) -> "salut joli monde",
    # cannot hold for any insertion (it mixes two translations of "hello world"); the English
    # one, insert("hello world", "wild ", 6) -> "hello wild world", inserts AT index 6:
    assert s.insert("hello world", "wild ", 6) == "hello wild world"
    assert s.insert("salut monde", "joli ", 6) == "salut joli monde"
    assert s.insert("salut tout le monde", "joli", 6) == "salut jolitout le monde"


def test_insert_edges():
    assert s.insert("abc", "X", 0) == "Xabc"
    assert s.insert("abc", "X", 3) == "abcX"
    assert s.insert("abc", "X", 50) == "abcX"  # 3.4.3: appended beyond the end
    assert s.insert("", "", 0) == ""
    assert s.insert("中文", "X", 1) == "中X文"
    assert error_code(s.insert, "abc", "X", -1) == 70  # 3.4.3


def test_insert_truncates_to_128_bytes():
    # 3.4.3: "Le résultat est tronqué s'il dépasse 128 octets."
    assert s.insert("a" * 120, "b" * 20, 0) == "b" * 20 + "a" * 108
    assert s.insert("a" * 126, "é", 126) == "a" * 126 + "é"
    assert s.insert("a" * 127, "é", 127) == "a" * 127
    assert s.insert("a" * 127, "é", 0) == "é" + "a" * 126


def test_delete_manual_example():
    # The French example, delete("salut joli monde", 5, 6) -> "salut tout le monde", is
    # inconsistent too; the English one is delete("hello wild world", 5, 6) -> "hello world".
    assert s.delete("hello wild world", 5, 6) == "hello world"
    assert s.delete("salut joli monde", 5, 6) == "salut monde"


def test_delete_edges():
    assert s.delete("abc", 10, 1) == "a"
    assert s.delete("abc", 0, 1) == "abc"
    assert s.delete("abc", 1, 3) == "abc"
    assert s.delete("abc", 1, 10) == "abc"  # 3.4.3: nPosition beyond the length
    assert s.delete("", 1, 0) == ""
    assert s.delete("a中b", 1, 1) == "ab"
    assert error_code(s.delete, "abc", -1, 0) == 70
    assert error_code(s.delete, "abc", 1, -1) == 70


def test_replace_manual_example():
    # 3.4.3: replace("salut • monde", "joli", 1, 6) renvoie "salut joli monde"
    assert s.replace("salut • monde", "joli", 1, 6) == "salut joli monde"


def test_replace_edges():
    assert s.replace("abcdef", "XY", 3, 1) == "aXYef"
    assert s.replace("abc", "XY", 10, 1) == "aXY"
    assert s.replace("abc", "XY", 0, 1) == "aXYbc"
    assert s.replace("abc", "XY", 1, 3) == "abcXY"  # at the length: appended
    assert s.replace("abc", "XY", 1, 4) == "abc"  # 3.4.3: beyond the length: unchanged
    assert s.replace("abc", "", 1, 1) == "ac"
    assert s.replace("a" * 128, "bb", 1, 0) == "bb" + "a" * 126
    assert s.replace("a" * 127, "中", 0, 127) == "a" * 127
    assert error_code(s.replace, "abc", "X", -1, 0) == 70
    assert error_code(s.replace, "abc", "X", 0, -1) == 70


# --- find, len, getDisplayLen -------------------------------------------------------------------


def test_find_and_len_manual_examples():
    assert s.find("salut joli monde", "joli") == 6.0  # 3.4.3
    assert s.len_("salut joli monde") == 16.0  # 3.4.3


def test_find_edges():
    assert s.find("salut joli monde", "moche") == -1.0  # 3.4.3
    assert s.find("abcabc", "c") == 2.0
    assert s.find("中文abc", "abc") == 2.0  # index in characters
    assert s.find("", "a") == -1.0
    assert s.find("abc", "") == 0.0  # strstr behaviour
    assert s.find("ab", "abc") == -1.0


def test_len_counts_characters_not_bytes():
    assert s.len_("") == 0.0
    assert s.len_("é中😀") == 3.0
    assert s.len_(CHINESE * 42) == 42.0


def test_get_display_len():
    # 4.3: same as len() for ASCII; Chinese characters take two columns
    assert s.get_display_len("salut joli monde") == s.len_("salut joli monde") == 16.0
    assert s.get_display_len("中文") == 4.0
    assert s.get_display_len("a中") == 3.0
    assert s.get_display_len("é") == 1.0
    assert s.get_display_len("") == 0.0


@pytest.mark.parametrize("func", [s.left, s.right])
def test_non_finite_sizes_are_error_11(func):
    assert error_code(func, "abc", math.nan) == 11
