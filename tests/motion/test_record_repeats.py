"""The motion records of repeated motions (motion/record_repeats.py, issue 29): a command that
repeats an earlier one takes its length, peak and per-interval limits; its limit seconds are its
own; an input that differs in anything makes it a new command; and a long run's records are those
computed afresh for every command."""

from __future__ import annotations

from array import array

import numpy as np
import pytest

from val3check.motion import motion_records as records_module
from val3check.motion import record_seconds as seconds_module
from val3check.motion.mdesc import Limits
from val3check.motion.motion_records import motion_records
from val3check.motion.record_repeats import Repeats, noise
from val3check.motion.trajectory import Profile

from .pick_place_run import TX, pick_place_machine


@pytest.fixture(scope="module")
def pick_place():
    """Two minutes of the bundled pick-and-place (its scenario): about forty cycles' commands."""
    machine = pick_place_machine(120)
    q = machine.arm.queue_in_use
    return q, machine.end_time / 1e6


def _spy(monkeypatch) -> list:
    """Whether each look-up of a command found an earlier one."""
    found = []
    find_block = Repeats.find_block

    def spy(self, asks):
        out = find_block(self, asks)
        found.extend(earlier is not None for earlier, _, _ in out)
        return out

    monkeypatch.setattr(Repeats, "find_block", spy)
    return found


@pytest.mark.parametrize("planned", [False, True])
def test_a_long_run_reusing_its_records_gives_the_fresh_records(pick_place, monkeypatch, planned):
    """`planned`: as planned (no end: a done command's start and breakpoints are found with its block,
    RecordMaker._place), else as the run ended."""
    q, end = pick_place
    end = None if planned else end
    fresh = motion_records(q, end, reuse=False)
    found = _spy(monkeypatch)
    doubts = []  # per repeat with a near tie: its intervals in doubt
    decide = records_module._decide

    def counted(queue, prof, out, pending):
        doubts.extend(int((~figures[3]).sum()) for _, _, figures, *_ in pending)
        return decide(queue, prof, out, pending)

    monkeypatch.setattr(records_module, "_decide", counted)
    reused = motion_records(q, end)
    assert len(fresh) == len(reused) > 200
    assert sum(found) > 0.5 * len(found)  # most commands repeat an earlier one (the first cycles are new)
    # the limit of an interval was a near tie in some commands: decided again for each repetition
    assert len(doubts) > 0 and min(doubts) >= 1 and min(doubts) <= 2
    for a, b in zip(fresh, reused):
        # all but length and peak exactly the fresh ones (the seconds under each limit included)
        assert (a.id, a.kind, a.source, a.state, a.recorded, a.start, a.end, a.dominant, a.limit_share, a.target,
                a.tool) == (b.id, b.kind, b.source, b.state, b.recorded, b.start, b.end, b.dominant, b.limit_share,
                            b.target, b.tool)
        # length and peak: an earlier repetition's, which differ from this one's by the rounding of
        # the run's positions (record_repeats.py), and print the same
        assert b.length_mm == pytest.approx(a.length_mm, rel=1e-9, abs=1e-9)
        assert b.peak_tcp_mm_s == pytest.approx(a.peak_tcp_mm_s, rel=1e-9, abs=1e-9)
        assert (round(a.length_mm, 3), round(a.peak_tcp_mm_s, 3)) == (round(b.length_mm, 3), round(b.peak_tcp_mm_s, 3))


def _moved(q):
    """(command, s0, s1, k0, k1) of each command that moved: its path positions and the profile's
    breakpoints around them."""
    import bisect

    prof = q.trajectory.profile
    for command in q.history:
        place = command.placement
        if place.s_begin is None or place.s_end is None or place.s_end - place.s_begin < 1e-6:
            continue
        s0, s1 = place.s_begin, place.s_end
        yield command, s0, s1, bisect.bisect_left(prof.S, s0), bisect.bisect_right(prof.S, s1)


def _first_repeat(q, repeats: Repeats):
    """(inputs of a command, the arguments that gave them) for the first command that repeats an
    earlier one, with the earlier one's inputs already seen."""
    for command, s0, s1, k0, k1 in _moved(q):
        args = (command.tool, q.limits_of(command), s0, s1, max(k0 - 1, 0), k1)
        if repeats.find(repeats.inputs(*args))[0] is not None:
            return args
    raise AssertionError("no command repeats another")


def _profile(prof, which: str, k: int, delta: float) -> Profile:
    """A copy of `prof` with breakpoint k's time, position or path speed moved by delta."""
    out = Profile()
    out.T, out.S, out.SD = array("d", prof.T), array("d", prof.S), array("d", prof.SD)
    getattr(out, which)[k] += delta
    return out


def test_a_command_that_differs_in_any_input_is_not_a_repeat(pick_place):
    q, _ = pick_place
    prof = q.trajectory.profile
    seen = Repeats(q.path, prof)
    args = _first_repeat(q, seen)
    tool, lim, s0, s1, lo, k1 = args

    def found(repeats=seen, **change) -> bool:
        a = dict(zip(("tool", "lim", "s0", "s1", "lo", "k1"), args))
        a.update(change)
        return repeats.find(repeats.inputs(*a.values()))[0] is not None

    assert found()  # itself again
    assert not found(tool=np.eye(4) if tool is None else np.asarray(tool) + 1e-6)  # its tool
    assert not found(lim=Limits(lim.V, lim.A * 1.000001, lim.D, lim.tvel, lim.rvel))  # its limits
    assert not found(lim=Limits(lim.V, lim.A, lim.D * 1.000001, lim.tvel, lim.rvel))
    assert not found(lim=Limits(lim.V * 1.000001, lim.A, lim.D, lim.tvel, lim.rvel))
    assert not found(lim=Limits(lim.V, lim.A, lim.D, lim.tvel * 0.5, lim.rvel))
    assert not found(lim=Limits(lim.V, lim.A, lim.D, lim.tvel, lim.rvel * 0.5))
    assert not found(s1=s1 - 1e-6)  # where it ends
    assert not found(s0=s0 + 1e-6)  # where it starts
    assert not found(lo=lo + 1)  # the breakpoints it reads
    # the profile: a breakpoint's position, time or path speed
    k = lo + (k1 - lo) // 2
    for which, delta in (("S", 1e-7), ("T", 1e-7), ("SD", 1e-5)):
        moved = Repeats(q.path, _profile(prof, which, k, delta))
        moved.seen = seen.seen
        assert not found(moved), which
    # the path: another geometry over the same positions
    i = q.path.locate(0.5 * (s0 + s1))[0]
    span = q.path.spans[i]
    keep = span.geom
    span.geom = type(keep).__new__(type(keep))
    span.geom.__dict__.update(keep.__dict__)
    try:
        assert not found()
    finally:
        span.geom = keep
    # its own rounding is not a difference: positions, times, speeds moved by a few units in the last place
    for which in ("S", "T", "SD"):
        moved = Repeats(q.path, _profile(prof, which, k, 4 * np.spacing(getattr(prof, which)[k])))
        moved.seen = seen.seen
        assert found(moved), which


def _reference_share(q, command, s0: float, s1: float) -> dict:
    """The seconds under each limit as the interval loop computed them before issue 29's reuse."""
    import bisect

    from val3check.motion.paths import tcp_rates

    prof, lim = q.trajectory.profile, q.limits_of(command)
    k0, k1 = bisect.bisect_left(prof.S, s0), bisect.bisect_right(prof.S, s1)
    lo = max(k0 - 1, 0)
    S, T, SD = (np.asarray(a[lo:k1 + 1]) for a in (prof.S, prof.T, prof.SD))
    mids = 0.5 * (S[1:] + S[:-1])
    q1, q2 = q.path.q(mids, 1), q.path.q(mids, 2)
    pt, rt = tcp_rates(q.kin, q.path.q(mids), q1, command.tool)
    out: dict = {}
    n = len(lim.V)
    for j in range(len(S) - 1):
        ds = S[j + 1] - S[j]
        if not (ds > 0 and S[j + 1] > s0 and S[j] < s1):
            continue
        x0, x1 = SD[j] ** 2, SD[j + 1] ** 2
        x, u = 0.5 * (x0 + x1), (x1 - x0) / (2.0 * ds)
        if abs(u) > 1e-6 * max(1.0, x):
            acc = np.abs(q1[j] * u + q2[j] * x) / (lim.A if u > 0 else lim.D)
            label = f"j{int(np.argmax(acc)) + 1} {'accel' if u > 0 else 'decel'}"
        else:
            sd = np.sqrt(x)
            speed = np.concatenate([np.abs(q1[j]) * sd / lim.V, [pt[j] * sd / lim.tvel, rt[j] * sd / lim.rvel]])
            k = int(np.argmax(speed))
            label = f"j{k + 1} speed" if k < n else ("tvel" if k == n else "rvel")
        frac = min(max((min(S[j + 1], s1) - max(S[j], s0)) / ds, 0.0), 1.0)
        out[label] = out.get(label, 0.0) + float((T[j + 1] - T[j]) * frac)
    return out


def test_the_seconds_under_each_limit_are_the_interval_loops(pick_place):
    """With and without reuse, the seconds under each limit are those of the loop over intervals
    the records were first computed with (its labels and its sums, bit for bit)."""
    q, end = pick_place
    checked = 0
    for reuse in (False, True):
        for r, command in zip(motion_records(q, end, reuse=reuse), q.history):
            place = command.placement
            if r.end is None or command.state != "done" or place.s_end is None:
                continue
            assert r.limit_share == _reference_share(q, command, place.s_begin, place.s_end)
            assert r.dominant == (max(r.limit_share, key=r.limit_share.get) if r.limit_share else "")
            checked += 1
    assert checked > 300


def test_the_tcp_speed_skips_the_samples_at_rest_and_gives_every_sample_s_speed(pick_place):
    """arm_record.tcp_speed: the forward kinematics only where the arm moves (at rest the pose is
    the same twice: 0), the same values as every sample through the flange's poses."""
    from val3check.simulation.arm_record import TCP_STEP_S, tcp_speed
    from val3check.simulation.collect import ModelKinematics

    q, end = pick_place
    kin = ModelKinematics(TX)
    times, Q, V = q.trajectory.sample(0.0, 40.0, 0.004)
    records = motion_records(q, end)
    uses = [(r.start, c.tool) for r, c in zip(records, q.history) if r.start is not None and r.kind != "connection"]
    got = tcp_speed(kin, TX.flange_frame, uses, times, Q, V)
    at_rest = np.all(V == 0.0, axis=1)
    assert 0 < at_rest.sum() < len(times)
    assert np.all(got[at_rest] == 0.0)
    P0 = kin.link_poses_many(Q)[TX.flange_frame]
    P1 = kin.link_poses_many(Q + TCP_STEP_S * V)[TX.flange_frame]
    starts = np.array([t for t, _ in uses])
    for k in np.linspace(0, len(times) - 1, 400).astype(int).tolist():
        tool = uses[max(int(np.searchsorted(starts, times[k], side="right")) - 1, 0)][1]
        p = np.array([0.0, 0.0, 0.0, 1.0]) if tool is None else np.asarray(tool)[:, 3]
        assert got[k] == pytest.approx(np.linalg.norm((P1[k] @ p - P0[k] @ p)[:3]) / TCP_STEP_S, rel=1e-9, abs=1e-6)


@pytest.mark.parametrize("block", [1, 2, 5])
def test_records_made_as_the_blocks_fill_are_the_fresh_ones(pick_place, monkeypatch, block):
    """Blocks of new commands evaluated as soon as they fill: a repeat met after its first one was
    evaluated is made at once, one met before waits for it; either way the fresh record."""
    q, end = pick_place
    fresh = motion_records(q, end, reuse=False)
    monkeypatch.setattr(records_module, "RECORD_BLOCK", block)
    waited, at_once = [], []
    repeat, many = records_module._repeat, records_module.seconds_many

    def spy(prof, out, item, dt, slot, doubts, *window):
        waited.append(out[item[0]] is None and slot.figures is not None)
        return repeat(prof, out, item, dt, slot, doubts, *window)

    def spy_many(S, rows):
        at_once.extend(rows)
        return many(S, rows)

    monkeypatch.setattr(records_module, "_repeat", spy)
    monkeypatch.setattr(records_module, "seconds_many", spy_many)
    reused = motion_records(q, end)
    assert len(waited) + len(at_once) > 100
    for a, b in zip(fresh, reused, strict=True):
        assert (a.id, a.start, a.end, a.dominant, a.limit_share) == (b.id, b.start, b.end, b.dominant, b.limit_share)
        assert (round(a.length_mm, 3), round(a.peak_tcp_mm_s, 3)) == (round(b.length_mm, 3), round(b.peak_tcp_mm_s, 3))


def _asks(q) -> list:
    """(tool, limits, s0, s1, lo, hi, i0, i1) of each command that moved, as RecordMaker.add makes them."""
    prof, path = q.trajectory.profile, q.path
    out = []
    for command, s0, s1, k0, k1 in _moved(q):
        lo, hi = max(k0 - 1, 0), min(k1, len(prof.S) - 1)
        out.append((command.tool, q.limits_of(command), s0, s1, lo, hi, path.locate(min(prof.S[lo], s0))[0],
                    path.locate(max(prof.S[hi], s1))[0]))
    return out


@pytest.mark.parametrize("block", [1, 7, 128, 10_000])
def test_a_block_of_look_ups_answers_as_one_look_up_at_a_time(pick_place, block):
    """find_block: the same answers (which earlier command, or a new one), the same durations and the
    same keys kept as `inputs` and `find` one command at a time, whatever the block."""
    q, _ = pick_place
    prof = q.trajectory.profile
    asks = _asks(q)
    one, many = Repeats(q.path, prof), Repeats(q.path, prof)
    expected = []
    for tool, lim, s0, s1, lo, hi, _, _ in asks:
        inputs = one.inputs(tool, lim, s0, s1, lo, hi)
        expected.append((*one.find(inputs), inputs[3]))
    got = []
    for at in range(0, len(asks), block):
        got.extend(many.find_block(asks[at:at + block]))
    names_one, names_many = {}, {}  # each Slot named by the command that made it

    def name(names, r, earlier, slot):
        if slot is not None:
            names[id(slot)] = r
            return ("new", r)
        return ("repeats", names[id(earlier)])

    assert len(got) == len(expected) > 200
    for r, ((e1, n1, d1), (e2, n2, d2)) in enumerate(zip(expected, got)):
        assert name(names_one, r, e1, n1) == name(names_many, r, e2, n2)
        assert d1.tobytes() == d2.tobytes()
    assert one.hits == many.hits > 0.5 * len(asks)
    assert len(one.seen) == len(many.seen)
    for kept in one.seen.values():  # the values kept per key: the same bytes (keys differ in form only)
        assert any([g.tobytes() for g, _ in kept] == [g.tobytes() for g, _ in other] for other in many.seen.values())


def test_a_block_with_a_span_appended_at_a_command_s_end_is_looked_up_one_at_a_time(pick_place, monkeypatch):
    """A span that begins where a command's last read breakpoint lies, appended after the command was
    added, would change the key made from the path now: that block is looked up one at a time."""
    q, _ = pick_place
    asks = _asks(q)[:20]
    tool, lim, s0, s1, lo, hi, i0, _ = asks[3]
    asks[3] = (tool, lim, s0, s1, lo, hi, i0, i0 - 1)  # as if its last span were then the path's last
    calls = []
    one = Repeats._one
    monkeypatch.setattr(Repeats, "_one", lambda self, ask: calls.append(ask) or one(self, ask))
    Repeats(q.path, q.trajectory.profile).find_block(asks)
    assert len(calls) == len(asks)


def test_the_order_of_limits_is_their_first_appearance_and_each_interval_s_place_in_it():
    """_order (what a repeat's seconds are summed by): as np.unique's first indices gave it."""
    rng = np.random.default_rng(7)
    for _ in range(500):
        codes = rng.integers(0, 15, rng.integers(0, 60)).astype(np.intp)
        labels, rank = seconds_module._order(codes, 6)
        first = np.sort(np.unique(codes, return_index=True)[1])
        assert labels == [seconds_module._label(int(codes[k]), 6) for k in first]
        assert rank.dtype == np.intp and [labels[x] for x in rank.tolist()] == [seconds_module._label(int(c), 6)
                                                                                  for c in codes]


def test_the_order_of_limits_kept_is_the_order_made_afresh_and_each_input_changed_misses():
    """_order is kept by its codes' bytes and the number of axes: each kept answer equals one made
    with nothing kept, a code changed or the axes changed gives another answer, and what is
    kept cannot be written through."""
    rng = np.random.default_rng(11)
    runs = [rng.integers(0, 15, rng.integers(1, 40)).astype(np.intp) for _ in range(200)]
    runs += [c.copy() for c in runs]  # every one asked twice: the second from what is kept
    kept = [seconds_module._order(c, 6) for c in runs]
    seconds_module._ORDERS.clear()
    for c, (labels, rank) in zip(runs, kept):
        fresh = seconds_module._order(c, 6)
        seconds_module._ORDERS.clear()
        assert labels == fresh[0] and rank.tobytes() == fresh[1].tobytes()
        with pytest.raises(ValueError):
            rank[0] = 0
    codes = np.array([13, 13, 2, 7], dtype=np.intp)
    base = seconds_module._order(codes, 6)
    other = codes.copy()
    other[2] = 3
    assert seconds_module._order(other, 6)[0] != base[0]  # a code
    assert seconds_module._order(codes, 7)[0] != base[0]  # the axes (the labels' numbering)
    assert seconds_module._order(codes.astype(np.int32), 6)[1] is base[1]  # the same codes in another integer type


def test_noise_from_a_window_list_or_array_is_the_profiles(pick_place):
    """record_repeats.noise read from a window of the profile's path speeds (a list, or an array as
    _decide_block passes it) gives the bits read from the profile itself."""
    q, _ = pick_place
    prof = q.trajectory.profile
    n = len(prof.S)
    rng = np.random.default_rng(5)
    for _ in range(300):
        lo = int(rng.integers(0, n - 2))
        k1 = int(rng.integers(lo + 1, n + 3))  # (past the last breakpoint: clipped to it)
        base = int(rng.integers(0, lo + 1))
        s_max = float(rng.random() * 1e4 * rng.choice([-1.0, 1.0]))
        arr = np.asarray(prof.SD[base:n], dtype=float)
        want = noise(prof, lo, k1, s_max)
        for SD in (arr, arr.tolist()):
            got = noise(prof, lo, k1, s_max, SD, base)
            assert [float(x).hex() for x in got] == [float(x).hex() for x in want]


def test_where_the_offsets_fall_among_the_positions_is_searchsorted():
    """record_repeats._at_or_before (the span each breakpoint of a block's window falls on, counted
    from the offsets' places among the positions) is offs.searchsorted(S, "right"): rests (equal
    positions), offsets on a position, before the first and past the last."""
    from val3check.motion.record_repeats import _at_or_before

    rng = np.random.default_rng(17)
    for _ in range(500):
        S = np.sort(rng.choice(rng.random(int(rng.integers(1, 60))) * 100, int(rng.integers(1, 200))))
        offs = np.sort(np.concatenate([rng.choice(S, int(rng.integers(0, 5))), rng.random(int(rng.integers(0, 8))) * 120
                                       - 10]))
        got = _at_or_before(offs, S)
        want = offs.searchsorted(S, "right")
        assert got.dtype == want.dtype and got.tobytes() == want.tobytes()
