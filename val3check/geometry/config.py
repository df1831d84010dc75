"""The `config` type (9.7): a tuple of strings, ``(shoulder, elbow, wrist)`` for RX/TX arms,
``(shoulder,)`` for RS/TS arms.

Values (9.7.2): shoulder righty/lefty/ssame/sfree, elbow epositive/enegative/esame/efree, wrist
wpositive/wnegative/wsame/wfree. A *concrete* config (what `config(joint)` returns and what the
kinematics' `config_of` must return) holds only righty/lefty, epositive/enegative,
wpositive/wnegative. `==`/`!=` (9.7.3) compare the fields.
"""

from __future__ import annotations

from collections.abc import Sequence

Config = tuple[str, ...]

FIELDS = ("shoulder", "elbow", "wrist")
VALUES = {
    "shoulder": ("righty", "lefty", "ssame", "sfree"),
    "elbow": ("epositive", "enegative", "esame", "efree"),
    "wrist": ("wpositive", "wnegative", "wsame", "wfree"),
}
FREE = frozenset({"sfree", "efree", "wfree"})
SAME = frozenset({"ssame", "esame", "wsame"})
DEFAULT: Config = ("ssame", "esame", "wsame")  # what the interpreter gives an unwritten config


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
