"""A plan timed relative to the span the arm is on and remembered (planner.Planner._plan, issue 29),
and the queue's next event kept until something it depends on changes (MotionQueue.next_event):
each input changed in turn misses, and long runs with reuse are the same floats as without."""

from __future__ import annotations

import numpy as np

from val3check.motion import queue as queue_mod
from val3check.motion import trial_memo
from val3check.motion.planner import Planner, _joined
from val3check.motion.queue import QueueFull
from val3check.motion.timing import TimedPiece
from val3check.motion.trajectory import Profile

from .motionhelp import HOME, ROBOT, movel, point, queue
from .test_plan_reuse import VARIANTS, _cycle, _run


def _counting(monkeypatch) -> list:
    """Every plan asked, with whether it was a remembered one."""
    seen: list = []
    original = Planner._plan

    def counted(self, ahead, a, v0, shift):
        key = self.memo.key(ahead, a, v0, "plan")
        hit = self.memo.get(key, ahead, lambda g, a_: self.profile.speed_at(g + shift, a_ + shift))
        got = original(self, ahead, a, v0, shift)
        seen.append(hit is not None)
        if hit is not None:
            assert got is hit
        return got

    monkeypatch.setattr(Planner, "_plan", counted)
    return seen


def test_a_long_cyclic_run_plans_by_look_up_and_equals_a_fresh_computation(monkeypatch):
    """12 cycles of the test cell (records at rest and while the arm moves): after the first
    cycles every plan is a remembered one, and every command's times and the whole profile are
    the same floats as the same run computed without reuse."""
    seen = _counting(monkeypatch)
    on, prof_on, _ = _run([""] * 12, True, monkeypatch)
    assert len(seen) >= 12 and all(seen[len(seen) // 3:]), seen  # (18: records merge into a plan)
    off, prof_off, _ = _run([""] * 12, False, monkeypatch)
    assert on == off
    assert prof_on == prof_off


def test_each_input_changed_in_a_cycle_misses_and_is_never_stale(monkeypatch):
    """Each input of the cycle (vel, accel, leave, reach, blend kind, start joints, target, tool,
    monitor speed) changed in one cycle, twice, between base cycles: the same floats as without
    reuse, and the changed cycles' plans are not the base cycles' answers."""
    cycles = [""] * 3
    for v in VARIANTS:
        cycles += [v, "", v, ""]
    on, prof_on, _ = _run(cycles, True, monkeypatch)
    off, prof_off, _ = _run(cycles, False, monkeypatch)
    assert on == off and prof_on == prof_off


def _planned(q, t_r: float):
    """The plan of `q` from t_r, asked of Planner._plan directly: (key inputs, answer)."""
    p = q.planner
    p.flush()
    p.profile.cut(t_r)
    s_r, sd_r = p.profile.s_end, p.profile.SD[-1]
    i0, _ = p.path.locate(s_r)
    shift = p.path.offsets[i0]
    return p, p.path.spans[i0:], s_r - shift, sd_r, shift


def test_each_input_of_the_plan_key_changed_in_turn_misses(monkeypatch):
    """The plan of a queue, asked again: remembered; then each input changed in turn (the start
    position, the start speed, a span's part, its smoothness, its tool, its owner's limits): a
    miss, and the answer is the computed one."""
    q = queue()
    q.record(movel(point(dx=60.0)), 0.0)
    q.record(movel(point(dx=60.0, dy=40.0)), 0.0)
    p, ahead, a, v0, shift = _planned(q, 0.0)
    first = p._plan(ahead, a, v0, shift)  # computed (its parameterisations are new)
    again = p._plan(ahead, a, v0, shift)  # computed on remembered ones: kept
    assert p._plan(ahead, a, v0, shift) is again
    for x, y in zip(first, again):
        assert np.array_equal(x, y)

    def fresh(spans, a_, v_):
        monkeypatch.setattr(trial_memo, "REUSE", False)
        try:
            return p._plan(spans, a_, v_, shift)
        finally:
            monkeypatch.setattr(trial_memo, "REUSE", True)

    def check(spans, a_, v_):
        got = p._plan(spans, a_, v_, shift)
        assert got is not again
        want = fresh(spans, a_, v_)
        for x, y in zip(got, want):
            assert x.tobytes() == y.tobytes()
        return got

    check(ahead, a + 1.0, v0)  # the start position
    check(ahead, a, v0 + 1.0)  # the start speed
    sp = ahead[1]
    part = type(sp)(sp.geom, sp.a, 0.5 * (sp.a + sp.b), sp.owners, sp.smooth, sp.tool)
    check([ahead[0], part], a, v0)  # a span's part
    smooth = type(sp)(sp.geom, sp.a, sp.b, sp.owners, not sp.smooth, sp.tool)
    check([ahead[0], smooth], a, v0)  # its smoothness
    tool = np.eye(4)
    tool[2, 3] = 50.0
    tooled = type(sp)(sp.geom, sp.a, sp.b, sp.owners, sp.smooth, tool)
    check([ahead[0], tooled], a, v0)  # its tool
    q.set_monitor_speed(60.0, 0.0)  # the owners' limits
    assert p._plan(ahead, a, v0, shift) is not again


def test_a_plan_is_refused_when_the_speed_it_read_changed(monkeypatch):
    """A plan from a moving arm reads the plan's speed where it re-times from; when that speed is
    another, the remembered plan is not used."""
    q = queue()
    for k in range(3):
        q.record(movel(point(dx=60.0 + 10 * k, dy=40.0 * (k % 2))), 0.0)
    q.planner.flush()
    k = len(q.profile.T) // 3
    t_mid = 0.5 * (q.profile.T[k] + q.profile.T[k + 1])  # between gridpoints: the plan's speed is read
    memo = q.planner.memo
    calls_seen = []
    keep = memo.keep

    def kept(key, spans, started, calls, answer):
        calls_seen.append(list(calls))
        return keep(key, spans, started, calls, answer)

    monkeypatch.setattr(memo, "keep", kept)
    p, ahead, a, v0, shift = _planned(q, t_mid)
    assert v0 > 0.0
    p._plan(ahead, a, v0, shift)
    second = p._plan(ahead, a, v0, shift)
    assert p._plan(ahead, a, v0, shift) is second and calls_seen[-1]  # it asked the plan's speed
    g, a_, v = calls_seen[-1][0]
    monkeypatch.setattr(p.profile, "speed_at", lambda s, until: v * 0.5)
    assert p._plan(ahead, a, v0, shift) is not second


def test_a_shifted_plan_is_the_appended_one_to_the_last_bits():
    """Profile.extend_shifted (the plan's times from its start, positions shifted) against the
    pieces appended one by one at the path's positions: the same breakpoints to a few ulps (the
    last bits of a plan changed once with this, docs/performance.md), the last position exactly the
    path's end, and a rest breakpoint first when the plan starts after the profile ends."""
    s1 = np.array([0.0, 0.3, 1.1, 2.0])
    v1 = np.array([0.2, 1.0, 0.7, 0.0])
    s2 = np.array([2.0, 2.5, 3.25])
    v2 = np.array([0.0, 0.9, 0.0])
    pieces = [TimedPiece(s1, v1, False, 1), TimedPiece(s2, v2, False, 2)]
    shift = 12345.678
    end = 3.25 + shift
    for t0, t_end in ((5.0, 5.0), (7.0, 5.0)):
        a, b = Profile(shift, 0.0), Profile(shift, 0.0)
        for p in (a, b):
            p.append(t_end, np.array([shift, shift]), np.array([0.0, 0.2]))
        a.extend_shifted(t0, *_joined(pieces), shift, end)
        t = t0
        for piece in pieces:
            b.append(t, piece.s + shift, piece.sd)
            t = b.t_end
        assert len(a.T) == len(b.T) == 2 + (t0 > t_end) + 5
        assert a.S[-1] == end
        # the times differ by ~1e-12 s: those of the path's positions carry their rounding (an ulp
        # of s = 12345 is 1.8e-12), the plan's do not (5 + 2 * 0.3 / 1.2 is 5.5 to the bit)
        assert np.allclose(list(a.T), list(b.T), rtol=0, atol=1e-11)
        assert a.T[2 + (t0 > t_end)] == t0 + 0.5 and b.T[2 + (t0 > t_end)] != t0 + 0.5
        assert np.allclose(list(a.S), list(b.S), rtol=0, atol=1e-9)
        assert list(a.SD) == list(b.SD)


def test_a_plan_that_does_not_move_adds_nothing():
    p = Profile(3.0, 1.0)
    p.extend_shifted(2.0, *_joined([]), 0.0, 3.0)
    assert list(p.T) == [1.0] and list(p.S) == [3.0]


# ---- the next event kept until what it depends on changes (MotionQueue.next_event) -----------------

class _Checked(queue_mod.MotionQueue):
    """A queue that compares every next event it answers with a fresh computation then."""

    kept = 0

    def next_event(self, now):
        before = self._next
        got = super().next_event(now)
        saved, self._next = self._next, ()
        try:
            assert super().next_event(now) == got
        finally:
            self._next = saved
        if before and self._next is before:
            type(self).kept += 1
        return got


def _scheduled(cls, reuse: bool, monkeypatch) -> tuple:
    """A scheduler's questions over 8 cycles: next_event asked several times per step (as the
    scheduler does), records ahead of the arm, QueueFull, a stop and a restart, a power cut and
    a monitor speed change: every answer, and the profile."""
    monkeypatch.setattr(trial_memo, "REUSE", reuse)
    q = cls(ROBOT, HOME)
    now, answers = 0.0, []
    for n in range(8):
        moves = _cycle("tool" if n == 5 else "")
        k = 0
        while k < len(moves):
            r = q.record(moves[k], now)
            if isinstance(r, QueueFull):
                now = r.until
                continue
            k += 1
            answers.append((r, q.next_event(now), q.next_event(now), q.get_move_id(now)))
            if k % 2:
                nxt = q.next_event(now)
                if nxt is not None:
                    half = now + 0.5 * (nxt - now)
                    answers.append((q.next_event(half), q.next_event(half)))
                    now = nxt
                    q.advance(now)
                    answers.append((q.next_event(now), q.get_move_id(now), q.is_settled(now)))
        if n == 3:
            q.stop_move(now + 0.1)
            answers.append(q.next_event(now + 0.1))
            q.restart_move(now + 0.3)
        if n == 4:
            q.set_power(False, now + 0.05)
            answers.append(q.next_event(now + 0.05))
            q.set_power(True, now + 0.2)
        if n == 6:
            q.set_monitor_speed(70.0, now)
        while (nxt := q.next_event(now)) is not None:
            answers.append(q.next_event(now))
            now = nxt
            q.advance(now)
            answers.append((now, q.next_event(now), q.get_move_id(now), q.is_empty(now), q.is_settled(now)))
    prof = q.profile
    return answers, (list(prof.T), list(prof.S), list(prof.SD))


def test_the_kept_next_event_is_the_computed_one_over_a_long_run(monkeypatch):
    _Checked.kept = 0
    on = _scheduled(_Checked, True, monkeypatch)
    assert _Checked.kept > 50
    off = _scheduled(queue_mod.MotionQueue, False, monkeypatch)
    assert on == off  # floats compared exactly


def test_the_next_event_misses_when_each_input_changes():
    """Kept: asked again later, before the answer. Asked again: the profile changed (a stop, a
    replan), the first command changed (one completed), its end moved, the time went back, the
    answer passed."""
    q = queue()
    q.record(movel(point(dx=60.0)), 0.0)
    q.record(movel(point(dx=60.0, dy=40.0)), 0.0)
    t1 = q.next_event(0.0)
    kept = q._next
    assert q.next_event(0.5 * t1) == t1 and q._next is kept  # kept
    assert q.next_event(t1) != t1 and q._next is not kept  # the answer passed
    q._next = kept
    q.advance(t1)  # the first command completes: another first command
    assert q.next_event(t1) == q._first_done_time() and q._next is not kept
    kept = q._next
    end = q.pending[0].placement.s_end
    q.pending[0].placement.s_end = end - 1.0  # its end moved
    assert q.next_event(t1) == q.profile.time_at(end - 1.0) and q._next is not kept
    q.pending[0].placement.s_end = end
    kept = q._next
    q.next_event(0.5 * t1)  # the time went back: asked again
    assert q._next is not kept
    kept = q._next
    q.stop_move(t1 + 0.01)  # the profile changed
    assert q.next_event(t1 + 0.01) == q.profile.t_end and q._next is not kept


# ---- a time-optimal parameterisation solved relative to its grid's start (timing.Timing._topp) ------

def test_a_first_parameterisation_is_the_remembered_one_to_the_bit():
    """A piece of path far along the run's path (after a long span): solved relative to the grid's
    start, the first answer and the remembered one are the same bits (a trial or plan that read a
    parameterisation computed then is kept, trial_memo.py), and the ends are the grid's exactly;
    the same piece at the path's start has the same profile to rounding."""
    from val3check.motion.paths import JointLine, Path, Span
    from val3check.motion.timing import Timing
    from val3check.motion.timing.grid import sample_path

    from .motionhelp import KIN

    geom = JointLine(HOME, HOME + np.array([30.0, -20.0, 10.0, 40.0, 25.0, -35.0]))
    far = JointLine(HOME, HOME + 9000.0)  # 22,000 degrees of joint motion before the piece
    answers = []
    for lead in (None, far):
        path = Path(HOME)
        if lead is not None:
            path.append(Span(lead, 0.0, 1.0, [(1, 0.0)]))
        off = path.append(Span(geom, 0.0, 1.0, [(1, 0.0)], False, None))
        grid, _ = sample_path(path, off, path.end, KIN, lambda k: _limits())
        timing = Timing(KIN)
        first = timing._topp(grid, 0.0)
        again = timing._topp(grid, 0.0)
        assert timing.misses == 1
        assert first.s.tobytes() == again.s.tobytes() and first.sd.tobytes() == again.sd.tobytes()
        assert first.s[0] == grid.s[0] and first.s[-1] == grid.s[-1]
        answers.append((first.s - grid.s[0], first.sd))
    assert np.allclose(answers[0][0], answers[1][0], rtol=0, atol=1e-9)
    assert np.allclose(answers[0][1], answers[1][1], rtol=1e-9, atol=1e-9)


def _limits():
    from val3check.motion.mdesc import CommandLimits, MDesc

    from .motionhelp import KIN

    limits = CommandLimits(KIN, 100.0)
    limits.register(1, MDesc(blend="off"), False)
    return limits.of(1)


def test_the_final_braking_read_in_place_is_the_general_answer():
    """Profile.final_decel_start reads the chunk being written in place: the same index as the
    general loop on a plain sequence, for braking wholly inside the chunk, crossing its start,
    and a profile with one breakpoint in it (chunks of 8 so that they are often short)."""
    import random

    from val3check.motion import history

    rng = random.Random(7)
    old = history.CHUNK
    history.CHUNK = 8
    try:
        for n in range(1, 40):
            for _ in range(5):
                sd = [rng.choice([0.0, 1.0, 2.0, 3.0]) for _ in range(n)]
                sd[-1] = 0.0
                p = Profile(0.0, 0.0)
                p.SD.extend(sd)  # (only SD is read)
                ref = Profile(0.0, 0.0)
                ref.SD = [0.0, *sd]
                assert p.final_decel_start() == ref.final_decel_start(), sd
    finally:
        history.CHUNK = old
