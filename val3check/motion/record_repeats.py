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
        s_at = S.tolist()
        ib0, ib1 = min(a[6] for a in asks), max(a[7] for a in asks)
        for a in asks:
            i1 = a[7]
            if i1 + 1 < len(offsets) and offsets[i1 + 1] <= max(s_at[a[5] - lo_b], a[3]):
                # a span appended since at the command's end: the key made then (`inputs`) differs
                return [self._one(a) for a in asks]
        offs = np.asarray(offsets[ib0:ib1 + 1])
        moves = S[1:] > S[:-1]
        moved = moves.tobytes()
        dt_all = np.where(moves, T[1:] - T[:-1], 0.0)
        g = offs.searchsorted(S, "right")  # + ib0: offsets at or before each breakpoint
        g_at = g.tolist()
        steps = (g[1:] - g[:-1]).tobytes()
        ends = np.array([a[2] for a in asks] + [a[3] for a in asks])
        left, right = (S.searchsorted(ends, side).tolist() for side in ("left", "right"))
        b = len(asks)
        groups: dict = {}  # exact part -> [row of each ask]
        rows = []
        for r, (tool, lim, s0, s1, lo, hi, i0, i1) in enumerate(asks):
            held = self._limits.get(id(lim))
            if held is None or held[0] is not lim:
                held = self._limits[id(lim)] = (lim, (lim.V.tobytes(), lim.A.tobytes(), lim.D.tobytes(), lim.tvel,
                                                      lim.rvel))
            n, m, k = hi - lo + 1, i1 - i0 + 1, lo - lo_b
            # the searches in the window: the block's clamped to it (`inputs`)
            left0, right0 = min(max(left[r] - k, 0), n), min(max(right[r] - k, 0), n)
            left1, right1 = min(max(left[b + r] - k, 0), n), min(max(right[b + r] - k, 0), n)
            where = (left0, right0, left1, right1, min(max(bisect.bisect_right(offsets, s0) - i0, 0), m),
                     min(max(bisect.bisect_right(offsets, s1) - i0, 0), m))
            # the span each breakpoint falls on, from i0 (`inputs`: offs.searchsorted(S, "right")):
            # its first and its steps (it never leaves 0..m: the spans hold the window)
            exact = (tuple((id(sp.geom), sp.a, sp.b) for sp in self.path.spans[i0:i1 + 1]),
                     None if tool is None else np.asarray(tool, dtype=float).tobytes(), held[1], n, where,
                     moved[k:k + n - 1], (g_at[k] + ib0 - i0, steps[8 * k:8 * (k + n - 1)]))
            groups.setdefault(exact, []).append(r)
            rows.append((k, n, m, i0 - ib0, s0, s1, max(1.0, abs(s_at[k + n - 1]), abs(s1)),
                         max(1.0, abs(T[k + n - 1])), right0, left1))
        out: list = [None] * b
        for exact, members in groups.items():
            self._find_group(exact, members, rows, S, SD, offs, dt_all, out)
        return out

    def _find_group(self, exact, members: list, rows: list, S, SD, offs, dt_all, out: list) -> None:
        """`find_block` of the asks with one exact part (`members`, in order): their compared values
        as rows of one matrix, compared with each earlier command kept in one pass."""
        k, n, m, j0, s0, s1, mag_s, mag_t, right0, left1 = (np.array(c) for c in zip(*(rows[r] for r in members)))
        n, m = int(n[0]), int(m[0])
        at = k[:, None] + np.arange(n)
        pos, sd = S[at] - s0[:, None], SD[at]
        cols = np.arange(n - 1)
        dt = dt_all[at[:, :-1]]
        dt[(cols < np.maximum(right0 - 1, 0)[:, None]) | (cols >= left1[:, None])] = 0.0
        got = np.hstack((pos, offs[j0[:, None] + np.arange(m)] - s0[:, None], (s1 - s0)[:, None], dt, sd))
        tol = np.column_stack((POS_TOL * mag_s, TIME_TOL * mag_t, SPEED_TOL * np.maximum(1.0, sd.max(axis=1))))
        tol = tol[:, _pattern(n, m)]
        kept = self.seen.setdefault(exact, [])
        match = [(np.abs(got - earlier) <= tol).all(axis=1).tolist() for earlier, _ in kept]
        slots = [slot for _, slot in kept]
        for x, r in enumerate(members):
            for e, hit in enumerate(match):
                if hit[x]:
                    self.hits += 1
                    out[r] = (slots[e], None, dt[x])
                    break
            else:
                slot = Slot()
                out[r] = (None, slot, dt[x])
                if len(kept) < KEPT:
                    kept.append((got[x].copy(), slot))
                    slots.append(slot)
                    match.append([False] * (x + 1) + (np.abs(got[x + 1:] - got[x]) <= tol[x + 1:]).all(axis=1).tolist())

    def _one(self, ask: tuple) -> tuple:
        """`find_block` of one ask, alone (`inputs`, `find`)."""
        tool, lim, s0, s1, lo, hi, _, _ = ask
        inputs = self.inputs(tool, lim, s0, s1, lo, hi)
        earlier, slot = self.find(inputs)
        return earlier, slot, inputs[3]


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


def noise(prof, lo: int, k1: int, s_max: float) -> tuple[float, float]:
    """(positions, path speeds): how far a repetition's inputs may lie from these (`Repeats`)."""
    hi = min(k1, len(prof.S) - 1)
    return POS_TOL * max(1.0, abs(s_max)), SPEED_TOL * max(1.0, max(prof.SD[lo:hi + 1]))
