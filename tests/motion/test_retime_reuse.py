"""The acceleration range's re-timing (motion/retime.py, issue 29): each distinct piece of path is
timed once (a repeated piece reuses it, a piece that differs in any input is timed again), and the
re-timing stops when the wall-clock budget is spent, the range then said to be partial."""

from __future__ import annotations

import pytest

from interpretation.simsupport import sim
from val3check.motion.motion_records import motion_records
from val3check.motion.retime import Retiming, Stretches, piece_key, retimed, retimed_range
from val3check.robot import load_robot
from val3check.simulation import collect as collect_module

from .test_acceleration_range import GLOBALS, LOOP

TX = load_robot("TX2-60")


@pytest.fixture(scope="module")
def machine_run(tmp_path_factory):
    from val3check.simulation.run import run_machine
    from interpretation.simsupport import build
    from val3check.config import Settings
    from val3check.lint import run as lint_run
    from val3check.simulation import SimOptions

    # twenty passes of the U cycle: the same pieces again and again
    folder = build(tmp_path_factory.mktemp("u"), LOOP.replace("to 6", "to 20"), globals_=GLOBALS, locals_=["num l_i"])
    ws = lint_run([str(folder)], Settings()).workspace
    machine, result = run_machine(ws, ws.apps[ws.targets[0]], SimOptions(duration=600, robot=TX))
    return machine, result


def _fresh(queue, factor):
    """The re-timing of every stretch with nothing reused (the reference)."""
    from val3check.motion import retime

    keep = retime.piece_key
    retime.piece_key = lambda *a: None
    try:
        return Retiming(queue, factor)
    finally:
        retime.piece_key = keep


def test_a_repeated_piece_is_timed_once_and_gives_the_same_times(machine_run):
    machine, _ = machine_run
    q = machine.arm.queue_in_use
    records = motion_records(q)
    for factor in (0.5, 2.0):
        rt = Retiming(q, factor)
        ref = _fresh(q, factor)
        assert ref.timed == ref.stretches
        # two stops per pass; the blends' curves repeat every third pass (blending.candidate's reuse)
        assert rt.stretches == ref.stretches == 41 and rt.timed <= 8
        for r in records:
            for t in (r.start, r.end):
                if t is not None:
                    assert rt.time(t) == pytest.approx(ref.time(t), abs=1e-9)


def test_a_piece_that_differs_in_any_input_has_another_key(machine_run):
    machine, _ = machine_run
    q = machine.arm.queue_in_use
    path, limits = q.planner.path, q.limits.of
    prof = q.planner.profile
    moving = [(prof.S[i], prof.S[i + 1]) for i in range(len(prof.S) - 1) if prof.S[i + 1] > prof.S[i]]
    a, b = moving[0][0], moving[-1][1]
    a, b = path.offsets[1], path.offsets[3]
    base = piece_key(path, a, b, limits)
    assert piece_key(path, a, b, limits) == base
    assert piece_key(path, a, b - 0.5, limits) != base  # where it ends
    assert piece_key(path, path.offsets[2], b, limits) != base  # where it starts (other spans)

    def other(key):
        lim = limits(key)
        from val3check.motion.mdesc import Limits
        return Limits(lim.V, lim.A * 1.000001, lim.D, lim.tvel, lim.rvel)

    assert piece_key(path, a, b, other) != base  # its limits
    span = path.spans[1]
    keep = span.tool
    span.tool = None if keep is not None else __import__("numpy").eye(4)
    try:
        assert piece_key(path, a, b, limits) != base  # its tool
    finally:
        span.tool = keep


def test_the_retiming_stops_when_the_budget_is_spent(machine_run):
    machine, _ = machine_run
    q = machine.arm.queue_in_use
    records = motion_records(q)
    calls = []

    def out_of_time():
        calls.append(1)
        return len(calls) > 1  # spent after the first look

    moved, rt = retimed(q, records, 2.0, out_of_time)
    assert rt.cut is not None and 0.0 < rt.cut < records[-1].start
    assert all(r.start is None for r, o in zip(moved, records) if o.start is not None and o.start >= rt.cut)
    assert any(r.start is not None for r in moved)


def test_a_partial_range_is_said(tmp_path, monkeypatch):
    monkeypatch.setattr(collect_module.RunBudget, "out_of_time", lambda self: True)
    r = sim(tmp_path, LOOP, globals_=GLOBALS, locals_=["num l_i"], robot=TX)
    spread = r.motion.acceleration_range
    assert spread.partial is not None and "covers the run up to" in spread.partial
    (task,) = [t for t, s in r.motion.cycles.items() if s.times]
    assert spread.cycle_time(task) is None  # nothing re-timed: no range given, not a wrong one
    said = [d for d in r.diagnostics if d.code == "R006" and "re-timing" in d.message]
    assert len(said) == 1 and said[0].message == spread.partial


def test_the_factors_share_the_stretches_and_places_but_not_their_timing(machine_run):
    """retimed_range finds the stretches, their keys and the records' places once for all the
    factors: each factor's records are those of its own fresh re-timing (nothing reused across
    them), and another factor gives other times."""
    machine, _ = machine_run
    q = machine.arm.queue_in_use
    records = motion_records(q)
    both = retimed_range(q, records, (0.5, 2.0))
    for factor, (moved, rt) in zip((0.5, 2.0), both):
        ref = _fresh(q, factor)
        assert rt.timed < ref.timed
        for r, o in zip(moved, records):
            assert r == __import__("dataclasses").replace(o, start=r.start, end=r.end)  # only the times moved
            for new, t in ((r.start, o.start), (r.end, o.end)):
                assert (new is None) == (t is None)
                if t is not None:
                    assert new == rt.time(t) and new == pytest.approx(ref.time(t), abs=1e-9)
    assert [r.end for r in both[0][0]] != [r.end for r in both[1][0]]
    assert retimed(q, records, 2.0)[0] == both[1][0]


def test_the_limits_memo_gives_the_keys_made_without_it(machine_run):
    machine, _ = machine_run
    q = machine.arm.queue_in_use
    path, limits, prof = q.planner.path, q.limits.of, q.planner.profile
    st = Stretches(q)
    assert st.spans and len(st.spans) == Retiming(q, 2.0).stretches
    for i, j, key in st.spans:
        assert key == piece_key(path, prof.S[i], prof.S[j], limits)


def test_one_stretches_for_many_factors_gives_each_factor_s_fresh_records(machine_run):
    """fit.py re-times the run for each factor it tries with one Stretches: each factor's records
    are those found with stretches of its own, and another queue's stretches are refused."""
    machine, _ = machine_run
    q = machine.arm.queue_in_use
    records = motion_records(q)
    st = Stretches(q)
    for factor in (0.25, 0.5, 1.5, 2.0, 0.25):
        moved, rt = retimed(q, records, factor, stretches=st)
        fresh, ref = retimed(q, records, factor)
        assert moved == fresh and rt.new_starts == ref.new_starts and rt.shift_end == ref.shift_end

    class Other:
        planner = q.planner
        limits = q.limits

    with pytest.raises(ValueError):
        Retiming(Other(), 2.0, stretches=st)


def test_next_true_finds_what_a_search_of_every_index_finds():
    import numpy as np

    from val3check.motion.retime import _next_true

    rng = np.random.default_rng(7)
    for n, p in ((0, 0.5), (1, 1.0), (5, 0.0), (300, 0.9), (5000, 0.001), (200_000, 0.00002)):
        mask = rng.random(n) < p
        at = np.flatnonzero(mask)
        for i in {0, 1, n // 3, max(n - 1, 0), n, *rng.integers(0, max(n, 1), 20).tolist()}:
            k = at.searchsorted(i)
            assert _next_true(mask, i) == (int(at[k]) if k < len(at) else -1)


def test_window_is_a_view_and_the_profile_grows_while_it_lives():
    import numpy as np

    from val3check.motion.history import History
    from val3check.motion.trajectory import Profile, window

    p = Profile()
    p.append(0.0, np.array([0.0, 1.0, 3.0]), np.array([0.0, 2.0, 0.0]))
    w = window(p.S, 1, 10)
    assert w.tolist() == [1.0, 3.0] and not w.flags.owndata
    assert window([5.0, 6.0, 7.0], 1, 3).tolist() == [6.0, 7.0] and window(p.T, 3, 3).tolist() == []
    # a history's chunks are allocated full: growing never resizes what a view sees (history.py)
    p.append(p.t_end, np.array([3.0, 4.0]), np.array([0.0, 0.0]))
    assert isinstance(p.S, History) and p.S[-1] == 4.0 and w.tolist() == [1.0, 3.0]


@pytest.mark.parametrize("spent_after", [None, 3])
def test_places_and_times_found_together_are_those_found_one_at_a_time(machine_run, spent_after):
    """Stretches.places and Retiming.times_at (what each_retimed uses): the same place and the same
    re-timed time, bit for bit, as `place` and `time_at` of each time alone, at every breakpoint,
    between breakpoints, before the run, past its end, None, and past a cut."""
    import numpy as np

    machine, _ = machine_run
    q = machine.arm.queue_in_use
    prof = q.planner.profile
    st = Stretches(q)
    T = np.asarray(list(prof.T))
    times = [None, -1.0, 0.0, *T.tolist(), *(0.5 * (T[1:] + T[:-1])).tolist(), *(T[1:] - 1e-9).tolist(),
             T[-1] + 5.0, None, *st.starts, *st.ends]
    t, k, rel = st.places(times)
    for x, tt, kk, rr in zip(times, t.tolist(), k.tolist(), rel.tolist()):
        one = st.place(x)
        if one is None:
            assert tt != tt
            continue
        assert (one[0], one[1]) == (tt, kk)
        assert (one[2] is None and rr != rr) or one[2] == rr
    calls = []

    def out_of_time():
        calls.append(1)
        return spent_after is not None and len(calls) > spent_after

    for factor in (0.5, 2.0):
        calls.clear()
        rt = Retiming(q, factor, out_of_time, st)
        assert (rt.cut is not None) == (spent_after is not None)
        many = rt.times_at(t, k, rel).tolist()
        for x, m in zip(times, many):
            one = rt.time(x)
            assert (one is None and m != m) or one == m


def test_places_read_the_profile_a_stretch_at_a_time(machine_run, monkeypatch):
    """Stretches.places reads the profile around each block of times, in time order: never the whole
    run at once (an 8 h run holds millions of breakpoints), even when the times come unsorted (the
    records' starts, then their ends)."""
    from val3check.motion import retime

    machine, _ = machine_run
    q = machine.arm.queue_in_use
    records = motion_records(q)
    st = Stretches(q)
    sizes = []
    window = retime.window
    monkeypatch.setattr(retime, "window", lambda v, lo, hi: sizes.append(hi - lo) or window(v, lo, hi))
    monkeypatch.setattr(retime, "_PLACES", 8)
    st.places([r.start for r in records] + [r.end for r in records])
    assert sizes and max(sizes) < len(q.planner.profile.T) / 4


def test_the_owners_limits_kept_by_command_and_by_limits_object_are_those_made_afresh():
    """piece_key's memo: an owner's limits key is kept by its command's key and by its Limits object
    (the queue shares one per mdesc); two commands with other limits get other keys, two with the
    same Limits object one, and every key equals the one made with nothing kept."""
    import numpy as np

    from val3check.motion.mdesc import Limits
    from val3check.motion.retime import _limits_key, _owner_limits

    kin_v = np.full(6, 100.0)
    a = Limits(kin_v, kin_v * 2, kin_v * 3, 250.0, 90.0)
    b = Limits(kin_v, kin_v * 2, kin_v * 3, 250.0, 45.0)  # rvel only
    of = {1: a, 2: b, 3: a}
    memo: dict = {}
    keys = {k: _owner_limits(memo, of.__getitem__, k) for k in (1, 2, 3)}
    assert keys[1] != keys[2] and keys[1] == keys[3]
    assert all(keys[k] == _limits_key(of[k]) for k in keys)
    of[4] = Limits(kin_v, kin_v * 2, kin_v * 3.5, 250.0, 90.0)  # a new object, D only
    assert _owner_limits(memo, of.__getitem__, 4) == _limits_key(of[4]) != keys[1]


def test_a_tool_pose_s_matrix_is_made_once_per_pose_and_each_component_changed_misses():
    """collect's open()/close() rows share one read-only matrix per tool pose, kept by the pose's
    bits: it equals the matrix made afresh, and each component changed in turn (even 0.0 to -0.0)
    makes another."""
    poses: dict = {}
    base = (10.0, -20.0, 130.0, 0.0, 180.0, 90.0)
    m = collect_module._shared_matrix(base, poses)
    assert collect_module._shared_matrix(list(base), poses) is m
    assert m.tobytes() == collect_module._matrix(base).tobytes() and not m.flags.writeable
    for k in range(6):
        for v in (base[k] + 1.0, -base[k] if base[k] else -0.0):
            other = list(base)
            other[k] = v
            o = collect_module._shared_matrix(other, poses)
            assert o is not m and o.tobytes() == collect_module._matrix(other).tobytes()
    assert len(poses) == 13


def test_the_rounding_kept_gives_round_s_value_and_the_same_keys():
    """piece_key keeps round(x, 9) by x: the value round gives, the second time too; a zero's sign
    may come from the other zero's, which changes neither a key's equality nor its hash."""
    import math

    import numpy as np

    from val3check.motion.retime import _round9

    rng = np.random.default_rng(3)
    xs = [*rng.uniform(-1e3, 1e3, 500).tolist(), *(rng.uniform(0, 1e-8, 200)).tolist(), 0.0, -0.0, 5e-10, 1.5e-9,
          math.inf, -math.inf, math.nan, 123456789.123456789]
    kept: dict = {}
    for x in xs + xs[::-1]:
        r = _round9(kept, x)
        want = round(x, 9)
        assert (r == want and math.copysign(1.0, r) == math.copysign(1.0, want)) or (r != r and want != want) \
            or (r == 0.0 == want and hash((r,)) == hash((want,)))


def test_the_limits_kept_by_mdesc_are_those_made_afresh():
    """collect's motion rows share one MotionLimits per distinct value, kept by the mdesc object as
    well: the same object for the same mdesc and for an equal one, another for each field changed
    in turn (0.0 to -0.0 too), and every one equal to the limits made with nothing kept."""
    from dataclasses import replace

    from val3check.motion.mdesc import MDesc

    same: dict = {}
    base = MDesc(accel=80.0, vel=50.0, decel=70.0, tvel=250.0, rvel=90.0)
    lim = collect_module._limits(base, same)
    assert lim == collect_module._limits(base, None)
    assert collect_module._limits(base, same) is lim
    assert collect_module._limits(replace(base), same) is lim  # another object, the same values
    assert collect_module._limits(replace(base, blend="joint"), same) is lim  # not a limit
    made = [lim]
    for name in ("accel", "vel", "decel", "tvel", "rvel"):
        for v in (getattr(base, name) + 1.0, 0.0, -0.0):
            md = replace(base, **{name: v})
            got = collect_module._limits(md, same)
            assert got == collect_module._limits(md, None) and repr(got) == repr(collect_module._limits(md, None))
            assert all(got is not m for m in made)
            made.append(got)
            assert collect_module._limits(md, same) is got
