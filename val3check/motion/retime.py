"""The run's motions re-timed with every acceleration and deceleration scaled (issue 23): what the
cycle time would be if the accelerations the model assumes were off by that factor.

Stäubli publishes no joint accelerations: where the model assumes them (RobotModel.accelerations_
assumed), the reports give the cycle time with the range it takes for accelerations half and twice
the assumption (robot.models.ASSUMED_ACCELERATION_RANGE). The same geometric path is timed again,
piece by piece between the arm's stops, with the scaled limits; the arm's rests keep their
length (the program waits as long for its inputs, grippers and delays); every time of the run
moves with the motions before it. The motion records of the re-timed run are the run's with their
start and end moved, so that the cycles are found exactly as in the run (cycle.cycle_stats).

A cyclic program stops at the same places of the same motions again and again: a piece is timed
once per distinct piece (`piece_key`: the same parts of the same geometries with the same tools,
owners and limits), and the re-timing stops when `out_of_time()` says the run's wall-clock budget
is spent (the range then covers the run up to `Retiming.cut`, simulation/collect.py says so).
The records' places and their re-timed times are found a block at a time (`Stretches.places`,
`Retiming.times_at`), with the arithmetic of `place` and `time_at`.

    records_if = retimed(queue, records, 2.0)    # MotionRecords of the run with accelerations × 2
"""

from __future__ import annotations

import bisect
from dataclasses import fields, replace
from operator import attrgetter

import numpy as np

from .mdesc import Limits
from .trajectory import Profile, bisect_right, window


def piece_key(path, a: float, b: float, limits, memo: dict | None = None) -> tuple | None:
    """What determines the timing of the piece [a, b] of `path` (paths.Path) from rest to rest,
    up to its position on the path: per span touched, its geometry (the same object for a repeated
    motion, construction.py), its part, tool, junction and owners with their limits, and where a
    and b fall in the first and last. None when the path has no span there. `memo`: the owners'
    limits keys already made for this `limits` (a command's limits never change once queued)."""
    i0, _ = path.locate(a)
    if i0 < 0:
        return None
    if memo is None:
        memo = {}
    rounded = memo.get(_ROUNDED)
    if rounded is None:
        rounded = memo[_ROUNDED] = {}
    parts: list = [_round9(rounded, b - a)]
    i = i0
    spans, offsets = path.spans, path.offsets
    while i < len(spans):
        off = offsets[i]
        if off > b + 1e-12:
            break
        sp = spans[i]
        lo, hi = max(a - off, 0.0), min(b - off, (sp.b - sp.a) * sp.geom.ell)  # (Span.length)
        if hi < lo - 1e-12:
            break
        owners = tuple([(_round9(rounded, k_start), memo.get(key) or _owner_limits(memo, limits, key))
                        for key, k_start in sp.owners])
        tool = None if sp.tool is None else sp.tool.tobytes()
        # positions in the span to 1e-9 path units (1e-9 degrees of joint motion): the same stop of a
        # repeated motion lies at another global position, found by sums that differ in the last bits
        parts.append((id(sp.geom), sp.a, sp.b, tool, sp.smooth, owners, _round9(rounded, lo), _round9(rounded, hi)))
        i += 1
    return tuple(parts)


_ROUNDED = ("rounded",)  # piece_key's memo: round(x, 9) of the numbers already rounded


def _round9(rounded: dict, x: float) -> float:
    """round(x, 9), kept in `rounded` by x (a cyclic run's spans repeat their lengths and owners'
    starts; round is slow). -0.0 may read 0.0's: equal in a key, and with the same hash."""
    r = rounded.get(x)
    if r is None:
        r = rounded[x] = round(x, 9)
    return r


def _owner_limits(memo: dict, limits, key) -> tuple:
    """The limits key of the command `key` (`piece_key`), kept in `memo` by command and by Limits
    object (the queue shares one per distinct mdesc: mdesc.CommandLimits)."""
    lim = limits(key)
    held = memo.get(("limits", id(lim)))
    if held is None or held[0] is not lim:
        held = memo[("limits", id(lim))] = (lim, _limits_key(lim))
    memo[key] = held[1]
    return held[1]


def _limits_key(lim: Limits) -> tuple:
    """A command's limits as a key (mdesc.Limits: arrays and two numbers)."""
    return (lim.V.tobytes(), lim.A.tobytes(), lim.D.tobytes(), lim.tvel, lim.rvel)


def _next_true(mask: np.ndarray, i: int) -> int:
    """The first index k >= i where `mask` is true, -1 when none: a window at a time (the next leave
    is usually the breakpoint itself or the next)."""
    w = 8
    while i < len(mask):
        part = mask[i:i + w]
        k = int(part.argmax())
        if part[k]:
            return i + k
        i += w
        w = min(w * 8, 1 << 16)
    return -1


_BLOCK = 1 << 16  # breakpoints read at a time by `Stretches`
_PLACES = 1024  # times placed at a time by `Stretches.places` (their window of the profile: a few MB at most)


class Stretches:
    """The moving stretches of `queue`'s profile (from a rest to the next) and their piece keys:
    the same for every factor, found once for all of them (`retimed_range`)."""

    def __init__(self, queue) -> None:
        planner = queue.planner
        planner.flush()
        prof = planner.profile
        self.queue = queue
        self.profile = prof
        self.spans: list[tuple] = []  # (i, j, piece_key) per stretch: profile indices of its ends
        memo: dict = {}
        keys: dict = {}  # one object per distinct key (a cyclic run repeats a few thousand times)
        T, S, SD = prof.T, prof.S, prof.SD
        n = len(T)
        # a stretch starts at a breakpoint the arm leaves (moves or goes forward after it) and ends
        # at the next breakpoint at rest (or the last). A block of the profile at a time (8 hours
        # hold millions of breakpoints, most in a file: history.py); a mask of one byte per
        # breakpoint for the leaves, an index array for the rests (a few per motion)
        leaves = np.empty(max(n - 1, 0), dtype=bool)
        rests_in: list = []
        for lo in range(0, n - 1, _BLOCK):
            hi = min(lo + _BLOCK, n - 1)  # breakpoints lo..hi: the leaves lo..hi-1, the rests lo+1..hi
            s_, sd_ = window(S, lo, hi + 1), window(SD, lo, hi + 1)
            leaves[lo:hi] = ~((sd_[1:] <= 0.0) & (s_[1:] <= s_[:-1]))
            rests_in.append(np.flatnonzero(~(sd_[1:min(hi, n - 2) - lo + 1] > 0.0)) + lo + 1)
            del s_, sd_
        rests = np.append(np.concatenate(rests_in) if rests_in else np.zeros(0, dtype=np.intp), n - 1)
        ends: list = []  # (i, j) per stretch
        i = 0
        while True:
            i = _next_true(leaves, i)
            if i < 0:
                break
            j = int(rests[rests.searchsorted(i, "right")])
            ends.append((i, j))
            i = j
        # each stretch's ends read once, a block of the profile at a time (a History reads old
        # values one by one through its chunk cache), for the keys, `place` and every factor
        at = np.array(ends, dtype=np.intp).reshape(-1, 2).ravel()
        t_at, s_at = np.empty(len(at)), np.empty(len(at))
        for lo in range(0, n, _BLOCK):
            r0, r1 = at.searchsorted((lo, lo + _BLOCK)).tolist()  # (the ends are in order)
            if r1 > r0:
                t_at[r0:r1] = window(T, lo, lo + _BLOCK)[at[r0:r1] - lo]
                s_at[r0:r1] = window(S, lo, lo + _BLOCK)[at[r0:r1] - lo]
        self.starts, self.ends = t_at[0::2].tolist(), t_at[1::2].tolist()
        self.s_starts, self.s_ends = s_at[0::2].tolist(), s_at[1::2].tolist()
        for (i, j), a, b in zip(ends, self.s_starts, self.s_ends):
            key = piece_key(planner.path, a, b, queue.limits.of, memo)
            self.spans.append((i, j, keys.setdefault(key, key)))

    def places(self, times: list) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """`place(t)` of many times (None: nan) as arrays (t, k, rel; rel nan at rest), the state at
        each read from the profile a block at a time with `Profile.state`'s arithmetic."""
        t = np.array([np.nan if x is None else x for x in times], dtype=float)
        k = np.searchsorted(np.asarray(self.starts), t, "right") - 1  # (nan sorts last: masked below)
        known = ~np.isnan(t)
        k = np.where(known, k, -1)
        rel = np.full(len(t), np.nan)
        ends = np.asarray(self.ends)
        moving = np.flatnonzero(known & (k >= 0) & (t < ends[np.maximum(k, 0)])) if len(ends) else k[:0]
        moving = moving[np.argsort(t[moving], kind="stable")]  # in time order: each block reads a short window
        prof = self.profile
        n = len(prof.T)
        for at in range(0, len(moving), _PLACES):
            rows = moving[at:at + _PLACES]
            x = t[rows]
            # the breakpoints around these times (a stretch of the run, not the whole of it)
            lo = max(bisect_right(prof.T, float(x.min())) - 1, 0)
            hi = min(bisect_right(prof.T, float(x.max())) + 1, n)
            T, S, SD = (window(v, lo, hi) for v in (prof.T, prof.S, prof.SD))
            j = T.searchsorted(x, "right") - 1  # as `state`: bisect_right(T, t) - 1
            s = np.empty(len(x))
            first = x <= prof.T[0]
            past = (j + lo >= n - 1) & ~first
            mid = ~first & ~past
            s[first] = prof.S[0]
            s[past] = prof.S[n - 1]
            jm, xm = j[mid], x[mid]
            dt = T[jm + 1] - T[jm]
            flat = dt <= 0.0  # `_between`: a zero-length interval is the state after it
            sd0 = SD[jm]
            tau = xm - T[jm]
            with np.errstate(divide="ignore", invalid="ignore"):
                u = (SD[jm + 1] - sd0) / dt
                s[mid] = np.where(flat, S[jm + 1], S[jm] + sd0 * tau + 0.5 * u * tau * tau)
            del T, S, SD
            rel[rows] = s - np.asarray(self.s_starts)[k[rows]]
        return t, k, rel

    def place(self, t: float | None) -> tuple | None:
        """Where the run was at time t, for `Retiming.time_at`: the stretch k it was in or had last
        ended, and its path position from that stretch's start (None at rest after it)."""
        if t is None:
            return None
        k = bisect.bisect_right(self.starts, t) - 1
        if k < 0:
            return (t, k, None)
        if t >= self.ends[k]:
            return (t, k, None)
        s, _, _ = self.profile.state(t)
        return (t, k, s - self.s_starts[k])


class Retiming:
    """The run's profile re-timed piece by piece (module docstring): `time(t)` maps a time of the
    run to the same point of the re-timed run, None past `cut` (the re-timing was stopped there:
    `out_of_time()` became true; `cut` is None when the whole run was re-timed)."""

    def __init__(self, queue, factor: float, out_of_time=None, stretches: Stretches | None = None) -> None:
        """The moving stretches of `queue`'s profile (`stretches`, found here when not given), each
        timed again with accelerations and decelerations × `factor`."""
        st = stretches if stretches is not None else Stretches(queue)
        if st.queue is not queue:
            raise ValueError("the stretches are another queue's")
        planner = queue.planner
        prof = st.profile
        limits = queue.limits.of

        def scaled(key: int) -> Limits:
            lim = limits(key)
            return Limits(lim.V, lim.A * factor, lim.D * factor, lim.tvel, lim.rvel)

        self.profile = prof
        self._place = st.place  # where t falls, for `time`
        self.starts: list[float] = []  # run time at the start of each moving stretch
        self.ends: list[float] = []
        self.new_starts: list[float] = []
        self.pieces: list[Profile] = []  # each stretch re-timed, path positions from its start
        self.cut: float | None = None
        self.stretches = len(st.spans)  # moving stretches in the run
        self.timed = 0  # distinct pieces timed
        done: dict = {}  # piece_key -> the re-timed piece (relative Profile)
        shift = 0.0
        for (_, _, key), t_i, t_j, s_i, s_j in zip(st.spans, st.starts, st.ends, st.s_starts, st.s_ends):
            p = done.get(key) if key is not None else None
            if p is None:
                if out_of_time is not None and out_of_time():  # before each piece timed
                    self.cut = t_i
                    break
                piece = planner.timing.time(planner.path, s_i, s_j, 0.0, scaled)
                p = Profile(0.0, 0.0)
                p.append(0.0, piece.s - s_i, piece.sd)
                self.timed += 1
                if key is not None:
                    done[key] = p
            self.starts.append(t_i)
            self.ends.append(t_j)
            self.new_starts.append(t_i + shift)
            self.pieces.append(p)
            shift += p.t_end - (t_j - t_i)
        self.shift_end = shift

    def time(self, t: float | None) -> float | None:
        """The time of the re-timed run at the point the run reached at time t."""
        return self.time_at(self._place(t))

    def times_at(self, t: np.ndarray, k: np.ndarray, rel: np.ndarray) -> np.ndarray:
        """`time_at` of many places (`Stretches.places`: t, k, rel) as an array, nan for None: the
        same arithmetic, each distinct piece's times found together (`_piece_times`)."""
        out = t.copy()  # before the first stretch: t (and nan stays nan)
        if self.cut is not None:
            out[t >= self.cut] = np.nan
        live = np.flatnonzero((k >= 0) & ~np.isnan(out))
        starts, ends, new_starts = (np.asarray(v) for v in (self.starts, self.ends, self.new_starts))
        t_end = np.array([p.t_end for p in self.pieces])
        kk = k[live]
        rest = np.isnan(rel[live])
        r, kr = live[rest], kk[rest]
        out[r] = t[r] + (new_starts[kr] - starts[kr]) + t_end[kr] - (ends[kr] - starts[kr])
        m, km = live[~rest], kk[~rest]
        # the rows of each distinct piece together, in their order (a stable sort by piece number)
        number: dict = {}
        pieces = self.pieces
        of = np.array([number.setdefault(id(p), len(number)) for p in pieces], dtype=np.intp)
        distinct = {n: p for p, n in zip(pieces, of.tolist())}
        g = of[km]
        order = np.argsort(g, kind="stable")
        cuts = [0, *(np.flatnonzero(np.diff(g[order])) + 1).tolist(), len(m)] if len(m) else [0]
        for lo, hi in zip(cuts[:-1], cuts[1:]):
            rows = m[order[lo:hi]]
            piece = distinct[int(g[order[lo]])]
            at = _piece_times(piece, rel[rows])
            out[rows] = new_starts[k[rows]] + np.where(np.isnan(at), piece.t_end, at)
        return out

    def time_at(self, place: tuple | None) -> float | None:
        """`time(t)` from `Stretches.place(t)` (found once for every factor): the same arithmetic."""
        if place is None:
            return None
        t, k, rel = place
        if self.cut is not None and t >= self.cut:
            return None
        if k < 0:
            return t
        if rel is None:  # at rest after stretch k
            return t + (self.new_starts[k] - self.starts[k]) + self.pieces[k].t_end - (self.ends[k] - self.starts[k])
        at = self.pieces[k].time_at(rel)
        return self.new_starts[k] + (at if at is not None else self.pieces[k].t_end)


def _piece_times(p: Profile, x: np.ndarray) -> np.ndarray:
    """`p.time_at(s)` of each s in x (nan for None), with its arithmetic (trajectory._solve)."""
    T, S, SD = (np.asarray(list(v), dtype=float) for v in (p.T, p.S, p.SD))
    out = np.full(len(x), np.nan)
    xs = x - 1e-12 * np.maximum(1.0, np.abs(x))
    k = S.searchsorted(xs, "left")
    out[k == 0] = T[0]
    inside = np.flatnonzero((k > 0) & (k < len(S)))
    xi, ki = x[inside], k[inside]
    at_point = np.abs(S[ki] - xi) <= 1e-9 * np.maximum(1.0, np.abs(xi))
    j = ki - 1
    dt = T[j + 1] - T[j]
    ds = xi - S[j]
    sd0 = SD[j]
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        u = (SD[j + 1] - sd0) / dt
        tau = np.where(np.abs(u) < 1e-15, np.where(sd0 > 0, ds / sd0, dt),
                       (-sd0 + np.sqrt(np.maximum(sd0 * sd0 + 2.0 * u * ds, 0.0))) / u)
        solved = T[j] + np.minimum(np.maximum(tau, 0.0), dt)
    solved = np.where((ds <= 0.0) | (dt <= 0.0), np.where(ds <= 0.0, T[j], T[j + 1]), solved)
    out[inside] = np.where(at_point, T[ki], solved)
    return out


def retimed(queue, records: list, factor: float, out_of_time=None,
            stretches: Stretches | None = None) -> tuple[list, Retiming]:
    """The motion records (records.MotionRecord) of the run re-timed with accelerations × factor
    (the same records, their start and end moved: module docstring), and the Retiming (its `cut`:
    where it stopped when `out_of_time()` became true; the records after it have no start).
    `stretches`: the queue's, found once by a caller that re-times it for many factors (fit.py)."""
    return retimed_range(queue, records, (factor,), out_of_time, stretches)[0]


def retimed_range(queue, records: list, factors, out_of_time=None,
                  stretches: Stretches | None = None) -> list[tuple[list, Retiming]]:
    """`retimed` for each factor in turn, the stretches, their keys and where each record's start
    and end fall found once for all the factors (`stretches`: found here when not given)."""
    return list(each_retimed(queue, records, factors, out_of_time, stretches))


def each_retimed(queue, records: list, factors, out_of_time=None, stretches: Stretches | None = None):
    """`retimed_range` one factor at a time (a generator: a caller that takes what it needs of a
    factor's records holds one factor's at a time)."""
    n = len(records)
    if records and all(f.init for f in fields(records[0])) and all(type(r) is type(records[0]) for r in records):
        # each record's other fields read once for all the factors (what `replace` does per call)
        names = [f.name for f in fields(records[0])]
        i_start, i_end = names.index("start"), names.index("end")
        values = list(map(list, map(attrgetter(*names), records)))
        make = type(records[0])
    else:
        values = None
    times = [r.start for r in records] + [r.end for r in records]
    for at, rt in each_retimed_times(queue, times, factors, out_of_time, stretches):
        if values is None:
            moved = [replace(r, start=a, end=b) for r, a, b in zip(records, at[:n], at[n:])]
        else:
            moved = []
            for v, a, b in zip(values, at[:n], at[n:]):
                v[i_start], v[i_end] = a, b
                moved.append(make(*v))
        yield moved, rt
        del moved  # before the next factor's


def each_retimed_times(queue, times: list, factors, out_of_time=None, stretches: Stretches | None = None):
    """Times of the run (None: never) at the same points of each factor's re-timed run, a factor
    at a time: (their list, None where the point was never reached or lies past the cut; the
    Retiming). What `each_retimed` does to the records' starts and ends, for a caller that needs
    only some of them (collect.acceleration_range: the first command of each pass)."""
    st = stretches if stretches is not None else Stretches(queue)
    places = st.places(times)
    for factor in factors:
        rt = Retiming(queue, factor, out_of_time, st)
        yield [None if x != x else x for x in rt.times_at(*places).tolist()], rt  # (nan: None)
