"""A motion record's seconds under each limit (motion_records.py): summed per limit in the order of
the intervals, for a command evaluated (`_seconds`), a repeat (`_seconds_of`: the earlier command's
intervals and limits, its own durations) or a block of repeats in one pass (`seconds_many`: the
same arithmetic, the same bits; tests/motion/test_record_seconds.py).
"""

from __future__ import annotations

import numpy as np


def _seconds(rows, codes: np.ndarray, n: int) -> dict:
    """Seconds under each limit: each interval's duration × its share, summed per limit in the order
    of the intervals (as a running sum would: bincount adds in that order)."""
    dt, frac = rows[3], rows[4]
    if not len(codes):
        return {}
    total = np.bincount(codes, weights=dt * frac)
    first = np.unique(codes, return_index=True)[1]
    return {_label(int(codes[k]), n): float(total[codes[k]]) for k in np.sort(first)}


_ORDERS: dict = {}  # (codes' bytes, n) -> `_order` (a function of them only; a cyclic cell has a few)


def _order(codes: np.ndarray, n: int) -> tuple[list, np.ndarray]:
    """The limits of `codes` as `_seconds` lists them (in order of first appearance, labelled) and
    each interval's place in that list (a dict: a command has a few dozen intervals). Read only."""
    key = (codes.astype(np.intp, copy=False).tobytes(), n)
    hit = _ORDERS.get(key)
    if hit is None:
        place: dict = {}
        rank = np.array([place.setdefault(c, len(place)) for c in codes.tolist()], dtype=np.intp)
        rank.flags.writeable = False
        hit = ([_label(c, n) for c in place], rank)
        if len(_ORDERS) >= 4096:
            _ORDERS.clear()
        _ORDERS[key] = hit
    return hit


def _seconds_of(S, lo: int, s0: float, s1: float, i: np.ndarray, order: tuple, dt: np.ndarray) -> dict:
    """`_seconds(_intervals(...), codes, n)` of a repeat whose intervals `i` (from S[lo]: the
    profile's positions, or a window of them) and limits (`order` of the codes) are the earlier
    command's, `dt` its durations: the same arithmetic. Only the first and last intervals can lie
    partly outside (s0, s1): the share of any other, (b - a) / (b - a), is exactly 1."""
    labels, rank = order
    if not labels:
        return {}
    w = dt[i]
    last = len(i) - 1
    for e in (0, last) if last else (0,):
        k = int(i[e])
        a, b = S[lo + k], S[lo + k + 1]
        w[e] = float(dt[k]) * min(max((min(b, s1) - max(a, s0)) / (b - a), 0.0), 1.0)
    return dict(zip(labels, np.bincount(rank, weights=w).tolist()))


def _label(code: int, n: int) -> str:
    """The name of a limit code (`_limits_on`) of an arm of n axes."""
    if code < 2 * n:
        return f"j{code // 2 + 1} {'accel' if code % 2 == 0 else 'decel'}"
    k = code - 2 * n
    return f"j{k + 1} speed" if k < n else ("tvel" if k == n else "rvel")


def seconds_many(S: np.ndarray, rows: list) -> list[dict]:
    """`_seconds_of(S, lo, s0, s1, i, order, dt)` of each row (lo, s0, s1, i, order, dt), S an
    array: the rows' weights gathered, their edges shared and summed in one pass (one `bincount`,
    each row's limits its own bins: each bin adds its row's weights in their order, as alone)."""
    out: list = [None] * len(rows)
    idx, ranks, dts, at, ends, made = [], [], [], [], [], []
    for n, (lo, s0, s1, i, order, dt) in enumerate(rows):
        if not order[0]:
            out[n] = {}  # (each record its own)
        else:
            idx.append(i)
            ranks.append(order[1])
            dts.append(dt)
            at.append(lo)
            ends.append((s0, s1))
            made.append(n)
    if not made:
        return out
    lens = np.array([len(i) for i in idx])
    k = np.concatenate(idx)
    dt_all = np.concatenate(dts)
    dt_at = np.repeat(np.cumsum([len(d) for d in dts]) - np.array([len(d) for d in dts]), lens)
    w = dt_all[k + dt_at]
    # only the first and last intervals can lie partly outside (s0, s1) (`_seconds_of`)
    last = np.cumsum(lens) - 1
    first = last - (lens - 1)
    s0, s1 = np.array(ends).T
    lo = np.array(at)
    for e in (first, last):
        ke = k[e]
        a, b = S[lo + ke], S[lo + ke + 1]
        w[e] = dt_all[ke + dt_at[e]] * np.minimum(np.maximum((np.minimum(b, s1) - np.maximum(a, s0)) / (b - a), 0.0),
                                                   1.0)
    nlab = [len(rows[n][4][0]) for n in made]  # (each row's ranks cover its labels: `_order`)
    base = np.cumsum(nlab) - np.array(nlab)
    total = np.bincount(np.concatenate(ranks) + np.repeat(base, lens), weights=w).tolist()
    for n, (labels, _), b, m in zip(made, (rows[n][4] for n in made), base.tolist(), nlab):
        out[n] = dict(zip(labels, total[b:b + m]))
    return out
