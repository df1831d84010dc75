"""The `config` type (9.7): a tuple of strings, ``(shoulder, elbow, wrist)`` for RX/TX arms,
``(shoulder,)`` for RS/TS arms.

Values (9.7.2): shoulder righty/lefty/ssame/sfree, elbow epositive/enegative/esame/efree, wrist
wpositive/wnegative/wsame/wfree. A *concrete* config (what `config(joint)` returns and what the
kinematics' `config_of` must return) holds only righty/lefty, epositive/enegative,
wpositive/wnegative. `==`/`!=` (9.7.3) compare the fields.
"""

from __future__ import annotations

from collections.abc import Sequence

from ..language.types import load_types

Config = tuple[str, ...]

# From language/types.toml: the config type's fields and the values of each (9.7.2).
FIELDS: tuple[str, ...] = tuple(f.name for f in load_types()["config"].fields)
VALUES: dict[str, tuple[str, ...]] = {f: load_types()[f].values for f in FIELDS}
FREE = frozenset(v for vs in VALUES.values() for v in vs if v.endswith("free"))
SAME = frozenset(v for vs in VALUES.values() for v in vs if v.endswith("same"))
# the values an arm position has (config(joint), 9.7.4): neither same nor free
CONCRETE: dict[str, tuple[str, ...]] = {f: tuple(v for v in vs if v not in FREE and v not in SAME)
                                        for f, vs in VALUES.items()}
DEFAULT: Config = tuple(f.default for f in load_types()["config"].fields)  # an unwritten config


def from_dict(d: dict) -> Config:
    """From the interpreter's dict shape {"shoulder": .., "elbow": .., "wrist": ..} (RS arms:
    only "shoulder")."""
    return tuple(str(d[f]) for f in FIELDS if f in d)


def to_dict(c: Sequence[str]) -> dict[str, str]:
    return {f: v for f, v in zip(FIELDS, c)}


def resolve(required: Sequence[str], initial: Sequence[str]) -> Config:
    """Replace each `same` field of `required` by the field of the concrete config `initial`
    (pointToJoint, 9.6.3: `same` imposes jInitial's configuration)."""
    return tuple(i if r.lower() in SAME else r for r, i in zip(required, initial))


def matches(required: Sequence[str], actual: Sequence[str], initial: Sequence[str] | None = None) -> bool:
    """Does the concrete config `actual` satisfy `required`? `free` fields accept anything,
    `same` fields need `initial`'s value (without `initial`, `same` accepts anything)."""
    for k, r in enumerate(required):
        rl = r.lower()
        if rl in FREE:
            continue
        if rl in SAME:
            if initial is not None and actual[k].lower() != initial[k].lower():
                return False
            continue
        if actual[k].lower() != rl:
            return False
    return True
