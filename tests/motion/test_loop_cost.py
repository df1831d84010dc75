"""What the scheduler's loop keeps to answer its frequent questions cheaply (issue 29, fifth
round) is what a fresh computation gives: the queue's count of completed commands (the progress
display's motions done) against the count over the history."""

from __future__ import annotations

from pathlib import Path

from val3check.config import Settings
from val3check.lint import run as lint_run
from val3check.simulation import SimOptions
from val3check.simulation.moving_arm import MovingArm
from val3check.simulation.run import run_machine
from val3check.simulation.scenario import load_scenario

from .pick_place_run import TX

ROOT = Path(__file__).resolve().parents[2]


def _done_over_history(queue) -> int:
    return sum(1 for c in queue.history if c.state == "done" and c.id is not None)


def test_motions_done_is_the_count_over_the_history_at_every_progress_call():
    ws = lint_run([str(ROOT / "fixtures/valid/PickPlace")], Settings()).workspace
    scenario = load_scenario(str(ROOT / "fixtures/scenarios/pickplace.toml"))
    seen: list[tuple[int, int]] = []
    arms: list[MovingArm] = []

    def progress(sim_s, motions_done):
        queue = arms[0].queue_in_use if arms else None
        seen.append((motions_done(), 0 if queue is None else _done_over_history(queue)))

    options = SimOptions(duration=60.0, max_wall=900, robot=TX, progress=progress)
    from val3check.simulation import run as run_mod

    made = run_mod.build_machine

    cycles: list[tuple[int, int]] = []

    def build(*a, **k):
        m = made(*a, **k)
        arms.append(m.arm)

        def each_cycle(time_us, cycle):  # after each record and at each cycle the arm advances
            q = m.arm.queue_in_use
            if q is not None:
                cycles.append((q.completed, _done_over_history(q)))

        m.arm.watch(each_cycle)
        return m

    run_mod.build_machine = build
    try:
        machine, _ = run_machine(ws, ws.apps[ws.targets[0]], options, scenario)
    finally:
        run_mod.build_machine = made
    assert seen and len(cycles) > 200 and cycles[-1][0] > 30
    assert all(a == b for a, b in seen + cycles)
    q = machine.arm.queue_in_use
    # a resetMotion cancels what is pending; the completed stay counted
    q.reset_motion(q.profile.t_end)
    assert q.completed == _done_over_history(q)


# ---- the rotation matrices kept by their angles (geometry/rotation.py) --------------------------

def test_a_kept_rotation_matrix_is_the_computed_one_and_each_angle_changes_it():
    import random

    from val3check.geometry import rotation as R

    rnd = random.Random(29)
    angles = [(rnd.uniform(-400, 400), rnd.uniform(-400, 400), rnd.uniform(-400, 400)) for _ in range(200)]
    angles += [(0.0, 0.0, 0.0), (-0.0, 0.0, -0.0), (180.0, 0.0, 0.0), (-180.0, 90.0, 45.0), (360.0, -0.0, 30.0)]
    for a in angles * 2:  # the second pass reads what the first kept
        assert R.matrix(*a) == R._matrix(*a)
    base = (10.0, 20.0, 30.0)
    for i in range(3):  # each input changed in turn: another matrix, the computed one
        changed = list(base)
        changed[i] += 1e-9
        assert R.matrix(*changed) != R.matrix(*base)
        assert R.matrix(*changed) == R._matrix(*changed)
    # -0.0 and 0.0 are one key: their matrices are the same bits (norm180 makes -0.0 0.0)
    import struct

    def bits(m):
        return struct.pack("9d", *m)

    assert bits(R._matrix(-0.0, -0.0, -0.0)) == bits(R._matrix(0.0, 0.0, 0.0))
    for k in range(R.MATRICES_KEPT + 10):  # bounded
        R.matrix(float(k), 1.0, 2.0)
    assert len(R._MATRICES) <= R.MATRICES_KEPT


# ---- the shared mdesc and source of a record (moving_arm.py, ch10_motion.py) ---------------------

MD = {"accel": 100.0, "vel": 80.0, "decel": 90.0, "tvel": 500.0, "rvel": 300.0, "blend": "joint",
      "leave": 20.0, "reach": 30.0}


def test_the_mdesc_kept_by_its_fields_is_the_one_made_from_them():
    from val3check.motion.mdesc import MDesc

    arm = MovingArm(TX)
    first = arm._mdesc(dict(MD), 1.0)
    assert first == MDesc.from_fields(MD, 1.0)
    assert arm._mdesc(dict(MD), 1.0) is first  # kept
    changes = {"accel": 50.0, "vel": 81.0, "decel": 1.0, "tvel": 499.0, "rvel": 1.5, "blend": "Cartesian",
               "leave": 21.0, "reach": 31.0}
    for name, value in changes.items():  # each field changed in turn: another mdesc, the one made
        md = {**MD, name: value}
        got = arm._mdesc(md, 1.0)
        assert got == MDesc.from_fields(md, 1.0) and got != first, name
    inch = arm._mdesc(dict(MD), 25.4)  # the unit
    assert inch == MDesc.from_fields(MD, 25.4) and inch.tvel == 500.0 * 25.4
    # a zero field is not kept: 0.0 and -0.0 are the same key but not the same mdesc
    zero, minus = {**MD, "leave": 0.0}, {**MD, "leave": -0.0}
    assert repr(arm._mdesc(zero, 1.0)) == repr(MDesc.from_fields(zero, 1.0))
    assert repr(arm._mdesc(minus, 1.0)) == repr(MDesc.from_fields(minus, 1.0))
    assert repr(MDesc.from_fields(zero, 1.0)) != repr(MDesc.from_fields(minus, 1.0))
    odd = {**MD, "extra": [1.0]}  # not hashable: made every time
    assert arm._mdesc(odd, 1.0) == MDesc.from_fields(odd, 1.0)


def test_the_source_kept_by_its_values_changes_with_each():
    from types import SimpleNamespace

    from val3check.motion.findings import Source
    from val3check.simulation import ch10_motion

    where = ["p.pgx", 3, 5, "pick"]

    def task(name="robot"):
        machine = SimpleNamespace(line_running=lambda: tuple(where), app=SimpleNamespace(path="app.pjx"))
        return SimpleNamespace(machine=machine, name=name, program="pick")

    first = ch10_motion._source(task())
    assert first == Source("p.pgx", 3, 5, "pick", "robot")
    assert ch10_motion._source(task()) is first
    for i, value in enumerate(["q.pgx", 4, 6, "place"]):  # each value changed in turn
        where[i], old = value, where[i]
        assert ch10_motion._source(task()) == Source(*where, "robot")
        where[i] = old
    assert ch10_motion._source(task("other")) == Source("p.pgx", 3, 5, "pick", "other")


# ---- a blend decision's three timings remembered together (planner._trials) ---------------------

def test_the_blend_decisions_timings_remembered_together_are_the_computed_ones(monkeypatch):
    """A scheduled run of the test cycles (records while the arm moves, QueueFull, each input of
    the cycle changed in turn, twice): every answer of `_trials` is compared with the same call
    computed without reuse, float for float, and most answers were remembered ones."""
    from val3check.motion import trial_memo
    from val3check.motion.planner import Planner

    from .test_plan_reuse import VARIANTS, _run

    original = Planner._trials
    hits, compared = [], []
    get = trial_memo.TrialMemo.get

    def counted(self, key, spans, speed_at=None, shift=None):
        hit = get(self, key, spans, speed_at, shift)
        if key is not None and key[-1] == "pays":
            hits.append(hit is not None)
        return hit

    def checked(self, *args):
        got = original(self, *args)
        monkeypatch.setattr(trial_memo, "REUSE", False)
        try:
            fresh = original(self, *args)
        finally:
            monkeypatch.setattr(trial_memo, "REUSE", True)
        assert got == fresh  # (blend trial, stop trial, alone from rest to rest): the same floats
        compared.append(got)
        return got

    monkeypatch.setattr(trial_memo.TrialMemo, "get", counted)
    monkeypatch.setattr(Planner, "_trials", checked)
    cycles = [""] * 6
    for v in VARIANTS:
        cycles += [v, "", v, ""]
    _run(cycles, True, monkeypatch)
    assert len(compared) > 100 and sum(hits) > len(hits) // 3, (sum(hits), len(hits))  # 79 of 167


# ---- a grid's rows kept by the spans' rows and the owners' limits (timing/grid.py) ---------------

def _grid_arrays(g):
    return [g.s, g.q1, g.q2, g.pt, g.rt, g.V, g.A, g.D, g.tv, g.rv]


def test_a_kept_grid_is_the_assembled_one_at_every_call_of_a_run(monkeypatch):
    """Every grid of a scheduled run of the test cycles (each input changed in turn, twice),
    assembled with its rows kept, is compared with the same grid assembled afresh, array for
    array and bit for bit; most were kept ones."""
    import numpy as np

    from val3check.motion.timing import grid as G

    from .test_plan_reuse import VARIANTS, _run

    original = G._assemble
    kept = []

    def checked(parts, limits, seen=None, kin=None):
        store = kin.reuse.get("grid-rows") if kin is not None else None
        before = {id(v[1][-1]) for v in store.values()} if store else set()
        grid, own = original(parts, limits, seen, kin)
        fresh, own2 = original(parts, limits)
        assert np.array_equal(own, own2)
        for x, y in zip(_grid_arrays(grid), _grid_arrays(fresh)):
            assert x.dtype == y.dtype and x.shape == y.shape and x.tobytes() == y.tobytes()
        if grid.rows is not None:
            assert grid.rows == tuple(x.tobytes() for x in _grid_arrays(fresh)[1:])
            assert not grid.q1.flags.writeable  # shared: never changed in place
        kept.append(id(grid.rows) in before)
        return grid, own

    monkeypatch.setattr(G, "_assemble", checked)
    cycles = [""] * 6
    for v in VARIANTS:
        cycles += [v, "", v, ""]
    _run(cycles, True, monkeypatch)
    assert len(kept) > 100 and sum(kept) > len(kept) // 3, (sum(kept), len(kept))


def test_each_input_of_a_kept_grid_changed_in_turn_misses():
    """The key: each span's rows (the very tuple), each owner's limits (the very object), which
    positions are kept; the owners and the positions themselves are never taken from the kept one."""
    import numpy as np

    from val3check.motion.kin import ArmKin
    from val3check.motion.mdesc import Limits, MDesc
    from val3check.motion.timing import grid as G

    kin = ArmKin(TX)
    lim = {1: Limits.of(kin, MDesc(), 1.0), 2: Limits.of(kin, MDesc(vel=50.0), 1.0)}
    n = 5

    def rows(seed):
        r = np.random.default_rng(seed)
        return (np.linspace(0.0, 1.0, n), r.random((n, 6)), r.random((n, 6)), r.random(n), r.random(n), None)

    def parts(rws, off, owner):
        return [(rw[0] + o, *rw[1:5], np.full(n, k)) for rw, o, k in zip(rws, off, owner)]

    r1, r2 = rows(1), rows(2)

    def make(rws=(r1, r2), off=(0.0, 1.0), owner=(1, 1), limits=None):
        limits = limits or lim
        seen = [(rw, (limits[k],)) for rw, k in zip(rws, owner)]
        return G._assemble(parts(rws, off, owner), limits.get, seen, kin)

    def same(g1, g2):
        return all(x.tobytes() == y.tobytes() for x, y in zip(_grid_arrays(g1), _grid_arrays(g2)))

    base, _ = make()
    again, _ = make()
    assert again.rows is base.rows and same(again, base)  # kept
    moved, _ = make(off=(100.0, 101.0))  # other positions: the same rows, new s
    assert moved.rows is base.rows and np.array_equal(moved.s, base.s + 100.0)
    owners = make(owner=(1, 1), limits={1: lim[1]})  # owner keys themselves: read fresh
    assert np.array_equal(owners[1], np.ones(2 * n - 1))
    changes = {
        "rows": make(rws=(r1, rows(2))),  # equal values, another tuple
        "limits": make(limits={1: Limits.of(kin, MDesc(), 1.0)}),  # equal values, another object
        "owner's limits": make(owner=(1, 2)),
        "positions kept": make(off=(0.0, 1.5)),  # the junction no longer repeats a position
    }
    for name, (g, _) in changes.items():
        assert g.rows is not base.rows, name
        fresh, _ = G._assemble(parts(*(
            ((r1, rows(2)), (0.0, 1.0), (1, 1)) if name == "rows" else
            ((r1, r2), (0.0, 1.0), (1, 2)) if name == "owner's limits" else
            ((r1, r2), (0.0, 1.5), (1, 1)) if name == "positions kept" else
            ((r1, r2), (0.0, 1.0), (1, 1)))), {1: lim[1], 2: lim[2]}.get if name != "limits" else lim.get)
        assert same(g, fresh), name
    assert not same(changes["owner's limits"][0], base)
    assert len(changes["positions kept"][0].s) == 2 * n
