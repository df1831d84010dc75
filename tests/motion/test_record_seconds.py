"""A block of repeats' seconds under each limit in one pass (record_seconds.seconds_many): the same
bits as `_seconds_of` one repeat at a time."""

from __future__ import annotations

import numpy as np

from val3check.motion.record_seconds import _order, _seconds_of, seconds_many


def _rows(rng, count: int, S: np.ndarray) -> list:
    """Random repeats over the positions S: their intervals, limits, durations and ends, some with
    one interval, some with none, ends inside, on and outside their first and last intervals."""
    rows = []
    for _ in range(count):
        n = int(rng.integers(2, 40))  # breakpoints the repeat reads
        lo = int(rng.integers(0, len(S) - n))
        dt = rng.random(n - 1) * rng.choice([1e-3, 1.0, 30.0])
        dt[rng.random(n - 1) < 0.1] = 0.0
        kind = rng.integers(0, 4)
        if kind == 0:
            i = np.zeros(0, dtype=np.intp)
        elif kind == 1:
            i = np.array([int(rng.integers(0, n - 1))], dtype=np.intp)
        else:
            i = np.sort(rng.choice(n - 1, size=int(rng.integers(2, n)) if n > 2 else 1, replace=False)).astype(np.intp)
        i = i[S[lo + i + 1] > S[lo + i]]  # (the intervals that count move: `_intervals`)
        codes = rng.integers(0, 14, size=len(i))
        order = _order(codes, 6)
        a, b = S[lo + int(i[0])] if len(i) else S[lo], S[lo + int(i[-1]) + 1] if len(i) else S[lo + 1]
        edge = rng.integers(0, 4)
        span = b - a
        s0 = (a, a - span, a + 0.3 * span, a + span)[edge]
        s1 = (b, b + span, b - 0.4 * span, a)[rng.integers(0, 4)]
        rows.append((lo, float(s0), float(s1), i, order, dt))
    return rows


def test_seconds_many_is_seconds_of_each_bit_for_bit():
    rng = np.random.default_rng(29)
    for scale in (1.0, 1e4, 1e7):
        S = np.cumsum(rng.random(400) * scale)
        S[50:53] = S[50]  # a rest repeats a position (its intervals never count)
        rows = _rows(rng, 300, S)
        many = seconds_many(S, rows)
        S_list = S.tolist()
        for row, got in zip(rows, many, strict=True):
            lo, s0, s1, i, order, dt = row
            want = _seconds_of(S_list, lo, s0, s1, i, order, dt.copy())
            assert list(got) == list(want)  # the same limits, in the same order
            assert [v.hex() for v in got.values()] == [v.hex() for v in want.values()]
        empty = [id(d) for d in many if not d]
        assert empty and len(set(empty)) == len(empty)  # each record its own dict, as `_seconds_of` makes
    assert seconds_many(S, []) == []


def test_seconds_many_keeps_each_row_to_its_own_durations():
    """Each row's seconds change with its own durations and ends only."""
    rng = np.random.default_rng(3)
    S = np.cumsum(rng.random(200))
    rows = [r for r in _rows(rng, 40, S) if r[4][0] and len(r[3]) > 2]
    base = seconds_many(S, rows)
    for n in (0, len(rows) // 2, len(rows) - 1):
        lo, s0, s1, i, order, dt = rows[n]
        dt2 = dt.copy()
        dt2[i[1]] += 1.0
        changed = seconds_many(S, rows[:n] + [(lo, s0, s1, i, order, dt2)] + rows[n + 1:])
        assert changed[n] != base[n]
        assert changed[:n] + changed[n + 1:] == base[:n] + base[n + 1:]
