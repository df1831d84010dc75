"""Steps of the checks between motions that are not done again when what they are made of did
not change (issue 29, seventh round): the scene's key (`World.key`), the static set's boxes at a
replayed open()/close(). Each input changed in turn gives what a fresh computation gives."""

from __future__ import annotations

import numpy as np
import pytest

from .helpers import TOOL, checker
from .test_reuse import BALL, PICK, PLACE, _grip_cell, _q

MUTATIONS = {
    "set a pair": lambda d, a, b: d.__setitem__(frozenset((id(a), id(b))), (a, b)),
    "set it again, the other way": lambda d, a, b: d.__setitem__(frozenset((id(a), id(b))), (b, a)),
    "delete": lambda d, a, b: d.__delitem__(next(iter(d))),
    "clear": lambda d, a, b: d.clear(),
    "pop": lambda d, a, b: d.pop(next(iter(d))),
    "popitem": lambda d, a, b: d.popitem(),
    "setdefault": lambda d, a, b: d.setdefault(frozenset((id(a), id(b))), (a, b)),
    "update": lambda d, a, b: d.update({frozenset((id(a), id(b))): (a, b)}),
    "update by keywords": lambda d, a, b: d.update(**{}),
    "|=": lambda d, a, b: d.__ior__({frozenset((id(b), id(a))): (b, a)}),
}


def _fresh_key(w) -> tuple:
    """`World.key` computed without its memo."""
    links = getattr(w.arm.links, "current", w.arm.links)
    return links, w.per_scene("key", w._scene_id), tuple(w.allowed_names())


@pytest.mark.parametrize("how", list(MUTATIONS))
def test_the_scene_key_follows_every_change_of_the_pairs_allowed_to_touch(how):
    chk = checker(_grip_cell(), frames={"fBall": BALL})
    chk.refresh(0.0)
    w = chk.world
    a, b = w.static[0], next(iter(w.link_groups.values())).bodies[0]
    c = w.static[1]
    w.allowed[frozenset((id(c), id(b)))] = (c, b)
    before = w.key()
    assert w.key() is before and before == _fresh_key(w)  # nothing changed: the same answer
    stamp = w.allowed.stamp
    MUTATIONS[how](w.allowed, a, b)
    assert w.allowed.stamp != stamp  # every mutator stamps, even one that leaves the content as it was
    assert w.key() == _fresh_key(w)
    w.allowed = {}  # a new dict: a new stamp
    assert w.key() == _fresh_key(w) and w.key()[2] == ()


def test_the_scene_key_follows_the_scene_and_the_arm_geometry():
    chk = checker(_grip_cell(), frames={"fBall": BALL})
    chk.refresh(0.0)
    w = chk.world
    first = w.key()
    chk.gripper("tTool", "close", 1.0, joints=_q(PICK))  # a part carried: another scene
    carried = w.key()
    assert carried[1] != first[1] and carried == _fresh_key(w)
    chk.gripper("tTool", "open", 2.0, joints=_q(PLACE))  # left in the cell
    assert w.key()[1] not in (first[1], carried[1]) and w.key() == _fresh_key(w)
    chk.clear_parts("brick")  # the scene the cycle started in: its number
    assert w.key() == first

    class Epochs:  # setDH (11.4): the geometry in force changes
        def __init__(self, current):
            self.current = current

        def __getattr__(self, name):
            return getattr(self.current, name)

    w.arm.links, real = Epochs(w.arm.links), w.arm.links
    try:
        key = w.key()
        assert key[0] is real and key == _fresh_key(w)
        w.arm.links.current = object()
        assert w.key()[0] is w.arm.links.current and w.key() == _fresh_key(w)
    finally:
        w.arm.links = real


def _boxes(w) -> tuple:
    """The static set's boxes computed afresh from its bodies."""
    if not w.static:
        return b"", b""
    return (np.array([b.aabb()[0] for b in w.static]).tobytes(), np.array([b.aabb()[1] for b in w.static]).tobytes())


def test_a_replayed_open_or_close_leaves_the_static_boxes_a_fresh_computation_gives():
    frames = {"fBall": BALL}
    chk = checker(_grip_cell(), frames=frames, tools={"tTool": TOOL, "tOther": TOOL})
    w = chk.world
    seen = []
    chk.gripper("tTool", "close", 0.5, joints=_q(PICK))
    chk.gripper("tTool", "open", 0.6, joints=_q(PICK))  # the brick lies at PICK
    for cycle in range(4):  # taken from where it lies, left at the other place, and back
        t = 10.0 * cycle
        for k, (instr, at) in enumerate((("close", PICK), ("open", PLACE), ("close", PLACE), ("open", PICK))):
            chk.gripper("tTool", instr, t + k, joints=_q(at))
            seen.append((w.static_lo.tobytes(), w.static_hi.tobytes()))
            assert seen[-1] == _boxes(w)
            assert not w.static_lo.flags.writeable and not w.static_hi.flags.writeable  # shared with the record
    assert w.grips_reused >= 12
    assert seen[0:4] == seen[4:8] == seen[12:16] and len(set(seen[:4])) == 3  # carried twice: the obstacles alone
    chk.clear_parts("brick")  # after replays, the boxes kept from them: the same numbers
    assert (w.static_lo.tobytes(), w.static_hi.tobytes()) == _boxes(w)
    for cycle in range(2):  # after a replay, the obstacle placed again: its box made again, the part's kept
        chk.gripper("tTool", "close", 100.0 + cycle, joints=_q(PICK))
        chk.gripper("tTool", "open", 100.5 + cycle, joints=_q(PLACE))
        frames["fBall"] = (BALL[0] + 40.0 * (cycle + 1), *BALL[1:])
        chk.refresh(101.0 + cycle)
        assert (w.static_lo.tobytes(), w.static_hi.tobytes()) == _boxes(w) and len(w.static) > 1
