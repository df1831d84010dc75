"""The `joint` type (9.2): operators of 9.2.2 and abs, isInRange of 9.2.3.

A joint value is a sequence of floats, one per axis (6 for RX/TX arms, 4 for RS/TS arms),
degrees for rotary axes, the length unit for linear ones; results are tuples. Two joint values
with different numbers of axes raise 81 (incompatible kinematics, 12.1).
"""

from __future__ import annotations

from collections.abc import Sequence

from ..language.runtime_errors import Val3RuntimeError

Joint = tuple[float, ...]
FIELDS = ("j1", "j2", "j3", "j4", "j5", "j6")

# 9.2.2: == and != compare "à la précision du robot près"; the manual gives no figure. This is
# the tolerance per field (degrees or length unit).
JOINT_EPS = 1e-6


def _pair(a: Sequence[float], b: Sequence[float]) -> None:
    if len(a) != len(b):
        raise Val3RuntimeError(81, f"joint values with {len(a)} and {len(b)} axes")


def from_dict(d: dict) -> Joint:
    """From the interpreter's dict shape {"j1": .., "j2": .., ...}."""
    return tuple(float(d[f]) for f in FIELDS if f in d)


def to_dict(j: Sequence[float]) -> dict[str, float]:
    return {f: float(v) for f, v in zip(FIELDS, j)}


def add(a: Sequence[float], b: Sequence[float]) -> Joint:
    """`+`: field by field sum."""
    _pair(a, b)
    return tuple(x + y for x, y in zip(a, b))


def sub(a: Sequence[float], b: Sequence[float]) -> Joint:
    """`-`: field by field difference."""
    _pair(a, b)
    return tuple(x - y for x, y in zip(a, b))


def eq(a: Sequence[float], b: Sequence[float], eps: float = JOINT_EPS) -> bool:
    """`==`: every field equal to the corresponding one within the robot's precision."""
    _pair(a, b)
    return all(abs(x - y) <= eps for x, y in zip(a, b))


def ne(a: Sequence[float], b: Sequence[float], eps: float = JOINT_EPS) -> bool:
    """`!=`: some field differs by more than the robot's precision."""
    return not eq(a, b, eps)


def gt(a: Sequence[float], b: Sequence[float]) -> bool:
    """`>`: EVERY field of a strictly greater than the corresponding field of b (so `a > b` is
    not `!(a < b)`, 9.2.2)."""
    _pair(a, b)
    return all(x > y for x, y in zip(a, b))


def lt(a: Sequence[float], b: Sequence[float]) -> bool:
    """`<`: every field of a strictly smaller (named by 9.2.3, missing from the table of 9.2.2)."""
    _pair(a, b)
    return all(x < y for x, y in zip(a, b))


def abs_(a: Sequence[float]) -> Joint:
    """9.2.3 abs(joint): absolute value field by field."""
    return tuple(abs(x) + 0.0 for x in a)


def herej(current: Sequence[float]) -> Joint:
    """9.2.3 herej(): the current (commanded) joint position, as a new value."""
    return tuple(float(x) for x in current)


def is_in_range(j: Sequence[float], limits: Sequence[tuple[float, float]]) -> bool:
    """9.2.3 isInRange(joint): every axis within its software limits (min, max), bounds
    included. `limits` has one (min, max) per axis (the arm model provides them)."""
    if len(j) != len(limits):
        raise Val3RuntimeError(81, f"a joint value with {len(j)} axes for an arm with {len(limits)}")
    return all(lo <= x <= hi for x, (lo, hi) in zip(j, limits))
