"""What makes a reused motion's check cheap (issue 29, fifth round) gives what the code it replaces
gave, bit for bit, and is keyed by everything that determines it: the motions' keys computed in
blocks (`own_clocks`), the joints at a gripper event (`Positions`), a part's solids copied
(`bodies.copies`) and the timeline's tool matrix (`TimelineLog._matrix`)."""

from __future__ import annotations

import numpy as np
import pytest

from val3check.collision.bodies import copies, make_bodies
from val3check.collision.fcl_backend import FclBackend
from val3check.motion.paths import JointLine, Path, Span
from val3check.motion.trajectory import Profile, Trajectory
from val3check.simulation import own_clock as oc
from val3check.simulation.cell_timeline import TimelineLog

OUT = JointLine([0, 0, 90, 0, 45, 0], [40, 10, 80, 5, 50, 30])
BACK = JointLine(OUT.q1, OUT.q0)


def _run(pieces, starts):
    """A run of motions, each [(span, ...)] crossed in one profile (speed up to half way, then
    down) started at its time in `starts`: the arm rests between them."""
    path, prof = Path(pieces[0][0].geom.q([pieces[0][0].a])[0]), Profile(0.0, 0.0)
    out = []
    for spans, t0 in zip(pieces, starts):
        off = None
        for sp in spans:
            o = path.append(Span(sp.geom, sp.a, sp.b))
            off = o if off is None else off
        end = path.end
        prof.append(t0, np.array([off, 0.5 * (off + end), end]), np.array([0.0, 80.0, 0.0]))
        out.append((t0, prof.t_end))
    return Trajectory(path, prof), out


def _long_run():
    half = [Span(OUT, 0.0, 0.5), Span(OUT, 0.5, 1.0)]  # one motion over two spans
    pieces = [[Span(OUT, 0.0, 1.0)], [Span(BACK, 0.0, 1.0)], half, [Span(BACK, 0.0, 1.0)]] * 3
    starts = np.cumsum([0.3] + [2.7013] * (len(pieces) - 1)).tolist()
    return _run(pieces, starts)


def _windows(spans):
    """Every motion, and windows that start before the profile, end after it, have no length,
    start inside a motion, or span two motions."""
    out = list(spans)
    t_end = spans[-1][1]
    out += [(-1.0, 0.2), (0.0, 0.0), (t_end, t_end + 3.0), (t_end + 1.0, t_end + 2.0), (spans[3][0], spans[3][0]),
            (spans[2][0] + 0.1, spans[2][1]), (spans[1][0], spans[2][1]), (spans[5][1], spans[6][0])]
    return out


@pytest.mark.parametrize("block", [1, 3, 512])
def test_the_keys_computed_in_blocks_are_own_clocks_keys_and_samples(monkeypatch, block):
    monkeypatch.setattr(oc, "BLOCK", block)
    traj, spans = _long_run()
    windows = _windows(spans)
    batch = list(oc.own_clocks(traj, windows))
    assert len(batch) == len(windows)
    for (a, b), got in zip(windows, batch):
        one = oc.own_clock(traj, a, b)
        assert got.key == one.key and got.key is not None
        assert got.times.tobytes() == one.times.tobytes()
        assert got.joints.tobytes() == one.joints.tobytes()
        assert got.q_at(0.01).tobytes() == one.q_at(0.01).tobytes()
    # a motion that repeats has one key; another curve, timing or part of a motion another
    keys = [o.key for o in batch[:len(spans)]]
    assert keys[0] == keys[4] == keys[8] and keys[2] == keys[6] and keys[1] == keys[5]
    assert len({keys[0], keys[1], keys[2]}) == 3


@pytest.mark.parametrize("block", [1, 2, 3, 512])
def test_the_blocks_read_a_profile_with_breakpoints_at_one_time_as_own_clock(monkeypatch, block):
    # a replan cuts the profile and continues from the same instant: two breakpoints at one time
    from array import array

    monkeypatch.setattr(oc, "BLOCK", block)
    traj, _ = _long_run()
    prof = traj.profile
    prof.T = array("d", [0.0, 1.0, 1.0, 2.0, 3.0, 3.0, 3.0, 4.5, 6.0])
    prof.S = array("d", [0.0, 5.0, 5.5, 20.0, 40.0, 40.0, 41.0, 60.0, 70.0])
    prof.SD = array("d", [0.0, 10.0, 12.0, 15.0, 10.0, 9.0, 9.0, 5.0, 0.0])
    windows = [(1.0, 1.0), (1.0, 3.0), (3.0, 3.0), (0.5, 1.0), (3.0, 4.5), (2.0, 3.0), (-1.0, 0.0), (4.5, 7.0),
               (6.0, 6.0), (0.0, 6.0), (2.5, 2.5)]
    for (a, b), got in zip(windows, oc.own_clocks(traj, windows)):
        one = oc.own_clock(traj, a, b)
        assert got.key == one.key and got.joints.tobytes() == one.joints.tobytes()


def test_the_blocks_read_the_profile_exactly_as_profile_state():
    traj, spans = _long_run()
    prof = traj.profile
    T = np.asarray(prof.T)
    ts = np.concatenate([T, T[:-1] + 0.5 * np.diff(T), [T[0] - 1.0, T[-1] + 1.0]])
    s, sd = oc._states(T, np.asarray(prof.S), np.asarray(prof.SD), ts)
    for t, a, b in zip(ts.tolist(), s.tolist(), sd.tolist()):
        s1, sd1, _ = prof.state(t)
        assert (a, b) == (s1, sd1)


def test_a_trajectory_of_another_kind_is_sampled_as_it_is_in_blocks_too():
    traj, spans = _long_run()

    class Shifted(Trajectory):
        def positions(self, times):
            return super().positions(times) + 1.0

    moved = Shifted(traj.path, traj.profile)
    own = list(oc.own_clocks(moved, spans[:2]))
    assert own[0].key is None and np.array_equal(own[0].joints, moved.positions(spans[0][0] + own[0].times))


def test_the_joints_at_an_event_are_the_trajectorys_and_found_again_only_by_their_key():
    traj, spans = _long_run()
    pos = oc.Positions(traj)
    # every tick of the run, and the motions' ends: a long reused run against a fresh computation
    times = np.arange(0.0, spans[-1][1] + 0.5, 0.004).tolist() + [b for _, b in spans] + [a for a, _ in spans]
    for t in times:
        assert pos(t).tobytes() == traj.position(t).tobytes()
    assert pos.hits > len(spans)  # the ends of repeated motions, the rests
    # each input of the key: the span's geometry (a copy of the curve is another), its ends, the
    # position along it; the answer is never the memo's own array
    pos = oc.Positions(traj)
    end0 = spans[0][1]
    a = pos(end0)
    a[:] = 0.0
    assert pos(end0).tobytes() == traj.position(end0).tobytes() and pos.hits == 1
    copy = JointLine(OUT.q0, OUT.q1)
    other, ospans = _run([[Span(copy, 0.0, 1.0)], [Span(OUT, 0.0, 0.5)], [Span(OUT, 0.0, 1.0)]], [0.3, 3.0, 6.0])
    pos = oc.Positions(other)
    for t in (ospans[0][1], ospans[1][1], ospans[2][1], 0.5 * sum(ospans[2])):
        assert pos(t).tobytes() == other.position(t).tobytes()
    assert pos.hits == 0 and len(pos.memo) == 4
    assert pos(ospans[2][1] + 0.5).tobytes() == other.position(ospans[2][1]).tobytes() and pos.hits == 1  # at rest


@pytest.mark.parametrize("block", [1, 7, 4096])
def test_the_joints_at_many_events_are_the_trajectorys_computed_in_blocks(monkeypatch, block):
    """`Positions.each` (the path positions of a block of events at once) gives, event by event,
    what the trajectory gives and what `Positions` alone gives, with the same memo hits; times
    before the profile, after it, at its breakpoints and out of order too."""
    monkeypatch.setattr(oc, "BLOCK", block)
    traj, spans = _long_run()
    times = (np.arange(-0.5, spans[-1][1] + 0.5, 0.0037).tolist() + [b for _, b in spans] + [a for a, _ in spans]
             + list(traj.profile.T) + [3.0, 0.1, 20.0, 0.0])
    one, many = oc.Positions(traj), oc.Positions(traj)
    for t, q in zip(times, many.each(times), strict=True):
        assert q.tobytes() == traj.position(t).tobytes() == one(t).tobytes(), t
    assert many.hits == one.hits > len(spans) and many.memo.keys() == one.memo.keys()


def test_a_motions_joints_at_one_time_are_its_joints_at_many_bit_for_bit():
    """`Own.q_at(t)` (one time between two samples, without arrays) gives `q_at.many([t])`'s bits:
    at every breakpoint of the motion's profile, between them, before its start and after its end."""
    traj, spans = _long_run()
    for own, (a, b) in zip(oc.own_clocks(traj, spans), spans):
        breaks = np.frombuffer(own.key[1], dtype=np.int64).reshape(3, -1)[0] * oc.Q_T  # its profile's times
        knots = np.unique(np.concatenate([breaks, own.times, np.linspace(-0.01, b - a + 0.01, 97)]))
        for t in np.concatenate([knots, 0.5 * (knots[1:] + knots[:-1]), np.nextafter(knots, np.inf)]).tolist():
            assert own.q_at(t).tobytes() == own.q_at.many(np.array([t]))[0].tobytes(), t


def test_the_joints_of_another_kind_of_trajectory_are_asked_every_time():
    traj, spans = _long_run()

    class Shifted(Trajectory):
        def position(self, t):
            return super().position(t) + 1.0

    pos = oc.Positions(Shifted(traj.path, traj.profile))
    assert np.array_equal(pos(spans[0][1]), traj.position(spans[0][1]) + 1.0)
    assert np.array_equal(pos(spans[0][1]), traj.position(spans[0][1]) + 1.0) and pos.hits == 0 and not pos.memo


def _lshape():
    """A non-convex closed mesh (an L of two boxes) cut into several pieces."""
    import trimesh

    b = trimesh.creation.box((20.0, 100.0, 20.0))
    b.apply_translation((40.0, 40.0, 0.0))
    m = trimesh.util.concatenate([trimesh.creation.box((100.0, 20.0, 20.0)).subdivide().subdivide(), b])
    return m.vertices, m.faces


@pytest.mark.parametrize("kind", ["box", "mesh"])
def test_a_copy_of_a_parts_solids_is_what_making_them_again_gives(kind):
    if kind == "box":
        made = make_bodies("part", "brick", "brick", "part 'brick'", "box", (40.0, 30.0, 20.0), np.eye(4))
        again = make_bodies("part", "brick", "brick", "part 'brick'", "box", (40.0, 30.0, 20.0), np.eye(4))
    else:
        v, f = _lshape()
        made = make_bodies("part", "ell", "ell", "part 'ell'", "mesh", (), np.eye(4), v, f)
        again = make_bodies("part", "ell", "ell", "part 'ell'", "mesh", (), np.eye(4), v, f)
    for i, b in enumerate(made):
        b.made_from = ("part", 0, i)
    got = copies(made)
    assert len(got) == len(made) == len(again)
    for c, b in zip(got, made):
        assert c is not b and c.obj is not b.obj and (c.exact is None) == (b.exact is None)
        assert c.exact is None or c.exact is not b.exact
        assert c.made_from == b.made_from and c.label == b.label and c.kind == b.kind
        assert c.local is not b.local and np.array_equal(c.local, b.local) and np.array_equal(c.pose, np.eye(4))
    # one solid: its pieces share a number no other solid has (neither the original nor another copy)
    assert len({c.whole for c in got}) == 1 and {c.whole for c in got}.isdisjoint({b.whole for b in made})
    assert {c.whole for c in got}.isdisjoint({c.whole for c in copies(made)})
    # placed, a copy measures what a solid made again measures, and the original is never moved
    table = make_bodies("obstacle", "table", "table", "obstacle 'table'", "box", (400.0, 400.0, 40.0), np.eye(4))[0]
    table.place(np.eye(4))
    backend = FclBackend()
    P = np.eye(4)
    P[:3, 3] = (30.0, -20.0, 41.5)
    P[:3, :3] = [[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]]
    for c, b in zip(got, again):
        c.place(P)
        b.place(P)
        dc, db = backend.distance(c, table), backend.distance(b, table)
        assert dc.mm == db.mm and np.array_equal(c.aabb()[0], b.aabb()[0])
    assert all(np.array_equal(b.pose, np.eye(4)) for b in made)


def test_the_timelines_tool_matrix_is_converted_again_for_another_value():
    from val3check.collision import Cell, Part, Shape
    from val3check.collision.cellfile import trsf_matrix

    cell = Cell(path="test")
    cell.parts.append(Part("brick", "tTool", "close", Shape("box", (40.0, 40.0, 40.0)), np.eye(4)))

    class Watch:
        value = None

        def tool(self, name, t):
            return self.value

    watch = Watch()
    log = TimelineLog(cell, watch, run=None, unit_mm=2.0)
    first = trsf_matrix((0.0, 0.0, 10.0, 0, 0, 0))
    watch.value = first
    m1 = log._matrix(first)
    assert m1[2, 3] == 20.0 and log._matrix(first) is m1
    other = trsf_matrix((0.0, 0.0, 10.0, 0, 0, 0))  # equal values, another reading
    m2 = log._matrix(other)
    assert m2 is not m1 and np.array_equal(m1, m2)
    moved = trsf_matrix((0.0, 5.0, 10.0, 0, 0, 0))
    assert log._matrix(moved)[1, 3] == 10.0
    watch.value = moved
    log._take("brick", 1.0)
    assert np.array_equal(log.spans[-1]["pose"], log._matrix(moved))


def test_the_gap_between_boxes_is_the_sum_of_squares_the_reduction_gave_bit_for_bit():
    from val3check.collision.bodies import aabb_gap

    def summed(lo_a, hi_a, lo_b, hi_b):  # as it was: numpy's reduction over the last axis
        gap = np.maximum(0.0, np.maximum(lo_a - hi_b, lo_b - hi_a))
        return np.sqrt((gap * gap).sum(axis=-1))

    rng = np.random.default_rng(29)
    for sa, sb in [((3,), (3,)), ((5, 3), (5, 3)), ((7, 1, 3), (1, 9, 3)), ((40, 12, 3), (1, 12, 3)), ((60, 20, 3), (60, 20, 3))]:
        for _ in range(20):
            lo_a, lo_b = rng.normal(0.0, 400.0, sa), rng.normal(0.0, 400.0, sb)
            hi_a, hi_b = lo_a + rng.random(sa) * 300.0, lo_b + rng.random(sb) * 300.0
            for a in (lo_a, np.moveaxis(np.ascontiguousarray(np.moveaxis(lo_a, -1, 0)), 0, -1)):  # strided too
                assert aabb_gap(a, hi_a, lo_b, hi_b).tobytes() == summed(a, hi_a, lo_b, hi_b).tobytes()
    one = np.zeros(3), np.ones(3)
    assert aabb_gap(*one, np.array([0.5, 0.5, 0.5]), np.array([2.0, 2.0, 2.0])) == 0.0  # overlapping
    assert aabb_gap(*one, np.array([4.0, 5.0, 0.0]), np.array([5.0, 6.0, 1.0])) == 5.0  # 3, 4 apart: 5
