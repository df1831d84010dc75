"""motion/history.py: the run-long sequence of doubles in chunks, the old ones in a temporary file,
held against a plain array('d') for every operation, at its chunk boundaries, cut across them, and
a run's reports with tiny chunks against the same run with the default ones."""

from __future__ import annotations

import bisect
import gc
import os
from array import array
from pathlib import Path

import numpy as np
import pytest

from val3check.motion import history, retime, trajectory
from val3check.motion.history import History, HistoryFull

hypothesis = pytest.importorskip("hypothesis")
from hypothesis import HealthCheck, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402


@pytest.fixture
def tiny(monkeypatch):
    """Chunks of 4 doubles (a new tail of 1, grown), one kept behind the tail, one read back cached:
    every path of the history taken by a few dozen values."""
    monkeypatch.setattr(history, "FIRST", 1)
    monkeypatch.setattr(history, "CHUNK", 4)
    monkeypatch.setattr(history, "KEEP", 1)
    monkeypatch.setattr(history, "CACHE", 1)


def _same(h: History, ref: array) -> None:
    assert len(h) == len(ref)
    if h._file is not None:  # (a cut shortens the file only when chunks leave it)
        assert os.fstat(h._file.fileno()).st_size == h._held
    assert h[:].tobytes() == ref.tobytes()
    assert array("d", iter(h)).tobytes() == ref.tobytes()
    assert all(h[i] == ref[i] or (h[i] != h[i] and ref[i] != ref[i]) for i in range(-len(ref), len(ref)))


FLOATS = st.floats(allow_nan=False, width=64)
OPS = st.lists(st.one_of(
    st.tuples(st.just("append"), FLOATS),
    st.tuples(st.just("extend"), st.lists(FLOATS, max_size=11)),
    st.tuples(st.just("extend array"), st.lists(FLOATS, max_size=11), st.sampled_from([1, 2])),  # (in place)
    st.tuples(st.just("frombytes"), st.lists(FLOATS, max_size=9)),
    st.tuples(st.just("set"), st.integers(-60, 60), FLOATS),
    st.tuples(st.just("cut"), st.integers(-60, 60)),
    st.tuples(st.just("slice"), st.integers(-70, 70), st.integers(-70, 70), st.sampled_from([1, 1, 2, 3, -1])),
    st.tuples(st.just("window"), st.integers(0, 70), st.integers(0, 70)),
), max_size=60)
SETTINGS = settings(max_examples=150, derandomize=True, deadline=None, suppress_health_check=[HealthCheck.too_slow])


@SETTINGS
@given(ops=OPS)
def test_every_operation_as_a_plain_array(ops):
    old = history.CHUNK, history.KEEP, history.CACHE, history.FIRST
    history.CHUNK, history.KEEP, history.CACHE, history.FIRST = 4, 1, 1, 1
    try:
        h, ref = History(), array("d")
        for op in ops:
            kind = op[0]
            if kind == "append":
                h.append(op[1])
                ref.append(op[1])
            elif kind == "extend":
                h.extend(op[1])
                ref.extend(op[1])
            elif kind == "extend array":  # an array of doubles (strided too): copied into the tail's room
                values = np.array(op[1], dtype=float)[::op[2]]
                h.extend(values)
                ref.extend(values.tolist())
            elif kind == "frombytes":
                data = np.array(op[1], dtype=float).tobytes()
                h.frombytes(data)
                ref.frombytes(data)
            elif kind == "set":
                if -len(ref) <= op[1] < len(ref):
                    h[op[1]] = op[2]
                    ref[op[1]] = op[2]
                else:
                    with pytest.raises(IndexError):
                        h[op[1]] = op[2]
            elif kind == "cut":
                del h[op[1]:]
                del ref[op[1]:]
            elif kind == "slice":
                s = slice(op[1], op[2], op[3])
                assert h[s].tobytes() == ref[s].tobytes()
            else:
                lo, hi = op[1], op[2]
                assert h.window(lo, hi).tobytes() == np.asarray(ref[lo:hi], dtype=float).tobytes()
            _same(h, ref)
        for i in (len(ref), -len(ref) - 1):
            with pytest.raises(IndexError):
                h[i]
    finally:
        history.CHUNK, history.KEEP, history.CACHE, history.FIRST = old


@SETTINGS
@given(steps=st.lists(st.one_of(st.just(0.0), st.floats(0.0, 10.0)), max_size=50),
       probes=st.lists(st.floats(-1.0, 300.0), max_size=8), cut=st.integers(0, 50))
def test_bisect_of_sorted_values_as_a_plain_array(steps, probes, cut):
    old = history.CHUNK, history.KEEP, history.CACHE
    history.CHUNK, history.KEEP, history.CACHE = 4, 1, 1
    try:
        ref = array("d", np.cumsum(steps).tolist())
        h = History(ref)
        for _ in range(2):  # whole, then cut (into a chunk in the file)
            values = [*probes, *ref[::3]]
            for x in values:
                for lo, hi in ((0, len(ref)), (len(ref) // 3, len(ref)), (1, max(len(ref) - 2, 1))):
                    if lo > hi:
                        continue
                    assert h.bisect_left(x, lo, hi) == bisect.bisect_left(ref, x, lo, hi)
                    assert h.bisect_right(x, lo, hi) == bisect.bisect_right(ref, x, lo, hi)
                    assert bisect.bisect_right(h, x, lo, hi) == bisect.bisect_right(ref, x, lo, hi)
                    for seq in (h, ref, ref.tolist()):  # the readers' helpers, on a history or not
                        assert trajectory.bisect_left(seq, x, lo, hi) == bisect.bisect_left(ref, x, lo, hi)
                        assert trajectory.bisect_right(seq, x, lo) == bisect.bisect_right(ref, x, lo)
                assert h.bisect_left(x, 5, 2) == bisect.bisect_left(ref, x, 5, 2)  # hi before lo
            del h[cut:]
            del ref[cut:]
    finally:
        history.CHUNK, history.KEEP, history.CACHE = old


def test_chunk_boundaries(tiny):
    h = History()
    ref = array("d")
    for k in range(1, 26):  # each length from one to beyond six chunks, one value at a time
        h.append(k * 0.5)
        ref.append(k * 0.5)
        _same(h, ref)
        assert h.tail_start == ((len(ref) - 1) // 4) * 4 and h.tail_len == len(ref) - h.tail_start
    # every window: inside one chunk a view, across chunks a copy, the same values
    for lo in range(len(ref) + 1):
        for hi in range(lo, len(ref) + 2):
            w = h.window(lo, hi)
            assert w.tolist() == ref[lo:hi].tolist()
            if w.size and lo // 4 == (hi - 1) // 4 and hi <= len(ref):
                assert not w.flags.owndata
    # chunks 0..4 full: the tail (6) and one kept (5) in memory, the rest in the file
    assert history.disk_bytes() >= 5 * 4 * 8 and os.fstat(h._file.fileno()).st_size == 5 * 4 * 8


def test_the_cut_across_chunk_boundaries_and_into_the_file(tiny):
    base = history.disk_bytes()
    values = [float(k) for k in range(40)]
    for at in (40, 39, 36, 33, 32, 31, 17, 16, 5, 4, 1, 0):
        h = History(values)
        ref = array("d", values)
        del h[at:]
        del ref[at:]
        _same(h, ref)
        assert history.disk_bytes() - base <= 4 * 8 * max((at + 3) // 4 - 1, 0)  # only chunks before the tail
        assert h._file is None or os.fstat(h._file.fileno()).st_size == h._held
        # growing again writes over the cut: the same as the array grown the same way
        more = [100.0 + k for k in range(13)]
        h.extend(more)
        ref.extend(more)
        h[at] = -1.0 if at < len(ref) else 0.0
        ref[at] = -1.0 if at < len(ref) else 0.0
        _same(h, ref)
        del h
    assert history.disk_bytes() == base  # a history gone gives back what its file held


def test_a_view_survives_the_growth_and_the_spill(tiny):
    h = History([1.0, 2.0, 3.0])
    w = h.window(0, 3)
    h.extend(range(4, 40))  # the viewed chunk full, then written to the file and dropped from memory
    assert h._chunks[0] is None and w.tolist() == [1.0, 2.0, 3.0]


def test_too_much_on_disk_ends_the_run(tiny, monkeypatch):
    monkeypatch.setattr(history, "DISK_LIMIT", history.disk_bytes() + 3 * 4 * 8)
    h = History()
    h.extend(range(20))  # five chunks: three written
    with pytest.raises(HistoryFull, match="temporary file") as e:
        h.extend(range(8))
    assert isinstance(e.value, MemoryError)
    assert h[:20].tolist() == [float(k) for k in range(20)]


def test_only_the_cut_at_the_end():
    h = History([1.0, 2.0, 3.0])
    for bad in (slice(0, 1), slice(0, None, 2), 1):
        with pytest.raises(TypeError):
            del h[bad]
    with pytest.raises(TypeError):
        h[0:1] = array("d", [5.0])
    with pytest.raises(TypeError):
        h["a"]
    del h[5:]
    assert h[:].tolist() == [1.0, 2.0, 3.0]


def test_a_run_with_tiny_chunks_writes_the_same_reports(monkeypatch):
    """The bundled pick-and-place for two minutes with its cell (collision checks) and the acceleration
    range, once with chunks of 16 breakpoints and the stretches of the range found 7 at a time (most of the profile read back from the file, replans
    cut across chunks) and once with the default chunks: the same JSON and page, byte for byte."""
    from val3check.config import Settings
    from val3check.lint import run
    from val3check.reporting.sim_render import render_sim
    from val3check.reporting.sim_report import build_report
    from val3check.robot import load_robot
    from val3check.rules.catalogue import catalogue
    from val3check.simulation import SimOptions, simulate
    from val3check.simulation.scenario import load_scenario

    root = Path(__file__).resolve().parents[2]
    app, scenario, cell = (root / "fixtures/valid/PickPlace", root / "fixtures/scenarios/pickplace.toml",
                           root / "tests/reporting/data/pickplace-cell.toml")
    monkeypatch.chdir(root)

    def reports():
        ws = run([str(app)], Settings()).workspace
        options = SimOptions(duration=120.0, robot=load_robot("tx2-60"), collisions=True, cell=str(cell),
                             cell_found="option", max_wall=900)
        result = simulate(ws, ws.apps[ws.targets[0]], options, load_scenario(str(scenario)))
        report = build_report(result, Settings(), catalogue(), "test")
        return render_sim("json", report), render_sim("html", report)

    fresh = reports()
    monkeypatch.setattr(history, "CHUNK", 16)
    monkeypatch.setattr(history, "KEEP", 1)
    monkeypatch.setattr(history, "CACHE", 2)
    monkeypatch.setattr(retime, "_BLOCK", 7)  # the acceleration range's stretches read in small blocks
    before = history.disk_bytes()
    spilled: list = []
    real = History._spill

    def spill(self, c):
        spilled.append(c)
        real(self, c)

    monkeypatch.setattr(History, "_spill", spill)
    tiny_chunks = reports()
    assert len(spilled) > 1000  # the run's profile mostly in the file
    assert tiny_chunks[0] == fresh[0]
    assert tiny_chunks[1] == fresh[1]
    gc.collect()
    assert history.disk_bytes() == before


def test_a_profile_refused_by_the_disk_bound_keeps_its_three_sequences_alike(tiny, monkeypatch):
    from val3check.motion.trajectory import Profile

    monkeypatch.setattr(history, "DISK_LIMIT", history.disk_bytes() + 2 * 3 * 4 * 8)
    p = Profile()
    with pytest.raises(HistoryFull):
        for k in range(20):
            p.append(p.t_end, np.array([p.s_end, p.s_end + 1.0, p.s_end + 2.0]), np.array([0.0, 1.0, 0.0]))
    assert len(p.T) == len(p.S) == len(p.SD) > 1


def test_a_run_near_the_disk_bound_ends_with_r006_not_a_traceback(monkeypatch, capsys, tmp_path):
    """A run whose profile would fill its temporary file ends between two lines with R006 (the
    budget check asks `history.over`), its report written; never `HistoryFull` inside a line (that
    would be the application's runtime error 40)."""
    import json

    from val3check.cli import main

    root = Path(__file__).resolve().parents[2]
    monkeypatch.chdir(root)
    monkeypatch.setattr(history, "DISK_LIMIT", history.disk_bytes() + (1 << 20))  # ~10 minutes of the cell
    out = tmp_path / "r.json"
    main(["sim", "fixtures/valid/PickPlace", "--robot", "tx2-60", "--scenario", "fixtures/scenarios/pickplace.toml",
          "--duration", "3600", "--max-wall", "900", "--report", "json", "-o", str(out)])
    findings = json.loads(out.read_text())["diagnostics"]
    said = [d for d in findings if d["code"] == "R006"]
    assert said and "temporary file" in said[0]["message"] and "DISK_LIMIT" in said[0]["message"]
    assert not any(d["code"] == "R040" or "runtime error 40" in d["message"] for d in findings)
    assert "Traceback" not in capsys.readouterr().err
