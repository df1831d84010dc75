"""What the queue keeps between scheduler cycles and records (issue 29, fourth round) is never
stale: a span's end kept on its geometry, the queue's done time kept until the profile changes,
a read-only tool keyed by its object. Each input of a key changed in turn misses, and a long run
that reuses them answers every question as a fresh computation does, bit for bit."""

from __future__ import annotations

import numpy as np

from val3check.motion import queue as queue_mod
from val3check.motion import trial_memo
from val3check.motion.mdesc import CommandLimits, MDesc
from val3check.motion.paths import JointLine, Span
from val3check.motion.queue import QueueFull

from .motionhelp import HOME, KIN, movel, point, queue
from .test_plan_reuse import TOOL, _cycle, _run


def test_a_span_end_is_its_evaluation_bit_for_bit(monkeypatch):
    _, _, q = _run(["", "", "blend", "", "tool"], True, monkeypatch)
    kinds = set()
    for sp in q.path.spans:
        kinds.add(type(sp.geom).__name__)
        fresh = sp.q([sp.length])[0]
        assert np.array_equal(sp.end(), fresh)
        assert np.array_equal(Span(sp.geom, sp.a, sp.b).end(), fresh)  # another span, the same part: kept
        assert not sp.end().flags.writeable  # shared: never changed in place
    assert {"JointLine", "JointSpline", "JointBlend"} <= kinds, kinds


class _Counted(JointLine):
    """A JointLine that counts its evaluations."""

    def __init__(self, q0, q1):
        super().__init__(q0, q1)
        self.evaluated = 0

    def q(self, lam, order=0):
        self.evaluated += 1
        return super().q(lam, order)


def test_each_input_of_a_span_end_changed_in_turn_misses():
    line = _Counted(HOME, HOME + 30.0)
    base = Span(line, 0.0, 0.5).end()
    assert line.evaluated == 1
    Span(line, 0.0, 0.5, [(3, 0.0)], True, TOOL).end()  # owners, smooth, tool: not read
    assert line.evaluated == 1
    for a, b in [(0.1, 0.5), (0.0, 0.6)]:  # the end is evaluated at a + (b - a)·ell / ell
        end = Span(line, a, b).end()
        assert line.evaluated == 2
        assert np.array_equal(end, line.q([a + (b - a) * line.ell / line.ell])[0])
        line.evaluated = 1
    other = _Counted(HOME, HOME + 40.0)
    assert not np.array_equal(Span(other, 0.0, 0.5).end(), base)
    assert other.evaluated == 1


def test_the_path_end_follows_its_spans():
    from val3check.motion.paths import Path

    line = JointLine(HOME, HOME + 30.0)
    path = Path(HOME)
    assert np.array_equal(path.q_rest, HOME)
    path.append(Span(line, 0.0, 0.5))
    assert np.array_equal(path.q_rest, line.q([0.5])[0])
    path.append(Span(line, 0.5, 1.0, smooth=True))
    assert np.allclose(path.q_rest, HOME + 30.0, atol=1e-12)
    path.cut(path.end / 4.0)
    assert np.allclose(path.q_rest, HOME + 7.5, atol=1e-12)


def test_the_done_time_misses_when_each_input_changes():
    q = queue()
    q.record(movel(point(dx=60.0)), 0.0)
    q.record(movel(point(dx=60.0, dy=40.0)), 0.0)
    q.planner.flush()
    first, second = q.pending
    t1 = q._done_time(first)
    assert t1 == q.profile.time_at(first.placement.s_end)
    assert q._done_time(first) == t1  # kept
    t2 = q._done_time(second)  # another command
    assert t2 == q.profile.time_at(second.placement.s_end) and t2 > t1
    # the profile changes (a brake, then a replan), the same command: asked again
    q.stop_move(t1 / 2.0)
    assert q._done_time(first) is None  # the arm stops before its end
    q.restart_move(t1)
    t1b = q._done_time(first)
    assert t1b == q.profile.time_at(first.placement.s_end) and t1b > t1
    # the command's end moves (the profile unchanged): asked again
    end = first.placement.s_end
    first.placement.s_end = end / 2.0
    assert q._done_time(first) == q.profile.time_at(end / 2.0) < t1b
    first.placement.s_end = end
    assert q._done_time(first) == t1b


class _Checked(queue_mod.MotionQueue):
    """A queue that compares every done time it keeps with the profile's answer then."""

    asked = 0

    def _done_time(self, command):
        t = super()._done_time(command)
        end = command.placement.s_end
        assert t == (None if end is None else self.profile.time_at(end))
        type(self).asked += 1
        return t


def _scheduled(cls, reuse: bool, monkeypatch) -> tuple:
    """A scheduler's questions over 8 cycles (next_event every cycle, records ahead of the arm,
    a stop and a restart, a monitor speed change): every answer, and the profile."""
    monkeypatch.setattr(trial_memo, "REUSE", reuse)
    from .motionhelp import ROBOT

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
            answers.append((r, q.next_event(now), q.get_move_id(now), q.is_empty(now)))
            if k % 2:
                nxt = q.next_event(now)
                if nxt is not None:
                    now = nxt
                    q.advance(now)
                    answers.append((q.next_event(now), q.get_move_id(now), q.is_settled(now)))
        if n == 3:
            q.stop_move(now + 0.1)
            q.restart_move(now + 0.3)
        if n == 6:
            q.set_monitor_speed(70.0, now)
        while (nxt := q.next_event(now)) is not None:
            now = nxt
            q.advance(now)
            answers.append((now, q.get_move_id(now), q.is_empty(now), q.is_settled(now)))
    prof = q.profile
    return answers, (list(prof.T), list(prof.S), list(prof.SD))


def test_a_long_run_answers_the_scheduler_as_a_fresh_computation(monkeypatch):
    _Checked.asked = 0
    on = _scheduled(_Checked, True, monkeypatch)
    assert _Checked.asked > 100
    off = _scheduled(queue_mod.MotionQueue, False, monkeypatch)
    assert on == off  # floats compared exactly


def test_a_read_only_tool_is_keyed_by_its_object_a_writable_one_by_its_values():
    cl = CommandLimits(KIN, 100.0)
    cl.register(1, MDesc(), False)
    memo = trial_memo.TrialMemo(KIN, None, cl.of)
    line = JointLine(HOME, HOME + 30.0)

    def key(tool):
        return memo.key([Span(line, 0.0, 1.0, [(1, 0.0)], False, tool)], 0.0, 0.0)

    shared = TOOL.copy()
    shared.flags.writeable = False
    k_shared = key(shared)
    assert key(shared) == k_shared
    assert key(TOOL.copy()) == k_shared  # the same values
    other = TOOL.copy()
    other[2, 3] = 50.0
    other.flags.writeable = False
    assert key(other) != k_shared
    writable = TOOL.copy()
    k_w = key(writable)
    writable[2, 3] = 50.0  # changed in place: its key follows
    assert key(writable) != k_w
    assert key(None) != k_shared

