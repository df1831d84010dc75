"""The `string` instructions of VAL 3 (manual 3.4.3), `getDisplayLen` (4.3), the `+` operator
(3.4.2) and the display of a num by `put`/`putln` (4.3).

Strings are Python `str`. Sizes and positions (len, left, right, mid, insert, delete, replace,
find, asc) count CHARACTERS, i.e. Unicode code points (len is "the number of characters",
3.4.3; find returns "the index of the first character"). Only the storage limit counts BYTES:
a string is stored in 128 bytes of UTF-8 (3.4.1). Every string result is cut to at most 128
bytes, always between two characters (never inside a multi-byte character) -- the manual states
the truncation for `+` (3.4.2) and `insert`; we apply it to every result that could grow
(replace, toString...). Inputs are assumed to be valid VAL 3 strings (at most 128 bytes).

Integer parameters (sizes, positions, code points) are rounded to the nearest integer, as array
indices are (2.5.3); "negative" is judged after rounding and raises error 70 where the manual
says a negative value is an error.
"""

from __future__ import annotations

import math
import re
import unicodedata

from val3check.interpretation.builtins.numeric import finite, non_negative_int, to_int
from val3check.language.runtime_errors import Val3RuntimeError

MAX_BYTES = 128


def utf8_size(text: str) -> int:
    """Bytes of `text` in UTF-8 (lone surrogates count 3, as 'surrogatepass' encodes them)."""
    return sum(_char_size(c) for c in text)


def _char_size(c: str) -> int:
    o = ord(c)
    return 1 if o < 0x80 else 2 if o < 0x800 else 3 if o < 0x10000 else 4


def fit(text: str) -> str:
    """`text` cut to its longest prefix of at most 128 UTF-8 bytes that ends between two
    characters (3.4.1)."""
    if len(text) * 4 <= MAX_BYTES:
        return text
    used = 0
    for i, c in enumerate(text):
        used += _char_size(c)
        if used > MAX_BYTES:
            return text[:i]
    return text


def concat(text1: str, text2: str) -> str:
    """The `+` operator (3.4.2): text1 followed by text2, limited to 128 bytes."""
    return fit(text1 + text2)


# --- toString / put (3.4.3, 4.3) ---------------------------------------------------------------

_FORMAT = re.compile(r"(\d*)(?:\.(\d*))?")
# More decimals than any double has (at most 1074): larger precisions only add zeros.
_MAX_PRECISION = 1100


def to_string(fmt: str, value: float) -> str:
    """`string toString(string sFormat, num nValeur)` (3.4.3).

    sFormat is "size.precision" (both optional, default 0): `precision` digits after the
    decimal point, rounded like C printf (round-half-even on the exact binary value: ".0" of
    0.5 gives "0"); the trailing zeros of the decimals are then replaced by spaces, and when all
    decimals are zeros the decimal point too (our choice: the manual shows only "2.7000" ->
    "2.7   "); leading spaces up to `size` characters; the integer part is never cut. A value
    that rounds to zero is written without a minus sign. Any other format (e.g. "%5.2f", "-3",
    "a") is error 70 (our choice, the manual does not say).
    """
    match = _FORMAT.fullmatch(fmt)
    if match is None:
        raise Val3RuntimeError(70, f'invalid toString format {fmt!r} (expected "size.precision")')
    size = int(match.group(1) or 0)
    precision = min(int(match.group(2) or 0), _MAX_PRECISION)
    text = _fixed(finite(value), precision)
    padding = max(0, size - len(text))
    if padding >= MAX_BYTES:
        return " " * MAX_BYTES
    return fit(" " * padding + text)


def _fixed(value: float, precision: int) -> str:
    text = f"{value:.{precision}f}"
    if text.startswith("-") and not text.strip("-0."):
        text = text[1:]  # -0.00 -> 0.00
    if "." not in text:
        return text
    kept = text.rstrip("0").removesuffix(".")
    return kept + " " * (len(text) - len(kept))


def format_num_default(value: float) -> str:
    """A num as `put`/`putln` display it: "with 3 decimals" (4.3), without the trailing zeros,
    as the toNum example of 3.4.3 shows ("displays successively 90, 0, -7.6, 17.3").

    That is toString(".3", value) without its trailing spaces: 3.14159 -> "3.142",
    90 -> "90", -7.6 -> "-7.6", 0.0004 -> "0".
    """
    return to_string(".3", value).rstrip(" ")


# --- toNum (3.4.3) -----------------------------------------------------------------------------

# 3.2.1's constant format, plus the leading '+' of 3.4.3's example ("+90 0.0 -7.6 17.3") and the
# forms C strtod also reads ("5.", ".5", "1E3", "1e+3"). No hexadecimal, inf or nan.
_NUMBER = re.compile(r"[+-]?(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][+-]?\d+)?")
_LEADING_SPACE = re.compile(r"[ \t\r\n\f\v]*")


def to_num(text: str, value: float, report: bool) -> tuple[str, float, bool]:
    """`string toNum(string sChaîne, num& nValeur, bool& bRapport)` (3.4.3).

    Called with the current values of nValeur and bRapport; returns
    `(result, nValeur, bRapport)`. When sChaîne starts with a number (after optional blanks, as
    C strtod reads it), returns (the rest of sChaîne from the NEXT number on, or "" when no
    number follows, that number, True): toNum("10 20 30") -> ("20 30", 10, True),
    toNum("10 end") -> ("", 10, True). Otherwise returns (sChaîne unchanged, nValeur unchanged,
    False). A number too large for a num (e.g. "1e999") does not count as a number.
    """
    start = _LEADING_SPACE.match(text).end()
    match = _NUMBER.match(text, start)
    if match is None:
        return text, value, False
    number = float(match.group())
    if not math.isfinite(number):
        return text, value, False
    following = _NUMBER.search(text, match.end())
    rest = text[following.start() :] if following else ""
    return rest, number + 0.0, True


# --- characters (3.4.3) ------------------------------------------------------------------------


def chr_(code_point: float) -> str:
    """`string chr(num nCodePoint)` (3.4.3): the one-character string of this Unicode code point
    (rounded to the nearest integer), or "" if it is not a valid code point (negative, above
    0x10FFFF, or a UTF-16 surrogate 0xD800-0xDFFF). chr(0) is "\\x00" (0 is a valid code point)."""
    code = to_int(code_point, "nCodePoint")
    if code < 0 or code > 0x10FFFF or 0xD800 <= code <= 0xDFFF:
        return ""
    return chr(code)


def asc(text: str, position: float) -> float:
    """`num asc(string sTexte, num nPosition)` (3.4.3): code point of the character at index
    nPosition, or -1 if nPosition is negative or not the index of a character (>= len)."""
    index = to_int(position, "nPosition")
    if index < 0 or index >= len(text):
        return -1.0
    return float(ord(text[index]))


# --- substrings (3.4.3) ------------------------------------------------------------------------


def left(text: str, size: float) -> str:
    """`string left(string sTexte, num nTaille)`: the first nTaille characters (all of sTexte if
    it is shorter); error 70 if nTaille is negative."""
    return text[: non_negative_int(size, "nTaille")]


def right(text: str, size: float) -> str:
    """`string right(string sTexte, num nTaille)`: the last nTaille characters (all of sTexte if
    it is shorter); error 70 if nTaille is negative."""
    n = non_negative_int(size, "nTaille")
    return text[len(text) - n :] if n < len(text) else text


def mid(text: str, size: float, position: float) -> str:
    """`string mid(string sTexte, num nTaille, num nPosition)`: nTaille characters from index
    nPosition, stopping at the end ("" when nPosition >= len); error 70 if either is negative."""
    n = non_negative_int(size, "nTaille")
    start = non_negative_int(position, "nPosition")
    return text[start : start + n]


def insert(text: str, insertion: str, position: float) -> str:
    """`string insert(string sTexte, string sInsertion, num nPosition)` (3.4.3).

    sInsertion is inserted so that it starts at index nPosition (after the first nPosition
    characters: the manual's "after the character of index nPosition" is off by one against its
    own English examples); appended when nPosition >= len; result cut to 128 bytes; error 70 if
    nPosition is negative.
    """
    start = non_negative_int(position, "nPosition")
    return fit(text[:start] + insertion + text[start:])


def delete(text: str, size: float, position: float) -> str:
    """`string delete(string sTexte, num nTaille, num nPosition)` (3.4.3): sTexte without the
    nTaille characters from index nPosition (up to the end at most); sTexte when nPosition is
    beyond the end; error 70 if either is negative."""
    n = non_negative_int(size, "nTaille")
    start = non_negative_int(position, "nPosition")
    return text[:start] + text[start + n :]


def replace(text: str, replacement: str, size: float, position: float) -> str:
    """`string replace(string sTexte, string sRemplacement, num nTaille, num nPosition)` (3.4.3):
    the nTaille characters from index nPosition (up to the end at most) replaced by
    sRemplacement; sTexte unchanged when nPosition > len (at nPosition == len, sRemplacement is
    appended); result cut to 128 bytes; error 70 if nTaille or nPosition is negative."""
    n = non_negative_int(size, "nTaille")
    start = non_negative_int(position, "nPosition")
    if start > len(text):
        return text
    return fit(text[:start] + replacement + text[start + n :])


def find(text1: str, text2: str) -> float:
    """`num find(string sTexte1, string sTexte2)` (3.4.3): index (in characters) of the first
    occurrence of sTexte2 in sTexte1, -1 if none. An empty sTexte2 is found at 0 (as C strstr;
    the manual does not say)."""
    return float(text1.find(text2))


def len_(text: str) -> float:
    """`num len(string sTexte)` (3.4.3): the number of characters (code points, not bytes)."""
    return float(len(text))


def get_display_len(text: str) -> float:
    """`num getDisplayLen(string sTexte)` (4.3): columns needed on the MCP screen. Wide and
    full-width characters (East Asian Width W or F, e.g. Chinese) take 2 columns, every other
    character 1 (so it equals len() for ASCII, as the manual says)."""
    return float(sum(2 if unicodedata.east_asian_width(c) in "WF" else 1 for c in text))
