"""Issue 29, sixth round: what the page and the JSON report no longer compute twice, each reuse
held against a fresh computation, and each input of its key changed in turn.

- the page's TCP speed, once per distinct (tool, joints, joint velocities) row (run_trajectory._Seen);
- the motion table's repeated cells (page._where_cells, page._limit_cells);
- the JSON report's lists made as they are written (sim_json.Lazy), its per-sample clearances
  rounded a group at a time (sim_collision._Rounded)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from val3check.reporting import sim_collision, sim_json
from val3check.reporting.html import from_run, page, run_trajectory
from val3check.simulation.arm_record import tcp_speed

from .runhelp import CELL, ROOT, pickplace


@pytest.fixture(autouse=True)
def _in_root(monkeypatch):
    monkeypatch.chdir(ROOT)


@pytest.fixture(scope="module")
def run():
    return pickplace(20.0, cell=str(CELL))


def _fresh(m, times, q, v):
    """The TCP speed of every sample computed alone: no row reused."""
    out = np.zeros(len(times))
    for k in range(len(times)):
        out[k] = m.tcp_speed(times[k:k + 1], q[k:k + 1], v[k:k + 1])[0]
    return out


def test_the_page_s_tcp_speed_reused_over_many_blocks_is_the_speed_of_each_sample(run):
    """Rows that repeat (here each sample twice, as a cyclic cell's cycles repeat theirs): across
    blocks of every size, the speeds reused are the speeds computed sample by sample, to the bit,
    and each repeated row is computed once."""
    result, _ = run
    m = result.motion
    times, q, v = m.sample(0.0, m.end_s, 0.004)
    on = np.flatnonzero((v != 0.0).any(axis=1))
    times, q, v = (np.repeat(a[on], 2, axis=0) for a in (times, q, v))
    want = m.tcp_speed(times, q, v)
    assert want.tobytes() == _fresh(m, times, q, v).tobytes()
    for size in (1, 2, 7, 500, len(times)):
        tcp = run_trajectory._TcpSpeed(m)
        computed = []
        speed = tcp._speed
        tcp._speed = lambda t, a, b: computed.append(len(t)) or speed(t, a, b)
        got = np.concatenate([tcp(times[lo:lo + size], q[lo:lo + size], v[lo:lo + size])
                              for lo in range(0, len(times), size)])
        assert got.tobytes() == want.tobytes()
        assert sum(computed) <= len(times) // 2


def test_rows_whose_hashes_collide_are_each_computed_as_themselves(run, monkeypatch):
    """Every row given the same hash: the rows are still told apart by their bits, and each speed
    is the speed of its own row."""
    result, _ = run
    m = result.motion
    times, q, v = m.sample(0.0, m.end_s, 0.004)
    on = np.flatnonzero((v != 0.0).any(axis=1))[:400]
    times, q, v = (np.repeat(a[on], 2, axis=0) for a in (times, q, v))
    monkeypatch.setattr(run_trajectory, "_hash", lambda bits: np.zeros(len(bits), dtype=np.uint64))
    tcp = run_trajectory._TcpSpeed(m)
    got = np.concatenate([tcp(times[lo:lo + 50], q[lo:lo + 50], v[lo:lo + 50]) for lo in range(0, len(times), 50)])
    assert got.tobytes() == m.tcp_speed(times, q, v).tobytes()


def test_each_input_of_a_reused_tcp_speed_row_changed_is_computed_again(run):
    """The key is the tool, the joints and the joint velocities: a row equal in all three is reused;
    one differing in any of them (by one bit) is computed, and gives the fresh speed."""
    result, _ = run
    m = result.motion
    times, q, v = m.sample(0.0, m.end_s, 0.004)
    k = int(np.flatnonzero((v != 0.0).any(axis=1))[len(times) // 8])
    tcp = run_trajectory._TcpSpeed(m)
    computed = []
    speed = tcp._speed
    tcp._speed = lambda t, a, b: computed.append(len(t)) or speed(t, a, b)
    t1, q1, v1 = times[k:k + 1], q[k:k + 1].copy(), v[k:k + 1].copy()
    first = tcp(t1, q1, v1)
    assert computed == [1]
    assert tcp(t1, q1.copy(), v1.copy()).tobytes() == first.tobytes() and computed == [1]  # reused
    for axis in range(q.shape[1]):
        for which in ("q", "v"):
            q2, v2 = q1.copy(), v1.copy()
            row = q2 if which == "q" else v2
            row[0, axis] = np.nextafter(row[0, axis], math.inf)
            before = len(computed)
            got = tcp(t1, q2, v2)
            assert len(computed) == before + 1, (which, axis)
            assert got.tobytes() == m.tcp_speed(t1, q2, v2).tobytes()
    # the tool: the same row under another tool is computed with that tool
    tcp.tools = tcp.tools + 1.0
    tool = np.eye(4)
    tool[:3, 3] = (0.0, 0.0, 250.0)
    tcp.uses = [(t, tool) for t, _ in tcp.uses]
    before = len(computed)
    got = tcp(t1, q1, v1)
    assert len(computed) == before + 1
    scene = m.scene
    assert got.tobytes() == tcp_speed(scene.kinematics, scene.flange_frame, tcp.uses, t1, q1, v1).tobytes()
    assert got[0] != first[0]


def test_the_page_of_a_run_is_the_page_without_reuse(run, monkeypatch):
    """The whole page, its TCP speed reused over small blocks, is the page with every row computed."""
    _, report = run
    monkeypatch.setattr(run_trajectory, "BLOCK_SAMPLES", 300)
    reused = from_run.render_run(report)

    class Fresh(run_trajectory._TcpSpeed):
        def __call__(self, times, q, v):
            return self._speed(times, q, v)

    monkeypatch.setattr(run_trajectory, "_TcpSpeed", Fresh)
    assert reused == from_run.render_run(report)


_cached = page._where_cells, page._limit_cells


def test_a_motion_row_s_cells_made_once_are_the_cells_of_each_row():
    """The cached cells read their arguments alone: each changed in turn changes the row, and a
    row made from the cache is the row made afresh."""
    base = {"id": 3, "kind": "movel", "path": "a/b/pick.pgx", "line": 8, "column": 3, "task": "robot",
            "target": "pPick", "start": 1.5, "end": 2.25, "duration": 0.75, "dominant_limit": "speed",
            "vel": 100.0, "tvel": 250.0, "min_clearance": 12.5, "clearance_to": "guard"}
    page._where_cells.cache_clear()
    page._limit_cells.cache_clear()
    row = page._motion_row(base)
    assert page._motion_row(dict(base)) == row
    fresh = page._where_cells.__wrapped__, page._limit_cells.__wrapped__
    changes = {"path": "a/b/place.pgx", "line": 9, "column": 4, "task": "other", "kind": "movej", "target": "pPlace",
               "dominant_limit": "acceleration", "vel": 50.0, "tvel": None}
    for key, value in changes.items():
        other = page._motion_row({**base, key: value})
        assert other != row, key
        try:  # the same row with the caches bypassed
            page._where_cells, page._limit_cells = fresh
            assert page._motion_row({**base, key: value}) == other
        finally:
            page._where_cells, page._limit_cells = _cached
    # a number's type and sign are part of the key: 8 and 8.0, 0.0 and -0.0 write differently
    assert page._motion_row({**base, "line": 8.0}) != row
    assert page._motion_row({**base, "vel": -0.0}) != page._motion_row({**base, "vel": 0.0})


def test_the_json_report_s_lazy_lists_are_written_as_lists():
    rows = [{"a": 1, "b": [1.0, 2.0]}, {"a": 2, "b": []}]
    for indent in (0, 2):
        assert sim_json.dumps({"x": sim_json.Lazy(lambda: iter(rows))}, indent) == sim_json.dumps({"x": rows}, indent)
        assert "".join(sim_json.chunks({"x": sim_json.Lazy(lambda: iter(rows))}, indent)) == \
            sim_json.dumps({"x": rows}, indent)
        assert sim_json.dumps({"x": sim_json.Lazy(lambda: iter(()))}, indent) == sim_json.dumps({"x": []}, indent)


@pytest.mark.parametrize("group", [1, 5, 37, 10**9])
def test_clearances_rounded_a_group_at_a_time_are_rounded_as_all_at_once(run, monkeypatch, group):
    """The per-sample clearances of the JSON report, rounded a group of entries at a time and read
    in any order, are those rounded all at once (Python's rounding of each value)."""
    result, report = run
    reports = [r for r in result.collision.by_motion.values() if len(r.times)][:40]
    assert len(reports) > 10
    monkeypatch.setattr(sim_collision, "GROUP_SAMPLES", group)
    entries = [{"clearance": {}} for _ in reports]
    sim_collision._samples(entries, reports)
    order = list(range(len(reports)))
    for k in order[::3] + order[::-1]:
        for key, name, digits in (("times", "times", 6), ("mm", "clearance", 3)):
            want = [round(x, digits) + 0.0 if math.isfinite(x) else math.nan
                    for x in np.asarray(getattr(reports[k], name), dtype=float).tolist()]
            got = entries[k]["clearance"][key].a
            assert np.array_equal(got, np.array(want), equal_nan=True) and not np.signbit(got[got == 0.0]).any()
