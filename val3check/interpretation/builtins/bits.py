"""Bit fields (manual 3.3): bNot, bAnd, bOr, bXor, toBinary, fromBinary.

A bit field is a `num` holding an integer of [0, 2**32 - 1]. The bit-field instructions first
"round the numeric input to a positive integer in the range [0, 2^32]" (3.3.1): we round to the
nearest integer (halves upwards, like `round`) and then CLAMP to [0, 2**32 - 1] (the manual's
"[0, 2^32]" cannot be meant inclusively for a 32-bit field). So negative inputs become 0 and
too-large inputs 0xFFFFFFFF -- the manual's "rounded to a positive integer" reading, not a
two's-complement wrap.
"""

from __future__ import annotations

import math
import struct

from val3check.interpretation.builtins.numeric import finite, non_negative_int, round_half_up
from val3check.language.runtime_errors import Val3RuntimeError

MASK32 = 0xFFFFFFFF


def to_bitfield(x: float) -> int:
    """A num as a 32-bit field (3.3.1): rounded to the nearest integer, clamped to [0, 2**32-1]."""
    return int(min(max(round_half_up(x), 0.0), float(MASK32)))


def b_not(field: float) -> float:
    """`num bNot(num nChampBit)`: bitwise NOT on 32 bits (3.3.3)."""
    return float(~to_bitfield(field) & MASK32)


def b_and(field1: float, field2: float) -> float:
    """`num bAnd(num nChampBit1, num nChampBit2)`: bitwise AND on 32 bits (3.3.3)."""
    return float(to_bitfield(field1) & to_bitfield(field2))


def b_or(field1: float, field2: float) -> float:
    """`num bOr(num nChampBit1, num nChampBit2)`: bitwise OR on 32 bits (3.3.3)."""
    return float(to_bitfield(field1) | to_bitfield(field2))


def b_xor(field1: float, field2: float) -> float:
    """`num bXor(num nChampBit1, num nChampBit2)`: bitwise exclusive OR on 32 bits (3.3.3)."""
    return float(to_bitfield(field1) ^ to_bitfield(field2))


# --- toBinary / fromBinary (3.3.3) ------------------------------------------------------------

# The 14 encodings of the table of 3.3.3, as struct codes (byte order, code). Nothing else is
# accepted: "2.0b", "-4.0l", "1l", "8l" ... are "unsupported formats" (error 70).
FORMATS: dict[str, str] = {
    "-1": "<b",
    "1": "<B",
    "-2l": "<h",
    "-2b": ">h",
    "2l": "<H",
    "2b": ">H",
    "-4l": "<i",
    "-4b": ">i",
    "4l": "<I",
    "4b": ">I",
    "4.0l": "<f",
    "4.0b": ">f",
    "8.0l": "<d",
    "8.0b": ">d",
}


def _format(fmt: str) -> struct.Struct:
    code = FORMATS.get(fmt)
    if code is None:
        raise Val3RuntimeError(70, f"unsupported binary data format {fmt!r}")
    return struct.Struct(code)


def _count(n: float, available: int, what: str) -> int:
    count = non_negative_int(n, what)
    if count > available:
        raise Val3RuntimeError(70, f"{what} ({count}) is larger than the array ({available})")
    return count


def _encode(codec: struct.Struct, value: float) -> bytes:
    value = finite(value)
    code = codec.format[-1]
    if code in "fd":
        try:
            return codec.pack(value)
        except OverflowError:  # beyond the single-precision range: IEEE 754 gives an infinity
            return codec.pack(math.copysign(math.inf, value))
    bits = codec.size * 8
    low, high = (-(1 << (bits - 1)), (1 << (bits - 1)) - 1) if code.islower() else (0, (1 << bits) - 1)
    return codec.pack(int(min(max(round_half_up(value), float(low)), float(high))))


def to_binary(values: list[float], count: float, fmt: str, data: list[float]) -> tuple[float, list[float]]:
    """`num toBinary(num nValeur[], num nTailleValeur, string sFormatDonnées, num& nOctetDonnées[])`.

    Encodes the first `count` values of `values` into bytes (nums in [0, 255]) with `fmt`
    (one of FORMATS). Returns `(number of bytes written, new nOctetDonnées)`: the new array has
    the length of `data`, its first bytes replaced, the rest unchanged.

    Integer formats: the value is rounded to the nearest integer (halves upwards) and clamped
    to the format's range (e.g. 300 -> 255 and -1 -> 0 with "1"); the manual does not say.
    "4.0l"/"4.0b": IEEE conversion to single precision (a value beyond its range becomes an
    infinity). Errors 70 (3.3.3): unsupported format, negative count, count larger than
    `values`, `data` too small for all the bytes.
    """
    codec = _format(fmt)
    n = _count(count, len(values), "nTailleValeur")
    size = n * codec.size
    if size > len(data):
        raise Val3RuntimeError(70, f"nOctetDonnées has {len(data)} elements, {size} bytes are needed")
    encoded = b"".join(_encode(codec, v) for v in values[:n])
    return float(size), [float(b) for b in encoded] + list(data[size:])


def _byte(x: float) -> int | None:
    """A byte of nOctetDonnées, or None when it is outside [0, 255] (or not finite)."""
    if not math.isfinite(x) or x < 0 or x > 255:
        return None
    return int(round_half_up(x)) & 0xFF


def from_binary(data: list[float], count: float, fmt: str, values: list[float]) -> tuple[float, list[float]]:
    """`num fromBinary(num nOctetDonnées[], num nTailleDonnées, string sFormatDonnées, num& nValeur[])`.

    Decodes the first `count` bytes of `data` with `fmt`. Returns `(result, new nValeur)`: the
    new array has the length of `values`, its first elements replaced by the decoded values.

    The result is the number of decoded values. When a value is corrupt (one of its bytes outside
    [0, 255], or a float encoding that is NaN or infinite), decoding stops there and the result
    is MINUS the number of values correctly decoded before it (3.3.3); those are written, the
    rest of `values` is unchanged. Bytes with a fractional part are rounded. Trailing bytes that
    do not make a whole value are ignored (the manual does not say).

    Errors 70 (3.3.3): unsupported format, negative count, count larger than `data`, `values`
    too small for all the values.
    """
    codec = _format(fmt)
    n = _count(count, len(data), "nTailleDonnées")
    total = n // codec.size
    if total > len(values):
        raise Val3RuntimeError(70, f"nValeur has {len(values)} elements, {total} values are decoded")
    decoded: list[float] = []
    corrupt = False
    for i in range(total):
        raw = [_byte(x) for x in data[i * codec.size : (i + 1) * codec.size]]
        if any(b is None for b in raw):
            corrupt = True
            break
        (value,) = codec.unpack(bytes(b for b in raw if b is not None))
        if not math.isfinite(value):
            corrupt = True
            break
        decoded.append(float(value) + 0.0)
    result = -len(decoded) if corrupt else len(decoded)
    return float(result) + 0.0, decoded + list(values[len(decoded) :])
