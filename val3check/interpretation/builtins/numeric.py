"""The `num` instructions of VAL 3 (manual 3.2.3) and the checks shared by every built-in.

A VAL 3 `num` is a Python `float` (an IEEE double: "about 14 significant digits", 3.2.1).
Angles are in DEGREES. A `num` is always finite: a non-finite argument or result raises
error 11 (invalid numeric computation); -0.0 results are returned as 0.0.

Exactness: `sin(30)` must return 0.5 and `asin(0.5)` 30 (3.2.3). Computing through radians
gives 0.49999999999999994 and 30.000000000000004, so angles that are exact multiples of 30 or
45 degrees use exact values (the correctly rounded doubles of 0, 1/2, sqrt(2)/2, sqrt(3)/2, 1),
and the inverse functions map those values back to the exact angles. Other angles go through
radians, with the angle first reduced exactly to (-180, 180].
"""

from __future__ import annotations

import math

from val3check.language.runtime_errors import Val3RuntimeError

# --- helpers shared by bits.py and strings.py --------------------------------------------------


def finite(x: float, what: str = "value") -> float:
    """`x` as a float, or error 11 if it is infinite or NaN (a VAL 3 num is always finite)."""
    x = float(x)
    if not math.isfinite(x):
        raise Val3RuntimeError(11, f"{what} is not a finite number ({x!r})")
    return x + 0.0  # -0.0 becomes 0.0


def round_half_up(x: float) -> float:
    """Nearest integer, halves upwards: VAL 3 `round` (3.2.3: round(0.5)=1, round(-0.5)=0).

    The same rounding is used wherever the manual says a num is "rounded to the nearest integer"
    (array indices, 2.5.3; bit fields, 3.3.1) and for our integer parameters (sizes, positions).
    """
    x = finite(x)
    down = math.floor(x)
    return float(down + 1 if x - down >= 0.5 else down) + 0.0


def to_int(x: float, what: str = "value") -> int:
    """An integer parameter (size, position, code point, count): rounded like an array index."""
    return int(round_half_up(finite(x, what)))


def non_negative_int(x: float, what: str) -> int:
    """An integer parameter that the manual forbids to be negative: error 70 if it is (after
    rounding to the nearest integer, as array indices are, 2.5.3)."""
    n = to_int(x, what)
    if n < 0:
        raise Val3RuntimeError(70, f"{what} is negative ({x!r})")
    return n


# --- trigonometry (3.2.3), in degrees ---------------------------------------------------------

_HALF_SQRT2 = math.sqrt(2.0) / 2.0
_HALF_SQRT3 = math.sqrt(3.0) / 2.0
_SQRT3 = math.sqrt(3.0)
_INV_SQRT3 = 1.0 / math.sqrt(3.0)

# sin of the angles in [0, 90] that are multiples of 15 with an exact table value.
_SIN_EXACT: dict[int, float] = {0: 0.0, 30: 0.5, 45: _HALF_SQRT2, 60: _HALF_SQRT3, 90: 1.0}


def _reduce(angle: float) -> float:
    """`angle` reduced exactly to (-180, 180] (fmod and these subtractions are exact)."""
    r = math.fmod(finite(angle, "angle"), 360.0)
    if r > 180.0:
        r -= 360.0
    elif r <= -180.0:
        r += 360.0
    return r


def _sin_exact(r: float) -> float | None:
    """sin(r) for r in (-180, 180] when r is a multiple of 30 or 45 degrees, else None."""
    if r % 15.0 != 0.0:
        return None
    sign = -1.0 if r < 0 else 1.0
    a = abs(r)
    if a > 90.0:
        a = 180.0 - a  # sin(180 - a) = sin(a)
    value = _SIN_EXACT.get(int(a))
    return None if value is None else sign * value + 0.0


def sin(angle: float) -> float:
    """`num sin(num nAngle)`: sine of an angle in degrees (3.2.3: sin(30) = 0.5)."""
    r = _reduce(angle)
    exact = _sin_exact(r)
    return exact if exact is not None else finite(math.sin(math.radians(r)))


def cos(angle: float) -> float:
    """`num cos(num nAngle)`: cosine of an angle in degrees (3.2.3: cos(60) = 0.5)."""
    r = _reduce(angle)
    # cos(r) = sin(90 - |r|), exact subtraction for |r| <= 180
    exact = _sin_exact(90.0 - abs(r))
    return exact if exact is not None else finite(math.cos(math.radians(r)))


def tan(angle: float) -> float:
    """`num tan(num nAngle)`: tangent of an angle in degrees (3.2.3: tan(45) = 1.0).

    The manual states no error: at odd multiples of 90 degrees the result is the (huge, finite)
    tangent of the nearest double to pi/2, as a C `tan(x*pi/180)` would return.
    """
    r = _reduce(angle)
    s, c = _sin_exact(r), _sin_exact(90.0 - abs(r))
    if s is not None and c is not None and c != 0.0:
        return s / c + 0.0
    return finite(math.tan(math.radians(r)))


def _inverse_table() -> dict[float, float]:
    table: dict[float, float] = {}
    for degrees, value in _SIN_EXACT.items():
        table[value] = float(degrees)
        table[-value] = -float(degrees) + 0.0
    return table


_ASIN_EXACT = _inverse_table()
_ATAN_EXACT: dict[float, float] = {0.0: 0.0, 1.0: 45.0, _SQRT3: 60.0, _INV_SQRT3: 30.0}
_ATAN_EXACT.update({tan(30.0): 30.0})
_ATAN_EXACT.update({-k: -v for k, v in list(_ATAN_EXACT.items()) if k})


def _unit_interval(x: float, name: str) -> float:
    x = finite(x)
    if x > 1.0 or x < -1.0:
        raise Val3RuntimeError(11, f"{name}({x!r}): the value must be in [-1, 1]")
    return x


def asin(x: float) -> float:
    """`num asin(num nValeur)`: arc sine in degrees, in [-90, 90]; error 11 outside [-1, 1]
    (3.2.3: asin(0.5) = 30)."""
    x = _unit_interval(x, "asin")
    exact = _ASIN_EXACT.get(x)
    return exact if exact is not None else finite(math.degrees(math.asin(x)))


def acos(x: float) -> float:
    """`num acos(num nValeur)`: arc cosine in degrees, in [0, 180]; error 11 outside [-1, 1]
    (3.2.3: acos(0.5) = 60)."""
    x = _unit_interval(x, "acos")
    exact = _ASIN_EXACT.get(x)
    return 90.0 - exact + 0.0 if exact is not None else finite(math.degrees(math.acos(x)))


def atan(x: float) -> float:
    """`num atan(num nValeur)`: arc tangent in degrees, in [-90, 90] (3.2.3: atan(1) = 45)."""
    x = finite(x)
    exact = _ATAN_EXACT.get(x)
    return exact if exact is not None else finite(math.degrees(math.atan(x)))


# --- other functions (3.2.3) ------------------------------------------------------------------


def abs_(x: float) -> float:
    """`num abs(num nValeur)`: absolute value (3.2.3). (The joint overload, 9.2.3, is not here.)"""
    return abs(finite(x))


def sqrt(x: float) -> float:
    """`num sqrt(num nValeur)`: square root; error 11 if nValeur is negative (3.2.3)."""
    x = finite(x)
    if x < 0:
        raise Val3RuntimeError(11, f"sqrt({x!r}) of a negative value")
    return math.sqrt(x) + 0.0


def exp(x: float) -> float:
    """`num exp(num nValeur)`: e to the power nValeur; error 11 if the result is too large
    (3.2.3)."""
    x = finite(x)
    try:
        return finite(math.exp(x))
    except OverflowError:
        raise Val3RuntimeError(11, f"exp({x!r}) is too large") from None


def power(x: float, y: float) -> float:
    """`num power(num nX, num nY)`: nX to the power nY.

    3.2.3: "an execution error is generated if nX is negative or zero, or if the result is too
    large" -- so power(0, 2) and power(-2, 2) are errors (11), as the manual says.
    """
    x, y = finite(x), finite(y)
    if x <= 0:
        raise Val3RuntimeError(11, f"power({x!r}, {y!r}): nX must be strictly positive")
    try:
        return finite(math.pow(x, y))
    except OverflowError:
        raise Val3RuntimeError(11, f"power({x!r}, {y!r}) is too large") from None


def ln(x: float) -> float:
    """`num ln(num nValeur)`: natural logarithm; error 11 if nValeur <= 0 (3.2.3)."""
    x = finite(x)
    if x <= 0:
        raise Val3RuntimeError(11, f"ln({x!r}) of a value that is not strictly positive")
    return math.log(x) + 0.0


def log(x: float) -> float:
    """`num log(num nValeur)`: decimal logarithm; error 11 if nValeur <= 0 (3.2.3)."""
    x = finite(x)
    if x <= 0:
        raise Val3RuntimeError(11, f"log({x!r}) of a value that is not strictly positive")
    return math.log10(x) + 0.0


def round_up(x: float) -> float:
    """`num roundUp(num nValeur)`: smallest integer >= nValeur (3.2.3: roundUp(-7.8) = -7)."""
    return float(math.ceil(finite(x))) + 0.0


def round_down(x: float) -> float:
    """`num roundDown(num nValeur)`: largest integer <= nValeur (3.2.3: roundDown(-7.8) = -8)."""
    return float(math.floor(finite(x))) + 0.0


def round_(x: float) -> float:
    """`num round(num nValeur)`: nearest integer, halves upwards (3.2.3: round(0.5) = 1,
    round(-0.5) = 0)."""
    return round_half_up(x)


def min_(x: float, y: float) -> float:
    """`num min(num nX, num nY)` (3.2.3)."""
    return min(finite(x), finite(y))


def max_(x: float, y: float) -> float:
    """`num max(num nX, num nY)` (3.2.3)."""
    return max(finite(x), finite(y))


def limit(value: float, low: float, high: float) -> float:
    """`num limit(num nValeur, num nMini, num nMaxi)`: nValeur bounded by nMini and nMaxi.

    The manual does not say what happens when nMini > nMaxi; we apply nMini then nMaxi, so nMaxi
    wins (no error).
    """
    return min(max(finite(value), finite(low)), finite(high))


def sel(condition: bool, value1: float, value2: float) -> float:
    """`num sel(bool bCondition, num nValeur1, num nValeur2)`: nValeur1 if bCondition else
    nValeur2 (3.2.3)."""
    return finite(value1) if condition else finite(value2)


# --- operators of 3.2.2 with a runtime error (for the interpreter) ----------------------------


def divide(x: float, y: float) -> float:
    """`nValeur1 / nValeur2` (3.2.2): error 10 if nValeur2 is 0, error 11 on overflow."""
    x, y = finite(x), finite(y)
    if y == 0:
        raise Val3RuntimeError(10, f"{x!r} / 0")
    return finite(x / y, "quotient")


def modulo(x: float, y: float) -> float:
    """`nValeur1 % nValeur2` (3.2.2): remainder with the sign of nValeur1 (C `fmod`, also for
    non-integer operands); error 10 if nValeur2 is 0."""
    x, y = finite(x), finite(y)
    if y == 0:
        raise Val3RuntimeError(10, f"{x!r} % 0")
    return math.fmod(x, y) + 0.0
