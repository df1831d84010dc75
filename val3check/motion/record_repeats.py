"""The motion records of commands that repeat an earlier one (issue 29): a cyclic program goes over
the same spans of the same geometries again and again, with the same tool, the same limits and the
same timing relative to its start. Such a command takes the earlier one's TCP length, peak speed
and the limit each of its intervals is on (motion_records.py); its seconds under each limit are
summed from its own durations.

The key is what `motion_records` reads for a command over [s0, s1]: exactly, the spans of path its
evaluation reaches (geometry object, part), its tool and limits, the number of profile breakpoints
and how each of them, s0 and s1 fall against the others and the spans' offsets (which span a point
is evaluated on, which intervals count); then, within tolerances, the breakpoints' positions and
the spans' offsets relative to s0, the durations of the intervals that count and the path speeds.
A repeated motion's global positions and times differ from the earlier one's in their last bits
(sums over the whole run): the tolerances are a few hundred times that rounding. An interval whose
limit was a near tie (closer than the tolerances can move it: motion_records._limits_on) is decided
again on each repetition's own path, so that a reused record differs from a fresh one only in its
length and peak, by that rounding (docs/performance.md, "The run's record").

The keys of a block of commands are made together (`find_block`: a few numpy passes over the
block's part of the profile, every command's compared values in one flat array); the look-ups
stay in order and give what `inputs` and `find`, one command at a time, give.
"""

from __future__ import annotations

import bisect

import numpy as np

from .trajectory import window

POS_TOL = 1e-13  # × the magnitude of the run's path positions (their rounding: ~1e-16 per operation)
TIME_TOL = 1e-13  # × the magnitude of the run's times
SPEED_TOL = 1e-10  # × the largest path speed of the command (the timing's own rounding reaches 1e-11)
KEPT = 8  # distinct timings kept per piece of path (a cyclic program has one or two)


class Repeats:
    """The commands already met, by what determines their figures (module docstring)."""

    def __init__(self, path, prof) -> None:
        """Nothing met yet, on `path` (paths.Path) timed by `prof` (trajectory.Profile)."""
        self.path, self.prof = path, prof
        self.seen: dict = {}  # exact part -> [(compared part, the commands that repeat it)]
        self._limits: dict = {}  # id(Limits) -> (Limits, its key)
        self.hits = 0

    def inputs(self, tool, lim, s0: float, s1: float, lo: int, k1: int) -> tuple:
        """(exact part, compared part, tolerances, durations) of the command over [s0, s1] whose
        breakpoints are lo..k1 (what motion_records reads of the profile); the durations of its
        intervals that count (0 for the others) are those a repeat's seconds are summed from."""
        prof, path = self.prof, self.path
        hi = min(k1, len(prof.S) - 1)
        # views of the profile, not copies (none is returned: the profile may grow after)
        S, T, SD = window(prof.S, lo, hi + 1), window(prof.T, lo, hi + 1), window(prof.SD, lo, hi + 1)
        i0 = path.locate(min(S[0], s0))[0]
        i1 = path.locate(max(S[-1], s1))[0]
        offsets = path.offsets[i0:i1 + 1]
        offs = np.asarray(offsets)
        held = self._limits.get(id(lim))
        if held is None or held[0] is not lim:
            held = self._limits[id(lim)] = (lim, (lim.V.tobytes(), lim.A.tobytes(), lim.D.tobytes(), lim.tvel, lim.rvel))
        # how the breakpoints, s0 and s1 fall against each other (which intervals count, which
        # breakpoints are points of the length) and against the spans' offsets (the span each
        # point is evaluated on: the one at or before it); searches in the window equal the
        # profile's clamped to it (its positions are sorted)
        left0, left1 = S.searchsorted((s0, s1)).tolist()
        right0, right1 = S.searchsorted((s0, s1), "right").tolist()
        where = (left0, right0, left1, right1, bisect.bisect_right(offsets, s0), bisect.bisect_right(offsets, s1))
        moves = S[1:] > S[:-1]  # (S[k + 1] - S[k] > 0: a difference of floats is 0 only when equal)
        exact = (tuple((id(sp.geom), sp.a, sp.b) for sp in path.spans[i0:i1 + 1]),
                 None if tool is None else np.asarray(tool, dtype=float).tobytes(), held[1], len(S), where,
                 moves.tobytes(), offs.searchsorted(S, "right").tobytes())
        # the durations of the intervals that count only (a rest before the command, waiting for
        # the program, is as long as it is): those moving, after the last breakpoint at or before
        # s0 (S[k + 1] > s0) and before the first at or past s1 (S[k] < s1)
        dt = np.where(moves, T[1:] - T[:-1], 0.0)
        dt[:max(right0 - 1, 0)] = 0.0
        dt[left1:] = 0.0
        n = len(S)
        got = np.concatenate((S, offs, (s1,), dt, SD))
        got[:n + len(offs) + 1] -= s0
        tol = np.array((POS_TOL * max(1.0, abs(S[-1]), abs(s1)), TIME_TOL * max(1.0, abs(T[-1])),
                        SPEED_TOL * max(1.0, float(SD.max()))))[_pattern(n, len(offs))]
        return exact, got, tol, dt

    def find(self, inputs) -> tuple[Slot | None, Slot | None]:
        """(the Slot of an earlier command with these inputs, None), or (None, a new Slot) when
        none has them: the first command with them is computed and its figures kept in its Slot."""
        exact, got, tol = inputs[:3]
        kept = self.seen.setdefault(exact, [])
        for earlier, slot in kept:
            if (abs(got - earlier) <= tol).all():
                self.hits += 1
                return slot, None
        slot = Slot()
        if len(kept) < KEPT:
            kept.append((got, slot))
        return None, slot


    def find_block(self, asks: list) -> list:
        """`find(inputs(tool, lim, s0, s1, lo, k1))` of each ask (tool, lim, s0, s1, lo, hi, i0, i1:
        hi = min(k1, breakpoints - 1) and i0, i1 its first and last span, as when it was added) in
        turn: [(earlier Slot, new Slot, durations)]. The same keys, compared values and answers,
        made for the whole block in a few numpy passes over its part of the profile (the keys of a
        block are made together; the look-ups stay in order)."""
        prof, offsets = self.prof, self.path.offsets
        lo_b, hi_b = min(a[4] for a in asks), max(a[5] for a in asks)
        S, T, SD = (window(v, lo_b, hi_b + 1) for v in (prof.S, prof.T, prof.SD))
        # (only the values read: the window holds some 70 breakpoints per command)
        s_hi = S[[a[5] - lo_b for a in asks]].tolist()
        ib0, ib1 = min(a[6] for a in asks), max(a[7] for a in asks)
        for a, s in zip(asks, s_hi):
            i1 = a[7]
            if i1 + 1 < len(offsets) and offsets[i1 + 1] <= max(s, a[3]):
                # a span appended since at the command's end: the key made then (`inputs`) differs
                return [self._one(a) for a in asks]
        offs = np.asarray(offsets[ib0:ib1 + 1])
        moves = S[1:] > S[:-1]
        moved = moves.tobytes()
        dt_all = np.where(moves, T[1:] - T[:-1], 0.0)
        g = _at_or_before(offs, S)  # + ib0: offsets at or before each breakpoint
        steps = (g[1:] - g[:-1]).tobytes()
        tools, lims, s0, s1, lo, hi, i0, i1 = zip(*asks)
        s0, s1 = np.array(s0, dtype=float), np.array(s1, dtype=float)
        lo, hi, i0, i1 = (np.array(v, dtype=np.intp) for v in (lo, hi, i0, i1))
        n, m, k = hi - lo + 1, i1 - i0 + 1, lo - lo_b
        g_at = g[k].tolist()  # at each ask's first breakpoint
        # the searches in the window: the block's clamped to it (`inputs`); where s0 and s1 fall
        # among the spans' offsets: the block's offsets hold them (the spans hold the window)
        left0, right0 = np.clip(S.searchsorted(s0, "left") - k, 0, n), np.clip(S.searchsorted(s0, "right") - k, 0, n)
        left1, right1 = np.clip(S.searchsorted(s1, "left") - k, 0, n), np.clip(S.searchsorted(s1, "right") - k, 0, n)
        o0 = np.clip(offs.searchsorted(s0, "right") + (ib0 - i0), 0, m)
        o1 = np.clip(offs.searchsorted(s1, "right") + (ib0 - i0), 0, m)
        b = len(asks)
        keys = []
        # each span's part of the exact key, made once for the block (neighbouring commands share spans)
        parts = [(id(sp.geom), sp.a, sp.b) for sp in self.path.spans[ib0:ib1 + 1]]
        for tool, lim, i0_, i1_, n_, k_, g0, where in zip(tools, lims, i0.tolist(), i1.tolist(), n.tolist(), k.tolist(),
                                                         g_at, zip(*(v.tolist() for v in (left0, right0, left1, right1,
                                                                                          o0, o1)))):
            held = self._limits.get(id(lim))
            if held is None or held[0] is not lim:
                held = self._limits[id(lim)] = (lim, (lim.V.tobytes(), lim.A.tobytes(), lim.D.tobytes(), lim.tvel,
                                                      lim.rvel))
            # the span each breakpoint falls on, from i0 (`inputs`: offs.searchsorted(S, "right")):
            # its first and its steps (it never leaves 0..m: the spans hold the window)
            keys.append((tuple(parts[i0_ - ib0:i1_ + 1 - ib0]),
                         None if tool is None else np.asarray(tool, dtype=float).tobytes(), held[1], n_, where,
                         moved[k_:k_ + n_ - 1], (g0 + ib0 - i0_, steps[8 * k_:8 * (k_ + n_ - 1)])))
        j0, low = i0 - ib0, np.maximum(right0 - 1, 0)
        mag_s = np.maximum(np.maximum(1.0, np.abs(S[k + n - 1])), np.abs(s1))
        mag_t = np.maximum(1.0, np.abs(T[k + n - 1]))
        # every ask's compared values (`inputs`: S - s0, offsets - s0, s1 - s0, durations, SD) one
        # after the other in one flat array: five ranges of one source array per ask
        ns, no = len(S), len(offs)
        src = np.concatenate((S, offs, s1, dt_all, SD))
        ar = np.arange(b)
        starts = np.column_stack((k, ns + j0, ns + no + ar, ns + no + b + k, ns + no + b + ns - 1 + k)).ravel()
        lens = np.column_stack((n, m, np.ones(b, dtype=n.dtype), n - 1, n)).ravel()
        first = np.cumsum(lens) - lens  # where each range begins
        each = np.arange(int(lens.sum()))
        zero = np.zeros(b)
        got = src[np.repeat(starts - first, lens) + each] - np.repeat(np.column_stack((s0, s0, s0, zero, zero)).ravel(),
                                                                      lens)
        # the durations of the intervals that do not count: 0 (found among the durations only)
        nd = n - 1
        d_first = np.cumsum(nd) - nd
        d_local = np.arange(int(nd.sum())) - np.repeat(d_first, nd)
        out = (d_local < np.repeat(low, nd)) | (d_local >= np.repeat(left1, nd))
        got[(np.repeat(first[3::5], nd) + d_local)[out]] = 0.0
        sd_max = np.maximum.reduceat(got, first)[4::5]
        tol = np.repeat(np.column_stack((POS_TOL * mag_s, POS_TOL * mag_s, POS_TOL * mag_s, TIME_TOL * mag_t,
                                         SPEED_TOL * np.maximum(1.0, sd_max))).ravel(), lens)
        return self._look_up(keys, got, tol, first[::5].tolist(), (3 * n + m).tolist(), first[3::5].tolist(),
                             (n - 1).tolist())

    def _look_up(self, keys: list, got, tol, at: list, size: list, dt_at: list, dt_size: list) -> list:
        """`find` of each ask of a block in turn, its compared values and tolerances got[at:at + size],
        tol[...] (the durations at dt_at): compared with the commands kept before the block in one
        pass per place in their lists, then, in order, with those the block adds."""
        b = len(keys)
        kept = [self.seen.setdefault(key, []) for key in keys]
        before = [len(x) for x in kept]
        match = [-1] * b
        at_arr = np.array(at)
        for c in range(max(before, default=0)):
            ask = [r for r in range(b) if match[r] < 0 and before[r] > c]
            if not ask:
                break
            earlier = np.concatenate([kept[r][c][0] if before[r] > c and match[r] < 0 else got[at[r]:at[r] + size[r]]
                                      for r in range(b)])
            same = np.logical_and.reduceat(np.abs(got - earlier) <= tol, at_arr).tolist()
            for r in ask:
                if same[r]:
                    match[r] = c
        out: list = []
        for r in range(b):
            dt = got[dt_at[r]:dt_at[r] + dt_size[r]]
            c = match[r]
            if c >= 0:
                self.hits += 1
                out.append((kept[r][c][1], None, dt))
                continue
            mine, bound = got[at[r]:at[r] + size[r]], tol[at[r]:at[r] + size[r]]
            for earlier, slot in kept[r][before[r]:]:  # (kept by this block)
                if (abs(mine - earlier) <= bound).all():
                    self.hits += 1
                    out.append((slot, None, dt))
                    break
            else:
                slot = Slot()
                out.append((None, slot, dt))
                if len(kept[r]) < KEPT:
                    kept[r].append((mine.copy(), slot))
        return out

    def _one(self, ask: tuple) -> tuple:
        """`find_block` of one ask, alone (`inputs`, `find`)."""
        tool, lim, s0, s1, lo, hi, _, _ = ask
        inputs = self.inputs(tool, lim, s0, s1, lo, hi)
        earlier, slot = self.find(inputs)
        return earlier, slot, inputs[3]


def _at_or_before(offs: np.ndarray, S: np.ndarray) -> np.ndarray:
    """offs.searchsorted(S, "right") for sorted S (a window of the profile's positions, some 70 per
    command, against a few offsets per command): where each offset falls among the positions,
    counted (S[k] >= offs[j] exactly when k >= the number of positions below offs[j])."""
    return np.cumsum(np.bincount(S.searchsorted(offs, "left"), minlength=len(S) + 1)[:len(S)])


_PATTERNS: dict = {}  # (breakpoints, offsets) -> which tolerance each compared value takes


def _pattern(n: int, m: int) -> np.ndarray:
    """The index into (positions, times, speeds) of each value `Repeats.inputs` compares."""
    p = _PATTERNS.get((n, m))
    if p is None:
        p = _PATTERNS[(n, m)] = np.repeat(np.arange(3), [n + m + 1, n - 1, n])
    return p


class Slot:
    """The figures of the first command with some inputs (`figures`, None until computed), where
    they were computed (`place`), and the repeats met before that (`items`, then emptied)."""

    __slots__ = ("figures", "items", "place")

    def __init__(self) -> None:
        """Not computed yet, no repeat waiting."""
        self.figures: tuple | None = None
        self.place: tuple = ()
        self.items: list = []


def noise(prof, lo: int, k1: int, s_max: float, SD=None, base: int = 0) -> tuple[float, float]:
    """(positions, path speeds): how far a repetition's inputs may lie from these (`Repeats`).
    `SD`: the profile's path speeds from breakpoint `base` (a window of them, as a list or an
    array), else its own."""
    hi = min(k1, len(prof.S) - 1)
    SD = prof.SD if SD is None else SD
    seg = SD[lo - base:hi + 1 - base]
    return POS_TOL * max(1.0, abs(s_max)), SPEED_TOL * max(1.0, float(seg.max()) if seg.__class__ is np.ndarray
                                                              else max(seg))
