"""The arm's trajectory: a path plus a time parameterisation behind one interface.

`Profile` is the path parameter over simulated time, s(t): breakpoints (t, s, ṡ) with a constant
path acceleration between them (the exact form of both the bang-bang profiles and the
time-optimal solver's
output); at rest between motions ṡ = 0. It only grows at its end, except that a replan cuts it at
the replanning time and continues from the exact state there (position and speed continuous).

`Trajectory` joins it to the `paths.Path`: joint position and velocity at any time, and sampling
on the controller's 4 ms clock (`sample`). Times are seconds of simulated time.

The breakpoints are `history.History` sequences: the old ones in a temporary file, so that what a
long run holds of them is bounded (the readers index, slice, bisect and `window` them as arrays).
"""

from __future__ import annotations

import bisect
import math
from array import array

import numpy as np

from .history import History

TICK = 0.004  # the controller's motion cycle (s)
_SEGMENT_BLOCK = 8192  # ticks sampled at most in one call by `segments`


def tick_times(t0: float, t1: float, dt: float = TICK) -> np.ndarray:
    """The instants of the 4 ms clock from t0 to t1, both included (to rounding)."""
    k0 = math.ceil(t0 / dt - 1e-9)
    k1 = math.floor(t1 / dt + 1e-9)
    return np.arange(k0, k1 + 1) * dt



def _between(T, S, SD, k: int, t: float) -> tuple[float, float, float]:
    """(s, ṡ, s̈) at time t between breakpoints k and k + 1 of the sequences T, S, SD (constant
    path acceleration; a zero-length interval is the state after it)."""
    dt = T[k + 1] - T[k]
    if dt <= 0.0:
        return S[k + 1], SD[k + 1], 0.0
    sd0, sd1 = SD[k], SD[k + 1]
    u = (sd1 - sd0) / dt
    tau = t - T[k]
    return S[k] + sd0 * tau + 0.5 * u * tau * tau, sd0 + u * tau, u


class Profile:
    """s(t) as breakpoints; before the first breakpoint the arm rests at s0."""

    def __init__(self, s0: float = 0.0, t0: float = 0.0):
        """At rest at s0 from time t0."""
        # doubles, not lists of floats: a long run holds about 70 breakpoints per motion (8 bytes
        # each instead of 32), the old ones in a file (history.py); indexed and bisected as lists
        self.T = History([t0])
        self.S = History([s0])
        self.SD = History([0.0])

    @property
    def t_end(self) -> float:
        """The time of the last breakpoint (the arm at rest from then on)."""
        T = self.T
        return T.tail[T.tail_len - 1] if T.__class__ is History and T.tail_len else T[-1]

    @property
    def s_end(self) -> float:
        """The path position where the profile ends."""
        S = self.S
        return S.tail[S.tail_len - 1] if S.__class__ is History and S.tail_len else S[-1]

    def _cells(self, k: int) -> tuple:
        """(T, S, SD, j): sequences whose items j and j + 1 are breakpoints k and k + 1 (k + 1 in
        the profile): a chunk's arrays when both lie in one chunk of a History, read in place."""
        T = self.T
        if T.__class__ is History:
            j = k & ((1 << T.shift) - 1)
            if j + 1 < 1 << T.shift:
                c = k >> T.shift
                return T.chunk(c), self.S.chunk(c), self.SD.chunk(c), j
        return T, self.S, self.SD, k

    def state(self, t: float) -> tuple[float, float, float]:
        """(s, ṡ, s̈) at time t."""
        T = self.T
        if T.__class__ is History and T.tail_len > 1 and T.tail[0] < t:
            # the hot case (the arm now, the queue ahead): t in the chunk being written, read in place
            # (S and SD are chunked as T: the same length, the same chunk size)
            tail, n = T.tail, T.tail_len
            j = bisect.bisect_right(tail, t, 0, n) - 1
            S, SD = self.S.tail, self.SD.tail
            if j >= n - 1:
                return S[n - 1], 0.0, 0.0
            return _between(tail, S, SD, j, t)
        return self._state(t)

    def _state(self, t: float) -> tuple[float, float, float]:
        """`state`, on any sequences of breakpoints."""
        T = self.T
        if t <= T[0]:
            return self.S[0], 0.0, 0.0
        k = bisect_right(T, t) - 1
        if k >= len(T) - 1:
            return self.S[-1], 0.0, 0.0
        return _between(*self._cells(k), t)

    def states(self, t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(s, ṡ) at many times (vectorised)."""
        t = np.asarray(t, dtype=float)
        if len(t) == 0:
            return np.zeros(0), np.zeros(0)
        # only the breakpoints around the times asked (the profile holds the whole run)
        a = max(bisect_right(self.T, float(t.min())) - 1, 0)
        b = bisect_right(self.T, float(t.max())) + 1
        T, S, SD = np.asarray(self.T[a:b]), np.asarray(self.S[a:b]), np.asarray(self.SD[a:b])
        k = np.clip(np.searchsorted(T, t, side="right") - 1, 0, len(T) - 1)
        last = k >= len(T) - 1
        k1 = np.minimum(k + 1, len(T) - 1)
        dt = T[k1] - T[k]
        with np.errstate(divide="ignore", invalid="ignore"):
            u = np.where(dt > 0, (SD[k1] - SD[k]) / dt, 0.0)
        tau = np.clip(t - T[k], 0.0, None)
        s = np.where(last, S[-1], S[k] + SD[k] * tau + 0.5 * u * tau * tau)
        sd = np.where(last, 0.0, SD[k] + u * tau)
        before = t <= self.T[0]
        s = np.where(before, self.S[0], s)
        sd = np.where(before, 0.0, sd)
        return s, np.maximum(sd, 0.0)

    def cut(self, t: float) -> None:
        """Keep the profile up to t (and the exact state at t)."""
        if t >= self.T[-1]:
            return
        s, sd, _ = self.state(t)
        k = bisect_right(self.T, t)
        del self.T[k:]
        del self.S[k:]
        del self.SD[k:]
        if self.T[-1] < t:
            self.T.append(t)
            self.S.append(s)
            self.SD.append(sd)

    def append(self, t0: float, s: np.ndarray, sd: np.ndarray) -> None:
        """Add a motion starting at t0 from (s[0], sd[0]) (the current end of the profile)."""
        T = self.T
        if T.__class__ is History:  # refused before any of the three grows (history.DISK_LIMIT)
            T.reserve(len(s) + 1, 3)
        if t0 > T[-1]:
            T.append(t0)
            self.S.append(self.S[-1])
            self.SD.append(0.0)
        t = T[-1]
        s = np.asarray(s, dtype=float)
        sd = np.asarray(sd, dtype=float)
        ds = s[1:] - s[:-1]
        v = sd[:-1] + sd[1:]
        if len(ds) and ds.min() > 0.0:
            # every interval moves (the usual case): the general formula below, without its masks
            times = t + np.cumsum(2.0 * ds / np.maximum(v, 1e-300))
            T.extend(times)
            self.S.extend(s[1:])
            self.SD.extend(sd[1:])
            return
        with np.errstate(divide="ignore", invalid="ignore"):
            dt = np.where(ds > 0, 2.0 * ds / np.maximum(v, 1e-300), 0.0)
        times = t + np.cumsum(dt)
        keep = ~(ds <= 0.0)  # (as a loop skipping ds <= 0 would: a NaN kept)
        T.extend(times[keep])
        self.S.extend(s[1:][keep])
        self.SD.extend(sd[1:][keep])

    def extend_shifted(self, t0: float, T, S, SD, shift: float, end: float) -> None:
        """Add a plan timed relative to its start (planner.py): breakpoints at times t0 + T (t0 the
        current end of the profile or later, at rest until then), positions shift + S, the last
        one exactly `end` (where the path ends), speeds SD: one array operation each."""
        n = len(T)
        if n == 0:
            return
        T_ = self.T
        if T_.__class__ is History:  # refused before any of the three grows (history.DISK_LIMIT)
            T_.reserve(n + 1, 3)
        if t0 > T_[-1]:
            T_.append(t0)
            self.S.append(self.S[-1])
            self.SD.append(0.0)
        s = S + shift
        s[-1] = end
        T_.extend(T + T_[-1])
        self.S.extend(s)
        self.SD.extend(SD)

    def speed_at(self, s: float, until: float) -> float | None:
        """ṡ where the profile passed position s on its way to position `until` (the last time),
        None when it stood still in between or never got there."""
        S, SD = self.S, self.SD
        if S.__class__ is History and S.tail_len > 1 and S.tail[0] <= s:
            # in the chunk being written (the plan ahead): its arrays read in place, as `state`
            S, SD, n = S.tail, SD.tail, S.tail_len
            k = bisect.bisect_right(S, s, 0, n) - 1
        else:
            n = len(S)
            k = bisect_right(S, s) - 1
        if k < 0 or k >= n - 1:
            return None
        j = k + 1
        while j < n and S[j] < until:
            if SD[j] <= 0.0:
                return None
            j += 1
        ds = S[k + 1] - S[k]
        x = SD[k] ** 2 + (SD[k + 1] ** 2 - SD[k] ** 2) * (s - S[k]) / ds if ds > 0 else SD[k] ** 2
        return math.sqrt(max(x, 0.0))

    def time_at(self, s_target: float) -> float | None:
        """The first time at which s reaches s_target; None when the profile never gets there."""
        S = self.S
        x = s_target - 1e-12 * max(1.0, abs(s_target))  # s grows over a run
        if S.__class__ is History and S.tail_len > 1 and S.tail[0] < x:
            # the hot case (a command ahead or just done): in the chunk being written, read in place
            # (as `state`: T and SD chunked as S), the same values as the general path below
            tail, n = S.tail, S.tail_len
            j = bisect.bisect_left(tail, x, 0, n)
            if j >= n:
                return None
            if abs(tail[j] - s_target) <= 1e-9 * max(1.0, abs(s_target)):
                return self.T.tail[j]
            return _solve(self.T.tail, tail, self.SD.tail, j - 1, s_target)
        k = bisect_left(S, x)
        if k >= len(S):
            return None
        if k == 0:
            return self.T[0]
        T, S, SD, j = self._cells(k - 1)
        if abs(S[j + 1] - s_target) <= 1e-9 * max(1.0, abs(s_target)):
            return T[j + 1]  # a breakpoint (the end of a motion): exact
        return _solve(T, S, SD, j, s_target)

    def final_decel_start(self) -> int:
        """Index of the breakpoint where the last run of decreasing speed begins (the braking to
        the end of the profile)."""
        SD = self.SD
        k = len(SD) - 1
        if SD.__class__ is History and SD.tail_len > 1:
            # in the chunk being written, read in place (the braking is about 30 breakpoints)
            tail, j = SD.tail, SD.tail_len - 1
            while j > 0 and tail[j - 1] > tail[j] + 1e-12:
                j -= 1
            if j > 0:
                return SD.tail_start + j
            k = SD.tail_start
        while k > 0 and SD[k - 1] > SD[k] + 1e-12:
            k -= 1
        return k

    def rest_since(self, t: float) -> float | None:
        """When the arm came to rest, if it is at rest at t (else None); -inf when it has not
        moved yet."""
        _, sd, _ = self.state(t)
        if sd > 1e-12:
            return None
        k = min(bisect_right(self.T, t) - 1, len(self.T) - 1)
        k = max(k, 0)
        while k > 0 and self.SD[k - 1] <= 1e-12:
            k -= 1
        return -math.inf if k == 0 else self.T[k]


def _solve(T, S, SD, k: int, s_target: float) -> float:
    """Time within interval k (T[k]..T[k+1]) where s = s_target."""
    dt = T[k + 1] - T[k]
    ds = s_target - S[k]
    if ds <= 0.0 or dt <= 0.0:
        return T[k] if ds <= 0.0 else T[k + 1]
    sd0 = SD[k]
    u = (SD[k + 1] - sd0) / dt
    if abs(u) < 1e-15:
        tau = ds / sd0 if sd0 > 0 else dt
    else:
        disc = sd0 * sd0 + 2.0 * u * ds
        tau = (-sd0 + math.sqrt(max(disc, 0.0))) / u
    return T[k] + min(max(tau, 0.0), dt)


def bisect_right(a, x: float, lo: int = 0, hi: int | None = None) -> int:
    """bisect.bisect_right(a, x, lo, hi) of a profile's T or S: a History's reads one chunk (the
    module's would read one value per step through Python, most of them in the file)."""
    if a.__class__ is History:
        return a.bisect_right(x, lo, hi)
    return bisect.bisect_right(a, x, lo, len(a) if hi is None else hi)


def bisect_left(a, x: float, lo: int = 0, hi: int | None = None) -> int:
    """bisect.bisect_left(a, x, lo, hi) of a profile's T or S (`bisect_right`)."""
    if a.__class__ is History:
        return a.bisect_left(x, lo, hi)
    return bisect.bisect_left(a, x, lo, len(a) if hi is None else hi)


def window(values, lo: int, hi: int) -> np.ndarray:
    """values[lo:hi] of a profile's breakpoints as a numpy array: a view of an array('d') or of
    one chunk of a History (no copy; the caller drops it before the profile may be cut), a copy of
    anything else."""
    if values.__class__ is History:
        return values.window(lo, hi)
    if isinstance(values, array):
        hi = min(hi, len(values))
        return np.frombuffer(values, dtype=float, count=max(hi - lo, 0), offset=8 * lo)
    return np.asarray(values[lo:hi], dtype=float)


def _q01(path, s: np.ndarray) -> tuple:
    """(`path.q(s)`, `path.q(s, 1)`), in one evaluation where the path has one (paths.Path.q01)."""
    both = getattr(path, "q01", None)
    return both(s) if both is not None else (path.q(s), path.q(s, 1))


_MOVING_BLOCK = 1 << 16  # breakpoints per block in Trajectory.moving


class Trajectory:
    """A path plus a time parameterisation: joint position and velocity at any time."""

    def __init__(self, path, profile: Profile):
        """`path` (paths.Path) along `profile`."""
        self.path = path
        self.profile = profile

    def position(self, t: float) -> np.ndarray:
        """Joint positions at time t."""
        s, _, _ = self.profile.state(t)
        return self.path.q([s])[0]

    def positions(self, times) -> np.ndarray:
        """Joint positions at many times (N, axes), in one evaluation of the path."""
        s, _ = self.profile.states(np.asarray(times, dtype=float))
        return self.path.q(s)

    def velocity(self, t: float) -> np.ndarray:
        """Joint velocities at time t."""
        s, sd, _ = self.profile.state(t)
        if sd == 0.0:
            return np.zeros_like(self.path.q_rest)
        return self.path.q([s], 1)[0] * sd

    def sample(self, t0: float, t1: float, dt: float = TICK) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(times, joint positions (N, axes), joint velocities (N, axes)) on the 4 ms clock from
        t0 to t1."""
        times = tick_times(t0, t1, dt)
        if len(times) == 0:
            n = len(self.path.q_rest)
            return times, np.zeros((0, n)), np.zeros((0, n))
        s, sd = self.profile.states(times)
        # a sample with the same (s, ṡ) bits as the one before has the same position and velocity
        # (the arm at rest: about half of a cyclic run): the path evaluated once per run of them,
        # row by row the same arithmetic as on every sample, so the same bits (test_trajectory_sample)
        first = np.ones(len(s), dtype=bool)
        first[1:] = (s.view(np.int64)[1:] != s.view(np.int64)[:-1]) | (sd.view(np.int64)[1:] != sd.view(np.int64)[:-1])
        at = np.flatnonzero(first)
        if len(at) == len(s):
            q, q1 = _q01(self.path, s)
            return times, q, q1 * sd[:, None]
        q, q1 = _q01(self.path, s[at])
        qd = q1 * sd[at][:, None]
        back = np.cumsum(first) - 1  # each sample's run
        return times, q[back], qd[back]

    def moving(self, t_end: float) -> list[tuple[float, float]]:
        """The intervals [start, end] of simulated time in which the arm moves, up to t_end."""
        T, SD = self.profile.T, self.profile.SD
        out: list[tuple[float, float]] = []
        # the intervals up to the first breakpoint at or past t_end, moving at either end, each
        # joined to the one before when it starts within 1e-12 s of its end; block by block (copies:
        # the profile's arrays may grow later), so that an 8-hour profile needs no full-length temporaries
        last = len(T) - 1
        for lo in range(0, max(last, 0), _MOVING_BLOCK):
            hi = min(lo + _MOVING_BLOCK, last)
            t = np.array(T[lo:hi + 1], dtype=float)
            sd = np.array(SD[lo:hi + 1], dtype=float)
            stop = np.flatnonzero(~(t[:-1] < t_end))
            n = int(stop[0]) if len(stop) else hi - lo
            i = np.flatnonzero((sd[:n] > 0.0) | (sd[1:n + 1] > 0.0))
            if len(i):
                a = t[i]
                b = np.where(t_end < t[i + 1], t_end, t[i + 1])  # min(T[i + 1], t_end)
                new = np.ones(len(i), dtype=bool)
                new[1:] = ~(a[1:] <= b[:-1] + 1e-12)
                starts = np.flatnonzero(new)
                ends = np.append(starts[1:], len(i)) - 1
                block = list(zip(a[starts].tolist(), b[ends].tolist()))
                if out and block[0][0] <= out[-1][1] + 1e-12:  # joins the previous block's last
                    out[-1] = (out[-1][0], block[0][1])
                    block = block[1:]
                out.extend(block)
            if len(stop):
                break
        return out

    def segments(self, t_end: float, dt: float = TICK):
        """The trajectory on the clock of period dt, only where the arm moves: for each moving
        interval, (first tick index k, positions (N, axes), velocities (N, axes)) at the ticks
        k·dt ... from the last tick at or before the motion starts to the first at or after it
        ends (both at rest). Between segments the arm stands where the previous one ended."""
        return list(self.iter_segments(t_end, dt))

    def iter_segments(self, t_end: float, dt: float = TICK):
        """`segments` one group of samples at a time, made as they are asked (a report written as
        it goes holds one group, not the run's)."""
        ticks: list[list[int]] = []  # [first, last] tick of each segment
        last = -1
        for a, b in self.moving(t_end):
            k0 = max(math.floor(a / dt + 1e-9), last + 1)
            k1 = math.ceil(b / dt - 1e-9)
            if k1 < k0:
                continue
            if ticks and k0 == last + 1:  # touching the previous segment: one segment
                ticks[-1][1] = k1
            else:
                ticks.append([k0, k1])
            last = k1
        i = 0
        while i < len(ticks):
            # neighbouring segments sampled in one call (a tick's time is k·dt whatever the call,
            # so the same values; the rest between them costs little): one call per segment was
            # most of the JSON report's time. Each segment copied out: the rest is not kept.
            j = i + 1
            while j < len(ticks) and ticks[j][1] - ticks[i][0] < _SEGMENT_BLOCK:
                j += 1
            g0 = ticks[i][0]
            _, q, v = self.sample(g0 * dt, ticks[j - 1][1] * dt, dt)
            for k0, k1 in ticks[i:j]:
                yield k0, q[k0 - g0:k1 - g0 + 1].copy(), v[k0 - g0:k1 - g0 + 1].copy()
            i = j
