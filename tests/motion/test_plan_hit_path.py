"""A repeated command's hit path (issue 29, ninth round): the blend decision and the plan looked
up before anything is built, the plan's speeds read with the spans' shift, a scheduler cycle
where nothing is due answered by `MotionQueue.advance` alone. Each is held to the computation
without reuse."""

from __future__ import annotations

from val3check.motion import trial_memo
from val3check.motion.paths import JointLine, Span
from val3check.motion.queue import QueueFull

from .motionhelp import HOME, KIN, queue
from .test_plan_reuse import _cycle


def test_the_plans_speeds_are_read_at_the_spans_shift():
    """`get(..., shift)` compares each remembered speed with the plan's at the path position
    (relative position + shift): the same answer as the speed read shifted by hand, and a miss
    when any one speed or the shift differs."""
    from val3check.motion.timing import Timing

    memo = trial_memo.TrialMemo(KIN, Timing(KIN), lambda key: None)
    spans = [Span(JointLine(HOME, HOME + 10.0), 0.0, 1.0)]
    key = ("k",)
    started = memo.start()
    memo.stop()
    memo.keep(key, spans, started, [(1.0, 2.0, 3.0), (4.0, 5.0, 6.0)], "answer")
    speeds = {(11.0, 12.0): 3.0, (14.0, 15.0): 6.0}

    def at(g, a):
        return speeds.get((g, a))

    assert memo.get(key, spans, at, 10.0) == "answer"
    assert memo.get(key, spans, lambda g, a: at(g + 10.0, a + 10.0)) == "answer"
    assert memo.get(key, spans, at, 9.0) is None  # another shift
    for where in speeds:  # each speed changed in turn
        old = speeds[where]
        speeds[where] = old + 1e-9
        assert memo.get(key, spans, at, 10.0) is None
        speeds[where] = old
    assert memo.get(key, spans, at, 10.0) == "answer"


def _cycles(q, n: int, now: float, steps: int, log: list) -> float:
    """n cycles recorded ahead of the arm; between records and events the queue is advanced at
    `steps` times (most of them before anything completes), and its state logged after each."""
    def state(t):
        q.advance(t)
        log.append((t, q.pos_id, q.completed, len(q.pending), q.final_before(),
                    tuple((c.key, c.state, c.t_done) for c in q.history)))

    for _ in range(n):
        for k, move in enumerate(_cycle()):
            r = q.record(move, now)
            while isinstance(r, QueueFull):
                now = r.until
                state(now)
                r = q.record(move, now)
            if k % 2:
                nxt = q.next_event(now)
                if nxt is not None:
                    for i in range(1, steps + 1):  # times between now and the next event, then it
                        state(now + (nxt - now) * i / steps)
                    now = nxt
        end = q.wait_end_move(now)
        while (nxt := q.next_event(now)) is not None and nxt <= end:
            for i in range(1, steps + 1):
                state(now + (nxt - now) * i / steps)
            now = nxt
        now = max(now, end)
        state(now)
    return now


def test_advance_between_events_is_the_full_advance(monkeypatch):
    """A scheduled run advanced at many times between events (the cycles where nothing completes
    take `advance`'s short way): every state after every call is the one the run without reuse
    (every end time computed, the whole `_advance` each call) gives, and most calls took it."""
    from val3check.motion import queue as queue_mod

    calls, full = [], []
    advance, whole = queue_mod.MotionQueue.advance, queue_mod.MotionQueue._advance

    def counted(self, now):
        calls.append(now)
        return advance(self, now)

    def counted_whole(self, now, lenient=False):
        full.append(now)
        return whole(self, now, lenient)

    monkeypatch.setattr(queue_mod.MotionQueue, "advance", counted)
    monkeypatch.setattr(queue_mod.MotionQueue, "_advance", counted_whole)
    on, off = [], []
    _cycles(queue(), 5, 0.0, 6, on)
    short = len(calls) - len(full)  # (the record's own `_advance` counted too: at least this many)
    monkeypatch.setattr(trial_memo, "REUSE", False)
    _cycles(queue(), 5, 0.0, 6, off)
    assert on == off  # floats compared exactly
    assert len(on) > 150 and short > len(on) // 3, (short, len(on))


def test_the_limits_values_kept_by_command_key_follow_the_monitor_and_the_mdesc():
    """`TrialMemo.key` with `CommandLimits.value_keys` (the limits' values by command key, one
    look-up per owner) gives the key made from `limits_of` itself: after the values are kept, after
    another monitor speed, another mdesc and the reduced speed registered for a command."""
    from val3check.motion.mdesc import CommandLimits, MDesc

    cl = CommandLimits(KIN, 100.0)
    cl.register(1, MDesc(), False)
    cl.register(2, MDesc(vel=50.0), False)
    kept = trial_memo.TrialMemo(KIN, None, cl.of, cl.value_keys)
    plain = trial_memo.TrialMemo(KIN, None, cl.of)
    line = JointLine(HOME, HOME + 30.0)
    spans = [Span(line, 0.0, 0.5, [(1, 0.0)]), Span(line, 0.5, 1.0, [(2, 0.0)])]
    seen = []
    for change in ("none", "kept", "monitor", "mdesc", "reduced"):
        if change == "monitor":
            cl.set_monitor(50.0)
        elif change == "mdesc":
            cl.register(2, MDesc(vel=20.0), False)
        elif change == "reduced":
            cl.register(1, MDesc(), True)
        key = kept.key(spans, 0.5, 10.0)
        assert key == plain.key(spans, 0.5, 10.0), change
        assert set(cl.value_keys) == {1, 2}
        seen.append(key)
    assert seen[0] == seen[1]
    assert len(set(seen)) == 4


def test_a_registered_mdesc_object_is_not_hashed_again(monkeypatch):
    """`CommandLimits.register` finds an MDesc object it saw by the object (no MDesc hash) and gives
    the one tuple kept for its values: an equal object, the same tuple; another value or the
    reduced speed, another."""
    from val3check.motion.mdesc import CommandLimits, MDesc

    hashes = []
    plain = MDesc.__hash__
    monkeypatch.setattr(MDesc, "__hash__", lambda self: hashes.append(1) or plain(self))
    cl = CommandLimits(KIN, 100.0)
    md = MDesc(vel=40.0)
    first = cl.register(1, md, False)
    n = len(hashes)
    assert n >= 1
    assert cl.register(2, md, False) is first and len(hashes) == n
    assert cl.register(3, MDesc(vel=40.0), False) is first
    assert cl.register(4, md, True) is not first and cl.register(4, md, True)[1] is True
    other = cl.register(5, MDesc(vel=41.0), False)
    assert other is not first and other[0] == MDesc(vel=41.0)
    assert cl.of(2) is cl.of(1) and cl.of(5) is not cl.of(1)
