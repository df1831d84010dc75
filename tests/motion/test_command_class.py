"""A queued command's class (QueuedCommand.cls, issue 29) and the keys built on it: the blend
candidate (blending.candidate) and the blend decision (planner._trials). Each input changed in
turn gives another class or another key (a miss), equal inputs the same, numbers are never given
twice, and an answer found by a class key is the one computed without it."""

from __future__ import annotations

import numpy as np

from val3check.motion import blending, queue as queue_mod, trial_memo
from val3check.motion.mdesc import MDesc
from val3check.motion.paths import JointLine, Span
from val3check.motion.queued import Geometry, Request

from .motionhelp import HOME, OFF, movej, movel, point, queue

BLEND = MDesc(blend="joint", leave=20.0, reach=20.0)
TOOL = np.eye(4)
TOOL[2, 3] = 40.0
TOOL.flags.writeable = False  # (the run's tools are shared read-only: simulation/retention.py)


def _request(kind="movel", mdesc=BLEND, tool=None, reduced=False) -> Request:
    return Request(kind, None, 0.0, mdesc, tool, reduced=reduced)


def _class(q, request: Request, geometry: Geometry) -> int:
    """What MotionQueue._new_command gives a command of `request` and `geometry`."""
    return q._class_of(request, geometry, q.limits.register(0, request.mdesc, request.reduced))


def test_each_input_of_a_commands_class_changed_in_turn_gives_another_class():
    q = queue()
    line = JointLine(HOME, HOME + 30.0)
    tcp = object()
    geometry = Geometry(HOME.copy(), HOME + 30.0, line, tcp)
    base = _class(q, _request(), geometry)
    assert _class(q, _request(), Geometry(HOME.copy(), HOME + 30.0, line, tcp)) == base  # equal inputs
    assert _class(q, _request(mdesc=MDesc(blend="joint", leave=20.0, reach=20.0)), geometry) == base  # equal values
    others = {
        "kind": _class(q, _request(kind="movec"), geometry),
        "joint curve": _class(q, _request(), Geometry(HOME.copy(), HOME + 30.0, JointLine(HOME, HOME + 30.0), tcp)),
        "TCP curve": _class(q, _request(), Geometry(HOME.copy(), HOME + 30.0, line, object())),
        "start": _class(q, _request(), Geometry(HOME + 1e-9, HOME + 30.0, line, tcp)),
        "end": _class(q, _request(), Geometry(HOME.copy(), HOME + 30.000001, line, tcp)),
        "tool": _class(q, _request(tool=TOOL), geometry),
        "reduced": _class(q, _request(reduced=True), geometry),
    }
    for field in ("accel", "vel", "decel", "tvel", "rvel", "leave", "reach"):
        others[field] = _class(q, _request(mdesc=MDesc(**{"blend": "joint", "leave": 20.0, "reach": 20.0,
                                                               field: 7.0})), geometry)
    others["blend"] = _class(q, _request(mdesc=MDesc(blend="Cartesian", leave=20.0, reach=20.0)), geometry)
    for what, cls in others.items():
        assert cls != base, what
    assert len(set(others.values())) == len(others)


def test_class_numbers_are_never_given_twice_after_the_table_is_emptied(monkeypatch):
    monkeypatch.setattr(queue_mod, "CLASSES", 8)
    q = queue()
    line = JointLine(HOME, HOME + 30.0)
    seen, given, renumbered = {}, set(), 0
    for _ in range(3):  # 12 values through a table of 8: emptied; a value may get a new number, never an old one
        for k in range(12):
            n = _class(q, _request(), Geometry(HOME + k, HOME + 30.0, line, None))
            assert n == seen.get(k) or n not in given
            renumbered += k in seen and n != seen[k]
            seen[k] = n
            given.add(n)
            assert len(q._classes) <= 8
    assert renumbered


def test_repeated_commands_share_their_class_and_others_do_not():
    """In a cycle recorded again from the same place, every command has the class of its twin; the
    same target from another start, with another tool or mdesc has another class."""
    q = queue(capacity=32)
    above, down = point(dx=70.0, dy=30.0, dz=40.0), point(dx=70.0, dy=30.0)
    cycle = [movej(HOME, BLEND), movel(above, BLEND), movel(down, OFF), movel(above, BLEND)]
    for _ in range(3):
        for move in cycle:
            q.record(move, 0.0)
    classes = [c.cls for c in q.history]
    c = classes[4:8]  # (the first cycle starts elsewhere: from the queue's start)
    assert classes[8:12] == c and len(set(c)) == 4
    for move in (movej(HOME, BLEND), movel(above, BLEND, tool=TOOL), movej(HOME, BLEND),
                 movel(above, MDesc(blend="joint", leave=20.0, reach=20.0, vel=50.0)), movel(down, OFF),
                 movel(above, BLEND)):
        q.record(move, 0.0)
    new = [c.cls for c in q.history[12:]]
    assert new[0] == c[0]
    assert new[1] not in classes  # another tool
    assert new[2] not in classes  # movej(HOME) from another start
    assert new[3] not in classes  # another mdesc
    assert new[4] == c[2]  # the same start (above), target, tool and mdesc
    assert new[5] == c[3]


def _same_candidate(got, want) -> bool:
    """Two blending.Candidate (or None) alike: the same reach point, split and curve samples."""
    if got is None or want is None:
        return got is want
    lam = np.linspace(0.0, 1.0, 9)
    return got.lam_reach == want.lam_reach and got.split == want.split and \
        got.curve.q(lam).tobytes() == want.curve.q(lam).tobytes()


def test_the_blend_candidate_by_class_misses_when_an_input_changes_and_equals_the_computed_one(monkeypatch):
    q = queue()
    q.record(movej(HOME, BLEND), 0.0)
    q.record(movel(point(dx=70.0, dy=30.0, dz=40.0), BLEND), 0.0)
    previous = q.history[-1]
    q.record(movel(point(dx=20.0, dy=60.0, dz=50.0), BLEND), 0.0)
    command = q.history[-1]
    computed = []
    original = blending._candidate

    def counted(*args):
        computed.append(args[1:3])
        return original(*args)

    monkeypatch.setattr(blending, "_candidate", counted)
    limits = q.limits.of

    def fresh():
        return original(q.kin, previous, command, lambda c: limits(c.key))

    got = blending.candidate(q.kin, previous, command, lambda c: limits(c.key))
    assert computed == [] and _same_candidate(got, fresh())  # kept when the queue recorded them
    place = previous.placement
    for what, change, undo in (
            ("leave point", lambda: setattr(place, "lam_leave", place.lam_leave - 0.01),
             lambda v=place.lam_leave: setattr(place, "lam_leave", v)),
            ("blend", lambda: setattr(place, "blend", "Cartesian"), lambda v=place.blend: setattr(place, "blend", v)),
            ("previous class", lambda: setattr(previous, "cls", trial_memo.number()),
             lambda v=previous.cls: setattr(previous, "cls", v)),
            ("command class", lambda: setattr(command, "cls", trial_memo.number()),
             lambda v=command.cls: setattr(command, "cls", v))):
        n = len(computed)
        change()
        got = blending.candidate(q.kin, previous, command, lambda c: limits(c.key))
        assert len(computed) == n + 1, what  # a miss: computed
        assert _same_candidate(got, fresh()), what
        undo()
    assert _same_candidate(blending.candidate(q.kin, previous, command, lambda c: limits(c.key)), fresh())


def test_each_input_of_the_blend_decisions_key_changed_in_turn_misses():
    """planner._trials names its trial spans by the two commands' classes, the previous one's blend
    and leave point, and numbers the two commands with the owners of the spans ahead."""
    q = queue()
    memo = q.planner.memo
    for k in (1, 2, 3):
        q.limits.register(k, BLEND, False)
    q.limits.register(4, MDesc(blend="joint", leave=20.0, reach=20.0, vel=50.0), False)
    ahead = [Span(JointLine(HOME, HOME + 30.0), 0.0, 1.0, [(1, 0.0)], False, None)]

    def key(prev_cls=11, blend="joint", lam=0.9, cls=12, owners=(1, 2), a=0.5, v0=10.0):
        return memo.key(ahead, a, v0, prev_cls, blend, lam, cls, "pays", owners=owners)

    base = key()
    assert key() == base
    others = {"previous class": key(prev_cls=13), "previous blend": key(blend="Cartesian"),
              "leave point": key(lam=0.8), "command class": key(cls=13),
              "previous not the command ahead": key(owners=(2, 3)),
              "command's limits": key(owners=(1, 4)), "position": key(a=0.6), "speed": key(v0=11.0)}
    for what, k in others.items():
        assert k != base, what
    assert len(set(others.values())) == len(others)
    q.limits.set_monitor(50.0)  # the monitor speed: every limit
    assert key() != base
