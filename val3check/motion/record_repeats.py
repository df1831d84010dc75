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
