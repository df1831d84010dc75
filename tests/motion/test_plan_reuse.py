"""A repeated command's blend decision, trial timings, checks and joint target are reused (issue
29, motion/trial_memo.py), and never stale: each input of a key changed in turn misses, a run
with reuse gives every command exactly the timing of the same run without it, and each input
changed in a cycle changes that cycle's timing."""

from __future__ import annotations

import numpy as np
import pytest

from val3check.motion import trial_memo
from val3check.motion.mdesc import MDesc
from val3check.motion.paths import JointLine, Span
from val3check.motion.queue import QueueFull

from .motionhelp import HOME, KIN, OFF, movec, movej, movel, point, queue

BLEND = MDesc(blend="joint", leave=20.0, reach=20.0)
CART = MDesc(blend="Cartesian", leave=15.0, reach=15.0)
TOOL = np.eye(4)
TOOL[2, 3] = 40.0


def _cycle(variant: str = "") -> list:
    """One cycle of a pick-and-place; `variant` changes one input of the cycle's keys."""
    md = {"vel": MDesc(blend="joint", leave=20.0, reach=20.0, vel=10.0, tvel=200.0),
          "accel": MDesc(blend="joint", leave=20.0, reach=20.0, accel=50.0),
          "leave": MDesc(blend="joint", leave=35.0, reach=20.0),
          "reach": MDesc(blend="joint", leave=20.0, reach=35.0),
          "blend": CART}.get(variant, BLEND)
    start = HOME + (np.array([0.0, 0.0, 0.0, 0.0, 0.0, 3.0]) if variant == "start" else 0.0)
    dx = 75.0 if variant == "target" else 70.0
    tool = TOOL if variant == "tool" else None
    above = point(dx=dx, dy=30.0, dz=40.0)
    return [movej(start, BLEND),
            movel(above, md, tool=tool),
            movel(point(dx=dx, dy=30.0), OFF, tool=tool),
            movel(above, md, tool=tool),
            movec(point(dx=20.0, dy=60.0, dz=50.0), point(dx=-20.0, dy=70.0, dz=30.0), md, tool=tool),
            movel(point(dx=-20.0, dy=70.0), OFF, tool=tool)]


def _run(cycles: list[str], reuse: bool, monkeypatch) -> tuple:
    """Every command's (id, state, times, path positions) and the whole profile, after the cycles;
    the program records ahead of the arm (some records while it moves, some at rest)."""
    monkeypatch.setattr(trial_memo, "REUSE", reuse)
    q = queue()
    now = 0.0
    for n, variant in enumerate(cycles):
        if variant == "monitor":
            q.set_monitor_speed(80.0, now)
        for k, move in enumerate(_cycle(variant)):
            r = q.record(move, now)
            while isinstance(r, QueueFull):
                now = r.until
                r = q.record(move, now)
            if k == 2 and n % 2:  # the rest of this cycle recorded while the arm moves
                now = q.next_event(now) or now
        now = q.wait_end_move(now)
        q.advance(now)
        if variant == "monitor":
            q.set_monitor_speed(100.0, now)
    prof = q.profile
    commands = [(c.id, c.state, c.t_done, c.placement.s_begin, c.placement.s_end, c.rest_time) for c in q.history]
    return commands, (list(prof.T), list(prof.S), list(prof.SD)), q


def _cycle_times(commands, per=6) -> list[float]:
    done = [c[2] for c in commands]
    return [done[i + per - 1] - (done[i - 1] if i else 0.0) for i in range(0, len(done), per)]


VARIANTS = ["vel", "accel", "leave", "reach", "blend", "start", "target", "tool", "monitor"]


def test_a_long_run_with_reuse_times_every_command_as_without(monkeypatch):
    cycles = [""] * 12
    hits = []
    get = trial_memo.TrialMemo.get

    def counted(self, key, spans, speed_at=None, shift=None):
        hit = get(self, key, spans, speed_at, shift)
        hits.append(hit is not None)
        return hit

    monkeypatch.setattr(trial_memo.TrialMemo, "get", counted)
    on, prof_on, q = _run(cycles, True, monkeypatch)
    assert q.kin.reuse.get("trial-memo")
    assert sum(hits) > len(hits) // 2, (sum(hits), len(hits))  # most trials reused
    off, prof_off, q_off = _run(cycles, False, monkeypatch)
    assert "trial-memo" not in q_off.kin.reuse
    assert on == off  # floats compared exactly
    assert prof_on == prof_off


def test_each_input_changed_in_a_cycle_changes_its_timing_and_is_never_reused_stale(monkeypatch):
    # base cycles between the variants, each variant twice: a stale answer would be served then
    cycles = [""]
    for v in VARIANTS:
        cycles += [v, "", v, ""]
    on, prof_on, _ = _run(cycles, True, monkeypatch)
    off, prof_off, _ = _run(cycles, False, monkeypatch)
    assert on == off
    assert prof_on == prof_off
    times = _cycle_times(on)
    base = times[2]  # a base cycle after a base cycle (the first starts from rest elsewhere)
    for i, v in enumerate(VARIANTS):
        t = times[1 + 4 * i]
        assert t != pytest.approx(base, abs=1e-6), v
        assert times[3 + 4 * i] == pytest.approx(t, abs=1e-6), v  # the same variant again: the same


FIRST = JointLine(HOME + 30.0, HOME + 50.0)


def _spans(geom=None, a=0.0, b=1.0, smooth=True, tool=None, owners=((1, 0.0),), other=((2, 0.0),)):
    line = geom or JointLine(HOME, HOME + 30.0)
    return [Span(FIRST, 0.0, 1.0, list(other), False, None),
            Span(line, a, b, list(owners), smooth, tool)]


def test_each_input_of_the_trial_key_changed_in_turn_misses():
    limits = {1: MDesc(), 2: MDesc(), 3: MDesc(vel=50.0), 7: MDesc(), 8: MDesc()}
    from val3check.motion.mdesc import CommandLimits

    cl = CommandLimits(KIN, 100.0)
    for k, md in limits.items():
        cl.register(k, md, False)
    memo = trial_memo.TrialMemo(KIN, None, cl.of)
    line = JointLine(HOME, HOME + 30.0)
    base = memo.key(_spans(line), 0.5, 10.0)
    others = {
        "geometry": memo.key(_spans(JointLine(HOME, HOME + 30.0)), 0.5, 10.0),
        "part start": memo.key(_spans(line, a=0.1), 0.5, 10.0),
        "part end": memo.key(_spans(line, b=0.9), 0.5, 10.0),
        "smooth": memo.key(_spans(line, smooth=False), 0.5, 10.0),
        "tool": memo.key(_spans(line, tool=TOOL), 0.5, 10.0),
        "owner's limits": memo.key(_spans(line, owners=((3, 0.0),)), 0.5, 10.0),
        "same owner as the neighbour": memo.key(_spans(line, owners=((2, 0.0),)), 0.5, 10.0),
        "two owners": memo.key(_spans(line, owners=((1, 0.0), (2, 3.0))), 0.5, 10.0),
        "owner from": memo.key(_spans(line, owners=((1, 0.0), (2, 4.0))), 0.5, 10.0),
        "position": memo.key(_spans(line), 0.6, 10.0),
        "speed": memo.key(_spans(line), 0.5, 11.0),
    }
    assert memo.key(_spans(line, owners=((7, 0.0),), other=((8, 0.0),)), 0.5, 10.0) == base  # keys renamed
    for what, key in others.items():
        assert key != base, what
    assert len(set(others.values())) == len(others)
    cl.set_monitor(50.0)  # the monitor speed: every limit
    assert memo.key(_spans(line), 0.5, 10.0) != base
    trial_memo.REUSE = False
    try:
        assert memo.key(_spans(line), 0.5, 10.0) is None
    finally:
        trial_memo.REUSE = True


def test_an_answer_is_refused_when_what_it_read_changed():
    from val3check.motion.timing import Timing

    timing = Timing(KIN)
    memo = trial_memo.TrialMemo(KIN, timing, lambda k: None)
    line = JointLine(HOME, HOME + 30.0)
    spans = [Span(line, 0.0, 1.0, [(1, 0.0)])]
    key = ("k",)
    timing._cache["topp"] = entry = (np.zeros(2), np.zeros(2), False)
    started = memo.start()
    timing.used.append(("topp", entry))
    memo.stop()
    memo.keep(key, spans, started, [(1.0, 2.0, 3.0)], "answer")
    assert memo.get(key, spans, lambda g, a: 3.0) == "answer"
    assert memo.get(key, spans, lambda g, a: 3.5) is None  # the plan's speed there differs
    # another curve: another key (the key names each geometry; the entry holds them alive, so an
    # id in a kept key is never another object's)
    other = [Span(JointLine(HOME, HOME + 30.0), 0.0, 1.0)]
    assert memo.key(other, 0.0, 0.0) != memo.key([Span(line, 0.0, 1.0)], 0.0, 0.0)
    assert memo._store()  # (the test's own keys, not the memo's)
    timing._cache["topp"] = (np.zeros(2), np.zeros(2), False)  # forgotten and computed again
    assert memo.get(key, spans, lambda g, a: 3.0) is None
    # an answer that read a parameterisation computed then is kept: a remembered one is the same
    # bits (Timing._topp solves relative to the grid's start; test_plan_memo.py)
    started = memo.start()
    timing.misses += 1
    memo.stop()
    memo.keep(("k2",), spans, started, [], "first")
    assert memo.get(("k2",), spans) == "first"


def test_a_command_that_raises_is_checked_every_time():
    from val3check.motion.findings import MotionError

    q = queue()
    q.record(movel(point(dx=40.0)), 0.0)
    n = len(q.kin.reuse)
    bad = movel(point(dx=4000.0))  # out of reach: raised at the instruction each time
    for _ in range(2):
        with pytest.raises(MotionError):
            q.record(bad, 0.0)
    assert len(q.kin.reuse) == n


def _q_by_span(path, s, order):
    """Path.q one sample at a time, on the span that holds it (the reference)."""
    out = np.empty((len(s), 6))
    idx = np.clip(np.searchsorted(np.asarray(path.offsets), s, side="right") - 1, 0, len(path.spans) - 1)
    for k, i in enumerate(idx):
        sp = path.spans[int(i)]
        out[k] = sp.q(np.clip(s[k:k + 1] - path.offsets[int(i)], 0.0, sp.length), order)[0]
    return out


@pytest.mark.parametrize("order", [0, 1, 2])
def test_the_path_evaluated_by_geometry_is_the_path_span_by_span(order, monkeypatch):
    _, _, q = _run(["", "", "blend", "", "tool"], True, monkeypatch)
    path = q.path
    assert len({id(sp.geom) for sp in path.spans}) < len(path.spans)  # geometries shared
    kinds = {type(sp.geom).__name__ for sp in path.spans}
    assert {"JointLine", "JointSpline", "JointBlend"} <= kinds, kinds
    rng = np.random.default_rng(3)
    s = np.concatenate([rng.uniform(-1.0, path.end + 1.0, 3000), path.offsets, [path.end]])
    got = path.q(s, order)
    assert np.array_equal(got, _q_by_span(path, s, order))  # bit for bit
