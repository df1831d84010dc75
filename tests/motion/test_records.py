"""Per-motion records and cycle times."""

from __future__ import annotations

import numpy as np
import pytest

from val3check.motion.cycle import CycleCounter, Loop, Pass, cycle_stats
from val3check.motion.findings import Source
from val3check.motion.mdesc import MDesc
from val3check.motion.motion_records import busy_time, motion_records

from .motionhelp import HOME, movej, movel, point, queue, run


def test_movel_record_at_a_tvel_limit():
    q = queue()
    q.record(movel(point(dy=300.0, name="pA"), MDesc(blend="off", tvel=250.0), line=11), 0.0)
    t = run(q)
    (r,) = motion_records(q)
    assert r.id == 0 and r.kind == "movel" and r.source.line == 11 and r.state == "done"
    assert r.start == 0.0 and r.end == pytest.approx(t)
    assert r.length_mm == pytest.approx(300.0, rel=1e-6)
    assert r.peak_tcp_mm_s == pytest.approx(250.0, rel=1e-4)
    assert r.dominant == "tvel"
    assert r.target == "pA"


def test_movej_records_name_the_axis_and_the_phase():
    start = HOME.copy()
    start[3] = -250.0
    long_ = HOME.copy()
    long_[3] = 250.0  # 500° of j4 at 50 %: cruise most of the time
    q = queue(joints=start)
    q.record(movej(long_, MDesc(vel=50, blend="off")), 0.0)
    t = run(q)
    short = long_.copy()
    short[0] += 60.0
    q.record(movej(short, MDesc(decel=50, blend="off")), t)
    run(q, t)
    r1, r2 = motion_records(q)
    assert r1.dominant == "j4 speed"
    assert r2.dominant == "j1 decel"
    assert sum(r1.limit_share.values()) == pytest.approx(r1.duration, rel=1e-9)


def test_cycle_times_are_between_the_starts_of_the_loops_passes():
    q = queue()
    home = Source("app/start.pgx", 5, 3, "start", "robot")
    a = Source("app/start.pgx", 8, 5, "start", "robot")
    b = Source("app/start.pgx", 9, 5, "start", "robot")
    loop = Loop("app/start.pgx", 7, 3, "start", "while")
    counter = CycleCounter()
    contexts = []
    now = 0.0
    q.record(_mj(HOME + [10, 0, 0, 0, 0, 0], home), now)
    contexts.append(())
    counter.note("robot", ())
    for k in range(1, 5):
        for j, src in ((HOME + [40, 0, 0, 0, 0, 0], a), (HOME + [-20, 10, 0, 0, 0, 0], b)):
            q.record(_mj(j, src), now)
            contexts.append((Pass(loop, 1, k),))
            counter.note("robot", contexts[-1])
        now = run(q, now) + 0.3  # the program waits 0.3 s each cycle
    recs = motion_records(q, now)
    st = cycle_stats(recs, contexts)["robot"]
    assert st.loop == loop and st.marker == ("app/start.pgx", 7, 3) and st.passes == 4
    assert st.count == 3 == counter.completed("robot")
    times = st.times
    assert times[1] == pytest.approx(times[2], abs=1e-9)  # from the second pass on, the same cycle
    one = recs[4].end - recs[3].start  # a (from b) then b, then the program's 0.3 s
    assert times[1] == pytest.approx(one + 0.3, abs=1e-9)
    assert times[0] == pytest.approx(recs[2].end - recs[1].start + 0.3, abs=1e-9)
    busy, idle = busy_time(q.profile, now)
    assert busy + idle == pytest.approx(now) and idle >= 4 * 0.3 - 1e-9


def test_a_motion_the_arm_has_not_started_when_the_run_ends_has_no_start():
    """docs/sim-report.md: start and end are null when the motion never ran; one under way has
    no end, and only the part of the path it ran."""
    q = queue()
    for k in range(3):  # three 60-degree moves of j1, recorded at once, one after the other
        q.record(movej(HOME + [60 * (k + 1), 0, 0, 0, 0, 0]), 0.0)
    planned = motion_records(q)
    assert all(r.start is not None for r in planned)
    t_mid = 0.5 * (planned[1].start + planned[1].end)
    q.advance(t_mid)
    done, under_way, waiting = motion_records(q, t_mid)
    assert done.state == "done" and done.end == pytest.approx(planned[0].end)
    assert under_way.state == "pending" and under_way.start == pytest.approx(planned[1].start)
    assert under_way.end is None and 0 < under_way.length_mm < planned[1].length_mm
    assert waiting.state == "pending" and waiting.start is None and waiting.end is None
    assert waiting.length_mm == 0.0


def _mj(j, src):
    from val3check.motion.commands import MoveCommand, Target

    return MoveCommand("movej", Target.joint(j), MDesc(blend="off"), source=src)


def test_records_of_cancelled_and_failed_commands():
    q = queue()
    q.record(movej(HOME + [120, 0, 0, 0, 0, 0]), 0.0)
    q.reset_motion(0.1)
    (r,) = motion_records(q)
    assert r.state == "cancelled" and r.start == 0.0 and r.end > 0.1
    assert np.isfinite(r.length_mm)


def test_solve_many_is_solve_of_each_bit_for_bit():
    """The record's starts found a block at a time (`_solve_many`) are `trajectory._solve` of each:
    rests, zero-length intervals, constant speed, speeding up and slowing down, either side and
    at the interval's ends."""
    from val3check.motion.motion_records import _solve_many
    from val3check.motion.trajectory import _solve

    rng = np.random.default_rng(7)
    n = 400
    T = np.cumsum(rng.choice([0.0, 1e-3, 0.0137, 0.25], n))
    S = np.cumsum(rng.choice([0.0, 1e-9, 0.3, 2.5], n)) + 1234.5
    SD = rng.choice([0.0, 0.0, 1.7, 3.0, 1e-14], n)
    SD[1::7] = SD[0::7][:len(SD[1::7])]  # some intervals at constant speed
    k = rng.integers(0, n - 1, 3000)
    frac = rng.choice([-0.5, 0.0, 1e-12, 0.25, 0.5, 1.0, 1.5], len(k))
    s = S[k] + frac * (S[k + 1] - S[k]) + rng.choice([0.0, -1e-13, 1e-13], len(k))
    many = _solve_many(T, S, SD, k, s)
    Tl, Sl, SDl = T.tolist(), S.tolist(), SD.tolist()
    one = np.array([_solve(Tl, Sl, SDl, j, x) for j, x in zip(k.tolist(), s.tolist())])
    assert many.tobytes() == one.tobytes()
